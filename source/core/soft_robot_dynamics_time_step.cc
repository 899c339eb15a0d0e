// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{SoftRobotDynamics: the initial state and the time step}
//
// This file holds the phases of SoftRobotDynamics that compute the motion:
// the initial state (including a static equilibrium), one HHT step with its
// automatic cut-back, the assemblies they call, and the energy balance.

#include <core/config.h>
#include <core/soft_robot_dynamics.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/numerics/vector_tools.h>
#include <sstream>

namespace SoftRobot
{
  namespace
  {
    // Whether the modified Newton method keeps its matrix across steps.
    bool
    keeps_matrix(const Parameters::NonlinearSolver &parameters)
    {
      return parameters.tangent_update ==
             Parameters::NonlinearSolver::TangentUpdate::when_needed;
    }
  } // namespace


  // @sect4{SoftRobotDynamics::assemble_forces}
  //
  // The physics of every cell -- HyperelasticSolid's, then the drag on the
  // cell's faces and the stiffness of the pneumatic load on them (at the
  // pressure of its last evaluation; its force is added globally, see
  // evaluate_pneumatics()) -- added by the global assembler.
  template <int dim>
  AssemblyResult
  SoftRobotDynamics<dim>::assemble_forces(
    const TrilinosWrappers::MPI::Vector &u,
    const TrilinosWrappers::MPI::Vector *v,
    const AssemblyRequest               &request,
    TrilinosWrappers::MPI::Vector       &internal_force,
    TrilinosWrappers::MPI::Vector       *damping_force)
  {
    TimerOutput::Scope timer_section(computing_timer,
                                     request.matrix ? "Assemble system"
                                     : request.store_viscosity
                                       ? "Assemble state"
                                       : "Assemble residual");
    if (request.matrix)
      kept_matrix_dt = 0.;
    Assert(damping_force != nullptr || !request.second_force,
           ExcInternalError());
    Assert(!request.second_matrix || solid->has_damping() || drag,
           ExcInternalError());
    typename SystemAssembler<dim>::Targets targets;
    targets.force         = &internal_force;
    targets.second_force  = damping_force;
    targets.matrix        = &system_matrix;
    targets.second_matrix = &next_damping_matrix;
    std::vector<const TrilinosWrappers::MPI::Vector *> inputs = {&u};
    if (v != nullptr)
      inputs.push_back(v);
    return assembler->assemble(
      [this](CellContribution<dim> &local) {
        solid->cell_contribution(local);
        if (drag && local.input_values.size() > 1)
          drag->add_cell_contribution(local);
        if (pneumatics)
          pneumatics->add_cell_contribution(local);
      },
      inputs,
      request,
      targets);
  }



  // @sect4{SoftRobotDynamics::assemble_internal_force}
  template <int dim>
  AssemblyResult
  SoftRobotDynamics<dim>::assemble_internal_force(
    const TrilinosWrappers::MPI::Vector &u,
    const bool                           with_matrix,
    TrilinosWrappers::MPI::Vector       &internal_force)
  {
    AssemblyRequest request;
    request.matrix = with_matrix;
    return assemble_forces(u, nullptr, request, internal_force, nullptr);
  }



  // @sect4{SoftRobotDynamics::assemble_state}
  //
  // At the state a time step starts from (and at t = 0): the stiffness,
  // the damping matrix, and the forces, with the viscosity of the
  // Kelvin-Voigt damping recorded first, so that the damping force of the
  // state is that of the viscosity the next step keeps. The viscosity
  // needs the material tangent at the points, but not the matrices; they
  // are skipped when the next step keeps its matrix, unless the lagged
  // damping matrix is part of the damping force.
  template <int dim>
  AssemblyResult
  SoftRobotDynamics<dim>::assemble_state(const bool with_matrices)
  {
    const bool      matrices = with_matrices || lagged_matrix;
    AssemblyRequest request;
    request.matrix = matrices;
    request.second_matrix =
      matrices && damped && (solid->has_damping() || drag);
    request.second_force    = damped;
    request.store_viscosity = true;
    if (pneumatics)
      evaluate_pneumatics(current.u, current.time, current);
    const AssemblyResult assembly =
      assemble_forces(current.u,
                      damped ? &current.v : nullptr,
                      request,
                      current.internal_force,
                      damped ? &current.damping_force : nullptr);
    system_matrix_is_state_stiffness = request.matrix;
    if (request.second_matrix)
      damping_matrix.copy_from(next_damping_matrix);
    if (!damped)
      current.damping_force = 0.;
    else
      add_global_damping_forces(current.v, current.damping_force);
    return assembly;
  }



  // @sect4{SoftRobotDynamics::add_global_damping_forces}
  //
  // The lagged form of the stiffness-proportional damping applies the
  // damping matrix of the step's first state to the velocity; the
  // mass-proportional damping is its matrix times the velocity.
  template <int dim>
  void
  SoftRobotDynamics<dim>::add_global_damping_forces(
    const TrilinosWrappers::MPI::Vector &v,
    TrilinosWrappers::MPI::Vector       &force) const
  {
    if (lagged_matrix)
      damping_matrix.vmult_add(force, v);
    if (Inertia<dim>::has_mass_damping(parameters))
      inertia.mass_damping_for_products().vmult_add(force, v);
  }



  template <int dim>
  void
  SoftRobotDynamics<dim>::add_global_damping_matrices(
    const double                    factor,
    TrilinosWrappers::SparseMatrix &matrix) const
  {
    if (lagged_matrix)
      matrix.add(factor, damping_matrix);
    if (Inertia<dim>::has_mass_damping(parameters))
      matrix.add(factor, inertia.mass_damping);
  }



  // @sect4{SoftRobotDynamics::assemble_external_force}
  //
  // Gravity (assembled once with the mass matrix) plus the nominal
  // tractions on the boundaries the parameter file names and the body force
  // of the tests, if any, all scaled by the load factor of the static solve
  // (one during the time loop). The body force $\mathbf b(\mathbf X, t)$ per
  // unit reference volume is added to gravity and scaled like it by the
  // section of the reduced models; its work is booked with that of the
  // tractions.
  template <int dim>
  void
  SoftRobotDynamics<dim>::assemble_external_force(
    const double                   time,
    const double                   load_factor,
    TrilinosWrappers::MPI::Vector &force) const
  {
    force = inertia.gravity_force;
    if (!traction.empty())
      {
        TimerOutput::Scope timer_section(computing_timer, "Assemble tractions");
        TrilinosWrappers::MPI::Vector traction_force(locally_owned_dofs,
                                                     mpi_communicator);
        traction.add_forces(time, constraints, traction_force);
        traction_force.compress(VectorOperation::add);
        force += traction_force;
      }
    if (body_force)
      {
        TimerOutput::Scope               timer_section(computing_timer,
                                         "Assemble body force");
        TrilinosWrappers::MPI::Vector    body_force_vector(locally_owned_dofs,
                                                        mpi_communicator);
        FEValues<dim>                    fe_values(*mapping,
                                *fe,
                                *mass_quadrature,
                                update_values | update_quadrature_points |
                                  update_JxW_values);
        const FEValuesExtractors::Vector displacements(0);
        const unsigned int               dofs_per_cell = fe->n_dofs_per_cell();
        Vector<double>                   cell_force(dofs_per_cell);
        std::vector<types::global_dof_index> dof_indices(dofs_per_cell);
        Vector<double>                       value(dim);
        body_force->set_time(time);
        for (const auto &cell : dof_handler.active_cell_iterators())
          if (cell->is_locally_owned())
            {
              fe_values.reinit(cell);
              cell_force = 0.;
              const double section =
                parameters.by_id.at(cell->material_id()).section;
              for (const unsigned int q : fe_values.quadrature_point_indices())
                {
                  body_force->vector_value(fe_values.quadrature_point(q),
                                           value);
                  Tensor<1, dim> b;
                  for (unsigned int d = 0; d < dim; ++d)
                    b[d] = value[d];
                  for (const unsigned int i : fe_values.dof_indices())
                    cell_force(i) += fe_values[displacements].value(i, q) * b *
                                     fe_values.JxW(q) * section;
                }
              cell->get_dof_indices(dof_indices);
              constraints.distribute_local_to_global(cell_force,
                                                     dof_indices,
                                                     body_force_vector);
            }
        body_force_vector.compress(VectorOperation::add);
        force += body_force_vector;
      }
    force *= load_factor;
  }



  // @sect4{SoftRobotDynamics::evaluate_pneumatics}
  //
  // The pressure, volume and volume gradient of the pneumatic load at (u,
  // t), and its nodal forces $\mathbf f_p = p\,\mathbf g$. They enter the
  // residuals as a load that depends on the configuration: at both states
  // of the HHT equation, with the HHT weights (see evaluate_residual()).
  template <int dim>
  void
  SoftRobotDynamics<dim>::evaluate_pneumatics(
    const TrilinosWrappers::MPI::Vector &u,
    const double                         time,
    State                               &state)
  {
    TimerOutput::Scope timer_section(computing_timer, "Pneumatic load");
    const typename PneumaticLoad<dim>::Evaluation evaluation =
      pneumatics->evaluate(u, time, state.volume_gradient);
    state.pressure      = evaluation.pressure;
    state.gas_volume    = evaluation.volume;
    state.gas_stiffness = evaluation.stiffness;
    state.pressure_force.equ(evaluation.pressure, state.volume_gradient);
  }



  // @sect4{SoftRobotDynamics::prepare_linear_solver}
  //
  // The factorization (or multigrid hierarchy) of system_matrix, and on top
  // of it the Sherman-Morrison correction for the gas cavity's rank-one
  // term, if one is set: one more solve (see RankOneCorrection).
  template <int dim>
  void
  SoftRobotDynamics<dim>::prepare_linear_solver()
  {
    linear_solver.prepare(system_matrix);
    counters.linear_iterations += rank_one.prepare(linear_solver);
  }



  // @sect4{SoftRobotDynamics::newton_problem}
  //
  // What Newton's method needs of a problem: its residual, and a solver for
  // the tangent that the residual's evaluation left in system_matrix. The
  // solution of a linear system vanishes at the constrained dofs. The
  // linear iterations are counted here, so that those of a step that fails
  // and is cut back are counted too.
  template <int dim>
  NewtonSolver::Problem
  SoftRobotDynamics<dim>::newton_problem(
    const std::function<AssemblyResult(const TrilinosWrappers::MPI::Vector &,
                                       const bool,
                                       TrilinosWrappers::MPI::Vector &)>
      &evaluate)
  {
    NewtonSolver::Problem problem;
    problem.evaluate        = evaluate;
    problem.prepare_tangent = [this]() { prepare_linear_solver(); };
    problem.solve           = [this](const TrilinosWrappers::MPI::Vector &rhs,
                           TrilinosWrappers::MPI::Vector       &solution) {
      const auto solve_with_matrix =
        [this](const TrilinosWrappers::MPI::Vector &b,
               TrilinosWrappers::MPI::Vector       &x) {
          return rank_one.solve(linear_solver, b, x);
        };
      const unsigned int iterations =
        (rotate_kept_tangent && rotated_tangent)
                    ? rotated_tangent->solve(rhs, solution, solve_with_matrix)
                    : solve_with_matrix(rhs, solution);
      constraints.set_zero(solution);
      counters.linear_iterations += iterations;
      return iterations;
    };
    return problem;
  }



  // @sect4{SoftRobotDynamics::solve_static_equilibrium}
  //
  // The equilibrium $\mathbf f_\text{int}(\mathbf u, \mathbf 0) =
  // \lambda_g\mathbf f_g + \lambda_t\mathbf f_t(t)$ under gravity $\mathbf
  // f_g$ and the tractions $\mathbf f_t$, reached in two phases of equal
  // load steps: first the gravity factor $\lambda_g$ rises to one, then the
  // traction factor $\lambda_t$. The order matters for a hanging body pushed
  // sideways: under its weight it has the lateral (pendulum) stiffness of
  // gravity, which the unloaded body lacks, and Newton's method started
  // from the unloaded state would take a first step far beyond the
  // equilibrium. A load step whose Newton iteration fails is halved. The
  // line search decreases the total potential energy, whose minimum the
  // equilibrium is.
  template <int dim>
  void
  SoftRobotDynamics<dim>::solve_static_equilibrium(const double time)
  {
    rotate_kept_tangent = false;
    // The static tangent lacks the mass term: its factor in double
    // precision (LinearSolver::allow_single_precision_factor()).
    const DoublePrecisionFactor   double_precision(linear_solver);
    TrilinosWrappers::MPI::Vector traction_force(locally_owned_dofs,
                                                 mpi_communicator);
    assemble_external_force(time, 1., traction_force);
    traction_force -= inertia.gravity_force;
    // The pneumatic pressure of the time t rises with the tractions; a
    // closed cavity's load has the potential $-pV$, an open surface's none.
    const double pressure =
      pneumatics ? pneumatics->initial_pressure(time) : 0.;
    const bool has_gravity  = inertia.gravity_force.l2_norm() > 0.;
    const bool has_traction = traction_force.l2_norm() > 0. || pressure != 0.;
    double     pressure_factor = 0.;

    TrilinosWrappers::MPI::Vector external(traction_force);
    TrilinosWrappers::MPI::Vector internal(traction_force);
    TrilinosWrappers::MPI::Vector gradient(traction_force);
    const NewtonSolver::Problem   problem =
      newton_problem([&](const TrilinosWrappers::MPI::Vector &u,
                         const bool                           with_matrix,
                         TrilinosWrappers::MPI::Vector       &r) {
        double pressure_potential = 0.;
        if (pneumatics)
          {
            const auto evaluation =
              pneumatics->evaluate_at_pressure(u,
                                               pressure_factor * pressure,
                                               gradient);
            pressure_potential =
              pneumatics->has_volume()
                ? -evaluation.pressure *
                    (evaluation.volume - parameters.dead_volume) *
                    parameters.model_fraction
                : std::numeric_limits<double>::quiet_NaN();
          }
        AssemblyResult assembly =
          assemble_internal_force(u, with_matrix, internal);
        system_matrix_is_state_stiffness = false;
        if (with_matrix)
          rank_one.clear();
        r = internal;
        r -= external;
        if (pneumatics)
          r.add(-pressure_factor * pressure, gradient);
        assembly.force_scale = internal.l2_norm();
        assembly.potential_energy =
          assembly.strain_energy - external * u + pressure_potential;
        constraints.set_zero(r);
        return assembly;
      });

    // The load steps before the last stop at the looser `Load step
    // tolerance`: they only lead to the equilibrium, and the last step
    // converges to the full tolerance from wherever they end (what this
    // saves in the pendulums' starts: doc/performance_discussion.md).
    Parameters::NonlinearSolver path_parameters = parameters;
    path_parameters.newton_relative_tolerance =
      std::max(parameters.load_step_tolerance,
               parameters.newton_relative_tolerance);
    const NewtonSolver path_solver(path_parameters, pcout);
    // The last load step, to the `Equilibrium tolerance` where it is
    // tighter than the time steps'.
    Parameters::NonlinearSolver equilibrium_parameters = parameters;
    if (parameters.equilibrium_tolerance > 0.)
      equilibrium_parameters.newton_relative_tolerance =
        std::min(parameters.equilibrium_tolerance,
                 parameters.newton_relative_tolerance);
    const NewtonSolver equilibrium_solver(equilibrium_parameters, pcout);

    // The combined load parameter runs from 0 to 2: gravity factor
    // min(lambda, 1), traction factor max(lambda - 1, 0).
    double       load      = has_gravity ? 0. : 1.;
    const double end       = has_traction ? 2. : 1.;
    double       increment = 1. / parameters.load_steps;
    while (load < end - 1e-12)
      {
        const double phase_end = (load < 1. - 1e-12) ? 1. : 2.;
        const double target    = std::min(phase_end, load + increment);
        external               = 0.;
        external.add(std::min(target, 1.), inertia.gravity_force);
        external.add(std::max(target - 1., 0.), traction_force);
        pressure_factor                           = std::max(target - 1., 0.);
        const TrilinosWrappers::MPI::Vector saved = current.u;
        try
          {
            const bool          last = std::abs(target - end) < 1e-12;
            const NewtonSolver &solver =
              last ? equilibrium_solver : path_solver;
            const NewtonSolver::Result result =
              solver.solve(current.u, problem, external.l2_norm(), false);
            counters.newton_iterations += result.iterations;
            counters.last_residual = result.residual;
            load                   = target;
            if (std::abs(load - phase_end) < 1e-12)
              increment = 1. / parameters.load_steps;
          }
        catch (StepFailure &failure)
          {
            current.u = saved;
            increment *= 0.5;
            if (increment < 1e-4)
              throw RunAborted(
                "The static equilibrium at t = " + std::to_string(time) +
                " could not be found: " + failure.what());
          }
      }
    pcout << "Static equilibrium found (gravity, then tractions, in "
          << parameters.load_steps << " load steps each; last residual "
          << counters.last_residual << ")" << std::endl;
  }



  // @sect4{SoftRobotDynamics::compute_initial_acceleration}
  //
  // The HHT method needs $\mathbf a_0$, which the equation of motion at
  // $t=0$ determines: $\mathbf M\mathbf a_0 = \mathbf f_\text{ext}(0) -
  // \mathbf f_\text{int}(\mathbf u_0) - \mathbf C\mathbf v_0$.
  template <int dim>
  void
  SoftRobotDynamics<dim>::compute_initial_acceleration()
  {
    const AssemblyResult assembly = assemble_state();
    if (assembly.inverted_point_found)
      throw RunAborted("The initial displacement inverts elements (det F = " +
                       std::to_string(assembly.min_jacobian) + ").");
    energy.strain = assembly.strain_energy;

    TrilinosWrappers::MPI::Vector rhs(current.external_force);
    rhs -= current.internal_force;
    rhs -= current.damping_force;
    if (pneumatics)
      rhs += current.pressure_force;
    constraints.set_zero(rhs);
    SolverControl control(1000, 1e-12 * std::max(rhs.l2_norm(), 1e-300));
    SolverCG<TrilinosWrappers::MPI::Vector> solver(control);
    TrilinosWrappers::PreconditionJacobi    jacobi;
    jacobi.initialize(inertia.mass_for_products());
    current.a = 0.;
    if (rhs.l2_norm() > 0)
      solver.solve(inertia.mass_for_products(), current.a, rhs, jacobi);
    constraints.set_zero(current.a);
  }



  // @sect4{SoftRobotDynamics::initialize_state}
  template <int dim>
  void
  SoftRobotDynamics<dim>::initialize_state()
  {
    TimerOutput::Scope timer_section(computing_timer, "Initial state");
    current.time      = 0.;
    stiffness_history = StiffnessHistory();
    VectorTools::interpolate(*mapping,
                             dof_handler,
                             initial_displacement,
                             current.u);
    constraints.set_zero(current.u);
    const bool velocity_at_initial_state =
      parameters.velocity_coordinates ==
      Parameters::InitialConditions::VelocityCoordinates::initial_state;
    current.v = 0.;
    if (!velocity_at_initial_state)
      {
        VectorTools::interpolate(*mapping,
                                 dof_handler,
                                 initial_velocity,
                                 current.v);
        constraints.set_zero(current.v);
      }

    if (parameters.initial_state ==
        Parameters::InitialConditions::InitialState::static_equilibrium)
      solve_static_equilibrium(0.);
    if (velocity_at_initial_state)
      interpolate_velocity_at_current_positions();
    // A gas is sealed in the cavity of the initial state.
    if (pneumatics)
      pneumatics->seal(current.u);

    assemble_external_force(0., 1., current.external_force);
    compute_initial_acceleration();

    energy.kinetic =
      0.5 * inertia.mass_for_products().matrix_norm_square(current.v);
    energy.gravity_potential   = -(inertia.gravity_force * current.u);
    energy.traction_work       = 0.;
    energy.damping_dissipation = 0.;
    energy.pressure_work       = 0.;
    // The forces of the equation at t = 0, the first terms of the work and
    // dissipation sums (see update_energies()).
    hht_damping_force  = current.damping_force;
    hht_pressure_force = current.pressure_force;
    hht_traction_force = current.external_force;
    hht_traction_force -= inertia.gravity_force;
    initial_total_energy =
      energy.kinetic + energy.strain + energy.gravity_potential;
    counters.steps = 0;
  }



  // @sect4{SoftRobotDynamics::interpolate_velocity_at_current_positions}
  //
  // The velocity expression evaluated where the nodes are in the initial
  // state. A field that is rigid in the reference coordinates, $\mathbf v
  // = \mathbf W\mathbf X$, is not rigid for a body that the static
  // equilibrium has bent: its Green-Lagrange strain rate is
  // $\mathrm{sym}(\mathbf F^T\mathbf W) \ne 0$, which the Kelvin-Voigt
  // damping resists. Evaluated at $\mathbf x = \mathbf X + \mathbf u_0$,
  // $\mathbf v = \mathbf W\mathbf x$ is rigid for the initial state up to
  // the interpolation of $\mathbf x$ (exact on the nodes), except where
  // the constraints set the velocity to zero (a clamped node that the
  // rotation would move). The points are
  // the finite element's support points mapped by the scene's mapping, one
  // per local degree of freedom (the elements are Lagrange elements), so
  // each component of each node gets the value at its node's own current
  // position.
  template <int dim>
  void
  SoftRobotDynamics<dim>::interpolate_velocity_at_current_positions()
  {
    TrilinosWrappers::MPI::Vector ghosted_u(locally_owned_dofs,
                                            locally_relevant_dofs,
                                            mpi_communicator);
    ghosted_u = current.u;
    const Quadrature<dim> support_points(fe->get_unit_support_points());
    FEValues<dim>         fe_values(*mapping,
                            *fe,
                            support_points,
                            update_quadrature_points | update_values);
    const FEValuesExtractors::Vector     displacement(0);
    std::vector<Tensor<1, dim>>          u_values(support_points.size());
    std::vector<types::global_dof_index> dof_indices(fe->n_dofs_per_cell());
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          fe_values[displacement].get_function_values(ghosted_u, u_values);
          cell->get_dof_indices(dof_indices);
          for (unsigned int i = 0; i < dof_indices.size(); ++i)
            if (locally_owned_dofs.is_element(dof_indices[i]))
              {
                const Point<dim> x =
                  fe_values.quadrature_point(i) + u_values[i];
                current.v(dof_indices[i]) = initial_velocity.value(
                  x, fe->system_to_component_index(i).first);
              }
        }
    current.v.compress(VectorOperation::insert);
    constraints.set_zero(current.v);
  }



  // @sect4{SoftRobotDynamics::evaluate_residual}
  //
  // The HHT residual for a trial displacement $\mathbf u_{n+1}$: velocity
  // and acceleration follow from Newmark's relations, and
  // @f[
  //   \mathbf r = \mathbf M\mathbf a_{n+1}
  //   + (1+\alpha)\left[\mathbf f_\text{int}(\mathbf u_{n+1})
  //     + \mathbf f_\text{d}(\mathbf u_{n+1}, \mathbf v_{n+1})
  //     - \mathbf f_\text{ext}(t_{n+1})\right]
  //   - \alpha\left[\mathbf f_\text{int}(\mathbf u_n)
  //     + \mathbf f_\text{d}(\mathbf u_n, \mathbf v_n)
  //     - \mathbf f_\text{ext}(t_n)\right],
  // @f]
  // with the damping forces $\mathbf f_\text{d}$ (the Kelvin-Voigt stress
  // with the viscosity of the step, or the lagged damping matrix $\mathbf
  // C_n$ times the velocity, and the mass-proportional damping and the drag
  // if asked). Its derivative, the effective tangent, is $\mathbf
  // M/(\beta\Delta t^2) + (1+\alpha)\,d(\mathbf f_\text{int} + \mathbf
  // f_\text{d})/d\mathbf u_{n+1}$, where $\partial\mathbf
  // v_{n+1}/\partial\mathbf u_{n+1} = c_v = \gamma/(\beta\Delta t)$; the
  // cell integrals include their velocity terms with $c_v$ (see
  // AssemblyRequest), the global damping matrices are added here.
  //
  // The pneumatic load $\mathbf f_p(\mathbf u, t) = p\,\mathbf g(\mathbf
  // u)$ depends on the configuration (and, for a gas, on it alone). It is
  // treated like the other forces of the equation: evaluated at both
  // states, $\mathbf u_{n+1}$ (with the pressure of $t_{n+1}$, or of the
  // gas at $V(\mathbf u_{n+1})$) and $\mathbf u_n$ (kept from the last
  // step), with the HHT weights, so that the residual gets $-(1+\alpha)
  // \mathbf f_{p,n+1} + \alpha\,\mathbf f_{p,n}$. Its derivative, times
  // $1+\alpha$, is the load stiffness of the faces (in the cell integrals)
  // and the gas's rank-one term $(1+\alpha)\,s\,\mathbf g\mathbf g^T$, which
  // RankOneCorrection adds to the solves.
  template <int dim>
  AssemblyResult
  SoftRobotDynamics<dim>::evaluate_residual(
    const TrilinosWrappers::MPI::Vector &u_trial,
    const double                         dt,
    const bool                           with_matrix,
    TrilinosWrappers::MPI::Vector       &residual)
  {
    stepper.update_kinematics(
      u_trial, previous.u, previous.v, previous.a, dt, current.v, current.a);
    AssemblyRequest request;
    request.matrix               = with_matrix;
    request.second_force         = damped;
    request.velocity_coefficient = stepper.velocity_coefficient(dt);
    if (pneumatics)
      evaluate_pneumatics(u_trial, current.time, current);
    AssemblyResult assembly =
      assemble_forces(u_trial,
                      damped ? &current.v : nullptr,
                      request,
                      current.internal_force,
                      damped ? &current.damping_force : nullptr);
    if (with_matrix)
      system_matrix_is_state_stiffness = false;
    if (rotated_tangent)
      {
        rotated_tangent->set_iterate(u_trial);
        if (with_matrix)
          rotated_tangent->set_matrix_state(u_trial);
      }
    if (damped)
      add_global_damping_forces(current.v, current.damping_force);
    else
      current.damping_force = 0.;

    const double w = stepper.new_force_weight();
    inertia.mass_for_products().vmult(residual, current.a);
    assembly.force_scale =
      std::max(residual.l2_norm(), current.internal_force.l2_norm());
    residual.add(w, current.internal_force, w, current.damping_force);
    residual.add(-w, current.external_force);
    residual.add(1. - w,
                 previous.internal_force,
                 1. - w,
                 previous.damping_force);
    residual.add(w - 1., previous.external_force);
    if (pneumatics)
      residual.add(-w, current.pressure_force, w - 1., previous.pressure_force);
    constraints.set_zero(residual);

    if (with_matrix)
      {
        if (pneumatics && pneumatics->rank_one_in_matrix())
          rank_one.set(current.volume_gradient, w * current.gas_stiffness);
        else
          rank_one.clear();
        system_matrix *= w;
        add_global_damping_matrices(w * stepper.velocity_coefficient(dt),
                                    system_matrix);
        system_matrix.add(stepper.acceleration_coefficient(dt), inertia.mass);
      }
    return assembly;
  }



  // @sect4{SoftRobotDynamics::prepare_step_tangent}
  //
  // The matrix of the modified Newton method for a step of size dt:
  // $\mathbf M/(\beta\Delta t^2) + (1+\alpha)(\tilde{\mathbf K} + c_v
  // \mathbf C_n)$, with the damping matrix of the last converged state
  // $\mathbf u_n$ and a stiffness $\tilde{\mathbf K}$ from the stiffness
  // matrices of the converged states (assembled at the end of the previous
  // step; after a failed step the system matrix holds something else, and
  // the stiffness of $\mathbf u_n$ is assembled again).
  //
  // The iterations converge at a rate set by how far $\tilde{\mathbf K}$ is
  // from the stiffness at the end of the step, $\mathbf K_{n+1}$, which
  // they do not know. $\tilde{\mathbf K} = \mathbf K_n$ is off by
  // $O(\Delta t)$; the linear extrapolation from the last two states,
  // $\tilde{\mathbf K} = \mathbf K_n + \theta(\mathbf K_n - \mathbf
  // K_{n-1})$ with $\theta = \Delta t_{n+1}/\Delta t_n$, is off by
  // $O(\Delta t^2)$ for a smooth motion (parameter `Tangent
  // extrapolation`, on by default). The two matrices are kept as copies,
  // $\mathbf K_n$ recorded the first time a step starts from $\mathbf u_n$,
  // so that a step repeated after a cut back extrapolates from the same
  // pair. The residual is not changed, and with it the converged answer.
  template <int dim>
  void
  SoftRobotDynamics<dim>::prepare_step_tangent(const double dt)
  {
    // When the matrix is kept across steps, the end of a step assembles no
    // matrices, and the damping matrix of $\mathbf u_n$ is assembled here
    // with its stiffness; nor is the stiffness extrapolated, as the last
    // two converged states' stiffnesses are not at hand.
    const bool keep = keeps_matrix(parameters);
    if (!system_matrix_is_state_stiffness)
      {
        TrilinosWrappers::MPI::Vector force(locally_owned_dofs,
                                            mpi_communicator);
        if (pneumatics)
          {
            State state = previous;
            evaluate_pneumatics(previous.u, previous.time, state);
          }
        if (keep && damped && (solid->has_damping() || drag))
          {
            TrilinosWrappers::MPI::Vector damping_force(force);
            AssemblyRequest               request;
            request.matrix        = true;
            request.second_matrix = true;
            request.second_force  = true;
            assemble_forces(
              previous.u, &previous.v, request, force, &damping_force);
            damping_matrix.copy_from(next_damping_matrix);
          }
        else
          assemble_internal_force(previous.u, true, force);
      }
    StiffnessHistory &history = stiffness_history;
    if (parameters.tangent_extrapolation && !keep)
      {
        if (history.newer_time != previous.time)
          {
            std::swap(history.older, history.newer);
            std::swap(history.older_time, history.newer_time);
            if (!history.newer)
              history.newer =
                std::make_unique<TrilinosWrappers::SparseMatrix>();
            history.newer->copy_from(system_matrix);
            history.newer_time = previous.time;
          }
        if (history.older && history.older_time < previous.time)
          {
            const double theta = dt / (previous.time - history.older_time);
            system_matrix *= 1. + theta;
            system_matrix.add(-theta, *history.older);
          }
      }
    const double w   = stepper.new_force_weight();
    const double c_v = stepper.velocity_coefficient(dt);
    system_matrix *= w;
    if (solid->has_damping() || drag)
      system_matrix.add(w * c_v, damping_matrix);
    if (Inertia<dim>::has_mass_damping(parameters))
      system_matrix.add(w * c_v, inertia.mass_damping);
    system_matrix.add(stepper.acceleration_coefficient(dt), inertia.mass);
    system_matrix_is_state_stiffness = false;
    if (rotated_tangent)
      rotated_tangent->set_matrix_state(previous.u);
    // The gas's rank-one term of the state $\mathbf u_n$, like the
    // stiffness.
    if (pneumatics && pneumatics->rank_one_in_matrix())
      rank_one.set(previous.volume_gradient, w * previous.gas_stiffness);
    else
      rank_one.clear();
    prepare_linear_solver();
  }



  // @sect4{SoftRobotDynamics::solve_nonlinear_timestep}
  //
  // One HHT step of size dt from `previous` to `current`, starting Newton's
  // method from the constant-acceleration predictor.
  template <int dim>
  void
  SoftRobotDynamics<dim>::solve_nonlinear_timestep(const double dt)
  {
    current.time = previous.time + dt;
    assemble_external_force(current.time, 1., current.external_force);
    stepper.predict_displacement(
      previous.u, previous.v, previous.a, dt, current.u);

    const bool keep = keeps_matrix(parameters);
    const bool modified =
      keep || (parameters.tangent_update ==
               Parameters::NonlinearSolver::TangentUpdate::every_step);
    if (modified && !(keep && kept_matrix_dt == dt))
      prepare_step_tangent(dt);
    kept_matrix_dt = 0.;

    // An extrapolated stiffness already looks ahead; only a matrix of an
    // earlier state is rotated.
    rotate_kept_tangent =
      modified && (keep || !parameters.tangent_extrapolation);
    const NewtonSolver::Result result = newton_solver.solve(
      current.u,
      newton_problem([&](const TrilinosWrappers::MPI::Vector &u,
                         const bool                           with_matrix,
                         TrilinosWrappers::MPI::Vector       &r) {
        return evaluate_residual(u, dt, with_matrix, r);
      }),
      pneumatics ? std::max(current.external_force.l2_norm(),
                            previous.pressure_force.l2_norm())
                 : current.external_force.l2_norm(),
      modified);
    rotate_kept_tangent = false;
    // The matrix the iterations ended with (the one prepared before the
    // step, or the one they rebuilt) serves the next step of this size.
    if (keep)
      kept_matrix_dt = dt;
    counters.last_newton_iterations = result.iterations;
    counters.newton_iterations += result.iterations;
    counters.last_residual = result.residual;
    update_energies(result.assembly);
  }



  // @sect4{SoftRobotDynamics::update_energies}
  //
  // The energy balance of the step. Kinetic, strain and gravitational
  // energy are state functions. The work of the tractions and the energy
  // dissipated by the damping forces are accumulated over the displacement
  // increments, with the forces the scheme actually applied. Step $k$'s
  // equation of motion is $\mathbf M\mathbf a_k + \tilde{\mathbf F}_k = 0$
  // with the HHT forces $\tilde{\mathbf F}_k = (1+\alpha)\mathbf F_k -
  // \alpha\mathbf F_{k-1}$ (and $\tilde{\mathbf F}_0 = \mathbf F_0$, the
  // equation at $t = 0$). The mean of the equations at both ends of a step,
  // times the increment $\Delta\mathbf u$, is an exact identity:
  // @f[
  //   \Delta\mathbf u\cdot\mathbf M\tfrac12(\mathbf a_n + \mathbf a_{n+1})
  //   + \Delta\mathbf u\cdot\tfrac12(\tilde{\mathbf f}_{\text{int},n} +
  //   \tilde{\mathbf f}_{\text{int},n+1}) + \Delta D - \Delta W = 0,
  // @f]
  // with the damping and traction parts booked as $\Delta D = \Delta\mathbf
  // u\cdot\tfrac12(\tilde{\mathbf f}_{\text{d},n} + \tilde{\mathbf
  // f}_{\text{d},n+1})$ and $\Delta W$ alike. What the balance $\mathcal B =
  // T + \Pi + V_g - W + D - (T + \Pi + V_g)_0$ then collects is $\Delta T -
  // \Delta\mathbf u\cdot\mathbf M\tfrac12(\mathbf a_n + \mathbf a_{n+1})$
  // and $\Delta\Pi - \Delta\mathbf u\cdot\tfrac12(\tilde{\mathbf
  // f}_{\text{int},n} + \tilde{\mathbf f}_{\text{int},n+1})$ summed over
  // the steps: the algorithmic dissipation of the scheme, from its Newmark
  // parameters and from the shifted internal force, and nothing else. For
  // $\alpha = 0$ the weights are the trapezoidal rule's, and for the
  // trapezoidal rule on a linear problem both parts vanish. (Gravity is
  // constant; its work is the change of $V_g$ exactly.) The pneumatic load
  // is booked like the tractions, with its HHT forces: $\Delta W_p =
  // \Delta\mathbf u\cdot\tfrac12(\tilde{\mathbf f}_{p,n} + \tilde{\mathbf
  // f}_{p,n+1})$. For a closed cavity at a constant pressure that is the
  // trapezoidal rule for $\int p\,dV$; for a gas it is the work the gas
  // does on the walls, the decrease of its internal energy.
  template <int dim>
  void
  SoftRobotDynamics<dim>::update_energies(const AssemblyResult &assembly)
  {
    TrilinosWrappers::MPI::Vector increment(current.u);
    increment -= previous.u;
    // This step's HHT forces: damping (with this step's matrix, as in the
    // residual) and tractions (the external forces less gravity).
    const double                  w = stepper.new_force_weight();
    TrilinosWrappers::MPI::Vector damping_force(current.damping_force);
    damping_force.sadd(w, 1. - w, previous.damping_force);
    TrilinosWrappers::MPI::Vector traction_force(current.external_force);
    traction_force.sadd(w, 1. - w, previous.external_force);
    traction_force -= inertia.gravity_force;
    if (pneumatics)
      {
        TrilinosWrappers::MPI::Vector pressure_force(current.pressure_force);
        pressure_force.sadd(w, 1. - w, previous.pressure_force);
        energy.pressure_work +=
          0.5 * (increment * pressure_force + increment * hht_pressure_force);
        hht_pressure_force = pressure_force;
      }

    energy.kinetic =
      0.5 * inertia.mass_for_products().matrix_norm_square(current.v);
    energy.strain            = assembly.strain_energy;
    energy.gravity_potential = -(inertia.gravity_force * current.u);
    energy.traction_work +=
      0.5 * (increment * traction_force + increment * hht_traction_force);
    energy.damping_dissipation +=
      0.5 * (increment * damping_force + increment * hht_damping_force);
    hht_damping_force  = damping_force;
    hht_traction_force = traction_force;
  }



  // @sect4{SoftRobotDynamics::advance_one_step}
  //
  // One step of the time loop with automatic step-size control (see
  // TimeStepController): a failed step is repeated with half the time
  // step. After the step, the new state is assembled once (assemble_state()):
  // its stiffness is the next step's matrix in the modified Newton method,
  // its damping matrix and viscosity are the next step's, and its damping
  // force with them is the next step's force of the old state, so that the
  // damping is the same law at both ends of every step. (Newton's method
  // proper, without damping, needs none of it: its last iteration assembled
  // the new state's forces.)
  template <int dim>
  bool
  SoftRobotDynamics<dim>::advance_one_step()
  {
    if (step_controller.finished(current.time))
      return false;

    previous = current;
    while (true)
      {
        const double dt = step_controller.next_step(previous.time);
        try
          {
            solve_nonlinear_timestep(dt);
            break;
          }
        catch (StepFailure &failure)
          {
            current = previous;
            step_controller.record_failure(previous.time, dt, failure.what());
          }
      }
    ++counters.steps;
    if (damped || parameters.tangent_update ==
                    Parameters::NonlinearSolver::TangentUpdate::every_step)
      assemble_state(!keeps_matrix(parameters));
    step_controller.record_success(current.time);
    return true;
  }



  // The explicit instantiations of this file's member functions.
#define SOFT_ROBOT_INSTANTIATE(dim)                                                   \
  template AssemblyResult SoftRobotDynamics<dim>::assemble_forces(                    \
    const TrilinosWrappers::MPI::Vector &,                                            \
    const TrilinosWrappers::MPI::Vector *,                                            \
    const AssemblyRequest &,                                                          \
    TrilinosWrappers::MPI::Vector &,                                                  \
    TrilinosWrappers::MPI::Vector *);                                                 \
  template AssemblyResult SoftRobotDynamics<dim>::assemble_internal_force(            \
    const TrilinosWrappers::MPI::Vector &,                                            \
    const bool,                                                                       \
    TrilinosWrappers::MPI::Vector &);                                                 \
  template AssemblyResult SoftRobotDynamics<dim>::assemble_state(const bool);         \
  template void           SoftRobotDynamics<dim>::add_global_damping_forces(          \
    const TrilinosWrappers::MPI::Vector &, TrilinosWrappers::MPI::Vector &) \
    const;                                                                            \
  template void SoftRobotDynamics<dim>::add_global_damping_matrices(                  \
    const double, TrilinosWrappers::SparseMatrix &) const;                            \
  template void SoftRobotDynamics<dim>::assemble_external_force(                      \
    const double, const double, TrilinosWrappers::MPI::Vector &) const;               \
  template void SoftRobotDynamics<dim>::evaluate_pneumatics(                          \
    const TrilinosWrappers::MPI::Vector &, const double, State &);                    \
  template void SoftRobotDynamics<dim>::prepare_linear_solver();                      \
  template NewtonSolver::Problem SoftRobotDynamics<dim>::newton_problem(              \
    const std::function<AssemblyResult(const TrilinosWrappers::MPI::Vector &,         \
                                       const bool,                                    \
                                       TrilinosWrappers::MPI::Vector &)> &);          \
  template void SoftRobotDynamics<dim>::solve_static_equilibrium(                     \
    const double);                                                                    \
  template void SoftRobotDynamics<dim>::compute_initial_acceleration();               \
  template void SoftRobotDynamics<dim>::initialize_state();                           \
  template AssemblyResult SoftRobotDynamics<dim>::evaluate_residual(                  \
    const TrilinosWrappers::MPI::Vector &,                                            \
    const double,                                                                     \
    const bool,                                                                       \
    TrilinosWrappers::MPI::Vector &);                                                 \
  template void SoftRobotDynamics<dim>::prepare_step_tangent(const double);           \
  template void SoftRobotDynamics<dim>::solve_nonlinear_timestep(                     \
    const double);                                                                    \
  template void SoftRobotDynamics<dim>::update_energies(                              \
    const AssemblyResult &);                                                          \
  template bool SoftRobotDynamics<dim>::advance_one_step();
  SOFT_ROBOT_FOR_EACH_DIMENSION(SOFT_ROBOT_INSTANTIATE)
#undef SOFT_ROBOT_INSTANTIATE
} // namespace SoftRobot
