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
    , projection(geometry, dilatation_modes(parameters, geometry))
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



  // The modes of the projected dilatation: none for the displacement
  // formulation, the constant for the mean dilatation, the linear ones for
  // the linear dilatation (3D only).
  // A cell needs at least as many quadrature points as modes for the
  // projection: linear tetrahedra (one point) have too few for the linear
  // one.
  template <int dim>
  unsigned int
  HyperelasticSolid<dim>::dilatation_modes(
    const Parameters::AllParameters &parameters,
    const CellGeometry<dim>         &geometry)
  {
    using Formulation = Parameters::FiniteElement::VolumetricFormulation;
    if (dim != 3)
      return 0;
    switch (parameters.volumetric_formulation)
      {
        case Formulation::mean_dilatation:
          return 1;
        case Formulation::linear_dilatation:
          AssertThrow(geometry.n_q_points >= dim + 1,
                      ExcMessage(
                        parameters.where() +
                        "Finite element/Volumetric formulation = linear "
                        "dilatation projects the dilatation on 4 modes per "
                        "cell and needs as many quadrature points; these "
                        "cells have " +
                        std::to_string(geometry.n_q_points) +
                        " (linear tetrahedra: use 'mean dilatation', or "
                        "Polynomial degree = 2)."));
          return dim + 1;
        default:
          return 0;
      }
  }



  template <int dim>
  HyperelasticSolid<dim>::~HyperelasticSolid() = default;



  // @sect4{HyperelasticSolid::cell_dilatation}
  //
  // The projected-dilatation formulations (see the class documentation):
  // the projected volume change $\Theta - 1 = \Pi(J - 1)$ at the points,
  // the volumetric energy $\int U(\Theta)$, the pressure $\bar p =
  // \Pi\,U'(\Theta)$ every point feels, $U''(\Theta)$ at the points (the
  // viscosity of the Kelvin-Voigt damping records it) and the stiffness of
  // the moments $\mathbf A$. With one mode: the cell's mean volume ratio,
  // its energy $V_e U(\Theta)$, the pressure $U'(\Theta)$ and $\mathbf A =
  // U''(\Theta)/V_e$.
  template <int dim>
  typename HyperelasticSolid<dim>::CellDilatation
  HyperelasticSolid<dim>::cell_dilatation(const unsigned int cell,
                                          const std::vector<Tensor<2, dim>> &H,
                                          CellContribution<dim> &local) const
  {
    CellDilatation      result;
    const unsigned int  n_q       = geometry.n_q_points;
    CellWorkspace<dim> &workspace = local.workspace;
    workspace.point_volume_change.resize(n_q);
    workspace.point_pressure.resize(n_q);
    workspace.point_volumetric_stiffness.resize(n_q);
    workspace.point_viscous_pressure.assign(n_q, 0.);
    const NeoHookeanEnergy<dim> &law = *cell_law[cell];
    result.inverse_gram              = projection.inverse_gram(cell);
    for (unsigned int q = 0; q < n_q; ++q)
      workspace.point_volume_change[q] = NeoHookeanEnergy<dim>::volume_change(
        NeoHookeanEnergy<dim>::green_lagrange_strain(H[q]));
    const auto           change = projection.project(cell,
                                           result.inverse_gram,
                                           workspace.point_volume_change);
    std::vector<double> &t      = workspace.point_volume_change;
    for (unsigned int q = 0; q < n_q; ++q)
      {
        t[q] = projection.value(q, change);
        if (!(t[q] > -1.))
          {
            local.inverted = true;
            return result;
          }
      }
    for (unsigned int q = 0; q < n_q; ++q)
      {
        workspace.point_pressure[q] = law.volumetric_pressure(t[q]);
        workspace.point_volumetric_stiffness[q] =
          law.volumetric_stiffness(t[q]);
        local.strain_energy +=
          law.volumetric_energy(t[q]) * geometry.weight(cell, q);
      }
    // The pressure field: the projection of U'(Theta).
    const auto pressure =
      projection.project(cell, result.inverse_gram, workspace.point_pressure);
    for (unsigned int q = 0; q < n_q; ++q)
      workspace.point_pressure[q] = projection.value(q, pressure);
    if (local.request.matrix)
      result.stiffness =
        projection.weighted_stiffness(cell,
                                      result.inverse_gram,
                                      workspace.point_volumetric_stiffness);
    if (needs_volume_gradients(local))
      workspace.volume_gradients.reinit(projection.n_modes(),
                                        geometry.dofs_per_cell);
    return result;
  }



  // @sect4{HyperelasticSolid::add_point_contribution}
  //
  // The point's share of the force, and of the lower triangles of the
  // tangent and the damping matrix. The damping uses the positive
  // semi-definite part of the material tangent (see
  // positive_semidefinite_part()). With a projected dilatation the point
  // also adds to the derivatives of the moments of the volume, $G_{mi} =
  // \partial b_m/\partial u_i = \int N_m(\mathrm{cof}\,\mathbf
  // F)_{c_i}\cdot\nabla_0\varphi_i\,dV$, for the rank-n part of the
  // tangent.
  template <int dim>
  void
  HyperelasticSolid<dim>::add_point_contribution(
    const unsigned int     q,
    const Tensor<2, dim>  &H,
    MaterialResponse<dim> &response,
    CellContribution<dim> &local) const
  {
    const unsigned int               cell = local.cell;
    const unsigned int               n    = geometry.dofs_per_cell;
    const std::vector<unsigned int> &comp = geometry.components;
    // The gradients by dof, which only the matrices need (see
    // cell_contribution()).
    const Tensor<1, dim> *grad_phi =
      shape_gradients_by_dof(local)
        ? local.workspace.shape_gradients.data() + q * n
        : nullptr;
    const double                 JxW         = geometry.weight(cell, q);
    const NeoHookeanEnergy<dim> &law         = *cell_law[cell];
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
    const bool projected = projection.n_modes() > 0;
    if (projected)
      law.evaluate_with_pressure(H,
                                 local.workspace.point_pressure[q],
                                 with_tangent,
                                 response);
    else if (with_tangent)
      law.evaluate(H, response);
    else
      law.evaluate_stress(H, response);
    local.strain_energy += response.energy * JxW;

    if (projected && needs_volume_gradients(local))
      {
        const unsigned int n_modes = projection.n_modes();
        typename DilatationProjection<dim>::ModeVector w;
        for (unsigned int m = 0; m < n_modes; ++m)
          w[m] = projection.mode(q, m) * JxW;
        DilatationProjection<dim>::add_point_derivatives(
          J * transpose(invert(F)),
          grad_phi,
          comp,
          w,
          n_modes,
          local.workspace.volume_gradients);
      }

    // The force $\int\delta\mathbf E_i:\mathbf S = \int\mathbf
    // f_{c_i}\cdot\mathbf S\nabla_0\varphi_i$ with the first Piola-Kirchhoff
    // stress $\mathbf P = \mathbf F\mathbf S$, formed once per point and
    // multiplied out with the other points' (add_stress_forces()).
    const SymmetricTensor<2, dim> &S = response.second_piola;
    add_point_stress(q, 0, F * S, JxW, local.workspace.products);

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
        point.q        = q;
        point.grad_phi = grad_phi;
        point.F        = &F;
        point.L        = &local.workspace.velocity_gradients[q];
        point.material_tangent =
          with_tangent ? &response.material_tangent : nullptr;
        point.tangent = with_matrix ? &tangent : nullptr;
        point.damping_tangent =
          local.request.second_matrix ? &damping : nullptr;
        if (projected)
          {
            point.volume_pressure = local.workspace.point_viscous_pressure[q];
            point.n_modes         = projection.n_modes();
            for (unsigned int m = 0; m < projection.n_modes(); ++m)
              point.modes[m] = projection.mode(q, m);
          }
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
        add_point_tangent(geometry,
                          grad_phi,
                          tangent,
                          JxW,
                          tangent_symmetry(local),
                          local.workspace.tangent_block);
      }
    if (lagged_damping || (viscous_cell(local) && local.request.second_matrix))
      add_point_tangent(geometry,
                        grad_phi,
                        damping,
                        JxW,
                        Symmetry::symmetric,
                        local.workspace.damping_block);
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
    const unsigned int n    = geometry.dofs_per_cell;
    const unsigned int cell = local.cell;
    // The gradients by node for the forces and the fields' gradients, and
    // by dof for the matrices.
    CellProducts &products = local.workspace.products;
    reset_cell_products(geometry, cell, products);
    if (shape_gradients_by_dof(local))
      geometry.cell_gradients(cell, local.workspace.shape_gradients);
    std::vector<Tensor<2, dim>> &H = local.workspace.displacement_gradients;
    if (viscous_cell(local))
      field_gradients(geometry,
                      products,
                      {local.input_values[0], local.input_values[1]},
                      {&H, &local.workspace.velocity_gradients});
    else
      field_gradients(geometry, products, {local.input_values[0]}, {&H});
    if (local.request.matrix)
      reset_tangent_block(geometry, local.workspace.tangent_block);
    if (local.request.second_matrix)
      reset_tangent_block(geometry, local.workspace.damping_block);
    const bool projected = projection.n_modes() > 0;
    const bool rate_gradients =
      projected && viscous_cell(local) && local.request.matrix;
    local.workspace.rate_gradients.reinit(rate_gradients ? projection.n_modes()
                                                         : 0,
                                          rate_gradients ? n : 0);

    CellDilatation dilatation;
    if (projected)
      dilatation = cell_dilatation(cell, H, local);
    // The volumetric viscous pressure, whose point values the tangent
    // needs, from the rates $\dot J = \mathrm{cof}\,\mathbf F:\mathbf L_0$
    // before the points are integrated.
    if (projected && viscous_cell(local) && !local.inverted)
      {
        std::vector<double> &rate = local.workspace.point_volume_rate;
        rate.resize(geometry.n_q_points);
        for (unsigned int q = 0; q < geometry.n_q_points; ++q)
          {
            Tensor<2, dim> F = H[q];
            for (unsigned int d = 0; d < dim; ++d)
              F[d][d] += 1.;
            const Tensor<2, dim> cofactor =
              determinant(F) * transpose(invert(F));
            rate[q] =
              scalar_product(cofactor, local.workspace.velocity_gradients[q]);
          }
        viscous->volumetric_viscosity(projection,
                                      dilatation.inverse_gram,
                                      rate,
                                      local,
                                      dilatation.viscous_stiffness);
      }
    MaterialResponse<dim> response;
    for (unsigned int q = 0; q < geometry.n_q_points; ++q)
      add_point_contribution(q, H[q], response, local);

    add_stress_forces(geometry, products, local.force, local.second_force);
    if (projected && viscous_cell(local) && !local.inverted)
      viscous->add_volumetric_contribution(projection.n_modes(),
                                           dilatation.viscous_stiffness,
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
                              Symmetry::symmetric,
                              local.second_matrix);
          }
        return;
      }
    // The rank-n term $\mathbf G^T\mathbf A\mathbf G$ of the projected
    // dilatation (lower triangle), and in the lagged damping matrix $\zeta$
    // times it.
    if (projected && !local.inverted)
      {
        const double zeta = cell_zeta[cell];
        const bool   damped =
          !viscous && local.request.second_matrix && zeta > 0.;
        projection.add_rank_n_term(dilatation.stiffness,
                                   local.workspace.volume_gradients,
                                   local.workspace.mode_products,
                                   &local.matrix,
                                   1.,
                                   damped ? &local.second_matrix : nullptr,
                                   zeta);
      }
    for (unsigned int i = 0; i < n; ++i)
      for (unsigned int j = i + 1; j < n; ++j)
        {
          local.matrix(i, j)        = local.matrix(j, i);
          local.second_matrix(i, j) = local.second_matrix(j, i);
        }
    add_tangent_block(geometry,
                      local.workspace.tangent_block,
                      tangent_symmetry(local),
                      local.matrix);
    if (local.request.second_matrix)
      add_tangent_block(geometry,
                        local.workspace.damping_block,
                        Symmetry::symmetric,
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
    CellProducts products;
    reset_cell_products(geometry, cell, products);
    std::vector<Tensor<2, dim>> H;
    field_gradients(geometry, products, {cell_u}, {&H});
    const NeoHookeanEnergy<dim> &law = *cell_law[cell];
    CellContribution<dim>        local;
    local.cell = cell;
    if (projection.n_modes() > 0)
      cell_dilatation(cell, H, local);
    MaterialResponse<dim>   response;
    SymmetricTensor<2, dim> mean_sigma;
    double                  mean_J = 0.;
    for (unsigned int q = 0; q < H.size(); ++q)
      {
        const Tensor<2, dim> &G = H[q];
        Tensor<2, dim>        F = G;
        for (unsigned int d = 0; d < dim; ++d)
          F[d][d] += 1.;
        if (projection.n_modes() > 0 && !local.inverted)
          law.evaluate_with_pressure(G,
                                     local.workspace.point_pressure[q],
                                     false,
                                     response);
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
