// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Objective stiffness-proportional damping: a Kelvin-Voigt solid}
//
// See include/physics/kelvin_voigt_damping.h for the formulas.

#include <core/config.h>
#include <material/neo_hookean_energy.h>
#include <physics/kelvin_voigt_damping.h>
#include <physics/point_tangent.h>

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
    , volumetric_stiffness(geometry.n_cells * geometry.n_q_points, 0.)
  {
    Assert(cell_zeta.size() == geometry.n_cells, ExcInternalError());
  }



  // @sect4{KelvinVoigtDamping::add_point_contribution}
  //
  // The force $\int\delta\mathbf E_i:\mathbf S_v$ is computed as for the
  // elastic stress, $\int(\mathbf F\mathbf S_v)_{c_i}\cdot\nabla_0\varphi_i$.
  // The matrices' terms (see the header) in the form of point_tangent.h:
  // the damping matrix $\zeta\,\delta\mathbf E_i:\mathcal D:\delta\mathbf
  // E_j$ is $\zeta F_{cI}\mathcal D_{IJKL}F_{kK}$, the tangent adds it
  // times $c_v$, the geometric term of $\mathbf S_v$, the volume Hessian
  // times $p_v$ and, not symmetric, $\zeta\,\delta\mathbf E_i:\mathcal
  // D:\mathrm{sym}(\mathbf l_{c_j}\otimes\nabla_0\varphi_j)$, which is
  // $\zeta F_{cI}\mathcal D_{IJKL}L_{kK}$.
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
    const unsigned int               n        = geometry.dofs_per_cell;
    const std::vector<unsigned int> &comp     = geometry.components;
    const Tensor<1, dim>            *grad_phi = point.grad_phi;
    const double                     JxW      = geometry.weight(cell, point.q);
    SymmetricTensor<4, dim>         &D =
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
    Tensor<2, dim>                P_v   = F * S_v;
    // The volumetric viscous force $\mathbf G^T\boldsymbol\pi_v$ is the
    // integral of $p_v\,\mathrm{cof}\,\mathbf F:\nabla_0\delta\mathbf
    // u$, since $p_v = \mathbf N\cdot\boldsymbol\pi_v$ at the point: it
    // joins the point's stress, and $\mathbf G$ is formed only for the
    // matrices.
    if constexpr (dim == 3)
      if (point.volume_pressure != 0.)
        P_v += (point.volume_pressure * determinant(F)) * transpose(invert(F));
    add_point_stress(point.q, 1, P_v, JxW, local.workspace.products);

    if (point.tangent == nullptr && point.damping_tangent == nullptr)
      return;
    Tensor<4, dim> damping;
    add_pulled_tangent(F, D, F, zeta, damping);
    if (point.damping_tangent != nullptr)
      *point.damping_tangent += damping;
    if (point.tangent == nullptr)
      return;
    Tensor<4, dim> &tangent = *point.tangent;
    tangent += local.request.velocity_coefficient * damping;
    add_geometric_tangent(S_v, tangent);
    if constexpr (dim == 3)
      if (point.volume_pressure != 0.)
        add_volume_hessian(F, point.volume_pressure, tangent);
    if (symmetric_tangent)
      return;
    add_pulled_tangent(F, D, L, zeta, tangent);

    // With a projected dilatation also the derivatives of the moments of
    // the volume rate, $H_{mj} = \partial(\mathbf G\mathbf v)_m/\partial
    // u_j = \int N_m\,\partial(\mathrm{cof}\,\mathbf F:\mathbf
    // L_0)/\partial\mathbf F:\nabla_0\mathbf N_j\,dV$, for the
    // non-symmetric volumetric term.
    if (local.workspace.rate_gradients.n() == n)
      {
        const Tensor<2, dim> F_inverse = invert(F);
        const double         J         = determinant(F);
        const Tensor<2, dim> M =
          J * (trace(F_inverse * L) * transpose(F_inverse) -
               transpose(F_inverse * L * F_inverse));
        typename DilatationProjection<dim>::ModeVector w;
        for (unsigned int m = 0; m < point.n_modes; ++m)
          w[m] = point.modes[m] * JxW;
        DilatationProjection<dim>::add_point_derivatives(
          M, grad_phi, comp, w, point.n_modes, local.workspace.rate_gradients);
      }
  }



  // @sect4{KelvinVoigtDamping::volumetric_viscosity}
  template <int dim>
  void
  KelvinVoigtDamping<dim>::volumetric_viscosity(
    const DilatationProjection<dim>                      &projection,
    const typename DilatationProjection<dim>::ModeMatrix &inverse_gram,
    const std::vector<double>                            &point_rate,
    CellContribution<dim>                                &local,
    typename DilatationProjection<dim>::ModeMatrix       &stiffness) const
  {
    const unsigned int cell    = local.cell;
    const unsigned int n_q     = geometry.n_q_points;
    const double       zeta    = cell_zeta[cell];
    double            *kappa_v = &volumetric_stiffness[cell * n_q];
    if (local.request.store_viscosity)
      for (unsigned int q = 0; q < n_q; ++q)
        kappa_v[q] = local.workspace.point_volumetric_stiffness[q];
    const auto rate = projection.project(cell, inverse_gram, point_rate);
    // The viscous stress at the points, then its projection, in place.
    std::vector<double> &viscosity = local.workspace.point_viscosity;
    std::vector<double> &stress    = local.workspace.point_viscous_pressure;
    viscosity.resize(n_q);
    stress.resize(n_q);
    for (unsigned int q = 0; q < n_q; ++q)
      {
        viscosity[q] = zeta * kappa_v[q];
        stress[q]    = viscosity[q] * projection.value(q, rate);
      }
    const auto coefficients = projection.project(cell, inverse_gram, stress);
    for (unsigned int q = 0; q < n_q; ++q)
      stress[q] = projection.value(q, coefficients);
    if (local.request.matrix || local.request.second_matrix)
      stiffness = projection.weighted_stiffness(cell, inverse_gram, viscosity);
  }



  // @sect4{KelvinVoigtDamping::add_volumetric_contribution}
  template <int dim>
  void
  KelvinVoigtDamping<dim>::add_volumetric_contribution(
    const unsigned int                                    n_modes,
    const typename DilatationProjection<dim>::ModeMatrix &stiffness,
    CellContribution<dim>                                &local) const
  {
    if (!(cell_zeta[local.cell] > 0.))
      return;
    const unsigned int        n            = geometry.dofs_per_cell;
    const FullMatrix<double> &G            = local.workspace.volume_gradients;
    const bool                with_matrix  = local.request.matrix;
    const bool                with_damping = local.request.second_matrix;
    if (!with_matrix && !with_damping)
      return;
    // The lower triangle of $\mathbf G^T\mathbf A_v\mathbf G$.
    DilatationProjection<dim>::add_rank_n_term(
      stiffness,
      G,
      local.workspace.mode_products,
      with_damping ? &local.second_matrix : nullptr,
      1.,
      with_matrix ? &local.matrix : nullptr,
      local.request.velocity_coefficient);
    if (!with_matrix || symmetric_tangent)
      return;
    // $(\mathbf G^T\mathbf A_v)\mathbf H$, the product on the left formed
    // once per row.
    const FullMatrix<double> &H = local.workspace.rate_gradients;
    for (unsigned int i = 0; i < n; ++i)
      {
        typename DilatationProjection<dim>::ModeVector row = {};
        for (unsigned int k = 0; k < n_modes; ++k)
          for (unsigned int m = 0; m < n_modes; ++m)
            row[k] += G(m, i) * stiffness[m][k];
        for (unsigned int j = 0; j < n; ++j)
          {
            double value = 0.;
            for (unsigned int k = 0; k < n_modes; ++k)
              value += row[k] * H(k, j);
            local.workspace.nonsymmetric_matrix(i, j) += value;
          }
      }
    local.workspace.has_nonsymmetric_part = true;
  }



#define SOFT_ROBOT_INSTANTIATE(dim) template class KelvinVoigtDamping<dim>;
  SOFT_ROBOT_FOR_EACH_DIMENSION(SOFT_ROBOT_INSTANTIATE)
#undef SOFT_ROBOT_INSTANTIATE
} // namespace SoftRobot
