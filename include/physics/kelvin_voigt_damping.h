// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Objective stiffness-proportional damping: a Kelvin-Voigt solid}
//
// The damping of the reference study is stiffness-proportional, $\mathbf C
// = \zeta\mathbf K$, which gives a mode of angular frequency $\omega$ the
// damping ratio $\xi = \zeta\omega/2$. For a body that moves far, "the
// stiffness" has to be made precise, and how it is made precise decides
// whether the damping leaves rigid motions alone. A swinging actuator is
// mostly a rigid rotation with a little bending; its damping must come from
// the bending only. A damping *matrix* built at one configuration and
// applied to the velocity at another does not do that: its null space holds
// the rigid rotations of the configuration it was built at, not those of the
// body now, and every rotation is damped by an amount that grows with
// $\Omega^2\Delta t$ (a free cube spinning at 10 rad/s came to rest within
// one revolution). This class replaces the matrix by a stress.

// @sect4{The viscous stress}
//
// The body is a Kelvin-Voigt solid: besides the elastic stress it carries a
// viscous second Piola-Kirchhoff stress driven by the rate of the
// Green-Lagrange strain,
// @f[
//   \mathbf S_v = \mathcal D : \dot{\mathbf E},\qquad
//   \dot{\mathbf E} = \mathrm{sym}(\mathbf F^T\dot{\mathbf F})
//   = \mathrm{sym}(\mathbf F^T\mathbf L_0),\qquad
//   \mathbf L_0 = \nabla_0\mathbf v,
// @f]
// with the viscosity $\mathcal D = \zeta\,\mathcal C^+$, the damping
// coefficient times the positive semi-definite part of the material tangent
// $\mathcal C = \partial^2\Psi/\partial\mathbf E^2$ that Sacado computes
// for the elastic energy (see positive_semidefinite_part()). Its nodal
// forces are those of any second Piola-Kirchhoff stress,
// @f[
//   f^v_i = \int_{\Omega_0}\delta\mathbf E_i : \mathbf S_v\,dV,\qquad
//   \delta\mathbf E_i = \mathrm{sym}(\mathbf F^T\nabla_0\mathbf N_i).
// @f]
// Three properties follow.
// - *Objectivity.* For any rigid velocity of the current configuration,
//   $\mathbf v = \mathbf W\mathbf x + \mathbf c$ with $\mathbf W$ skew,
//   $\mathbf L_0 = \mathbf W\mathbf F$ and $\dot{\mathbf E} =
//   \mathrm{sym}(\mathbf F^T\mathbf W\mathbf F) = 0$: the force vanishes
//   exactly, for translations and finite rotations alike, at every state
//   the time integrator evaluates it at.
// - *Dissipation.* The power of the force is $\mathbf v\cdot\mathbf f^v =
//   \int\dot{\mathbf E}:\mathcal D:\dot{\mathbf E}\,dV \ge 0$.
// - *Small motions.* About an equilibrium $\mathbf u_e$ the force is, to
//   first order in the motion, $\mathbf C(\mathbf u_e)\mathbf v$ with
//   $C_{ij} = \zeta\int\delta\mathbf E_i:\mathcal C^+:\delta\mathbf E_j$,
//   the material part of the stiffness times $\zeta$: a mode gets $\xi =
//   \zeta\omega/2$ as before.
//
// The viscosity of a time step is that of the state the step starts from,
// $\mathcal D_n = \zeta\,\mathcal C^+(\mathbf E_n)$, kept per quadrature
// point for the whole step; it is recorded when the state is assembled at
// the end of the previous step (AssemblyRequest::store_viscosity). The
// force itself is evaluated at both states of the HHT equation, with the
// deformation and velocity of each, so the damping is objective at both;
// only the viscosity, which is a material property and changes little in a
// step, lags. Keeping it fixed within the step makes the force bilinear in
// $(\mathbf F, \mathbf L_0)$ for given $\mathcal D$, so that its tangent is
// exact in closed form (below), and it keeps the eigenvalue decomposition
// behind $\mathcal C^+$, which has no useful derivative where an eigenvalue
// changes sign, out of Newton's method.

// @sect4{The tangent}
//
// With Newmark's $\partial\mathbf v_{n+1}/\partial\mathbf u_{n+1} = c_v =
// \gamma/(\beta\Delta t)$, the derivative of the force by the nodal
// displacement $u_j$ ($\mathbf N_j = \varphi_j\mathbf e_{c_j}$) is
// @f[
//   \frac{\partial f^v_i}{\partial u_j} = \int\delta\mathbf E_i:\mathcal D:
//   \left(c_v\,\delta\mathbf E_j + \mathrm{sym}(\mathbf l_{c_j}\otimes
//   \nabla_0\varphi_j)\right) + \delta_{c_ic_j}\nabla_0\varphi_i\cdot
//   \mathbf S_v\nabla_0\varphi_j\;dV,
// @f]
// with $\mathbf l_c$ the row $c$ of $\mathbf L_0$. The first term is $c_v$
// times the damping matrix of the current configuration; the last is the
// geometric stiffness of the viscous stress. The middle term is not
// symmetric; it is of the order of the strain rate times the step relative
// to the first and is left out when the linear solver needs a symmetric
// matrix (CG), which only makes Newton's method slightly inexact.

// @sect4{The projected-dilatation formulations}
//
// There the volumetric energy acts on the projection $\Theta = \Pi J$ of
// the volume ratio on a few modes per cell (DilatationProjection), and so
// does the volumetric viscosity: the dissipation potential is $\frac12
// \int_e\zeta\kappa_v\dot\Theta^2\,dV$ with $\dot\Theta = \Pi\dot J$,
// $\dot J = \mathrm{cof}\,\mathbf F:\mathbf L_0$ (which vanishes for rigid
// motions) and $\kappa_v = U''(\Theta)$ at the step's first state. With the
// moments $\mathbf b$ of the volume and their derivatives $\mathbf G =
// \partial\mathbf b/\partial\mathbf u$ ($\dot{\mathbf b} = \mathbf G\mathbf
// v$) its force is $\mathbf G^T\boldsymbol\pi_v$, $\boldsymbol\pi_v =
// \mathbf M^{-1}\int\mathbf N\zeta\kappa_v\dot\Theta\,dV$ the
// coefficients of the viscous pressure $p_v = \Pi(\zeta\kappa_v\dot\Theta)$,
// and its derivatives are $\mathbf G^T\mathbf A_v(c_v\mathbf G + \mathbf
// H)$ with $\mathbf A_v = \mathbf M^{-1}\int\zeta\kappa_v\mathbf N\mathbf
// N^T\mathbf M^{-1}$ and $\mathbf H = \partial(\mathbf G\mathbf v)/\partial
// \mathbf u$ (not symmetric), and $\int p_v\,\partial^2 J/\partial\mathbf
// u^2\,dV$ (symmetric), with
// @f[
//   \frac{\partial^2 J}{\partial F_{aA}\,\partial F_{bB}} =
//   \varepsilon_{abk}\varepsilon_{ABK}F_{kK},\qquad
//   \frac{\partial(\mathrm{cof}\,\mathbf F:\mathbf L_0)}{\partial\mathbf F}
//   = J\left(\mathrm{tr}(\mathbf F^{-1}\mathbf L_0)\,\mathbf F^{-T} -
//   (\mathbf F^{-1}\mathbf L_0\mathbf F^{-1})^T\right).
// @f]
// With one mode (mean dilatation) that is the cell's viscous pressure $p_v
// = \zeta\kappa_v\mathbf g\cdot\mathbf v/V_{0,e}$, the force $p_v\mathbf
// g$ and the rank-one damping matrix $\zeta\kappa_v V_{0,e}^{-1}\mathbf
// g\mathbf g^T$.
//
// Implemented in source/physics/kelvin_voigt_damping.cc; HyperelasticSolid
// calls it at each quadrature point and once per cell.

#ifndef soft_robot_physics_kelvin_voigt_damping_h
#define soft_robot_physics_kelvin_voigt_damping_h

#include <assembly/cell_contribution.h>
#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>
#include <physics/cell_geometry.h>
#include <physics/dilatation_projection.h>
#include <vector>

namespace SoftRobot
{
  using namespace dealii;

  template <int dim>
  class KelvinVoigtDamping
  {
  public:
    // The damping coefficient $\zeta$ of each cell of `geometry` (which
    // must outlive this object). With `symmetric_tangent` the non-symmetric
    // parts of the tangent are left out.
    KelvinVoigtDamping(const CellGeometry<dim>   &geometry,
                       const std::vector<double> &cell_zeta,
                       const bool                 symmetric_tangent);

    // Whether the tangent it adds is symmetric (its non-symmetric parts
    // left out).
    bool
    has_symmetric_tangent() const
    {
      return symmetric_tangent;
    }

    // What the point contribution needs of the kinematics at a quadrature
    // point: the deformation gradient, the velocity gradient, and with a
    // matrix the strain variations $\delta\mathbf E_i$ and the material
    // tangent (from which the viscosity is recorded).
    struct PointKinematics
    {
      unsigned int q;
      // The gradients of the cell's shape functions at the point, by dof;
      // null where no matrix is formed.
      const Tensor<1, dim>          *grad_phi = nullptr;
      const Tensor<2, dim>          *F;
      const Tensor<2, dim>          *L;
      const SymmetricTensor<4, dim> *material_tangent;
      // Where the point's terms of the matrices go (see point_tangent.h):
      // the tangent (with its non-symmetric part unless the tangent must be
      // symmetric) and the damping matrix; null for a matrix not asked for.
      Tensor<4, dim> *tangent         = nullptr;
      Tensor<4, dim> *damping_tangent = nullptr;
      // The volumetric viscous pressure $p_v$ at the point (projected
      // dilatation; see volumetric_viscosity()), whose volume Hessian the
      // tangent gets, and the dilatation modes at the point.
      double       volume_pressure = 0.;
      unsigned int n_modes         = 0;
      double       modes[dim + 1]  = {};
    };

    // The viscous force of point q into `local.second_force`; the point's
    // terms of the tangent and of the damping matrix into the tensors of
    // `point`, and the point's share of $\partial(\mathbf g\cdot\mathbf
    // v)/\partial\mathbf u$ into `local.workspace.rate_gradient`. With
    // `local.request.store_viscosity` the viscosity of the point is first
    // recorded from the material tangent.
    void
    add_point_contribution(const PointKinematics &point,
                           CellContribution<dim> &local) const;

    // The volumetric viscosity of the projected-dilatation formulations
    // (see DilatationProjection and the section above): from the rates
    // $\dot J = \mathrm{cof}\,\mathbf F:\mathbf L_0$ at the cell's points
    // (`point_rate`) the rate $\dot\Theta = \Pi\dot J$ of the projected
    // volume ratio, and the viscous pressure $p_v = \Pi(\zeta\kappa_v
    // \dot\Theta)$: its point values (into
    // `local.workspace.point_viscous_pressure`, from which the points'
    // force is formed) and, when the cell's matrices are asked for,
    // $\mathbf A_v = \mathbf M^{-1}\int\zeta\kappa_v\mathbf N\mathbf
    // N^T dV\,\mathbf M^{-1}$ (into `stiffness`). $\kappa_v$ is the point's
    // recorded $U''$,
    // or with `local.request.store_viscosity` the current one
    // (`local.workspace.point_volumetric_stiffness`), which is recorded.
    void
    volumetric_viscosity(
      const DilatationProjection<dim>                      &projection,
      const typename DilatationProjection<dim>::ModeMatrix &inverse_gram,
      const std::vector<double>                            &point_rate,
      CellContribution<dim>                                &local,
      typename DilatationProjection<dim>::ModeMatrix       &stiffness) const;

    // The volumetric viscous terms of the matrices, with the derivatives
    // $\mathbf G$ of the volume's moments
    // (`local.workspace.volume_gradients`): in the tangent $\mathbf
    // G^T\mathbf A_v(c_v\mathbf G + \mathbf H)$ with the derivatives
    // $\mathbf H$ of the moments of the volume rate
    // (`local.workspace.rate_gradients`, left out for a symmetric tangent),
    // in the damping matrix $\mathbf G^T\mathbf A_v\mathbf G$. The force
    // $\mathbf G^T\boldsymbol\pi_v$ and the volume Hessian times $p_v$
    // came with the points.
    void
    add_volumetric_contribution(
      const unsigned int                                    n_modes,
      const typename DilatationProjection<dim>::ModeMatrix &stiffness,
      CellContribution<dim>                                &local) const;

  private:
    const CellGeometry<dim>  &geometry;
    const std::vector<double> cell_zeta;
    const bool                symmetric_tangent;
    // The positive part of the material tangent at the step's first state,
    // and $U''(\Theta)$, per cell and point, [cell][q]; written only in the
    // assemblies of a state, where each cell's entries are written by the
    // thread that integrates that cell.
    mutable std::vector<SymmetricTensor<4, dim>> viscosity;
    mutable std::vector<double>                  volumetric_stiffness;
  };
} // namespace SoftRobot

#endif
