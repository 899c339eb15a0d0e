// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{The hyperelastic solid: what one cell contributes}
//
// See include/physics/hyperelastic_solid.h for the formulas.

#include <core/config.h>
#include <physics/hyperelastic_solid.h>
#include <physics/point_tangent.h>

namespace SoftRobot
{
  // @sect4{HyperelasticSolid::HyperelasticSolid}
  //
  // The stiffness-proportional damping is either a Kelvin-Voigt stress
  // (KelvinVoigtDamping, the default) or the damping matrix of a state that
  // the simulator applies to the velocity (the lagged form kept for
  // comparison); with the first, the matrix of a state is the same, and the
  // force is the stress's.
  template <int dim>
  HyperelasticSolid<dim>::HyperelasticSolid(
    const Parameters::AllParameters &parameters,
    const CellGeometry<dim>         &geometry,
    const bool                       symmetric_tangent)
    : geometry(geometry)
    , mean_dilatation(
        (dim == 3) &&
        (parameters.volumetric_formulation ==
         Parameters::FiniteElement::VolumetricFormulation::mean_dilatation))
  {
    for (const auto &[id, material] : parameters.by_id)
      {
        laws.emplace(id,
                     NeoHookeanEnergy<dim>(material.shear_modulus,
                                           material.bulk_modulus));
        damped = damped || (material.damping_zeta > 0.);
      }
    for (const types::material_id id : geometry.material_ids)
      {
        cell_law.push_back(&laws.at(id));
        cell_zeta.push_back(parameters.by_id.at(id).damping_zeta);
      }
    if (damped && parameters.stiffness_damping ==
                    Parameters::Damping::StiffnessDamping::kelvin_voigt)
      viscous = std::make_unique<KelvinVoigtDamping<dim>>(geometry,
                                                          cell_zeta,
                                                          symmetric_tangent);
  }



  template <int dim>
  HyperelasticSolid<dim>::~HyperelasticSolid() = default;



  // @sect4{HyperelasticSolid::displacement_gradients}
  //
  // $\mathbf H = \nabla_0\mathbf u = \sum_i u_i\,\mathbf e_{c_i}\otimes
  // \nabla_0\varphi_i$ at every quadrature point of the cell.
  template <int dim>
  void
  HyperelasticSolid<dim>::displacement_gradients(
    const std::vector<Tensor<1, dim>> &grad_phi,
    const double                      *cell_u,
    std::vector<Tensor<2, dim>>       &H) const
  {
    const unsigned int               n_q  = geometry.n_q_points;
    const unsigned int               n    = geometry.dofs_per_cell;
    const std::vector<unsigned int> &comp = geometry.components;
    H.assign(n_q, Tensor<2, dim>());
    for (unsigned int q = 0; q < n_q; ++q)
      for (unsigned int i = 0; i < n; ++i)
        H[q][comp[i]] += cell_u[i] * grad_phi[q * n + i];
  }



  // @sect4{HyperelasticSolid::cell_pressure}
  //
  // The mean-dilatation formulation (see the class documentation): the
  // cell's mean volume ratio $\Theta = 1 + t$, its volumetric energy
  // $V_e\,U(\Theta)$, the pressure $p = U'(\Theta)$ every point of the cell
  // feels, and $U''(\Theta)/V_e$ for the tangent.
  template <int dim>
  typename HyperelasticSolid<dim>::CellPressure
  HyperelasticSolid<dim>::cell_pressure(const unsigned int                 cell,
                                        const std::vector<Tensor<2, dim>> &H,
                                        CellContribution<dim> &local) const
  {
    CellPressure result;
    if (!mean_dilatation)
      return result;
    const NeoHookeanEnergy<dim> &law           = *cell_law[cell];
    double                       volume_change = 0.;
    for (unsigned int q = 0; q < geometry.n_q_points; ++q)
      {
        const double JxW = geometry.weight(cell, q);
        result.volume += JxW;
        volume_change += NeoHookeanEnergy<dim>::volume_change(
                           NeoHookeanEnergy<dim>::green_lagrange_strain(H[q])) *
                         JxW;
      }
    const double t = volume_change / result.volume;
    if (!(t > -1.))
      local.inverted = true;
    else
      {
        result.pressure             = law.volumetric_pressure(t);
        result.volumetric_stiffness = law.volumetric_stiffness(t);
        local.strain_energy += law.volumetric_energy(t) * result.volume;
      }
    if (local.request.matrix || viscous_cell(local))
      local.workspace.volume_gradient.reinit(geometry.dofs_per_cell);
    return result;
  }



  // @sect4{HyperelasticSolid::add_point_contribution}
  //
  // The point's share of the force, and of the lower triangles of the
  // tangent and the damping matrix. The damping uses the positive
  // semi-definite part of the material tangent (see
  // positive_semidefinite_part()). With the mean-dilatation formulation the
  // point also adds to the derivative of the cell's volume,
  // $\partial(V_e\Theta)/\partial u_i = \int (\mathrm{cof}\,\mathbf
  // F)_{c_i}\cdot\nabla_0\varphi_i\,dV$, for the rank-one part of the
  // tangent.
  template <int dim>
  void
  HyperelasticSolid<dim>::add_point_contribution(
    const unsigned int     q,
    const Tensor<2, dim>  &H,
    const CellPressure    &pressure,
    MaterialResponse<dim> &response,
    CellContribution<dim> &local) const
  {
    const unsigned int               cell = local.cell;
    const unsigned int               n    = geometry.dofs_per_cell;
    const std::vector<unsigned int> &comp = geometry.components;
    const Tensor<1, dim> *grad_phi   = &local.workspace.shape_gradients[q * n];
    const double          JxW        = geometry.weight(cell, q);
    const NeoHookeanEnergy<dim> &law = *cell_law[cell];
    const bool                   with_matrix = local.request.matrix;

    Tensor<2, dim> F = H;
    for (unsigned int d = 0; d < dim; ++d)
      F[d][d] += 1.;
    const double J     = determinant(F);
    local.min_jacobian = std::min(local.min_jacobian, J);
    if (!(J > 0.) || local.inverted)
      {
        local.inverted = true;
        return;
      }
    // The material tangent, for the matrix or for the viscosity of the
    // state that the next step starts from.
    const bool with_tangent =
      with_matrix || (viscous_cell(local) && local.request.store_viscosity);
    if (mean_dilatation)
      law.evaluate_with_pressure(H, pressure.pressure, with_tangent, response);
    else if (with_tangent)
      law.evaluate(H, response);
    else
      law.evaluate_stress(H, response);
    local.strain_energy += response.energy * JxW;

    if (mean_dilatation && (with_matrix || viscous_cell(local)))
      {
        const Tensor<2, dim> cofactor = J * transpose(invert(F));
        for (unsigned int i = 0; i < n; ++i)
          local.workspace.volume_gradient(i) +=
            (cofactor[comp[i]] * grad_phi[i]) * JxW;
      }

    // The force $\int\delta\mathbf E_i:\mathbf S = \int\mathbf
    // f_{c_i}\cdot\mathbf S\nabla_0\varphi_i$ with the first Piola-Kirchhoff
    // stress $\mathbf P = \mathbf F\mathbf S$ formed once per point: a
    // dot product per shape function.
    const SymmetricTensor<2, dim> &S = response.second_piola;
    const Tensor<2, dim>           P = F * S;
    for (unsigned int i = 0; i < n; ++i)
      local.force(i) += (P[comp[i]] * grad_phi[i]) * JxW;

    // The matrices, as fourth-order tensors of the point (point_tangent.h):
    // the tangent $F_{cI}\mathcal C_{IJKL}F_{kK} + \delta_{ck}S_{JL}$ with
    // the viscous stress's terms, and the damping matrix of the state (the
    // lagged one uses the positive semi-definite part of the material
    // tangent).
    const double zeta = cell_zeta[cell];
    const bool   lagged_damping =
      with_matrix && !viscous && local.request.second_matrix && zeta > 0.;
    Tensor<4, dim> tangent, damping;
    if (viscous_cell(local))
      {
        typename KelvinVoigtDamping<dim>::PointKinematics point;
        point.q = q;
        point.F = &F;
        point.L = &local.workspace.velocity_gradients[q];
        point.material_tangent =
          with_tangent ? &response.material_tangent : nullptr;
        point.tangent = with_matrix ? &tangent : nullptr;
        point.damping_tangent =
          local.request.second_matrix ? &damping : nullptr;
        point.volume_pressure = pressure.viscous_pressure;
        viscous->add_point_contribution(point, local);
      }
    if (with_matrix)
      {
        add_pulled_tangent(F, response.material_tangent, F, 1., tangent);
        add_geometric_tangent(S, tangent);
        if (lagged_damping)
          add_pulled_tangent(F,
                             positive_semidefinite_part(
                               response.material_tangent),
                             F,
                             zeta,
                             damping);
        add_point_tangent(
          geometry, grad_phi, tangent, JxW, local.workspace.tangent_block);
      }
    if (lagged_damping || (viscous_cell(local) && local.request.second_matrix))
      add_point_tangent(
        geometry, grad_phi, damping, JxW, local.workspace.damping_block);
  }



  // @sect4{HyperelasticSolid::cell_contribution}
  //
  // The points' contributions, then the rank-one term of the condensed
  // pressure and dilatation, $U''(\Theta)/V_e\;\mathbf g\mathbf g^T$ with
  // the volume derivative $\mathbf g$: it is positive semi-definite and
  // belongs to the material part, so the damping matrix gets it too. The
  // matrices are symmetric; only their lower triangles are computed, and
  // copied into the upper ones at the end.
  template <int dim>
  void
  HyperelasticSolid<dim>::cell_contribution(CellContribution<dim> &local) const
  {
    const unsigned int           n        = geometry.dofs_per_cell;
    const unsigned int           cell     = local.cell;
    std::vector<Tensor<1, dim>> &grad_phi = local.workspace.shape_gradients;
    geometry.cell_gradients(cell, grad_phi);
    std::vector<Tensor<2, dim>> &H = local.workspace.displacement_gradients;
    displacement_gradients(grad_phi, local.input_values[0], H);
    if (viscous_cell(local))
      displacement_gradients(grad_phi,
                             local.input_values[1],
                             local.workspace.velocity_gradients);
    if (local.request.matrix)
      reset_tangent_block(geometry, local.workspace.tangent_block);
    if (local.request.second_matrix)
      reset_tangent_block(geometry, local.workspace.damping_block);
    const bool rate_gradient =
      mean_dilatation && viscous_cell(local) && local.request.matrix;
    local.workspace.rate_gradient.reinit(rate_gradient ? n : 0);

    CellPressure pressure = cell_pressure(cell, H, local);
    // The volumetric viscous pressure, which the points' tangent needs,
    // from the cell's volume rate $\sum_q w_q\,\mathrm{cof}\,\mathbf F:
    // \mathbf L_0$ before the points are integrated.
    if (mean_dilatation && viscous_cell(local) && local.request.matrix &&
        !local.inverted)
      {
        double volume_rate = 0.;
        for (unsigned int q = 0; q < geometry.n_q_points; ++q)
          {
            Tensor<2, dim> F = H[q];
            for (unsigned int d = 0; d < dim; ++d)
              F[d][d] += 1.;
            const Tensor<2, dim> cofactor =
              determinant(F) * transpose(invert(F));
            volume_rate +=
              scalar_product(cofactor, local.workspace.velocity_gradients[q]) *
              geometry.weight(cell, q);
          }
        pressure.viscous_pressure = viscous->cell_viscous_pressure(
          pressure.volume, volume_rate, pressure.volumetric_stiffness, local);
      }
    MaterialResponse<dim> response;
    for (unsigned int q = 0; q < geometry.n_q_points; ++q)
      add_point_contribution(q, H[q], pressure, response, local);

    if (mean_dilatation && viscous_cell(local) && !local.inverted)
      viscous->add_volumetric_contribution(pressure.volume,
                                           pressure.volumetric_stiffness,
                                           local);
    if (!local.request.matrix)
      {
        if (local.request.second_matrix)
          {
            for (unsigned int i = 0; i < n; ++i)
              for (unsigned int j = i + 1; j < n; ++j)
                local.second_matrix(i, j) = local.second_matrix(j, i);
            add_tangent_block(geometry,
                              local.workspace.damping_block,
                              local.second_matrix);
          }
        return;
      }
    if (mean_dilatation && !local.inverted)
      {
        const Vector<double> &g = local.workspace.volume_gradient;
        const double factor = pressure.volumetric_stiffness / pressure.volume;
        const double zeta   = cell_zeta[cell];
        const bool   damped =
          !viscous && local.request.second_matrix && zeta > 0.;
        for (unsigned int i = 0; i < n; ++i)
          for (unsigned int j = 0; j <= i; ++j)
            {
              local.matrix(i, j) += factor * g(i) * g(j);
              if (damped)
                local.second_matrix(i, j) += zeta * factor * g(i) * g(j);
            }
      }
    for (unsigned int i = 0; i < n; ++i)
      for (unsigned int j = i + 1; j < n; ++j)
        {
          local.matrix(i, j)        = local.matrix(j, i);
          local.second_matrix(i, j) = local.second_matrix(j, i);
        }
    add_tangent_block(geometry, local.workspace.tangent_block, local.matrix);
    if (local.request.second_matrix)
      add_tangent_block(geometry,
                        local.workspace.damping_block,
                        local.second_matrix);
    if (local.workspace.has_nonsymmetric_part)
      local.matrix.add(1., local.workspace.nonsymmetric_matrix);
  }



  // @sect4{HyperelasticSolid::cell_averages}
  template <int dim>
  std::pair<double, SymmetricTensor<2, dim>>
  HyperelasticSolid<dim>::cell_averages(const unsigned int cell,
                                        const double      *cell_u) const
  {
    std::vector<Tensor<1, dim>> grad_phi;
    geometry.cell_gradients(cell, grad_phi);
    std::vector<Tensor<2, dim>> H;
    displacement_gradients(grad_phi, cell_u, H);
    const NeoHookeanEnergy<dim> &law      = *cell_law[cell];
    double                       pressure = 0.;
    if (mean_dilatation)
      {
        double volume = 0., volume_change = 0.;
        for (unsigned int q = 0; q < geometry.n_q_points; ++q)
          {
            volume += geometry.weight(cell, q);
            volume_change +=
              NeoHookeanEnergy<dim>::volume_change(
                NeoHookeanEnergy<dim>::green_lagrange_strain(H[q])) *
              geometry.weight(cell, q);
          }
        pressure = law.volumetric_pressure(volume_change / volume);
      }
    MaterialResponse<dim>   response;
    SymmetricTensor<2, dim> mean_sigma;
    double                  mean_J = 0.;
    for (const Tensor<2, dim> &G : H)
      {
        Tensor<2, dim> F = G;
        for (unsigned int d = 0; d < dim; ++d)
          F[d][d] += 1.;
        if (mean_dilatation)
          law.evaluate_with_pressure(G, pressure, false, response);
        else
          law.evaluate_stress(G, response);
        mean_sigma += law.cauchy_stress(F, response.second_piola);
        mean_J += determinant(F);
      }
    mean_sigma /= H.size();
    return {mean_J / H.size(), mean_sigma};
  }



#define SOFT_ROBOT_INSTANTIATE(dim) template class HyperelasticSolid<dim>;
  SOFT_ROBOT_FOR_EACH_DIMENSION(SOFT_ROBOT_INSTANTIATE)
#undef SOFT_ROBOT_INSTANTIATE
} // namespace SoftRobot
