// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{A pressure on the deformed surface: the follower load}
//
// A gas pushes on the wall that holds it with the pressure $p$ on every
// piece of the wall's *current* area, along its current normal: the load
// follows the deformation. Per unit deformed area the traction is $-p\,\mathbf
// n$, with $\mathbf n$ the body's outer normal; on a cavity wall $\mathbf n$
// points into the gas, and the wall is pushed away from it. Nanson's
// formula, $\mathbf n\,da = J\mathbf F^{-T}\mathbf N\,dA$, turns it into a
// load per unit reference area. We write it with the area vector of the
// gas side,
// @f[
//   \mathbf a(\mathbf F) = -\mathrm{cof}(\mathbf F)\,\mathbf N
//   = -J\mathbf F^{-T}\mathbf N \quad (3D), \qquad
//   \mathbf a(\mathbf F) = -\mathbf F^{-T}\mathbf N \quad (1D, 2D),
// @f]
// so that the nodal forces are $f_i = p\,g_i$ with
// @f[
//   g_i(\mathbf u) = \int_{\Gamma_0} \mathbf N_i\cdot\mathbf a(\mathbf F)\,dA .
// @f]
// In the reduced models the body stands for an incompressible 3D body
// ($J_\text{3D} = 1$) whose out-of-plane thickness (2D) or cross-section
// (1D) shrinks as it stretches; their Nanson factor is $\mathbf F^{-T}$
// alone, and $dA$ carries the Section.
//

// @sect4{The load stiffness}
//
// The load depends on the displacement through $\mathbf F$ on the face.
// Its derivative, with $\partial\mathbf F/\partial u_j = \mathbf e_{c_j}
// \otimes\nabla_0\varphi_j$,
// @f[
//   \frac{\partial g_i}{\partial u_j} = \int_{\Gamma_0}\varphi_i\,
//   \frac{\partial a_{c_i}}{\partial F_{c_jB}}\,\partial_B\varphi_j\,dA,
// @f]
// is computed at each point with Sacado's forward numbers from
// $\mathbf a(\mathbf F)$ (as for AerodynamicDrag); the residual of the
// simulator holds $-p\,\mathbf g$, so its tangent gets $-p\,\partial\mathbf
// g/\partial\mathbf u$. The face matrix is not symmetric: it involves the
// tangential derivatives of the shape functions, $\partial(\mathrm{cof}
// \mathbf F)\mathbf N/\partial\mathbf F$ pairs $\varphi_i$ with
// $\nabla\varphi_j$. Summed over a *closed* surface it is: then $\mathbf g
// = \partial V/\partial\mathbf u$ is the gradient of the enclosed volume,
// the load has the potential $-pV$, and its stiffness $-p\,\partial^2
// V/\partial\mathbf u^2$ is a Hessian. Where the surface ends on a
// symmetry plane or a clamped face, the terms at its edge vanish with the
// fixed normal displacement there, and the assembled matrix is again
// symmetric (CavityClosure says which surfaces are closed). On a surface
// with free edges -- a pressure pad on part of a face -- it is not, and
// the load is not conservative.
//
// The linear solvers: the sparse direct solvers (KLU, MUMPS) and GMRES take
// the matrix as it is. CG needs a symmetric one; with CG the symmetric
// part $\tfrac12(\mathbf K_p + \mathbf K_p^T)$ of each face's matrix is
// assembled instead. For a closed surface the sum of the symmetric parts is
// the exact tangent (the sum is symmetric already), so nothing is lost; on
// a surface with free edges Newton's method then converges linearly (a
// rate not measured yet).
//

// @sect4{The enclosed volume}
//
// For a gas cavity the same faces give the volume the gas fills, by the
// divergence theorem along the axis $k$ from the origin $c$ that
// CavityClosure chose:
// @f[
//   V(\mathbf u) = \int_{\Gamma_0} (x_k - c)\,a_k(\mathbf F)\,dA,
//   \qquad \mathbf x = \mathbf X + \mathbf u .
// @f]
// Its derivative by a nodal displacement is $g_i$ above, exactly: moving a
// part of the boundary of a region by $\delta\mathbf x$ changes its volume
// by $\oint\delta\mathbf x\cdot\mathbf n\,da$ (Reynolds' transport theorem),
// and the faces are conforming, so the discrete cavity is a closed region
// with piecewise polynomial walls. On a face, $\mathrm{cof}(\mathbf
// F)\mathbf N\,dA = \mathbf x_{,\xi}\times\mathbf x_{,\eta}\,d\xi\,d\eta$
// with $\mathbf x$ of degree $p$ (the mapping is linear), so $(x_k -
// c)\,a_k$ and $\varphi_i a_{c_i}$ have degree $3p - 1$ per direction on
// quadrilateral faces and $3p - 2$ on triangles; the face quadrature, $p +
// 1$ Gauss points per direction (QGaussSimplex($p+1$) on triangles), is
// exact to degree $2p + 1$, which covers both for $p \le 2$. The identity
// holds to round-off, which the tests check. This is the 3D cavity; the
// reduced models' factor $\mathbf F^{-T}$ is not polynomial and bounds no
// volume, so a gas cavity in 1D and 2D needs the end load below.
//

// @sect4{The reduced models' end load}
//
// The 1D column and the 2D strip of the bellows have no cavity. The
// pressure in the bellows' cavity pulls on the end cap with a resultant
// $p\,A_\text{eq}$ along the axis. With `Equivalent area` $A_\text{eq} >
// 0$ the faces of the Pressure boundary ids (the column's end, the strip's
// end edge) carry that force, spread evenly over their reference area
// $A_\text{end}$ (times the Section) along their reference normal: $\mathbf
// a = (A_\text{eq}/A_\text{end})\,\mathbf N$, constant, and $V(\mathbf u) =
// \int (A_\text{eq}/A_\text{end})\,\mathbf u\cdot\mathbf N\,dA$, the
// cavity's growth (the Dead volume holds the cavity's own volume). The
// load is conservative and has no stiffness of its own.
//
// Which area? The principle of virtual work suggests $A_\text{eq} =
// dV/d\delta$, the rate at which the cavity's volume grows with the tip's
// elongation $\delta$, but that holds only if the cavity's shape were a
// function of $\delta$ alone. Under pressure the bellows' cavity holds
// more than it does at the same elongation under an end force: part of
// $dV$ does work on the walls, not on the elongation. The area that gives
// a reduced model the 3D actuator's elongation is the force-equivalent
// one, the end force that elongates the 3D model as far as the pressure
// does, per unit pressure. doc/pneumatics.md measures both areas, and the
// extra volume, on the 3D model (discussed in doc/pneumatics_discussion.md).
// A gas in a reduced model sees its volume change through the same
// $A_\text{eq}$, so with the force-equivalent area its volume grows more
// slowly than the 3D cavity's.
//
// Implemented in source/physics/follower_pressure.cc.

#ifndef soft_robot_physics_follower_pressure_h
#define soft_robot_physics_follower_pressure_h

#include <assembly/cell_contribution.h>
#include <core/parameters.h>
#include <deal.II/base/quadrature.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/trilinos_vector.h>
#include <physics/boundary_faces.h>
#include <physics/cavity_closure.h>
#include <physics/cell_geometry.h>
#include <vector>

namespace SoftRobot
{
  using namespace dealii;

  template <int dim>
  class FollowerPressure : private BoundaryFaces<dim>
  {
  public:
    // The faces of the locally owned cells on `Pneumatics/Pressure
    // boundary ids`, in the cell numbering of `geometry`; the volume is
    // taken along the axis and from the origin of `closure`.
    FollowerPressure(const Parameters::AllParameters &parameters,
                     const CellGeometry<dim>         &geometry,
                     const Mapping<dim>              &mapping,
                     const DoFHandler<dim>           &dof_handler,
                     const Quadrature<dim - 1>       &quadrature,
                     const CavityClosure             &closure,
                     const bool                       symmetric_tangent);

    // The gas-side area vector $\mathbf a$ per unit reference area at the
    // deformation gradient F and the reference normal N, and its
    // derivative by F, [c][a][b] = $\partial a_c/\partial F_{ab}$.
    Tensor<1, dim>
    area_vector(const Tensor<2, dim> &F,
                const Tensor<1, dim> &N,
                Tensor<3, dim>       *d_dF = nullptr) const;

    // The volume $V(\mathbf u)$ of the meshed part (summed over the
    // processes) and its gradient $\mathbf g$ into `gradient` (owned
    // entries, compressed, zero at the constrained dofs); `u` must hold the
    // locally relevant entries.
    double
    integrate(const TrilinosWrappers::MPI::Vector &u,
              const AffineConstraints<double>     &constraints,
              TrilinosWrappers::MPI::Vector       &gradient,
              const MPI_Comm                       mpi_communicator) const;

    // The load stiffness $-p\,\partial\mathbf g/\partial\mathbf u$ of the
    // cell's pressure faces at the displacement values
    // `local.input_values[0]`, added to `local.matrix` in full (its
    // symmetric part with a symmetric tangent). Nothing for the reduced
    // models' end load, and nothing unless a matrix is requested.
    void
    add_cell_contribution(CellContribution<dim> &local,
                          const double           pressure) const;

    // Whether the cell (in the numbering of CellGeometry) has loaded faces.
    bool
    loads_cell(const unsigned int cell) const
    {
      return this->has_faces(cell);
    }

    // The reference area of the loaded faces (times the Section), summed
    // over the processes.
    double
    reference_area(const MPI_Comm mpi_communicator) const;

  private:
    const bool         end_load;
    double             end_load_factor = 0.; // A_eq / A_end
    const unsigned int axis;
    const double       origin;
    const bool         symmetric_tangent;
    const unsigned int n_cells;
    const std::vector<types::global_dof_index> &dof_indices;
    using BoundaryFaces<dim>::n_q_points;
    using BoundaryFaces<dim>::dofs_per_cell;
    using BoundaryFaces<dim>::components;
    using BoundaryFaces<dim>::first_face;
    using BoundaryFaces<dim>::points;
    using BoundaryFaces<dim>::normals;
    using BoundaryFaces<dim>::weights;
    using BoundaryFaces<dim>::shape_values;
    using BoundaryFaces<dim>::shape_gradients;
  };
} // namespace SoftRobot

#endif
