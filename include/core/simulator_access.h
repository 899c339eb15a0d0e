// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Access to the simulator's internals}
//
// SoftRobotDynamics has a constructor and run(), nothing else. Tests,
// studies and the calibration command need more: run the phases one at a
// time, look at the state, assemble the tangent at a displacement of their
// choosing, impose a manufactured body force. They do it through this
// class, a friend of the simulator (ASPECT's SimulatorAccess is the model),
// so that what the simulator offers to the outside is in one place and the
// simulator's own interface stays that of a deal.II tutorial program.
//
// Implemented in source/core/simulator_access.cc.

#ifndef soft_robot_core_simulator_access_h
#define soft_robot_core_simulator_access_h

#include <core/soft_robot_dynamics.h>
#include <memory>
#include <string>
#include <utility>

namespace SoftRobot
{
  template <int dim>
  class SimulatorAccess
  {
  public:
    explicit SimulatorAccess(SoftRobotDynamics<dim> &simulator);

    // @sect4{The phases of run(), one at a time}
    void
    make_grid();
    void
    setup_system();
    // Equilibrium under the loads at time $t$ (load-stepped Newton).
    void
    solve_static_equilibrium(const double time);
    // Initial state, then steps of the nominal size until the end time; the
    // same as run() without any output. advance_one_step() returns false at
    // the end time.
    void
    initialize_state();
    bool
    advance_one_step();

    // An additional body force $\mathbf b(\mathbf X, t)$ per unit reference
    // volume (kg mm^-2 s^-2 in the program's units), a Function of the
    // reference position with dim components whose time is set to the time
    // of the load; added to gravity, scaled like it by the section of the
    // reduced models, its work booked with that of the tractions. The tests
    // impose manufactured solutions with it. Set it before
    // initialize_state().
    void
    set_body_force(const std::shared_ptr<Function<dim>> &force);

    // @sect4{The discretization}
    const DoFHandler<dim> &
    get_dof_handler() const;
    const Mapping<dim> &
    get_mapping() const;
    const AffineConstraints<double> &
    get_constraints() const;

    // @sect4{The physics of the cells}
    //
    // The reference geometry of the locally owned cells and the materials
    // on them, for tests that add the cells' contributions with assemblers
    // of their own (tests/system_assembler.cc compares the two global
    // additions on them).
    const CellGeometry<dim> &
    get_cell_geometry() const;
    const HyperelasticSolid<dim> &
    get_solid() const;

    // @sect4{The state}
    double
    time() const;
    const TrilinosWrappers::MPI::Vector &
    displacement() const;
    const TrilinosWrappers::MPI::Vector &
    velocity() const;
    const TrilinosWrappers::MPI::Vector &
    acceleration() const;
    // Mean displacement and velocity of the tip region (Output/Tip region).
    std::pair<Tensor<1, dim>, Tensor<1, dim>>
    tip_motion() const;
    const EnergyAccount &
    energies() const;
    // The angular momentum about the origin (see Inertia).
    Tensor<1, 3>
    angular_momentum() const;

    // @sect4{The linearised operators}
    //
    // The tangent stiffness at the current displacement or at any u, the
    // strain energy and internal force vector at u, and the mass matrix:
    // for tests of the linearisation and eigenfrequency checks.
    const TrilinosWrappers::SparseMatrix &
    tangent_stiffness_matrix();
    const TrilinosWrappers::SparseMatrix &
    tangent_stiffness_matrix(const TrilinosWrappers::MPI::Vector &u);
    double
    internal_force(const TrilinosWrappers::MPI::Vector &u,
                   TrilinosWrappers::MPI::Vector       &force);
    const TrilinosWrappers::SparseMatrix &
    mass_matrix() const;

    // @sect4{The damping forces}
    //
    // The damping laws keep something of the state a time step starts from
    // (the viscosity of the Kelvin-Voigt damping, the matrix of the lagged
    // form); record_damping_state() records it at the displacement u at
    // rest. damped_forces() then gives the elastic and damping forces at
    // (u, v) and, with `with_matrix`, the derivative of their sum by the
    // displacement at fixed v plus `velocity_coefficient` times its
    // derivative by the velocity: the tangent of a time step in which v
    // depends on u with that coefficient.
    void
    record_damping_state(const TrilinosWrappers::MPI::Vector &u);
    const TrilinosWrappers::SparseMatrix &
    damped_forces(const TrilinosWrappers::MPI::Vector &u,
                  const TrilinosWrappers::MPI::Vector &v,
                  const double                         velocity_coefficient,
                  const bool                           with_matrix,
                  TrilinosWrappers::MPI::Vector       &internal_force,
                  TrilinosWrappers::MPI::Vector       &damping_force);

    // @sect4{The pneumatic load}
    //
    // The load object (after setup_system(), with a Pneumatics subsection
    // that names boundaries), for tests that evaluate its forces and
    // volume at displacements of their choosing; and the gauge pressure,
    // gas volume and nodal pressure forces of the current state.
    PneumaticLoad<dim> &
    get_pneumatics();
    double
    pressure() const;
    double
    gas_volume() const;
    const TrilinosWrappers::MPI::Vector &
    pressure_force() const;

    // @sect4{The statistics of the run so far}
    unsigned int
    n_steps() const;
    unsigned int
    n_newton_iterations() const;
    // Matrix factorizations (or multigrid set-ups).
    unsigned int
    n_tangent_updates() const;
    // Iterations of the iterative linear solver (one per solve with the
    // direct solver).
    unsigned int
    n_linear_iterations() const;
    double
    multigrid_operator_complexity() const;
    // The linear solver that solved the last system (LinearSolver).
    std::string
    linear_solver_in_use() const;

  private:
    SoftRobotDynamics<dim> &simulator;
  };
} // namespace SoftRobot

#endif
