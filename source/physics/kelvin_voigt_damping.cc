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
    , volumetric_viscosity(geometry.n_cells, 0.)
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

    // In the mean-dilatation formulation also the derivative of the cell's
    // volume rate, $\partial(\mathbf g\cdot\mathbf v)/\partial u_j = \int
    // \partial(\mathrm{cof}\,\mathbf F:\mathbf L_0)/\partial\mathbf F :
    // \nabla_0\mathbf N_j\,dV$, for the non-symmetric volumetric term.
    if (local.workspace.rate_gradient.size() == n)
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



  // @sect4{KelvinVoigtDamping::cell_viscous_pressure}
  template <int dim>
  double
  KelvinVoigtDamping<dim>::cell_viscous_pressure(
    const double                 reference_volume,
    const double                 volume_rate,
    const double                 volumetric_stiffness,
    const CellContribution<dim> &local) const
  {
    const double stiffness = local.request.store_viscosity
                               ? volumetric_stiffness
                               : volumetric_viscosity[local.cell];
    return cell_zeta[local.cell] * stiffness * volume_rate / reference_volume;
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
  // v)/\partial\mathbf u)^T)$; the term $p_v\,\partial\mathbf g/\partial
  // \mathbf u$, from the second derivatives of $J$, was added at the
  // cell's points.
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
