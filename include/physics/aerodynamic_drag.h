// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Aerodynamic drag on the body's surface}
//
// A body that swings through air feels a drag. For the speeds of a soft
// actuator (up to a few hundred mm/s, Reynolds numbers of some thousands
// for a 30 mm body) the drag is quadratic in the speed; as a surface load
// it is, per unit deformed area,
// @f[
//   \mathbf t = -\tfrac12\rho_\text{air}C_d\,|\mathbf v\cdot\mathbf n|\,
//   (\mathbf v\cdot\mathbf n)\,\mathbf n,
// @f]
// with the current outer normal $\mathbf n$ and the velocity $\mathbf v$ of
// the surface: each piece of surface is pushed back against the part of its
// motion along its normal (a flat-plate, Newtonian model of the pressure
// drag; the skin friction is neglected). The model is off by default; its
// coefficient is the user's (bodies of the actuator's shape have $C_d$ of
// about 1).
//
// On the reference boundary, Nanson's formula $\mathbf n\,da =
// \mathrm{cof}(\mathbf F)\mathbf N\,dA = \mathbf a\,dA$ turns it into a
// load per reference area,
// @f[
//   \mathbf t_0 = \mathbf t\,\frac{da}{dA}
//   = -\tfrac12\rho_\text{air}C_d\,\frac{|\mathbf v\cdot\mathbf a|\,
//   (\mathbf v\cdot\mathbf a)}{|\mathbf a|^2}\,\mathbf a,
// @f]
// a function of the deformation gradient and the velocity at the face's
// quadrature points, whose nodal forces are $f_i = \int_{\Gamma_0}\mathbf
// N_i\cdot\mathbf t_0\,dA$. Its power $\mathbf v\cdot\mathbf t_0 \le 0$:
// the drag only dissipates, and it is booked with the damping. Its tangent
// follows from the derivatives of $\mathbf t_0(\mathbf F, \mathbf v)$ at
// each point, computed with Sacado's forward numbers, and Newmark's
// $\partial\mathbf v/\partial\mathbf u = c_v$:
// @f[
//   \frac{\partial f_i}{\partial u_j} = \int_{\Gamma_0}\mathbf N_i\cdot
//   \left(\frac{\partial\mathbf t_0}{\partial\mathbf F}:\nabla_0\mathbf
//   N_j + c_v\frac{\partial\mathbf t_0}{\partial\mathbf v}\mathbf N_j
//   \right)dA;
// @f]
// the second part (the damping matrix of the drag) is symmetric, the first
// is not and is left out when the linear solver needs a symmetric matrix.
//
// The drag is a follower load on the faces of the cells it acts on; the
// global addition calls add_cell_contribution() for every cell after the
// solid's integral, and cells without such faces return at once.
//
// Implemented in source/physics/aerodynamic_drag.cc.

#ifndef soft_robot_physics_aerodynamic_drag_h
#define soft_robot_physics_aerodynamic_drag_h

#include <assembly/cell_contribution.h>
#include <core/parameters.h>
#include <deal.II/base/quadrature.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/mapping.h>
#include <physics/boundary_faces.h>
#include <physics/cell_geometry.h>
#include <vector>

namespace SoftRobot
{
  using namespace dealii;

  template <int dim>
  class AerodynamicDrag : private BoundaryFaces<dim>
  {
  public:
    // The faces of the locally owned cells on `Damping/Drag boundary ids`,
    // in the cell numbering of `geometry`.
    AerodynamicDrag(const Parameters::AllParameters &parameters,
                    const CellGeometry<dim>         &geometry,
                    const Mapping<dim>              &mapping,
                    const DoFHandler<dim>           &dof_handler,
                    const Quadrature<dim - 1>       &quadrature,
                    const bool                       symmetric_tangent);

    // Whether the drag acts anywhere (on any process).
    bool
    empty() const
    {
      return boundary_ids.empty();
    }

    // The drag on the cell's faces (with the displacement and velocity
    // values `local.input_values[0]` and `[1]`): its force into
    // `second_force` (the damping forces), and as requested its tangent
    // into `matrix` and its damping matrix into `second_matrix`, in full.
    void
    add_cell_contribution(CellContribution<dim> &local) const;

    // The traction $\mathbf t_0$ per reference area for the deformation
    // gradient F, the velocity v and the reference normal N, and its
    // derivatives by F and v (for the tests).
    Tensor<1, dim>
    traction(const Tensor<2, dim> &F,
             const Tensor<1, dim> &v,
             const Tensor<1, dim> &N,
             Tensor<3, dim>       *d_dF = nullptr,
             Tensor<2, dim>       *d_dv = nullptr) const;

  private:
    const std::vector<unsigned int> boundary_ids;
    const double                    coefficient; // 1/2 rho_air C_d
    const bool                      symmetric_tangent;
    using BoundaryFaces<dim>::n_q_points;
    using BoundaryFaces<dim>::dofs_per_cell;
    using BoundaryFaces<dim>::components;
    using BoundaryFaces<dim>::first_face;
    using BoundaryFaces<dim>::normals;
    using BoundaryFaces<dim>::weights;
    using BoundaryFaces<dim>::shape_values;
    using BoundaryFaces<dim>::shape_gradients;
  };
} // namespace SoftRobot

#endif
