// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{The SoftRobotDynamics class template}
//
// This is the simulator: a hyperelastic body that moves under gravity,
// tractions and its own inertia, with stiffness-proportional damping,
// integrated in time by the HHT-$\alpha$ method, each step solved by
// Newton's method. The same class runs the 1D column, the 2D planar model
// and the 3D body; what differs between the dimensions is the strain energy
// (see NeoHookeanEnergy) and the mesh.
//
// The weak form of the balance of linear momentum in the reference
// configuration $\Omega_0$, for every test function $\delta\mathbf u$
// vanishing where the displacement is prescribed, is
// @f[
//   \int_{\Omega_0} \rho_0\,\delta\mathbf u\cdot\ddot{\mathbf u}\,dV
//   + \int_{\Omega_0} \nabla_0\delta\mathbf u : \mathbf P\,dV
//   + \delta\mathbf u\cdot\mathbf C\dot{\mathbf u}
//   = \int_{\Omega_0} \rho_0\,\delta\mathbf u\cdot\mathbf g\,dV
//   + \int_{\Gamma_\text{N}} \delta\mathbf u\cdot\bar{\mathbf t}\,dA,
// @f]
// with the elastic stress $\mathbf P = \mathbf F\mathbf S$ and the
// stiffness-proportional damping matrix $\mathbf C$ (see
// HyperelasticSolid). Its spatial discretization gives the equation of
// motion $\mathbf M\mathbf a + \mathbf f_\text{int}(\mathbf u) + \mathbf
// C\mathbf v = \mathbf f_\text{ext}(t)$, which HHTStepper integrates in
// time.
//
// The class is built like the solver of deal.II's step-44: a constructor
// from the parameters and run(), whose body is the algorithm, and private
// phases in the order run() calls them. The physics of one cell is
// HyperelasticSolid's, the loads' are Inertia's and TractionLoad's, the
// global addition is SystemAssembler's, the nonlinear and linear solvers
// are NewtonSolver and LinearSolver, the step-size control is
// TimeStepController's, and the output classes write what the run
// produces. This class strings them together. Tests and studies reach its
// internals through SimulatorAccess.
//
// The implementation is split by phase (doc/code-map.md):
// source/core/soft_robot_dynamics.cc (set-up and run()),
// source/core/soft_robot_dynamics_time_step.cc (initial state and time
// step), source/core/soft_robot_dynamics_output.cc (output) and
// source/core/soft_robot_dynamics_checkpoint.cc (checkpoints, restarts).

#ifndef soft_robot_core_soft_robot_dynamics_h
#define soft_robot_core_soft_robot_dynamics_h

#include <assembly/assembly_result.h>
#include <assembly/system_assembler.h>
#include <core/curved_geometry.h>
#include <core/exceptions.h>
#include <core/parameters.h>
#include <core/plausibility_guard.h>
#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/function.h>
#include <deal.II/base/function_parser.h>
#include <deal.II/base/index_set.h>
#include <deal.II/base/quadrature.h>
#include <deal.II/base/timer.h>
#include <deal.II/distributed/shared_tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/numerics/data_out.h>
#include <memory>
#include <output/cell_data.h>
#include <output/checkpoint.h>
#include <output/field_output.h>
#include <output/run_statistics.h>
#include <output/tip_region.h>
#include <output/trajectory_writer.h>
#include <output/xdmf_output.h>
#include <physics/aerodynamic_drag.h>
#include <physics/cell_geometry.h>
#include <physics/hyperelastic_solid.h>
#include <physics/inertia.h>
#include <physics/pneumatic_load.h>
#include <physics/traction_load.h>
#include <solvers/linear_solver.h>
#include <solvers/newton_solver.h>
#include <solvers/rank_one_correction.h>
#include <solvers/rotated_tangent.h>
#include <solvers/time_step_controller.h>
#include <time_integration/hht_stepper.h>
#include <vector>

namespace SoftRobot
{
  using namespace dealii;

  template <int dim>
  class SimulatorAccess;

  // @sect4{The terms of the energy balance}
  //
  // In the program's units kg mm^2 s^-2, i.e. micro-joules.
  struct EnergyAccount
  {
    double kinetic             = 0.; // $\tfrac12\mathbf v^T\mathbf M\mathbf v$
    double strain              = 0.; // $\int\Psi\,dV$
    double gravity_potential   = 0.; // $-\int\rho_0\mathbf g\cdot\mathbf u\,dV$
    double traction_work       = 0.; // work done by the tractions so far
    double damping_dissipation = 0.; // energy taken by the damping forces
    double pressure_work       = 0.; // work done by the pneumatic pressure
    double
    balance(const double initial_total) const
    {
      return kinetic + strain + gravity_potential - traction_work -
             pressure_work + damping_dissipation - initial_total;
    }
  };



  template <int dim>
  class SoftRobotDynamics
  {
  public:
    SoftRobotDynamics(const Parameters::AllParameters &parameters,
                      const MPI_Comm                   mpi_communicator);
    ~SoftRobotDynamics();

    // The whole simulation: mesh, initial state, time loop, output.
    void
    run();

  private:
    friend class SimulatorAccess<dim>;

    // @sect4{The phases of a run, in the order run() calls them}
    //
    // make_grid() and setup_system() check the mesh and the input that
    // depends on it (core/input_checks.h); check_initial_state() the state
    // that initialize_state() computed. Only then does the run write.
    void
    make_grid();
    void
    setup_system();
    void
    check_initial_state() const;
    // The initial displacement and velocity (or the static equilibrium),
    // the forces and acceleration at $t = 0$, and the energies the balance
    // is measured against.
    void
    initialize_state();
    // One step of the time loop, cut back and repeated as often as needed;
    // false at the end time.
    bool
    advance_one_step();
    void
    output_results();
    void
    write_trajectory_row();
    // The guards of PlausibilityGuard on the current state: finite (before
    // it is written), and a motion with a physical reading (after).
    void
    check_state_is_finite();
    void
    check_motion() const;
    // The fields of the current state, unless they are written already or
    // the state is not finite: the last output of every run, whatever its
    // end time and Output interval.
    void
    write_final_fields();
    void
    finish_run(const double wall_time);

    // @sect4{Checkpoints}
    //
    // After a step: a checkpoint of the run (output/checkpoint.h) every
    // Output/Checkpoint interval steps, and at an interruption, after which
    // the run stops (RunInterrupted). Implemented in
    // source/core/soft_robot_dynamics_checkpoint.cc.
    void
    checkpoint_or_stop();
    void
    write_checkpoint();
    // Instead of initialize_state() at a restart: the state and the
    // records of the checkpoint, and what the state determines assembled
    // again; returns the checkpoint for the output to go on from.
    CheckpointData
    restore_checkpoint();

    // @sect4{The initial state}
    void
    solve_static_equilibrium(const double time);
    void
    compute_initial_acceleration();

    // @sect4{One time step}
    void
    solve_nonlinear_timestep(const double dt);
    // The HHT residual for a trial displacement, with the effective
    // tangent if asked; the trial's velocity, acceleration and forces are
    // left in `current`.
    AssemblyResult
    evaluate_residual(const TrilinosWrappers::MPI::Vector &u_trial,
                      const double                         dt,
                      const bool                           with_matrix,
                      TrilinosWrappers::MPI::Vector       &residual);
    // The modified Newton method's matrix of a step of size dt.
    void
    prepare_step_tangent(const double dt);
    void
    update_energies(const AssemblyResult &assembly);
    // The Newton problem whose residual is `evaluate` and whose tangent
    // is system_matrix, solved by the linear solver.
    NewtonSolver::Problem
    newton_problem(
      const std::function<AssemblyResult(const TrilinosWrappers::MPI::Vector &,
                                         const bool,
                                         TrilinosWrappers::MPI::Vector &)>
        &evaluate);

    // @sect4{The assemblies}
    //
    // The forces of the state (u, v) that the cell integrals give: the
    // elastic internal force, and (if `damping_force` is given) the damping
    // forces of the Kelvin-Voigt stress and the drag; without v (a static
    // state) the velocity-dependent forces are left out. As `request`
    // asks, the tangent into system_matrix and the damping matrix of the
    // state into next_damping_matrix.
    AssemblyResult
    assemble_forces(const TrilinosWrappers::MPI::Vector &u,
                    const TrilinosWrappers::MPI::Vector *v,
                    const AssemblyRequest               &request,
                    TrilinosWrappers::MPI::Vector       &internal_force,
                    TrilinosWrappers::MPI::Vector       *damping_force);
    // The stiffness of a state alone (no velocity), for the static
    // equilibrium, the modified Newton method and the tests.
    AssemblyResult
    assemble_internal_force(const TrilinosWrappers::MPI::Vector &u,
                            const bool                           with_matrix,
                            TrilinosWrappers::MPI::Vector &internal_force);
    // Everything the next time step needs of the state `current`: its
    // internal and damping forces, its stiffness (into system_matrix), its
    // damping matrix (into damping_matrix) and the viscosity of the
    // Kelvin-Voigt damping. Without `with_matrices` (the modified Newton
    // method that keeps its matrix across steps) the two matrices are left
    // alone, unless the damping force needs the damping matrix.
    AssemblyResult
    assemble_state(const bool with_matrices = true);
    // The initial velocity expression interpolated at the nodes' positions
    // in the state `current.u` (Initial conditions/Velocity coordinates =
    // initial state).
    void
    interpolate_velocity_at_current_positions();
    // The damping forces that are not cell integrals, at velocity v, added
    // to `force`: the lagged damping matrix's and the mass-proportional
    // damping's; and their matrices times `factor`, added to `matrix`.
    void
    add_global_damping_forces(const TrilinosWrappers::MPI::Vector &v,
                              TrilinosWrappers::MPI::Vector       &force) const;
    void
    add_global_damping_matrices(const double                    factor,
                                TrilinosWrappers::SparseMatrix &matrix) const;
    // Gravity, the tractions and the body force at `time`, times the load
    // factor of the static solve.
    void
    assemble_external_force(const double                   time,
                            const double                   load_factor,
                            TrilinosWrappers::MPI::Vector &force) const;
    // The pneumatic load at displacement u and time t into `state`: its
    // pressure, gas volume and stiffness, the volume gradient and the
    // nodal forces $p\,\mathbf g$ (see PneumaticLoad).
    struct State;
    void
    evaluate_pneumatics(const TrilinosWrappers::MPI::Vector &u,
                        const double                         time,
                        State                               &state);
    // The linear solver prepared for system_matrix, with the rank-one term
    // of a gas cavity if one is set (see RankOneCorrection).
    void
    prepare_linear_solver();

    // @sect4{Output}
    void
    open_trajectory();
    // The nodal fields of the current state in a DataOut object, and the
    // per-cell fields beside it.
    std::pair<std::unique_ptr<DataOut<dim>>, CellData>
    field_data() const;
    // Writes the fields of the current state in every format asked for.
    void
    write_fields();
    // Norms and energies of the current state, for the checks of
    // finiteness.
    std::vector<std::pair<std::string, double>>
    state_values() const;
    void
    analyse_trajectory() const;
    void
    write_run_statistics(const double wall_time) const;
    void
    fill_and_write_statistics(RunStatistics &statistics,
                              const double   wall_time) const;
    // The angular momentum of the current state (see Inertia).
    Tensor<1, 3>
    angular_momentum() const;

    // @sect4{The data}
    const Parameters::AllParameters parameters;
    MPI_Comm                        mpi_communicator;
    ConditionalOStream              pcout;
    mutable TimerOutput             computing_timer;

    // The discretization.
    parallel::shared::Triangulation<dim> triangulation;
    // The positions field of a second-order mesh, which the mapping
    // refers to (empty for a linear mesh).
    std::unique_ptr<CurvedGeometry<dim>> curved_geometry;
    std::unique_ptr<Mapping<dim>>        mapping;
    std::unique_ptr<FESystem<dim>>       fe;
    DoFHandler<dim>                      dof_handler;
    std::unique_ptr<Quadrature<dim>>     cell_quadrature;
    std::unique_ptr<Quadrature<dim>>     mass_quadrature;
    std::unique_ptr<Quadrature<dim - 1>> face_quadrature;
    bool                                 simplex_mesh = false;
    IndexSet                             locally_owned_dofs;
    IndexSet                             locally_relevant_dofs;
    AffineConstraints<double>            constraints;

    // The physics and the global addition.
    CellGeometry<dim>                       cell_geometry;
    std::unique_ptr<HyperelasticSolid<dim>> solid;
    std::unique_ptr<AerodynamicDrag<dim>>   drag;
    std::unique_ptr<PneumaticLoad<dim>>     pneumatics;
    // Whether any damping acts (stiffness- or mass-proportional, drag), and
    // whether the stiffness-proportional one is the lagged matrix.
    bool                                  damped        = false;
    bool                                  lagged_matrix = false;
    Inertia<dim>                          inertia;
    TractionLoad<dim>                     traction;
    std::shared_ptr<Function<dim>>        body_force;
    FunctionParser<dim>                   initial_displacement;
    FunctionParser<dim>                   initial_velocity;
    std::unique_ptr<SystemAssembler<dim>> assembler;

    // The solvers.
    HHTStepper         stepper;
    NewtonSolver       newton_solver;
    TimeStepController step_controller;

    // The matrices. system_matrix holds the tangent of the last assembly
    // with a matrix, or the effective matrix of a step formed from it;
    // `system_matrix_is_state_stiffness` is true while it holds the
    // stiffness of the state `current` (after the assembly at the end of a
    // step), from which the next step's modified-Newton matrix is formed.
    // The damping matrix of the current step, and the one of the state
    // assembled last, which becomes the next step's when the step
    // succeeds.
    TrilinosWrappers::SparseMatrix system_matrix;
    bool                           system_matrix_is_state_stiffness = false;
    // With `Tangent update = when needed`: the step size of the effective
    // matrix that the linear solver holds prepared, while it is the matrix
    // of the last successful step and no assembly has written system_matrix
    // since; zero otherwise. The next step of that size keeps it.
    double                         kept_matrix_dt = 0.;
    TrilinosWrappers::SparseMatrix damping_matrix;
    TrilinosWrappers::SparseMatrix next_damping_matrix;
    // The stiffness matrices of the last two converged states and their
    // times, from which prepare_step_tangent() extrapolates.
    struct StiffnessHistory
    {
      std::unique_ptr<TrilinosWrappers::SparseMatrix> older, newer;
      double older_time = -std::numeric_limits<double>::max();
      double newer_time = -std::numeric_limits<double>::max();
    } stiffness_history;

    // The linear solver keeps the factorization or multigrid hierarchy of
    // system_matrix, and refers to it: it is declared after the matrices,
    // so that it is destroyed before them.
    LinearSolver linear_solver;
    // The gas cavity's rank-one term of the matrix prepared last.
    RankOneCorrection rank_one;
    // The kept matrix rotated with the body (Rotated tangent), and whether
    // the solves of the running Newton iteration use it.
    std::unique_ptr<RotatedTangent<dim>> rotated_tangent;
    bool                                 rotate_kept_tangent = false;

    // @sect4{The state of the motion}
    //
    // Displacement, velocity, acceleration at one time level, and the
    // vectors of internal, external and damping forces evaluated there,
    // which the HHT equation needs again at the next step.
    struct State
    {
      double                        time = 0.;
      TrilinosWrappers::MPI::Vector u, v, a;
      TrilinosWrappers::MPI::Vector internal_force, external_force;
      TrilinosWrappers::MPI::Vector damping_force;
      // The pneumatic load (empty vectors without one): nodal forces
      // $p\,\mathbf g$, the volume gradient $\mathbf g$, the gauge pressure,
      // the gas volume of the whole body and the gas stiffness $s$.
      TrilinosWrappers::MPI::Vector pressure_force, volume_gradient;
      double                        pressure      = 0.;
      double                        gas_volume    = 0.;
      double                        gas_stiffness = 0.;
    };
    State current;
    State previous;

    // The energy balance, with the HHT damping and traction forces of the
    // last step's equation of motion (see update_energies()).
    EnergyAccount                 energy;
    TrilinosWrappers::MPI::Vector hht_damping_force;
    TrilinosWrappers::MPI::Vector hht_traction_force;
    TrilinosWrappers::MPI::Vector hht_pressure_force;
    double                        initial_total_energy = 0.;

    // What the run has done so far.
    struct Counters
    {
      unsigned int steps                  = 0;
      unsigned int newton_iterations      = 0;
      unsigned int linear_iterations      = 0;
      unsigned int last_newton_iterations = 0;
      double       last_residual          = 0.;
    } counters;

    // The output, and the guards that keep nonsense out of it.
    TipRegion<dim>                    tip_region;
    PlausibilityGuard<dim>            guard;
    TrajectoryWriter                  trajectory;
    std::unique_ptr<FieldOutput<dim>> field_output;
    std::unique_ptr<XdmfOutput<dim>>  xdmf_output;
    double                            next_output_time = 0.;
    double last_output_time  = -std::numeric_limits<double>::max();
    bool   current_is_finite = true;
  };
} // namespace SoftRobot

#endif
