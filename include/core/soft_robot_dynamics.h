// @sect3{The SoftRobotDynamics class template}
//
// This is the solver: a hyperelastic body that moves under gravity,
// tractions and its own inertia, with stiffness-proportional damping,
// integrated in time by the HHT-$\alpha$ method, each step solved by
// Newton's method with algebraic multigrid. The same class runs the 1D
// column, the 2D planar model and the 3D body; what differs between the
// dimensions is the strain energy (see NeoHookeanEnergy) and the mesh.
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
// stiffness-proportional (Rayleigh) damping matrix of the reference study,
// $\mathbf C = \zeta\mathbf K$. In a nonlinear problem "the stiffness" has
// to be made precise; we use
// @f[
//   C_{ij} = \int_{\Omega_0} \zeta\;\delta\mathbf E_i : \mathcal
//   C^+(\mathbf u_n) : \delta\mathbf E_j\,dV,\qquad
//   \delta\mathbf E_i = \mathrm{sym}(\mathbf F^T\nabla_0\mathbf N_i),
// @f]
// the material part of the tangent stiffness at the start of each time
// step (the last converged state), with each material's own $\zeta$ and
// the positive semi-definite part $\mathcal C^+$ of the material tangent
// (which at large strains can have negative eigenvalues; with them, the
// Ecoflex actuator's damping fed energy into mesh-scale motions until
// elements inverted). It is symmetric and positive semi-definite, so the
// damping only dissipates;
// it leaves rigid-body motions undamped, also rotations of a prestressed
// body (which the geometric part of $\mathbf K$ would damp); and, being
// constant within a step, it keeps Newton's method exact (quadratically
// convergent) at no extra assembly cost: the matrix of the converged state
// of one step is assembled anyway in the last Newton iteration and is kept
// for the next step.
//
// For the reduced models every integral carries the material's `Section`
// factor (cross-section area in 1D, thickness in 2D).
//
// In 3D, `Finite element/Volumetric formulation = mean dilatation` replaces
// the volumetric energy $U(J)$ at each quadrature point by $V_e\,U(\Theta_e)$
// per cell, with the cell's mean volume ratio $\Theta_e = V_e^{-1}\int_e
// J\,dV$: the three-field formulation with pressure and dilatation constant
// per cell, condensed cell by cell (see doc/introduction.md). With
// quadratic elements it does not lock as $\kappa/\mu$ grows; the cell's
// pressure $U'(\Theta_e)$ enters the stress at every point of the cell, and
// the tangent gets the rank-one term $U''(\Theta_e)/V_e\;\mathbf g\mathbf
// g^T$ with the derivative $\mathbf g$ of the cell's volume.

#ifndef soft_robot_core_soft_robot_dynamics_h
#define soft_robot_core_soft_robot_dynamics_h

#include <assembly/assembly_result.h>
#include <core/exceptions.h>
#include <core/parameters.h>
#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/function_parser.h>
#include <deal.II/base/index_set.h>
#include <deal.II/base/quadrature.h>
#include <deal.II/base/timer.h>
#include <deal.II/distributed/shared_tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/vector.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deque>
#include <fstream>
#include <functional>
#include <material/neo_hookean_energy.h>
#include <memory>
#include <thread>
#include <time_integration/hht_stepper.h>
#include <vector>

// The prepared linear solvers are held by pointer; their definitions are
// needed only where they are used.
namespace dealii::TrilinosWrappers
{
  class PreconditionAMG;
} // namespace dealii::TrilinosWrappers
class Amesos_BaseSolver;
class Epetra_Import;
class Epetra_LinearProblem;
class Epetra_Map;
class Epetra_Vector;

namespace SoftRobot
{
  using namespace dealii;

  // @sect4{Energies of the motion}
  //
  // The terms of the energy balance, in the program's units kg mm^2 s^-2,
  // i.e. micro-joules.
  struct EnergyAccount
  {
    double kinetic             = 0.; // $\tfrac12\mathbf v^T\mathbf M\mathbf v$
    double strain              = 0.; // $\int\Psi\,dV$
    double gravity_potential   = 0.; // $-\int\rho_0\mathbf g\cdot\mathbf u\,dV$
    double traction_work       = 0.; // work done by the tractions so far
    double damping_dissipation = 0.; // energy taken by the damping forces
    double
    balance(const double initial_total) const
    {
      return kinetic + strain + gravity_potential - traction_work +
             damping_dissipation - initial_total;
    }
  };



  // A vector-valued function of x and t with dim components from an
  // expression of the parameter file ('' means zero); errors name the entry.
  template <int dim>
  void
  initialize_vector_function(FunctionParser<dim> &function,
                             const std::string   &expression,
                             const std::string   &constants,
                             const std::string   &entry_name);



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

    // @sect4{Pieces of the simulation for tests and studies}
    //
    // These are the phases run() calls; tests use them to check the
    // solver one piece at a time.
    void
    make_grid();
    void
    setup_system();
    // Equilibrium under the loads at time $t$ (load-stepped Newton).
    void
    solve_static_equilibrium(const double time);
    // The linearised operators at the current displacement: tangent
    // stiffness and mass matrix (for eigenfrequency checks).
    const TrilinosWrappers::SparseMatrix &
    tangent_stiffness_matrix();
    // The same at any displacement u, and the strain energy and internal
    // force vector there: for tests of the linearisation.
    const TrilinosWrappers::SparseMatrix &
    tangent_stiffness_matrix(const TrilinosWrappers::MPI::Vector &u);
    double
    internal_force(const TrilinosWrappers::MPI::Vector &u,
                   TrilinosWrappers::MPI::Vector       &force);
    const TrilinosWrappers::SparseMatrix &
    mass_matrix() const
    {
      return mass;
    }
    const DoFHandler<dim> &
    get_dof_handler() const
    {
      return dof_handler;
    }
    const Mapping<dim> &
    get_mapping() const
    {
      return *mapping;
    }
    const AffineConstraints<double> &
    get_constraints() const
    {
      return constraints;
    }
    const TrilinosWrappers::MPI::Vector &
    displacement() const
    {
      return current.u;
    }
    const TrilinosWrappers::MPI::Vector &
    velocity() const
    {
      return current.v;
    }
    const TrilinosWrappers::MPI::Vector &
    acceleration() const
    {
      return current.a;
    }
    // Mean displacement and velocity of the tip region (see Output/Tip
    // region), and the energies of the current state.
    std::pair<Tensor<1, dim>, Tensor<1, dim>>
    tip_motion() const;
    const EnergyAccount &
    energies() const
    {
      return energy;
    }
    double
    time() const
    {
      return current.time;
    }
    // The angular momentum about the origin, $\mathbf L = \int\rho_0\,
    // \mathbf x\times\mathbf v\;dV$ with $\mathbf x = \mathbf X +
    // \mathbf u$ (times the section in the reduced models), of the current
    // state, for the finite element fields $\mathbf x$ and $\mathbf v$:
    // the integral is that of the consistent mass matrix, of which the
    // cells keep their scalar blocks (without the constraints, which would
    // drop the fixed nodes' share); it is exact where the mass quadrature
    // is, on affine cells. In 2D only the z-component is nonzero, in 1D
    // none.
    Tensor<1, 3>
    angular_momentum() const;
    // An additional body force $\mathbf b(\mathbf X, t)$ per unit reference
    // volume (kg mm^-2 s^-2 in the program's units), a Function of the
    // reference position with dim components whose time is set to the time
    // of the load. It is added to gravity, scaled like it by the section of
    // the reduced models, and its work is booked with that of the
    // tractions. The tests impose manufactured solutions with it; loads that
    // a parameter file cannot express can use it too. Set it before
    // initialize_state().
    void
    set_body_force(const std::shared_ptr<Function<dim>> &force)
    {
      body_force = force;
    }
    // Initial state, then steps of the nominal size until the end time; the
    // same as run() without any output.
    void
    initialize_state();
    bool
    advance_one_step();
    // The statistics of the run so far.
    unsigned int
    n_steps() const
    {
      return step_number;
    }
    unsigned int
    n_newton_iterations() const
    {
      return total_newton_iterations;
    }
    // Matrix factorizations (or multigrid set-ups) so far.
    unsigned int
    n_tangent_updates() const
    {
      return total_tangent_updates;
    }
    // Iterations of the iterative linear solver so far (one per solve
    // with the direct solver).
    unsigned int
    n_linear_iterations() const
    {
      return total_linear_iterations;
    }
    // ML's operator complexity of the multigrid hierarchy: the nonzeros
    // of all its levels' matrices over those of the finest; zero when no
    // hierarchy has been built (the direct solvers).
    double
    multigrid_operator_complexity() const
    {
      return amg_operator_complexity;
    }
    // The linear solver that solved the last system: the class of the
    // Amesos solver that was created ("Amesos_Klu", "Amesos_Mumps"), or
    // "CG with ML" / "GMRES with ML"; empty before the first solve.
    std::string
    linear_solver_in_use() const;

  private:
    // @sect4{The state of the motion}
    //
    // Displacement, velocity, acceleration at one time level, and the
    // vectors of internal and external forces evaluated there, which the
    // HHT equation needs again at the next step.
    struct State
    {
      double                        time = 0.;
      TrilinosWrappers::MPI::Vector u, v, a;
      TrilinosWrappers::MPI::Vector internal_force, external_force;
      TrilinosWrappers::MPI::Vector damping_force;
    };

    // The phases of one time step, in the order they are called.
    void
    assemble_mass_matrix();
    void
    assemble_external_force(const double                   time,
                            const double                   load_factor,
                            TrilinosWrappers::MPI::Vector &force) const;
    AssemblyResult
    // With the matrix, also the damping matrix of the state unless
    // `with_damping_matrix` is false.
    assemble_internal_force(const TrilinosWrappers::MPI::Vector &u,
                            const bool                           with_matrix,
                            TrilinosWrappers::MPI::Vector &internal_force,
                            const bool with_damping_matrix = true);
    void
    solve_nonlinear_timestep(const double dt);
    unsigned int
    solve_linear_system(TrilinosWrappers::SparseMatrix      &matrix,
                        const TrilinosWrappers::MPI::Vector &rhs,
                        TrilinosWrappers::MPI::Vector       &solution);
    // The two halves of solve_linear_system(): factorize the matrix (or
    // build the multigrid hierarchy), and solve with what was prepared,
    // as often as needed.
    void
    prepare_linear_solver(TrilinosWrappers::SparseMatrix &matrix);
    unsigned int
    solve_prepared_system(const TrilinosWrappers::MPI::Vector &rhs,
                          TrilinosWrappers::MPI::Vector       &solution);
    // Modified Newton: the HHT matrix of a step of size dt from the
    // stiffness and damping of the last converged state, prepared for the
    // linear solver.
    void
    prepare_step_tangent(const double dt);
    void
    compute_initial_acceleration();
    void
    update_energies(const AssemblyResult &assembly);

    // Newton's method for $\mathbf r(\mathbf u) = 0$, where `evaluate`
    // assembles the residual and the tangent matrix at a trial $\mathbf u$.
    // With `modified`, the matrix prepared before the call is used for all
    // iterations until one converges too slowly (see the parameter
    // `Tangent update`), and the evaluations assemble no matrix.
    using ResidualEvaluator =
      std::function<AssemblyResult(const TrilinosWrappers::MPI::Vector &,
                                   const bool with_matrix,
                                   TrilinosWrappers::MPI::Vector &)>;
    AssemblyResult
    newton_solve(TrilinosWrappers::MPI::Vector &u,
                 const ResidualEvaluator       &evaluate,
                 const double                   force_scale,
                 unsigned int                  &iterations,
                 const bool                     modified = false);
    // Anderson acceleration of the modified Newton iterations (see
    // newton_solve()).
    bool
    anderson_step(const TrilinosWrappers::MPI::Vector       &iterate,
                  const TrilinosWrappers::MPI::Vector       &update,
                  const unsigned int                         depth,
                  bool                                      &have_last_update,
                  TrilinosWrappers::MPI::Vector             &last_iterate,
                  TrilinosWrappers::MPI::Vector             &last_update,
                  std::deque<TrilinosWrappers::MPI::Vector> &iterate_differences,
                  std::deque<TrilinosWrappers::MPI::Vector> &update_differences,
                  TrilinosWrappers::MPI::Vector             &step) const;
    void
    output_results(const unsigned int output_index);
    // Waits for the thread that writes the VTU files.
    void
    finish_output();
    // What output_results() hands to the writing thread: the DataOut object
    // with all fields, the time, the output's number, the PVD record up to
    // this output, the number of MPI processes and this one's rank (defined
    // in soft_robot_dynamics_output.cc).
    struct OutputJob;
    void
    write_output(OutputJob &job) const;
    // The job the writing thread works on; released by finish_output().
    std::shared_ptr<OutputJob> output_job;
    std::thread                output_writer;
    std::string                output_error;
    double                     background_output_seconds = 0.;
    void
    open_trajectory_file();
    void
    analyse_trajectory() const;
    void
    write_trajectory_line();

    // The HHT residual $\mathbf r(\mathbf u_{n+1})$ for a trial
    // displacement; returns the results of the assembly.
    AssemblyResult
    evaluate_residual(const TrilinosWrappers::MPI::Vector &u_trial,
                      const double                         dt,
                      const bool                           with_matrix,
                      TrilinosWrappers::MPI::Vector       &residual);

    // @sect4{The reference geometry of the cells}
    //
    // In the total Lagrangian formulation the shape-function gradients and
    // the quadrature weights refer to the undeformed mesh and never change.
    // setup_cell_geometry() computes them once for the locally owned
    // cells, so that the assembly of the internal forces, which runs in
    // every Newton iteration, does no FEValues::reinit() (for linear
    // tetrahedra that was a third of its time). A vector-valued shape
    // function $\mathbf N_i = \varphi_i\mathbf e_{c_i}$ of the FESystem has
    // one nonzero component $c_i$; only the gradient of $\varphi_i$ is
    // stored.
    struct CellGeometry
    {
      unsigned int n_cells       = 0;
      unsigned int dofs_per_cell = 0;
      unsigned int n_q_points    = 0;
      // the component c_i of each shape function of a cell
      std::vector<unsigned int> components;
      // per cell: the global dof indices, [cell][i]
      std::vector<types::global_dof_index> dof_indices;
      // per cell and point: the gradients of the scalar shape functions,
      // [cell][q][i], and the weight times the section factor, [cell][q]
      std::vector<Tensor<1, dim>> shape_gradients;
      std::vector<double>         JxW;
      // per cell: its material law and damping coefficient
      std::vector<const NeoHookeanEnergy<dim> *> material;
      std::vector<double>                        damping_zeta;
      // With only homogeneous constraints (fixed components): where each
      // entry of a cell matrix goes in the value array of the Epetra
      // matrices, [cell][i][j], -1 for a constrained row or column; where
      // the diagonal entry of each constrained dof of a cell is, [cell][i],
      // -1 if the dof is free. In parallel runs a row that another process
      // owns has -2 in both; its entries go through Epetra. In serial runs
      // also the index of each free dof in the vectors' value arrays,
      // [cell][i], -1 if constrained (empty in parallel runs). In parallel
      // runs instead `distributed_vector_positions`, [cell][i]: the index
      // in this process's part of the vectors for a dof it owns, -1 for a
      // constrained dof, and -2 - g for the free dof that another process
      // owns and that is entry g of the ghost vectors below. Empty
      // otherwise: then AffineConstraints adds the cell contributions.
      std::vector<int> matrix_positions;
      std::vector<int> diagonal_positions;
      std::vector<int> vector_positions;
      std::vector<int> distributed_vector_positions;
    };
    void
    setup_cell_geometry();

    // In parallel runs with direct addresses: the free dofs of the locally
    // owned cells that other processes own, in one Epetra vector for the
    // displacements read from their owners and one for the forces sent to
    // them, and the communication pattern between these vectors and the
    // distributed ones, set up once.
    std::unique_ptr<Epetra_Map>    ghost_map;
    std::unique_ptr<Epetra_Import> ghost_import;
    std::unique_ptr<Epetra_Vector> ghost_displacements, ghost_forces;

    // The boundary faces that carry the nominal tractions, with what their
    // forces need in the reference configuration, which never changes: the
    // quadrature points, and per point the values of the scalar shape
    // functions times the weight and the section factor, [face][q][i]
    // (the component of shape function i is CellGeometry::components[i]).
    // The traction is evaluated at the points every step; faces where it
    // vanishes -- every face after a release -- add nothing.
    struct TractionFaces
    {
      unsigned int                         n_faces    = 0;
      unsigned int                         n_q_points = 0;
      std::vector<types::global_dof_index> dof_indices;
      std::vector<Point<dim>>              points;
      std::vector<double>                  weighted_shape_values;
    };
    void
    setup_traction_faces();
    // The tip motion's weights, one vector per component, and their sum
    // (see tip_motion()).
    void
    setup_tip_weights();
    std::vector<TrilinosWrappers::MPI::Vector> tip_weights;
    double                                     tip_total_weight = 0.;
    void
    write_run_statistics(const double wall_time) const;

    // The scalar $\zeta$, $\rho_0$, section factor per cell.
    const Parameters::Material &
    material_of(
      const typename DoFHandler<dim>::active_cell_iterator &cell) const;

    const Parameters::AllParameters parameters;

    MPI_Comm            mpi_communicator;
    ConditionalOStream  pcout;
    mutable TimerOutput computing_timer;

    parallel::shared::Triangulation<dim> triangulation;
    std::unique_ptr<Mapping<dim>>        mapping;
    std::unique_ptr<FESystem<dim>>       fe;
    DoFHandler<dim>                      dof_handler;
    std::unique_ptr<Quadrature<dim>>     cell_quadrature;
    std::unique_ptr<Quadrature<dim>>     mass_quadrature;
    std::unique_ptr<Quadrature<dim - 1>> face_quadrature;
    bool                                 simplex_mesh = false;

    IndexSet                  locally_owned_dofs;
    IndexSet                  locally_relevant_dofs;
    AffineConstraints<double> constraints;

    std::map<types::material_id, NeoHookeanEnergy<dim>> materials;
    CellGeometry                                         cell_geometry;
    TractionFaces                                        traction_faces;
    std::map<types::material_id, double>                densities;

    HHTStepper                  stepper;
    mutable FunctionParser<dim> traction_function;
    std::shared_ptr<Function<dim>> body_force;
    // Per locally owned cell (in the order of the cell geometry): the
    // scalar mass matrix of its nodes, [cell][n][k], and the reference
    // positions of its nodes, [cell][n] (see angular_momentum()).
    std::vector<double>     cell_nodal_mass;
    std::vector<Point<dim>> cell_node_positions;
    FunctionParser<dim>         initial_displacement;
    FunctionParser<dim>         initial_velocity;
    Tensor<1, dim>              gravity;

    TrilinosWrappers::SparseMatrix mass;
    // The damping matrix of the current step, and the one of the state
    // assembled last, which becomes the next step's when the step succeeds.
    TrilinosWrappers::SparseMatrix damping_matrix;
    TrilinosWrappers::SparseMatrix next_damping_matrix;
    bool                           has_damping = false;
    TrilinosWrappers::MPI::Vector  gravity_force;
    TrilinosWrappers::SparseMatrix system_matrix;
    // True while system_matrix holds the stiffness of the state `current`
    // (after the assembly at the end of a step), from which the next
    // step's modified-Newton matrix is formed.
    bool system_matrix_is_state_stiffness = false;
    // The stiffness matrices of the last two converged states and their
    // times, from which prepare_step_tangent() extrapolates.
    std::unique_ptr<TrilinosWrappers::SparseMatrix> older_stiffness,
      newer_stiffness;
    double older_stiffness_time = -std::numeric_limits<double>::max();
    double newer_stiffness_time = -std::numeric_limits<double>::max();
    // The prepared linear solver: the sparse factorization (Amesos KLU or
    // MUMPS, whose symbolic analysis of the sparsity pattern is done once
    // per matrix object) or the multigrid hierarchy (whose aggregates are
    // likewise computed once per matrix object); `analysed_matrix` is the
    // Epetra matrix of that object.
    std::unique_ptr<Epetra_LinearProblem>              direct_problem;
    std::unique_ptr<Amesos_BaseSolver>                 direct_factorization;
    const void                                        *analysed_matrix = nullptr;
    std::unique_ptr<TrilinosWrappers::PreconditionAMG> amg_preconditioner;
    // The near null space the hierarchy was given (the rigid-body modes,
    // one column after another).
    std::vector<double> amg_null_space;
    // The nonzeros of all the hierarchy's level matrices together, over
    // the nonzeros of the finest (ML's operator complexity), for the run
    // statistics; zero until a hierarchy is built.
    double                                amg_operator_complexity = 0.;
    const TrilinosWrappers::SparseMatrix *prepared_matrix         = nullptr;
    State                          current;
    State                          previous;

    // The rigid-body modes of the mesh, the near null space for ML.
    std::vector<std::vector<double>> rigid_body_modes;

    EnergyAccount energy;
    // The HHT damping and traction forces of the last step's equation of
    // motion (see update_energies()).
    TrilinosWrappers::MPI::Vector hht_damping_force;
    TrilinosWrappers::MPI::Vector hht_traction_force;
    double        initial_total_energy = 0.;

    double       time_step;
    unsigned int step_number             = 0;
    unsigned int steps_since_cutback     = 0;
    unsigned int total_newton_iterations = 0;
    unsigned int total_linear_iterations = 0;
    unsigned int total_cutbacks          = 0;
    unsigned int total_tangent_updates   = 0;
    unsigned int last_newton_iterations  = 0;
    double       last_residual           = 0.;

    std::ofstream                               trajectory;
    std::vector<std::pair<double, std::string>> pvd_records;
  };
} // namespace SoftRobot

#endif
