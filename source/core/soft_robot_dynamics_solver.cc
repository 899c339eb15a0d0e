// @sect3{Solving: Newton's method, the linear solver, the time loop}
//
// This file holds the nonlinear and linear solvers of SoftRobotDynamics, the
// initial state (including a static equilibrium) and the time step with
// its automatic cut back.

#include <Amesos.h>
#include <Amesos_BaseSolver.h>
#include <Epetra_LinearProblem.h>
#include <Epetra_MultiVector.h>
#include <Teuchos_ParameterList.hpp>
#include <ml_MultiLevelPreconditioner.h>
#include <cmath>
#include <cstdlib>
#include <cxxabi.h>
#include <deque>
#include <core/soft_robot_dynamics.h>
#include <deal.II/base/function_parser.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/solver_gmres.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_solver.h>
#include <deal.II/numerics/vector_tools.h>
#include <sstream>
#include <typeinfo>

namespace SoftRobot
{
  namespace
  {
    // ML's preconditioner object behind deal.II's wrapper, whose hierarchy
    // prepare_linear_solver() recomputes and measures.
    ML_Epetra::MultiLevelPreconditioner &
    multilevel_preconditioner(const TrilinosWrappers::PreconditionAMG &amg)
    {
      return dynamic_cast<ML_Epetra::MultiLevelPreconditioner &>(
        const_cast<Epetra_Operator &>(amg.trilinos_operator()));
    }
  } // namespace



  // @sect4{SoftRobotDynamics::evaluate_residual}
  //
  // The HHT residual for a trial displacement $\mathbf u_{n+1}$:
  // velocity and acceleration follow from Newmark's relations, and
  // @f[
  //   \mathbf r = \mathbf M\mathbf a_{n+1}
  //   + (1+\alpha)\left[\mathbf f_\text{int}(\mathbf u_{n+1})
  //     + \mathbf C\mathbf v_{n+1} - \mathbf f_\text{ext}(t_{n+1})\right]
  //   - \alpha\left[\mathbf f_\text{int}(\mathbf u_n) + \mathbf C\mathbf v_n
  //     - \mathbf f_\text{ext}(t_n)\right],
  // @f]
  // with the damping matrix $\mathbf C$ of the step. Its derivative, the
  // effective tangent, is $\mathbf M/(\beta\Delta t^2) + (1+\alpha)(\mathbf K
  // + c_v\mathbf C)$ with $c_v = \gamma/(\beta\Delta t)$. The trial's
  // velocity, acceleration and forces are left in `current`.
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
    // Newton's method proper assembles the damping matrix of every iterate
    // (the last one's is the next step's); the modified one assembles it
    // at the end of the step only, so a matrix here is only a new tangent.
    const bool every_iteration =
      (parameters.tangent_update !=
       Parameters::NonlinearSolver::TangentUpdate::every_step);
    AssemblyResult assembly    = assemble_internal_force(u_trial,
                                                      with_matrix,
                                                      current.internal_force,
                                                      every_iteration);
    if (with_matrix)
      system_matrix_is_state_stiffness = false;
    if (has_damping)
      damping_matrix.vmult(current.damping_force, current.v);
    else
      current.damping_force = 0.;

    const double w = stepper.new_force_weight();
    mass.vmult(residual, current.a);
    assembly.force_scale =
      std::max(residual.l2_norm(), current.internal_force.l2_norm());
    residual.add(w, current.internal_force, w, current.damping_force);
    residual.add(-w, current.external_force);
    residual.add(1. - w,
                 previous.internal_force,
                 1. - w,
                 previous.damping_force);
    residual.add(w - 1., previous.external_force);
    constraints.set_zero(residual);

    if (with_matrix)
      {
        system_matrix *= w;
        if (has_damping)
          system_matrix.add(w * stepper.velocity_coefficient(dt),
                            damping_matrix);
        system_matrix.add(stepper.acceleration_coefficient(dt), mass);
      }
    return assembly;
  }



  // @sect4{SoftRobotDynamics::newton_solve}
  //
  // Newton's method with a backtracking line search, shared by the time
  // steps and the static equilibrium. The line search accepts a step that
  // lowers the residual norm or, in static problems, the total potential
  // energy: equilibrium is its minimum, and the residual norm alone is a
  // poor guide when a slender body rotates far; near the solution, where
  // energy differences drown in round-off, the residual decides.
  // `evaluate` computes the residual, and the tangent if asked, at a trial
  // displacement. The iteration has converged when the residual is below
  // the absolute tolerance, or below the relative tolerance times a force
  // scale: the largest of the external forces, the forces that balance in
  // the residual (internal and inertial), and the first residual. The
  // forces set the level of round-off, so a relative tolerance of
  // $10^{-12}$ is attainable however small the motion; the iteration also
  // stops when the update is at round-off level relative to the
  // displacement. Every failure -- too many iterations, a linear solver
  // that does not converge, a non-finite residual, an inverted element that
  // the line search cannot avoid -- throws StepFailure, and the caller
  // decides what to do.
  //
  // In the modified variant the matrix prepared by the caller (the tangent
  // of the last converged state) serves all iterations, and the
  // evaluations compute residuals only: they need first derivatives of the
  // energy instead of second ones, and no factorization. The price is
  // linear instead of quadratic convergence, at a rate given by how much
  // the tangent changes within the step -- for a time step that resolves
  // the motion, a factor of about 5 to 10 per iteration on the bellows,
  // whose geometric stiffness changes noticeably within a step. That is
  // still cheaper: an iteration with the old matrix costs a residual
  // assembly and a back substitution, a fifteenth of an iteration with a
  // new matrix. When an iteration reduces the residual by less than a
  // factor of two, when `Max iterations` iterations have used the same old
  // matrix, or when the line search fails with it, the tangent is rebuilt
  // at the current iterate. The modified variant is allowed twice the
  // iterations of the full one.
  //
  // The modified iterations are a fixed-point iteration $\mathbf u_{k+1} =
  // \mathbf u_k + \mathbf d_k$ with the update $\mathbf d_k = -\mathbf
  // K^{-1}\mathbf r(\mathbf u_k)$ of a fixed matrix, and Anderson
  // acceleration (Walker and Ni, SIAM J. Numer. Anal. 49, 2011) speeds up
  // such iterations cheaply: from the differences $\Delta\mathbf u_j$ of
  // the last $m$ iterates and $\Delta\mathbf d_j$ of their updates, the
  // coefficients $\gamma$ minimize $\|\mathbf d_k - \sum_j\gamma_j
  // \Delta\mathbf d_j\|$, and the step is $\mathbf d_k - \sum_j
  // \gamma_j(\Delta\mathbf u_j + \Delta\mathbf d_j)$. For a linear
  // problem this is GMRES on the preconditioned system in disguise; here
  // it learns, from the iterates, how the tangent has changed since the
  // matrix was built. The step is tried first; if it does not lower the
  // residual, the plain update (with the line search) is taken and the
  // history is dropped, as it is whenever the matrix changes. $m$ is the
  // parameter `Acceleration depth`; zero turns it off.
  template <int dim>
  AssemblyResult
  SoftRobotDynamics<dim>::newton_solve(TrilinosWrappers::MPI::Vector &u,
                                       const ResidualEvaluator       &evaluate,
                                       const double  force_scale,
                                       unsigned int &iterations,
                                       const bool    modified)
  {
    TrilinosWrappers::MPI::Vector residual(locally_owned_dofs,
                                           mpi_communicator);
    TrilinosWrappers::MPI::Vector trial_residual(residual), update(residual),
      trial(residual);

    // Anderson acceleration of the modified iterations: the differences of
    // the iterates and of their updates since the matrix last changed, the
    // last iterate and update, and the accelerated step.
    const unsigned int depth =
      modified ? parameters.acceleration_depth : 0;
    std::deque<TrilinosWrappers::MPI::Vector> iterate_differences,
      update_differences;
    TrilinosWrappers::MPI::Vector last_iterate(residual), last_update(residual),
      accelerated(residual);
    bool have_last_update = false;
    const auto forget_history = [&]() {
      iterate_differences.clear();
      update_differences.clear();
      have_last_update = false;
    };

    AssemblyResult assembly = evaluate(u, !modified, residual);
    if (assembly.inverted_point_found)
      throw StepFailure(
        "the predicted state has an inverted element (det F = " +
        std::to_string(assembly.min_jacobian) + ")");
    double norm      = residual.l2_norm();
    double reference = std::max({force_scale, norm, assembly.force_scale});
    const double initial_force_scale = reference;
    double potential_energy = assembly.potential_energy;
    // In the modified variant: whether the prepared matrix is the tangent
    // at the current iterate, and whether it must become so.
    bool         tangent_is_current      = !modified;
    bool         rebuild_tangent         = false;
    unsigned int iterations_with_tangent = 0;

    for (iterations = 0;; ++iterations)
      {
        if (!std::isfinite(norm))
          throw StepFailure("the residual is not finite");
        // The force scale follows the iterates, but an iterate whose forces
        // are a thousand times those the step started from is not a state
        // the step can reach: the iteration has run away (in the undamped
        // release of the stability study, into a state with 1e16 times the
        // strain energy, where any residual passed the relative test).
        if (assembly.force_scale > 1e3 * initial_force_scale)
          throw StepFailure("the iteration ran away (forces " +
                            std::to_string(assembly.force_scale) +
                            " against " + std::to_string(initial_force_scale) +
                            " at its start)");
        reference = std::max(reference, assembly.force_scale);
        if (norm <= parameters.newton_absolute_tolerance ||
            norm <= parameters.newton_relative_tolerance * reference)
          break;
        // The modified variant may take twice as many (cheaper) iterations.
        if (iterations == (modified ? 2 : 1) *
                            parameters.newton_max_iterations)
          {
            std::ostringstream message;
            message << "Newton's method did not converge in " << iterations
                    << " iterations (residual " << norm << ")";
            throw StepFailure(message.str());
          }

        if (modified && rebuild_tangent)
          {
            assembly = evaluate(u, true, residual);
            prepare_linear_solver(system_matrix);
            tangent_is_current = true;
            rebuild_tangent    = false;
            forget_history();
          }
        else if (!modified)
          prepare_linear_solver(system_matrix);
        // The forces of the current iterate; a rejected trial must not
        // stand for it in the tests above.
        const AssemblyResult assembly_at_iterate = assembly;
        residual *= -1.;
        const unsigned int linear_iterations =
          solve_prepared_system(residual, update);
        total_linear_iterations += linear_iterations;
        if (update.linfty_norm() <= 1e-14 * u.linfty_norm())
          break;

        const bool accelerate =
          (depth > 0) && anderson_step(u,
                                       update,
                                       depth,
                                       have_last_update,
                                       last_iterate,
                                       last_update,
                                       iterate_differences,
                                       update_differences,
                                       accelerated);
        bool accelerated_step_taken = false;
        if (accelerate)
          {
            trial = u;
            trial += accelerated;
            assembly   = evaluate(trial, false, trial_residual);
            const double accelerated_norm = trial_residual.l2_norm();
            if (!assembly.inverted_point_found &&
                std::isfinite(accelerated_norm) && accelerated_norm < norm)
              accelerated_step_taken = true;
            else
              {
                // Not better: forget the history, keep this iterate and
                // its update as the start of a new one.
                iterate_differences.clear();
                update_differences.clear();
              }
          }

        // Backtracking: the full step is taken if it lowers the residual;
        // otherwise it is halved. Without line search only a state that
        // is physically valid and finite is required. A direction from an
        // old matrix is not halved: if its full step does not lower the
        // residual, the matrix no longer describes the body well enough,
        // and the tangent is rebuilt at once. (Halving it cost up to six
        // residual assemblies; in the planar pendulum it happened in about
        // every third step, and a quarter of these searches failed
        // altogether. Without them the scene needs 7 % fewer residual
        // assemblies, and slightly fewer iterations and factorizations.)
        double             step_length = 1.;
        bool               accepted    = false;
        bool               trial_valid = false;
        double             trial_norm  = 0.;
        const double       old_norm    = norm;
        const unsigned int max_halvings =
          (parameters.line_search && (!modified || tangent_is_current)) ?
            parameters.max_line_search_steps :
            0;
        if (accelerated_step_taken)
          {
            accepted         = true;
            trial_valid      = true;
            u                = trial;
            residual         = trial_residual;
            norm             = trial_residual.l2_norm();
            potential_energy = assembly.potential_energy;
          }
        for (unsigned int halving = 0;
             !accelerated_step_taken && halving <= max_halvings;
             ++halving)
          {
            trial = u;
            trial.add(step_length, update);
            assembly   = evaluate(trial, !modified, trial_residual);
            trial_norm = trial_residual.l2_norm();
            trial_valid =
              !assembly.inverted_point_found && std::isfinite(trial_norm);
            const bool descent = trial_norm < norm ||
                                 (std::isfinite(assembly.potential_energy) &&
                                  assembly.potential_energy < potential_energy);
            if (trial_valid && (!parameters.line_search || descent))
              {
                accepted         = true;
                u                = trial;
                residual         = trial_residual;
                norm             = trial_norm;
                potential_energy = assembly.potential_energy;
                break;
              }
            step_length *= 0.5;
          }
        // Stagnation: no step lowers the residual, but it is already six
        // orders of magnitude below the forces that balance in it. This
        // happens when the tolerance asks for more digits than the
        // assembly's round-off leaves (the relative tolerance times the
        // force scale is then below it); the last trial state is accepted.
        if (!accepted && trial_valid && norm <= 1e-6 * reference)
          {
            u        = trial;
            residual = trial_residual;
            norm     = trial_norm;
            break;
          }
        if (parameters.verbose)
          pcout << "    Newton " << iterations << ": |r| = " << norm
                << " (scale " << reference << "), " << linear_iterations
                << " linear iterations, step length " << step_length
                << (accelerated_step_taken ? " (accelerated)" : "")
                << (modified && !tangent_is_current ? ", old tangent" : "")
                << std::endl;
        if (!accepted && modified && !tangent_is_current)
          {
            // The old matrix led nowhere: rebuild it here and try again.
            assembly        = assembly_at_iterate;
            rebuild_tangent = true;
            continue;
          }
        if (!accepted)
          throw StepFailure(
            "the line search found no admissible step (min det F = " +
            std::to_string(assembly.min_jacobian) + ")");
        if (modified)
          {
            if (tangent_is_current)
              iterations_with_tangent = 0;
            ++iterations_with_tangent;
            tangent_is_current = false;
            rebuild_tangent =
              (norm > 0.5 * old_norm) ||
              (iterations_with_tangent >=
               parameters.newton_max_iterations);
          }
      }
    last_residual = norm;
    return assembly;
  }



  // @sect4{SoftRobotDynamics::anderson_step}
  //
  // The accelerated step of newton_solve(): records the iterate $\mathbf
  // u_k$ and its update $\mathbf d_k$, and if there is a history, computes
  // $\mathbf d_k - \sum_j\gamma_j(\Delta\mathbf u_j + \Delta\mathbf
  // d_j)$ into `step` and returns true. The least-squares problem for
  // $\gamma$ is solved through its normal equations, which are at most
  // `depth` by `depth`: the Cholesky factorization of the Gram matrix of the
  // $\Delta\mathbf d_j$. When the differences are close to linearly
  // dependent (a pivot below $10^{-10}$ of its diagonal entry), the oldest
  // pair is dropped; round-off near convergence would otherwise make the
  // coefficients meaningless.
  template <int dim>
  bool
  SoftRobotDynamics<dim>::anderson_step(
    const TrilinosWrappers::MPI::Vector       &iterate,
    const TrilinosWrappers::MPI::Vector       &update,
    const unsigned int                         depth,
    bool                                      &have_last_update,
    TrilinosWrappers::MPI::Vector             &last_iterate,
    TrilinosWrappers::MPI::Vector             &last_update,
    std::deque<TrilinosWrappers::MPI::Vector> &iterate_differences,
    std::deque<TrilinosWrappers::MPI::Vector> &update_differences,
    TrilinosWrappers::MPI::Vector             &step) const
  {
    if (have_last_update)
      {
        iterate_differences.push_back(iterate);
        iterate_differences.back() -= last_iterate;
        update_differences.push_back(update);
        update_differences.back() -= last_update;
        if (update_differences.size() > depth)
          {
            iterate_differences.pop_front();
            update_differences.pop_front();
          }
      }
    last_iterate     = iterate;
    last_update      = update;
    have_last_update = true;

    while (!update_differences.empty())
      {
        const unsigned int m = update_differences.size();
        FullMatrix<double> gram(m, m);
        Vector<double>     gamma(m);
        for (unsigned int i = 0; i < m; ++i)
          {
            for (unsigned int j = 0; j <= i; ++j)
              gram(i, j) = update_differences[i] * update_differences[j];
            gamma(i) = update_differences[i] * update;
          }
        // Cholesky factorization G = L L^T in the lower triangle.
        bool well_conditioned = true;
        for (unsigned int j = 0; j < m && well_conditioned; ++j)
          {
            const double diagonal = gram(j, j);
            double       pivot    = diagonal;
            for (unsigned int k = 0; k < j; ++k)
              pivot -= gram(j, k) * gram(j, k);
            if (!(pivot > 1e-10 * diagonal))
              {
                well_conditioned = false;
                break;
              }
            gram(j, j) = std::sqrt(pivot);
            for (unsigned int i = j + 1; i < m; ++i)
              {
                double value = gram(i, j);
                for (unsigned int k = 0; k < j; ++k)
                  value -= gram(i, k) * gram(j, k);
                gram(i, j) = value / gram(j, j);
              }
          }
        if (!well_conditioned)
          {
            iterate_differences.pop_front();
            update_differences.pop_front();
            continue;
          }
        // Forward and backward substitution.
        for (unsigned int i = 0; i < m; ++i)
          {
            for (unsigned int k = 0; k < i; ++k)
              gamma(i) -= gram(i, k) * gamma(k);
            gamma(i) /= gram(i, i);
          }
        for (unsigned int i = m; i-- > 0;)
          {
            for (unsigned int k = i + 1; k < m; ++k)
              gamma(i) -= gram(k, i) * gamma(k);
            gamma(i) /= gram(i, i);
          }
        step = update;
        for (unsigned int j = 0; j < m; ++j)
          step.add(-gamma(j),
                   iterate_differences[j],
                   -gamma(j),
                   update_differences[j]);
        return true;
      }
    return false;
  }



  // @sect4{SoftRobotDynamics::solve_linear_system}
  //
  // CG (or GMRES) with Trilinos ML algebraic multigrid. ML is told that
  // the problem is elliptic and, for quadratic elements, that the matrix
  // comes from higher-order elements; its coarse spaces are built from the
  // rigid-body modes computed in setup_system(), passed through ML's own
  // parameter list because deal.II's interface takes only constant modes.
  // The sparse direct solvers (Amesos KLU, or MUMPS for larger problems)
  // are there for problems of up to some 10^5 unknowns and as a check.
  // Preparing -- the factorization, or the multigrid hierarchy -- is
  // separate from solving, so that the modified Newton method pays for it
  // once per step.
  template <int dim>
  unsigned int
  SoftRobotDynamics<dim>::solve_linear_system(
    TrilinosWrappers::SparseMatrix      &matrix,
    const TrilinosWrappers::MPI::Vector &rhs,
    TrilinosWrappers::MPI::Vector       &solution)
  {
    prepare_linear_solver(matrix);
    return solve_prepared_system(rhs, solution);
  }



  template <int dim>
  void
  SoftRobotDynamics<dim>::prepare_linear_solver(
    TrilinosWrappers::SparseMatrix &matrix)
  {
    ++total_tangent_updates;
    prepared_matrix = &matrix;
    if (parameters.linear_solver ==
        Parameters::LinearSolver::LinearSolverType::direct)
      {
        // The fill-reducing ordering depends only on the sparsity pattern,
        // which never changes: the symbolic analysis is done once per
        // matrix object, the numerical factorization for every new matrix.
        // (deal.II's SolverDirect repeats both every time, and it hands out
        // the Epetra matrix as const only, which the factorization reads.)
        // KLU also keeps the pivot sequence of its first factorization and
        // refactorizes the following matrices with it, which skips the
        // search for pivots: half the factorization's time on the coarse
        // bellows meshes, no gain at some 20,000 unknowns, where the
        // arithmetic dominates. When the old pivots give a poorly
        // conditioned factor (smallest over largest diagonal entry of U at
        // most 1e-12, Amesos' test), it factorizes with pivoting afresh.
        TimerOutput::Scope timer_section(computing_timer, "Factorization");
        Epetra_CrsMatrix &epetra_matrix =
          const_cast<Epetra_CrsMatrix &>(matrix.trilinos_matrix());
        if (analysed_matrix != &epetra_matrix)
          {
            direct_problem = std::make_unique<Epetra_LinearProblem>();
            direct_problem->SetOperator(&epetra_matrix);
            const std::string package =
              "Amesos_" + std::string(parameters.direct_solver ==
        Parameters::LinearSolver::DirectSolverType::mumps ?
                                        "Mumps" :
                                        "Klu");
            Amesos factory;
            direct_factorization.reset(
              factory.Create(package.c_str(), *direct_problem));
            AssertThrow(direct_factorization != nullptr,
                        ExcMessage("Trilinos has no " + package +
                                   " solver (Linear solver/Direct solver)."));
            if (parameters.direct_solver !=
        Parameters::LinearSolver::DirectSolverType::mumps)
              {
                Teuchos::ParameterList amesos_parameters;
                amesos_parameters.set("Refactorize", true);
                direct_factorization->SetParameters(amesos_parameters);
              }
            AssertThrow(direct_factorization->SymbolicFactorization() == 0,
                        ExcMessage(package +
                                   ": the symbolic factorization failed."));
            analysed_matrix = &epetra_matrix;
          }
        if (direct_factorization->NumericFactorization() != 0)
          throw StepFailure("the sparse factorization failed (singular "
                            "matrix?)");
      }
    else
      {
        TimerOutput::Scope timer_section(computing_timer,
                                         "Preconditioner setup");
        // ML's aggregates -- which unknowns each coarse unknown stands for
        // -- follow from the sparsity pattern, which never changes, and
        // from the strength of the couplings, which at the default
        // threshold counts nearly every coupling. After the first matrix
        // of a run, ML therefore recomputes the hierarchy on the aggregates
        // it has (ReComputePreconditioner()): the prolongators, coarse
        // matrices, smoothers and the coarse factorization come from the
        // new matrix, and only the aggregation is skipped, which on the
        // bellows takes a sixth to a quarter off a set-up's time
        // (doc/performance_discussion.md, item 25). ML would also keep the
        // old matrix's diagonal and the estimate of its largest eigenvalue,
        // which it caches with the finest level and does not clean there;
        // with them it smooths the prolongators and sets up the Chebyshev
        // smoother. They are cleared first (-666.666 is ML's mark for "not
        // computed"), so that the recomputed hierarchy comes from the new
        // matrix alone, on the old aggregates. (Without this,
        // CG diverges in the 1D run of tests/modified_newton.cc after four
        // time-step cut-backs in a row have multiplied the mass's share of
        // the matrix by 256.)
        if (amg_preconditioner != nullptr &&
            analysed_matrix == &matrix.trilinos_matrix())
          {
            auto &multilevel  = multilevel_preconditioner(*amg_preconditioner);
            ML   *ml          = const_cast<ML *>(multilevel.GetML());
            ML_Operator &fine = ml->Amat[ml->ML_finest_level];
            if (fine.diagonal != nullptr)
              ML_DVector_Destroy(&fine.diagonal);
            fine.diagonal   = nullptr;
            fine.lambda_max = -666.666;
            fine.lambda_min = -666.666;
            AssertThrow(multilevel.ReComputePreconditioner() == 0,
                        ExcMessage("ML could not recompute the multigrid "
                                   "hierarchy."));
            return;
          }
        TrilinosWrappers::PreconditionAMG::AdditionalData data;
        data.elliptic              = true;
        data.higher_order_elements = (parameters.degree > 1);
        data.smoother_sweeps       = parameters.smoother_sweeps;
        data.aggregation_threshold = parameters.aggregation_threshold;

        Teuchos::ParameterList              ml_parameters;
        std::unique_ptr<Epetra_MultiVector> constant_modes;
        data.set_parameters(ml_parameters,
                            constant_modes,
                            matrix.trilinos_matrix());
        // The near null space, one column per mode, in the layout of an
        // Epetra_MultiVector. ML keeps the pointer in its parameter list, so
        // the array lives as long as the hierarchy.
        const unsigned int n_local =
          matrix.trilinos_matrix().DomainMap().NumMyElements();
        amg_null_space.assign(rigid_body_modes.size() * n_local, 0.);
        for (unsigned int k = 0; k < rigid_body_modes.size(); ++k)
          std::copy(rigid_body_modes[k].begin(),
                    rigid_body_modes[k].end(),
                    amg_null_space.begin() + k * n_local);
        ml_parameters.set("null space: type", "pre-computed");
        ml_parameters.set("null space: dimension",
                          static_cast<int>(rigid_body_modes.size()));
        ml_parameters.set("null space: vectors", amg_null_space.data());
        amg_preconditioner =
          std::make_unique<TrilinosWrappers::PreconditionAMG>();
        amg_preconditioner->initialize(matrix, ml_parameters);
        analysed_matrix = &matrix.trilinos_matrix();

        // The hierarchy's size, for the run statistics: a CG iteration
        // applies every level's matrix, so its cost follows these nonzeros
        // (the aggregates, and with them this ratio, stay as long as the
        // matrix object; the recomputation above keeps them).
        ML *ml = const_cast<ML *>(
          multilevel_preconditioner(*amg_preconditioner).GetML());
        const int step =
          (ml->ML_coarsest_level >= ml->ML_finest_level ? 1 : -1);
        double all_levels = 0.;
        for (int level = ml->ML_finest_level;; level += step)
          {
            all_levels += ML_Operator_ComputeNumNzs(&ml->Amat[level]);
            if (level == ml->ML_coarsest_level)
              break;
          }
        amg_operator_complexity =
          Utilities::MPI::sum(all_levels, mpi_communicator) /
          static_cast<double>(matrix.n_nonzero_elements());
      }
  }



  template <int dim>
  unsigned int
  SoftRobotDynamics<dim>::solve_prepared_system(
    const TrilinosWrappers::MPI::Vector &rhs,
    TrilinosWrappers::MPI::Vector       &solution)
  {
    TimerOutput::Scope timer_section(computing_timer, "Linear solve");
    Assert(prepared_matrix != nullptr, ExcInternalError());
    solution                = 0.;
    unsigned int iterations = 1;
    try
      {
        if (parameters.linear_solver ==
        Parameters::LinearSolver::LinearSolverType::direct)
          {
            direct_problem->SetLHS(&solution.trilinos_vector());
            direct_problem->SetRHS(const_cast<Epetra_MultiVector *>(
              &rhs.trilinos_vector()));
            AssertThrow(direct_factorization->Solve() == 0,
                        ExcMessage("The direct solver's triangular solves "
                                   "failed."));
          }
        else
          {
            SolverControl control(parameters.linear_max_iterations,
                                  parameters.linear_relative_tolerance *
                                    rhs.l2_norm());
            if (parameters.linear_solver ==
                Parameters::LinearSolver::LinearSolverType::cg)
              {
                SolverCG<TrilinosWrappers::MPI::Vector> solver(control);
                solver.solve(*prepared_matrix,
                             solution,
                             rhs,
                             *amg_preconditioner);
              }
            else
              {
                SolverGMRES<TrilinosWrappers::MPI::Vector> solver(control);
                solver.solve(*prepared_matrix,
                             solution,
                             rhs,
                             *amg_preconditioner);
              }
            iterations = control.last_step();
          }
      }
    catch (SolverControl::NoConvergence &failure)
      {
        std::ostringstream message;
        message << "the linear solver did not converge in " << failure.last_step
                << " iterations (residual " << failure.last_residual << ")";
        throw StepFailure(message.str());
      }
    constraints.set_zero(solution);
    return iterations;
  }



  template <int dim>
  std::string
  SoftRobotDynamics<dim>::linear_solver_in_use() const
  {
    if (parameters.linear_solver !=
        Parameters::LinearSolver::LinearSolverType::direct)
      return amg_preconditioner ? Parameters::name_of(parameters.linear_solver) + " with ML" :
                                  "";
    if (!direct_factorization)
      return "";
    // The dynamic type of the object Amesos' factory created.
    const Amesos_BaseSolver &solver = *direct_factorization;
    int                      status = 0;
    char *name = abi::__cxa_demangle(typeid(solver).name(), nullptr, nullptr,
                                     &status);
    const std::string result =
      (status == 0 && name != nullptr) ? name : typeid(solver).name();
    std::free(name);
    return result;
  }



  // @sect4{SoftRobotDynamics::solve_static_equilibrium}
  //
  // The equilibrium $\mathbf f_\text{int}(\mathbf u, \mathbf 0) =
  // \lambda_g\mathbf f_g + \lambda_t\mathbf f_t(t)$ under gravity
  // $\mathbf f_g$ and the tractions $\mathbf f_t$, reached in two phases of
  // equal load steps: first the gravity factor $\lambda_g$ rises to one,
  // then the traction factor $\lambda_t$. The order matters for a hanging
  // body pushed sideways: under its weight it has the lateral (pendulum)
  // stiffness of gravity, which the unloaded body lacks, and Newton's method
  // started from the unloaded state would take a first step far beyond the
  // equilibrium. A load step whose Newton iteration fails is halved.
  template <int dim>
  void
  SoftRobotDynamics<dim>::solve_static_equilibrium(const double time)
  {
    TrilinosWrappers::MPI::Vector traction_force(locally_owned_dofs,
                                                 mpi_communicator);
    assemble_external_force(time, 1., traction_force);
    traction_force -= gravity_force;
    const bool has_gravity  = gravity_force.l2_norm() > 0.;
    const bool has_traction = traction_force.l2_norm() > 0.;

    TrilinosWrappers::MPI::Vector external(traction_force);
    TrilinosWrappers::MPI::Vector internal(traction_force);
    // The combined load parameter runs from 0 to 2: gravity factor
    // min(lambda, 1), traction factor max(lambda - 1, 0).
    double       load = has_gravity ? 0. : 1.;
    const double end  = has_traction ? 2. : 1.;
    double       increment   = 1. / parameters.load_steps;
    unsigned int iterations  = 0;
    while (load < end - 1e-12)
      {
        const double phase_end = (load < 1. - 1e-12) ? 1. : 2.;
        const double target    = std::min(phase_end, load + increment);
        external               = 0.;
        external.add(std::min(target, 1.), gravity_force);
        external.add(std::max(target - 1., 0.), traction_force);
        const ResidualEvaluator static_residual =
          [&](const TrilinosWrappers::MPI::Vector &u,
              const bool                           with_matrix,
              TrilinosWrappers::MPI::Vector       &r) {
            AssemblyResult assembly =
              assemble_internal_force(u, with_matrix, internal, false);
            system_matrix_is_state_stiffness = false;
            r = internal;
            r -= external;
            assembly.force_scale      = internal.l2_norm();
            assembly.potential_energy = assembly.strain_energy - external * u;
            constraints.set_zero(r);
            return assembly;
          };
        const TrilinosWrappers::MPI::Vector saved = current.u;
        try
          {
            newton_solve(current.u,
                         static_residual,
                         external.l2_norm(),
                         iterations);
            total_newton_iterations += iterations;
            load = target;
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
          << last_residual << ")" << std::endl;
  }



  // @sect4{SoftRobotDynamics::compute_initial_acceleration}
  //
  // The HHT method needs $\mathbf a_0$, which the equation of motion at
  // $t=0$ determines: $\mathbf M\mathbf a_0 = \mathbf f_\text{ext}(0) -
  // \mathbf f_\text{int}(\mathbf u_0, \mathbf v_0)$.
  template <int dim>
  void
  SoftRobotDynamics<dim>::compute_initial_acceleration()
  {
    const AssemblyResult assembly =
      assemble_internal_force(current.u, true, current.internal_force);
    system_matrix_is_state_stiffness = true;
    if (has_damping)
      {
        damping_matrix.copy_from(next_damping_matrix);
        damping_matrix.vmult(current.damping_force, current.v);
      }
    else
      current.damping_force = 0.;
    if (assembly.inverted_point_found)
      throw RunAborted("The initial displacement inverts elements (det F = " +
                       std::to_string(assembly.min_jacobian) + ").");
    energy.strain = assembly.strain_energy;

    TrilinosWrappers::MPI::Vector rhs(current.external_force);
    rhs -= current.internal_force;
    rhs -= current.damping_force;
    constraints.set_zero(rhs);
    SolverControl control(1000, 1e-12 * std::max(rhs.l2_norm(), 1e-300));
    SolverCG<TrilinosWrappers::MPI::Vector> solver(control);
    TrilinosWrappers::PreconditionJacobi    jacobi;
    jacobi.initialize(mass);
    current.a = 0.;
    if (rhs.l2_norm() > 0)
      solver.solve(mass, current.a, rhs, jacobi);
    constraints.set_zero(current.a);
  }



  // @sect4{SoftRobotDynamics::initialize_state}
  //
  // Displacement and velocity from the parameter file's expressions (or
  // the static equilibrium), the forces at $t=0$, the initial acceleration
  // and the energies the balance is measured against.
  template <int dim>
  void
  SoftRobotDynamics<dim>::initialize_state()
  {
    TimerOutput::Scope timer_section(computing_timer, "Initial state");
    current.time = 0.;
    older_stiffness.reset();
    newer_stiffness.reset();
    older_stiffness_time = -std::numeric_limits<double>::max();
    newer_stiffness_time = -std::numeric_limits<double>::max();
    VectorTools::interpolate(*mapping,
                             dof_handler,
                             initial_displacement,
                             current.u);
    VectorTools::interpolate(*mapping,
                             dof_handler,
                             initial_velocity,
                             current.v);
    constraints.set_zero(current.u);
    constraints.set_zero(current.v);

    if (parameters.initial_state ==
        Parameters::InitialConditions::InitialState::static_equilibrium)
      solve_static_equilibrium(0.);

    assemble_external_force(0., 1., current.external_force);
    compute_initial_acceleration();

    energy.kinetic             = 0.5 * mass.matrix_norm_square(current.v);
    energy.gravity_potential   = -(gravity_force * current.u);
    energy.traction_work       = 0.;
    energy.damping_dissipation = 0.;
    // The forces of the equation at t = 0, the first terms of the work and
    // dissipation sums (see update_energies()).
    hht_damping_force  = current.damping_force;
    hht_traction_force = current.external_force;
    hht_traction_force -= gravity_force;
    initial_total_energy =
      energy.kinetic + energy.strain + energy.gravity_potential;
    step_number = 0;
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

    const bool modified = (parameters.tangent_update ==
      Parameters::NonlinearSolver::TangentUpdate::every_step);
    if (modified)
      prepare_step_tangent(dt);

    const ResidualEvaluator hht_residual =
      [&](const TrilinosWrappers::MPI::Vector &u,
          const bool                           with_matrix,
          TrilinosWrappers::MPI::Vector       &r) {
        return evaluate_residual(u, dt, with_matrix, r);
      };
    unsigned int         iterations = 0;
    const AssemblyResult assembly   = newton_solve(current.u,
                                                 hht_residual,
                                                 current.external_force.l2_norm(),
                                                 iterations,
                                                 modified);
    last_newton_iterations = iterations;
    total_newton_iterations += iterations;
    update_energies(assembly);
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
  // The iterations converge at a rate set by how far $\tilde{\mathbf K}$
  // is from the stiffness at the end of the step, $\mathbf K_{n+1}$, which
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
    if (!system_matrix_is_state_stiffness)
      {
        TrilinosWrappers::MPI::Vector force(locally_owned_dofs,
                                            mpi_communicator);
        assemble_internal_force(previous.u, true, force, false);
      }
    if (parameters.tangent_extrapolation)
      {
        if (newer_stiffness_time != previous.time)
          {
            std::swap(older_stiffness, newer_stiffness);
            std::swap(older_stiffness_time, newer_stiffness_time);
            if (!newer_stiffness)
              newer_stiffness =
                std::make_unique<TrilinosWrappers::SparseMatrix>();
            newer_stiffness->copy_from(system_matrix);
            newer_stiffness_time = previous.time;
          }
        if (older_stiffness && older_stiffness_time < previous.time)
          {
            const double theta = dt / (previous.time - older_stiffness_time);
            system_matrix *= 1. + theta;
            system_matrix.add(-theta, *older_stiffness);
          }
      }
    const double w = stepper.new_force_weight();
    system_matrix *= w;
    if (has_damping)
      system_matrix.add(w * stepper.velocity_coefficient(dt), damping_matrix);
    system_matrix.add(stepper.acceleration_coefficient(dt), mass);
    system_matrix_is_state_stiffness = false;
    prepare_linear_solver(system_matrix);
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
  // f}_{\text{d},n+1})$ and $\Delta W$ alike. What the balance $\mathcal B
  // = T + \Pi + V_g - W + D - (T + \Pi + V_g)_0$ then collects is $\Delta
  // T - \Delta\mathbf u\cdot\mathbf M\tfrac12(\mathbf a_n + \mathbf
  // a_{n+1})$ and $\Delta\Pi - \Delta\mathbf u\cdot\tfrac12(\tilde{\mathbf
  // f}_{\text{int},n} + \tilde{\mathbf f}_{\text{int},n+1})$ summed over the
  // steps: the algorithmic dissipation of the scheme, from its Newmark
  // parameters and from the shifted internal force, and nothing else. For
  // $\alpha = 0$ the weights are the trapezoidal rule's, and for the
  // trapezoidal rule on a linear problem both parts vanish. (Gravity is
  // constant; its work is the change of $V_g$ exactly.)
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
    traction_force -= gravity_force;

    energy.kinetic           = 0.5 * mass.matrix_norm_square(current.v);
    energy.strain            = assembly.strain_energy;
    energy.gravity_potential = -(gravity_force * current.u);
    energy.traction_work +=
      0.5 * (increment * traction_force + increment * hht_traction_force);
    energy.damping_dissipation +=
      0.5 * (increment * damping_force + increment * hht_damping_force);
    hht_damping_force  = damping_force;
    hht_traction_force = traction_force;
  }



  // @sect4{SoftRobotDynamics::advance_one_step}
  //
  // One step of the time loop with automatic step-size control: a failed
  // step is repeated with half the time step, down to the minimum; after
  // `Regrowth steps` successful steps the step is doubled again, but only
  // at times that are multiples of the doubled step, so that the steps
  // return to the nominal grid $t_n = n\,\Delta t$ (which the spectral
  // analysis of the tip motion prefers). Returns false at the end time.
  template <int dim>
  bool
  SoftRobotDynamics<dim>::advance_one_step()
  {
    const double end_time  = parameters.end_time;
    const double tolerance = 1e-9 * parameters.time_step;
    if (current.time >= end_time - tolerance)
      return false;

    // The damping forces of the old state with this step's damping matrix,
    // so that the damping is linear within the step.
    previous = current;
    if (has_damping)
      damping_matrix.vmult(previous.damping_force, previous.v);
    while (true)
      {
        const double dt = std::min(time_step, end_time - previous.time);
        try
          {
            solve_nonlinear_timestep(dt);
            break;
          }
        catch (StepFailure &failure)
          {
            current = previous;
            time_step *= 0.5;
            ++total_cutbacks;
            steps_since_cutback = 0;
            pcout << "  step at t = " << previous.time + dt << " failed ("
                  << failure.what() << "); time step cut back to " << time_step
                  << " s" << std::endl;
            if (total_cutbacks > parameters.max_cutbacks)
              {
                std::ostringstream message;
                message << "More than " << parameters.max_cutbacks
                        << " time-step cut backs (Time integration/Max "
                           "cutbacks), the last at t = "
                        << previous.time << " s with dt = " << dt
                        << " s: " << failure.what()
                        << ". The motion cannot be followed with this mesh "
                           "and time step. The output up to this time has "
                           "been kept.";
                throw RunAborted(message.str());
              }
            if (time_step < parameters.minimum_time_step)
              {
                std::ostringstream message;
                message << "The time step fell below the minimum of "
                        << parameters.minimum_time_step
                        << " s at t = " << previous.time
                        << " s: " << failure.what()
                        << ". The output up to this time has been kept.";
                throw RunAborted(message.str());
              }
          }
      }
    ++step_number;
    // The damping matrix of the converged state is the next step's. Newton's
    // method proper assembled it in its last iteration; the modified one
    // assembled residuals only, and the stiffness and damping of the new
    // state are assembled here, once per step (the stiffness is the next
    // step's matrix).
    if (parameters.tangent_update ==
      Parameters::NonlinearSolver::TangentUpdate::every_step)
      {
        assemble_internal_force(current.u, true, current.internal_force);
        system_matrix_is_state_stiffness = true;
      }
    if (has_damping)
      damping_matrix.copy_from(next_damping_matrix);

    ++steps_since_cutback;
    if (time_step < parameters.time_step &&
        steps_since_cutback >= parameters.regrowth_steps)
      {
        const double doubled = 2. * time_step;
        const double n       = current.time / doubled;
        if (std::abs(n - std::round(n)) < 1e-6)
          {
            time_step           = std::min(doubled, parameters.time_step);
            steps_since_cutback = 0;
          }
      }
    return true;
  }



  // @sect4{SoftRobotDynamics::tangent_stiffness_matrix}
  template <int dim>
  const TrilinosWrappers::SparseMatrix &
  SoftRobotDynamics<dim>::tangent_stiffness_matrix()
  {
    TrilinosWrappers::MPI::Vector force(locally_owned_dofs, mpi_communicator);
    assemble_internal_force(current.u, true, force);
    system_matrix_is_state_stiffness = true;
    return system_matrix;
  }



  template <int dim>
  const TrilinosWrappers::SparseMatrix &
  SoftRobotDynamics<dim>::tangent_stiffness_matrix(
    const TrilinosWrappers::MPI::Vector &u)
  {
    TrilinosWrappers::MPI::Vector force(locally_owned_dofs, mpi_communicator);
    assemble_internal_force(u, true, force, false);
    // (The matrix is not that of the current state, and the damping matrix
    // of the state is left as it is.)
    system_matrix_is_state_stiffness = false;
    return system_matrix;
  }



  template <int dim>
  double
  SoftRobotDynamics<dim>::internal_force(const TrilinosWrappers::MPI::Vector &u,
                                         TrilinosWrappers::MPI::Vector &force)
  {
    return assemble_internal_force(u, false, force).strain_energy;
  }



#define SOFT_ROBOT_INSTANTIATE(dim)                                           \
  template AssemblyResult SoftRobotDynamics< \
    dim>::evaluate_residual(const TrilinosWrappers::MPI::Vector &,            \
                            const double,                                     \
                            const bool,                                       \
                            TrilinosWrappers::MPI::Vector &);                 \
  template AssemblyResult                    \
  SoftRobotDynamics<dim>::newton_solve(TrilinosWrappers::MPI::Vector &,       \
                                       const ResidualEvaluator &,             \
                                       const double,                          \
                                       unsigned int &,                        \
                                       const bool);                           \
  template void SoftRobotDynamics<dim>::prepare_linear_solver(               \
    TrilinosWrappers::SparseMatrix &);                                        \
  template unsigned int SoftRobotDynamics<dim>::solve_prepared_system(        \
    const TrilinosWrappers::MPI::Vector &, TrilinosWrappers::MPI::Vector &);  \
  template void SoftRobotDynamics<dim>::prepare_step_tangent(const double);   \
  template std::string SoftRobotDynamics<dim>::linear_solver_in_use() const; \
  template unsigned int SoftRobotDynamics<dim>::solve_linear_system(          \
    TrilinosWrappers::SparseMatrix &,                                         \
    const TrilinosWrappers::MPI::Vector &,                                    \
    TrilinosWrappers::MPI::Vector &);                                         \
  template void SoftRobotDynamics<dim>::solve_static_equilibrium(             \
    const double);                                                            \
  template void SoftRobotDynamics<dim>::compute_initial_acceleration();       \
  template void SoftRobotDynamics<dim>::initialize_state();                   \
  template void SoftRobotDynamics<dim>::solve_nonlinear_timestep(             \
    const double);                                                            \
  template void SoftRobotDynamics<dim>::update_energies(                      \
    const AssemblyResult &);                                                  \
  template bool SoftRobotDynamics<dim>::advance_one_step();                   \
  template const TrilinosWrappers::SparseMatrix &                             \
  SoftRobotDynamics<dim>::tangent_stiffness_matrix();                         \
  template const TrilinosWrappers::SparseMatrix &                             \
  SoftRobotDynamics<dim>::tangent_stiffness_matrix(                           \
    const TrilinosWrappers::MPI::Vector &);                                   \
  template double SoftRobotDynamics<dim>::internal_force(                     \
    const TrilinosWrappers::MPI::Vector &, TrilinosWrappers::MPI::Vector &);

  SOFT_ROBOT_INSTANTIATE(1)
  SOFT_ROBOT_INSTANTIATE(2)
  SOFT_ROBOT_INSTANTIATE(3)
#undef SOFT_ROBOT_INSTANTIATE
} // namespace SoftRobot
