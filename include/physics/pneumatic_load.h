// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{The pneumatic load: pressure, cavity and gas together}
//
// What the simulator sees of the pneumatics. A pressure $p$ acts on the
// faces of `Pneumatics/Pressure boundary ids` (FollowerPressure); it is
// prescribed as a function of time (PressureHistory) or it is the pressure
// of the gas enclosed in the cavity (GasCavity), whose volume the same
// faces give, closed by the symmetry planes (CavityClosure). At a state
// $(\mathbf u, t)$ this class computes, in one pass over the loaded faces,
// @f[
//   V(\mathbf u),\qquad \mathbf g(\mathbf u) = \frac{\partial V}{\partial
//   \mathbf u},\qquad p = p(t) \;\text{(prescribed)}\quad\text{or}\quad
//   p = p\bigl(V(\mathbf u)/f + V_\text{dead}, t\bigr) \;\text{(gas)}
// @f]
// ($f$ the model fraction), and the simulator takes the nodal forces
// $\mathbf f_p = p\,\mathbf g$ from them. The tangent of $-\mathbf f_p$ is
// @f[
//   -\frac{\partial\mathbf f_p}{\partial\mathbf u}
//   = -p\,\frac{\partial\mathbf g}{\partial\mathbf u}
//   + s\,\mathbf g\mathbf g^T,\qquad
//   s = -\frac{1}{f}\,\frac{dp}{dV} \ge 0 ,
// @f]
// the sparse load stiffness of the faces (add_cell_contribution(), in the
// cell integrals of the global assembly) and, for the gas, a rank-one term
// that couples every pair of cavity dofs. The rank-one term is not put
// into the sparse matrix (it would fill it); the simulator solves with it
// by the Sherman-Morrison formula (RankOneCorrection).
//
// The checks of the input that the pneumatics need are made here, in the
// constructor and in seal(), before anything is written: the pressure
// and inflow expressions at times over the run, the closure of a gas
// cavity, the positive gas volume.
//
// Implemented in source/physics/pneumatic_load.cc.

#ifndef soft_robot_physics_pneumatic_load_h
#define soft_robot_physics_pneumatic_load_h

#include <assembly/cell_contribution.h>
#include <core/parameters.h>
#include <deal.II/base/index_set.h>
#include <deal.II/base/quadrature.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/trilinos_vector.h>
#include <memory>
#include <physics/cavity_closure.h>
#include <physics/cell_geometry.h>
#include <physics/follower_pressure.h>
#include <physics/gas_cavity.h>
#include <physics/pressure_history.h>
#include <string>

namespace SoftRobot
{
  using namespace dealii;

  template <int dim>
  class PneumaticLoad
  {
  public:
    // What one evaluation gives besides $\mathbf g$: the gauge pressure
    // (kPa), the gas volume of the whole body (mm^3: the meshed cavity over
    // the model fraction plus the dead volume; zero for a surface that
    // bounds no volume) and the coefficient $s$ of the rank-one term
    // (zero for a prescribed pressure).
    struct Evaluation
    {
      double pressure  = 0.;
      double volume    = 0.;
      double stiffness = 0.;
    };

    PneumaticLoad(const Parameters::AllParameters &parameters,
                  const Triangulation<dim>        &triangulation,
                  const CellGeometry<dim>         &geometry,
                  const Mapping<dim>              &mapping,
                  const DoFHandler<dim>           &dof_handler,
                  const Quadrature<dim - 1>       &face_quadrature,
                  const AffineConstraints<double> &constraints,
                  const IndexSet                  &locally_owned_dofs,
                  const IndexSet                  &locally_relevant_dofs,
                  const MPI_Comm                   mpi_communicator,
                  const bool                       symmetric_tangent);

    // The load at the state (u, t), $\mathbf g$ into `gradient`. The
    // pressure becomes the one that add_cell_contribution() uses.
    Evaluation
    evaluate(const TrilinosWrappers::MPI::Vector &u,
             const double                         time,
             TrilinosWrappers::MPI::Vector       &gradient);

    // The same with the pressure given (the static equilibrium, which
    // ramps the initial pressure up), without the gas law.
    Evaluation
    evaluate_at_pressure(const TrilinosWrappers::MPI::Vector &u,
                         const double                         pressure,
                         TrilinosWrappers::MPI::Vector       &gradient);

    // The pressure of a static equilibrium at the time t: the prescribed
    // pressure at t, or, before the gas is sealed, its Initial pressure.
    double
    initial_pressure(const double time = 0.) const;

    // Gas: seals the cavity with the volume at the displacement u (the
    // initial state); an input error if that volume is not positive.
    void
    seal(const TrilinosWrappers::MPI::Vector &u);

    // The sealed gas's state for a checkpoint (empty without a gas), and the
    // seal restored from it.
    std::vector<double>
    gas_seal() const;
    void
    restore_gas_seal(const std::vector<double> &state);

    // The load stiffness of the cell's faces at the pressure of the last
    // evaluation (see FollowerPressure::add_cell_contribution()).
    void
    add_cell_contribution(CellContribution<dim> &local) const;

    bool
    is_gas() const
    {
      return gas != nullptr;
    }
    // Whether the loaded surface bounds a volume (a closed cavity, or the
    // reduced models' end load), so that the volume can be reported.
    bool
    has_volume() const;
    // Whether the rank-one term enters the Newton matrix
    // (Pneumatics/Rank-one tangent).
    bool
    rank_one_in_matrix() const
    {
      return rank_one_tangent;
    }
    const CavityClosure &
    closure() const
    {
      return cavity_closure;
    }
    const FollowerPressure<dim> &
    surface() const
    {
      return *follower;
    }
    // One line for the log: what acts where.
    std::string
    description() const;

  private:
    Evaluation
    integrate(const TrilinosWrappers::MPI::Vector &u,
              TrilinosWrappers::MPI::Vector       &gradient,
              double                              &mesh_volume);

    const Parameters::AllParameters       &parameters;
    const AffineConstraints<double>       &constraints;
    const MPI_Comm                         mpi_communicator;
    const CavityClosure                    cavity_closure;
    const bool                             rank_one_tangent;
    std::unique_ptr<FollowerPressure<dim>> follower;
    std::unique_ptr<PressureHistory>       prescribed;
    std::unique_ptr<GasCavity>             gas;
    TrilinosWrappers::MPI::Vector          ghosted_u;
    double                                 assembly_pressure = 0.;
  };
} // namespace SoftRobot

#endif
