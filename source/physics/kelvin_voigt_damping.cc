// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Objective stiffness-proportional damping: a Kelvin-Voigt solid}
//
// See include/physics/kelvin_voigt_damping.h for the formulas.

#include <core/config.h>
#include <material/neo_hookean_energy.h>
#include <physics/kelvin_voigt_damping.h>

namespace SoftRobot
{
  template <int dim>
  KelvinVoigtDamping<dim>::KelvinVoigtDamping(
    const CellGeometry<dim>   &geometry,
    const std::vector<double> &cell_zeta,
    const bool                 symmetric_tangent)
    : geometry(geometry)
    , cell_zeta(cell_zeta)
    , symmetric_tangent(symmetric_tangent)
    , viscosity(geometry.n_cells * geometry.n_q_points)
    , volumetric_viscosity(geometry.n_cells, 0.)
  {
    Assert(cell_zeta.size() == geometry.n_cells, ExcInternalError());
  }



  // @sect4{KelvinVoigtDamping::add_point_contribution}
  //
  // The force $\int\delta\mathbf E_i:\mathbf S_v$ is computed as for the
  // elastic stress, $\int(\mathbf F\mathbf S_v)_{c_i}\cdot\nabla_0\varphi_i$.
  // The damping matrix $\zeta\,\delta\mathbf E_i:\mathcal C^+:\delta\mathbf
  // E_j$ is the same product, in the same order, as that of the
  // stiffness-proportional damping matrix of HyperelasticSolid.
  template <int dim>
  void
  KelvinVoigtDamping<dim>::add_point_contribution(
    const PointKinematics &point,
    CellContribution<dim> &local) const
  {
    const unsigned int cell = local.cell;
    const double       zeta = cell_zeta[cell];
    if (!(zeta > 0.))
      return;
    const unsigned int               n    = geometry.dofs_per_cell;
    const std::vector<unsigned int> &comp = geometry.components;
    const Tensor<1, dim>            *grad_phi =
      &local.workspace.shape_gradients[point.q * n];
    const double             JxW = geometry.weight(cell, point.q);
    SymmetricTensor<4, dim> &D =
      viscosity[cell * geometry.n_q_points + point.q];
    if (local.request.store_viscosity)
      {
        Assert(point.material_tangent != nullptr, ExcInternalError());
        D = positive_semidefinite_part(*point.material_tangent);
      }
    const Tensor<2, dim>         &F     = *point.F;
    const Tensor<2, dim>         &L     = *point.L;
    const SymmetricTensor<2, dim> E_dot = symmetrize(transpose(F) * L);
    const SymmetricTensor<2, dim> S_v   = zeta * (D * E_dot);
    const Tensor<2, dim>          P_v   = F * S_v;
    for (unsigned int i = 0; i < n; ++i)
      local.second_force(i) += (P_v[comp[i]] * grad_phi[i]) * JxW;

    const bool with_matrix  = local.request.matrix;
    const bool with_damping = local.request.second_matrix;
    if (!with_matrix && !with_damping)
      return;
    Assert(point.delta_E != nullptr, ExcInternalError());
    const std::vector<SymmetricTensor<2, dim>> &dE = *point.delta_E;
    const double c_v          = local.request.velocity_coefficient;
    const bool   nonsymmetric = with_matrix && !symmetric_tangent;
    // The rate's variation by shape function j, formed once per point
    // instead of once per pair (i, j).
    std::vector<SymmetricTensor<2, dim>> &delta_rate =
      local.workspace.delta_rate;
    if (nonsymmetric)
      {
        delta_rate.resize(n);
        for (unsigned int j = 0; j < n; ++j)
          delta_rate[j] = symmetrize(outer_product(L[comp[j]], grad_phi[j]));
      }
    for (unsigned int i = 0; i < n; ++i)
      {
        const SymmetricTensor<2, dim> D_dE_i       = D * dE[i];
        const Tensor<1, dim>          S_v_grad_phi = S_v * grad_phi[i];
        for (unsigned int j = 0; j <= i; ++j)
          {
            const double damping = zeta * (D_dE_i * dE[j]) * JxW;
            if (with_damping)
              local.second_matrix(i, j) += damping;
            if (with_matrix)
              {
                double value = c_v * damping;
                if (comp[i] == comp[j])
                  value += (S_v_grad_phi * grad_phi[j]) * JxW;
                local.matrix(i, j) += value;
              }
          }
        if (nonsymmetric)
          {
            const double factor = zeta * JxW;
            for (unsigned int j = 0; j < n; ++j)
              local.workspace.nonsymmetric_matrix(i, j) +=
                factor * (D_dE_i * delta_rate[j]);
          }
      }
    if (nonsymmetric)
      local.workspace.has_nonsymmetric_part = true;

    // In the mean-dilatation formulation also the derivative of the cell's
    // volume rate, $\partial(\mathbf g\cdot\mathbf v)/\partial u_j = \int
    // \partial(\mathrm{cof}\,\mathbf F:\mathbf L_0)/\partial\mathbf F :
    // \nabla_0\mathbf N_j\,dV$, for the non-symmetric volumetric term.
    if (nonsymmetric && local.workspace.rate_gradient.size() == n)
      {
        const Tensor<2, dim> F_inverse = invert(F);
        const double         J         = determinant(F);
        const Tensor<2, dim> M =
          J * (trace(F_inverse * L) * transpose(F_inverse) -
               transpose(F_inverse * L * F_inverse));
        for (unsigned int j = 0; j < n; ++j)
          local.workspace.rate_gradient(j) += (M[comp[j]] * grad_phi[j]) * JxW;
      }
  }



  // @sect4{KelvinVoigtDamping::viscous_pressure}
  template <int dim>
  double
  KelvinVoigtDamping<dim>::viscous_pressure(
    const unsigned int    cell,
    const double          reference_volume,
    const Vector<double> &volume_gradient,
    const double         *cell_v) const
  {
    double rate = 0.;
    for (unsigned int i = 0; i < volume_gradient.size(); ++i)
      rate += volume_gradient(i) * cell_v[i];
    return cell_zeta[cell] * volumetric_viscosity[cell] * rate /
           reference_volume;
  }



  // @sect4{KelvinVoigtDamping::add_volumetric_contribution}
  //
  // The force $p_v\mathbf g$ and, with a matrix, $\kappa_v V_{0,e}^{-1}
  // (c_v\mathbf g\mathbf g^T + \mathbf g\,(\partial(\mathbf g\cdot\mathbf
  // v)/\partial\mathbf u)^T) + p_v\,\partial\mathbf g/\partial\mathbf u$,
  // the last from the second derivatives of $J$ at the cell's points.
  template <int dim>
  void
  KelvinVoigtDamping<dim>::add_volumetric_contribution(
    const double           reference_volume,
    const double           volumetric_stiffness,
    CellContribution<dim> &local) const
  {
    const unsigned int cell = local.cell;
    const double       zeta = cell_zeta[cell];
    if (!(zeta > 0.))
      return;
    if (local.request.store_viscosity)
      volumetric_viscosity[cell] = volumetric_stiffness;
    const unsigned int    n = geometry.dofs_per_cell;
    const Vector<double> &g = local.workspace.volume_gradient;
    const double          p_v =
      viscous_pressure(cell, reference_volume, g, local.input_values[1]);
    for (unsigned int i = 0; i < n; ++i)
      local.second_force(i) += p_v * g(i);

    const bool with_matrix  = local.request.matrix;
    const bool with_damping = local.request.second_matrix;
    if (!with_matrix && !with_damping)
      return;
    const double factor = volumetric_viscosity[cell] / reference_volume;
    const double c_v    = local.request.velocity_coefficient;
    for (unsigned int i = 0; i < n; ++i)
      for (unsigned int j = 0; j <= i; ++j)
        {
          const double damping = zeta * factor * g(i) * g(j);
          if (with_damping)
            local.second_matrix(i, j) += damping;
          if (with_matrix)
            local.matrix(i, j) += c_v * damping;
        }
    if (!with_matrix)
      return;

    // $p_v\,\partial^2 V_e/\partial u_i\partial u_j = p_v\int
    // \varepsilon_{c_ic_jk}\,\mathbf f_k\cdot(\nabla_0\varphi_i\times
    // \nabla_0\varphi_j)\,dV$ (3D only: the mean-dilatation formulation is
    // for the 3D material).
    if constexpr (dim == 3)
      if (p_v != 0.)
        {
          const std::vector<unsigned int> &comp = geometry.components;
          for (unsigned int q = 0; q < geometry.n_q_points; ++q)
            {
              Tensor<2, dim> F = local.workspace.displacement_gradients[q];
              for (unsigned int d = 0; d < dim; ++d)
                F[d][d] += 1.;
              const Tensor<1, dim> *grad_phi =
                &local.workspace.shape_gradients[q * n];
              const double w = p_v * geometry.weight(cell, q);
              for (unsigned int i = 0; i < n; ++i)
                for (unsigned int j = 0; j < i; ++j)
                  if (comp[i] != comp[j])
                    {
                      const unsigned int k = 3 - comp[i] - comp[j];
                      const double       sign =
                        ((comp[i] + 1) % 3 == comp[j]) ? 1. : -1.;
                      local.matrix(i, j) +=
                        w * sign *
                        (F[k] * cross_product_3d(grad_phi[i], grad_phi[j]));
                    }
            }
        }
    if (!symmetric_tangent)
      {
        const Vector<double> &h = local.workspace.rate_gradient;
        for (unsigned int i = 0; i < n; ++i)
          for (unsigned int j = 0; j < n; ++j)
            local.workspace.nonsymmetric_matrix(i, j) +=
              zeta * factor * g(i) * h(j);
        local.workspace.has_nonsymmetric_part = true;
      }
  }



#define SOFT_ROBOT_INSTANTIATE(dim) template class KelvinVoigtDamping<dim>;
  SOFT_ROBOT_FOR_EACH_DIMENSION(SOFT_ROBOT_INSTANTIATE)
#undef SOFT_ROBOT_INSTANTIATE
} // namespace SoftRobot
