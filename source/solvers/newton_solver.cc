// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Implementation of NewtonSolver}
//
// The iteration of solve() and its pieces: the tests at the top of every
// iteration, the matrix of the iteration, the accelerated trial, the line
// search, the acceptance of a stagnated iteration, and the decision to
// rebuild the matrix of the modified variant. See
// include/solvers/newton_solver.h for the method as a whole.
//
// Why the modified variant pays: its evaluations compute residuals only,
// which need first derivatives of the energy instead of second ones, and
// no factorization. The price is linear instead of quadratic convergence,
// at a rate given by how much the tangent changes within the step -- for a
// time step that resolves the motion, a factor of about 5 to 10 per
// iteration on the bellows, whose geometric stiffness changes noticeably
// within a step. That is still cheaper: an iteration with the old matrix
// costs a residual assembly and a back substitution, a fifteenth of an
// iteration with a new matrix. The rules for rebuilding it (see
// schedule_tangent_update() and solve()) keep the rate from falling far
// below that.

#include <algorithm>
#include <cmath>
#include <core/exceptions.h>
#include <deal.II/base/exceptions.h>
#include <limits>
#include <solvers/anderson_acceleration.h>
#include <solvers/newton_solver.h>
#include <sstream>
#include <string>

namespace SoftRobot
{
  // @sect4{NewtonSolver::IterationState}
  //
  // What the iterations of one solve() share. The vectors have the layout
  // of the unknowns (the locally owned entries, without ghosts). The norm
  // of the residual and the potential energy are those of the current
  // iterate; `reference` is the force scale of the convergence test, which
  // follows the iterates, and `initial_force_scale` the one the solve
  // started from. In the modified variant, `tangent_is_current` says
  // whether the prepared matrix is the tangent at the current iterate (it
  // is not, at the start: the caller's matrix belongs to the last converged
  // state), and `rebuild_tangent` whether it must become so in the next
  // iteration. The step length, the validity and the residual norm of the
  // last trial of the line search are kept for the acceptance of a
  // stagnated iteration and for the output.
  struct NewtonSolver::IterationState
  {
    IterationState(const TrilinosWrappers::MPI::Vector &u,
                   const bool                           modified,
                   const unsigned int                   acceleration_depth)
      : modified(modified)
      , residual(u.locally_owned_elements(), u.get_mpi_communicator())
      , trial_residual(residual)
      , update(residual)
      , trial(residual)
      , accelerated(residual)
      , anderson(acceleration_depth)
      , tangent_is_current(!modified)
    {
    }

    const bool modified;

    TrilinosWrappers::MPI::Vector residual;
    TrilinosWrappers::MPI::Vector trial_residual;
    TrilinosWrappers::MPI::Vector update;
    TrilinosWrappers::MPI::Vector trial;
    TrilinosWrappers::MPI::Vector accelerated;
    AndersonAcceleration          anderson;

    AssemblyResult assembly;
    double         norm                = 0.;
    double         reference           = 0.;
    double         initial_force_scale = 0.;
    double         potential_energy = std::numeric_limits<double>::quiet_NaN();

    bool         tangent_is_current;
    bool         rebuild_tangent         = false;
    unsigned int iterations_with_tangent = 0;

    unsigned int iterations        = 0;
    unsigned int linear_iterations = 0;

    double step_length = 1.;
    bool   trial_valid = false;
    double trial_norm  = 0.;
  };



  NewtonSolver::NewtonSolver(const Parameters::NonlinearSolver &parameters,
                             const ConditionalOStream          &pcout)
    : parameters(parameters)
    , pcout(pcout)
  {
    AssertThrow(parameters.newton_max_iterations > 0,
                ExcMessage("Nonlinear solver/Max iterations must be at "
                           "least 1."));
  }



  // @sect4{NewtonSolver::solve}
  //
  // The iteration itself. The first evaluation is at the caller's starting
  // point (the predictor of a time step, the last load step's state), with
  // the tangent in Newton's method proper; a starting point with an
  // inverted element is not a state to start from. Its residual and forces
  // set the first force scale.
  //
  // Every iteration then tests for convergence, prepares its matrix,
  // solves for the update $\mathbf d_k = -\mathbf K^{-1}\mathbf r(\mathbf
  // u_k)$, and moves to a new iterate: the accelerated one if it is better,
  // otherwise one along $\mathbf d_k$ found by the line search. When no
  // step is admissible, the iteration either stops because the residual is
  // at round-off level already, or, in the modified variant with an old
  // matrix, rebuilds the matrix at the same iterate and tries again (the
  // forces of the iterate, not of the rejected trial, then stand for it),
  // or fails.
  NewtonSolver::Result
  NewtonSolver::solve(TrilinosWrappers::MPI::Vector &u,
                      const Problem                 &problem,
                      const double                   force_scale,
                      const bool                     modified) const
  {
    AssertThrow(problem.evaluate && problem.prepare_tangent && problem.solve,
                ExcMessage("NewtonSolver::solve() needs all three functions "
                           "of its Problem."));
    IterationState state(u,
                         modified,
                         modified ? parameters.acceleration_depth : 0);

    state.assembly = problem.evaluate(u, !modified, state.residual);
    if (state.assembly.inverted_point_found)
      throw StepFailure(
        "the predicted state has an inverted element (det F = " +
        std::to_string(state.assembly.min_jacobian) + ")");
    state.norm = state.residual.l2_norm();
    state.reference =
      std::max({force_scale, state.norm, state.assembly.force_scale});
    state.initial_force_scale = state.reference;
    state.potential_energy    = state.assembly.potential_energy;

    for (state.iterations = 0;; ++state.iterations)
      {
        if (converged(state))
          break;
        prepare_matrix(u, state, problem);
        const AssemblyResult assembly_at_iterate = state.assembly;

        // The update solves $\mathbf K\mathbf d_k = -\mathbf r_k$; the
        // residual vector serves as the right-hand side (an accepted step
        // replaces it, a rebuild evaluates it again). An update at round-off
        // level relative to the displacement cannot improve it any further.
        // (That is the case where the matrix is stiff against a residual at
        // round-off level, as in tests/modified_newton.cc; it relies on the
        // linear solver's own test being on the true residual, see
        // LinearSolver::solve_iterative().)
        state.residual *= -1.;
        const unsigned int linear_iterations =
          problem.solve(state.residual, state.update);
        state.linear_iterations += linear_iterations;
        if (state.update.linfty_norm() <= 1e-14 * u.linfty_norm())
          break;

        // The new iterate: the accelerated one, or one of the line search,
        // or, at round-off level, the last trial.
        const double previous_norm = state.norm;
        const bool   accelerated   = try_accelerated_step(u, state, problem);
        const bool   accepted = accelerated || line_search(u, state, problem);
        if (!accepted && accept_stagnated_trial(u, state))
          break;
        if (parameters.verbose)
          print_iteration(state, linear_iterations, accelerated);

        if (!accepted && modified && !state.tangent_is_current)
          {
            // The old matrix led nowhere: rebuild it here and try again.
            state.assembly        = assembly_at_iterate;
            state.rebuild_tangent = true;
            continue;
          }
        if (!accepted)
          throw StepFailure(
            "the line search found no admissible step (min det F = " +
            std::to_string(state.assembly.min_jacobian) + ")");
        if (modified)
          schedule_tangent_update(state, previous_norm);
      }

    Result result;
    result.assembly          = state.assembly;
    result.iterations        = state.iterations;
    result.linear_iterations = state.linear_iterations;
    result.residual          = state.norm;
    return result;
  }



  // @sect4{NewtonSolver::converged}
  //
  // The tests at the top of an iteration, in this order. A residual that is
  // not finite cannot become one. The force scale follows the iterates, but
  // an iterate whose forces are a thousand times those the solve started
  // from is not a state the step can reach: the iteration has run away (in
  // the undamped release of the stability study, into a state with
  // $10^{16}$ times the strain energy, where any residual passed the
  // relative test). Then the convergence test proper,
  // @f[
  //   \|\mathbf r\| \le \varepsilon_\text{abs}
  //   \quad\text{or}\quad
  //   \|\mathbf r\| \le \varepsilon_\text{rel}\max_{j\le k} s_j,
  // @f]
  // with the force scales $s_j$ of the iterates so far, the external forces
  // and the first residual, and last the limit on the iterations: the
  // modified variant may take twice as many (cheaper) iterations.
  bool
  NewtonSolver::converged(IterationState &state) const
  {
    if (!std::isfinite(state.norm))
      throw StepFailure("the residual is not finite");
    if (state.assembly.force_scale > 1e3 * state.initial_force_scale)
      throw StepFailure(
        "the iteration ran away (forces " +
        std::to_string(state.assembly.force_scale) + " against " +
        std::to_string(state.initial_force_scale) + " at its start)");
    state.reference = std::max(state.reference, state.assembly.force_scale);
    if (state.norm <= parameters.newton_absolute_tolerance ||
        state.norm <= parameters.newton_relative_tolerance * state.reference)
      return true;
    if (state.iterations ==
        (state.modified ? 2 : 1) * parameters.newton_max_iterations)
      {
        std::ostringstream message;
        message << "Newton's method did not converge in " << state.iterations
                << " iterations (residual " << state.norm << ")";
        throw StepFailure(message.str());
      }
    return false;
  }



  // @sect4{NewtonSolver::prepare_matrix}
  //
  // Newton's method proper prepares the tangent that the last accepted
  // evaluation left (the iterate's). The modified variant keeps its matrix
  // unless the previous iteration asked for a new one; the tangent is then
  // assembled at the current iterate (its residual too, which is the same)
  // and prepared, and the Anderson history, which belongs to the old
  // matrix, is forgotten entirely.
  void
  NewtonSolver::prepare_matrix(const TrilinosWrappers::MPI::Vector &u,
                               IterationState                      &state,
                               const Problem &problem) const
  {
    if (state.modified && state.rebuild_tangent)
      {
        state.assembly = problem.evaluate(u, true, state.residual);
        problem.prepare_tangent();
        state.tangent_is_current = true;
        state.rebuild_tangent    = false;
        state.anderson.clear();
      }
    else if (!state.modified)
      problem.prepare_tangent();
  }



  // @sect4{NewtonSolver::try_accelerated_step}
  //
  // In the modified variant, the Anderson step from the iterate and its
  // update is tried before the line search. It is taken if its state is
  // valid and its residual lower than the iterate's; its length is one. If
  // it is not better, the differences are forgotten, but the iterate and
  // its update stay as the start of a new history: the matrix is the same.
  // (The trial asks for no matrix; only the modified variant accelerates.)
  bool
  NewtonSolver::try_accelerated_step(TrilinosWrappers::MPI::Vector &u,
                                     IterationState                &state,
                                     const Problem &problem) const
  {
    if (state.anderson.depth() == 0)
      return false;
    Assert(state.modified, ExcInternalError());
    if (!state.anderson.accelerated_step(u, state.update, state.accelerated))
      return false;

    state.trial = u;
    state.trial += state.accelerated;
    state.assembly = problem.evaluate(state.trial, false, state.trial_residual);
    const double accelerated_norm = state.trial_residual.l2_norm();
    if (!state.assembly.inverted_point_found &&
        std::isfinite(accelerated_norm) && accelerated_norm < state.norm)
      {
        u                      = state.trial;
        state.residual         = state.trial_residual;
        state.norm             = accelerated_norm;
        state.potential_energy = state.assembly.potential_energy;
        state.step_length      = 1.;
        state.trial_valid      = true;
        return true;
      }
    state.anderson.clear_differences();
    return false;
  }



  // @sect4{NewtonSolver::line_search}
  //
  // Backtracking: the full step is taken if it lowers the residual, or in
  // static problems the potential energy; otherwise it is halved, up to
  // `Max line search steps` times. Without line search only a state that is
  // physically valid and finite is required.
  //
  // A direction from an old matrix is not halved: if its full step does not
  // lower the residual, the matrix no longer describes the body well
  // enough, and the tangent is rebuilt at once. (Halving it would cost up to
  // six residual assemblies, and with an old matrix such a search often ends
  // without an admissible step.)
  //
  // In Newton's method proper every trial assembles the tangent, so that
  // the accepted one leaves its own for the next iteration.
  bool
  NewtonSolver::line_search(TrilinosWrappers::MPI::Vector &u,
                            IterationState                &state,
                            const Problem                 &problem) const
  {
    const unsigned int max_halvings =
      (parameters.line_search && (!state.modified || state.tangent_is_current))
        ? parameters.max_line_search_steps
        : 0;
    state.step_length = 1.;
    state.trial_valid = false;
    state.trial_norm  = 0.;
    for (unsigned int halving = 0; halving <= max_halvings; ++halving)
      {
        state.trial = u;
        state.trial.add(state.step_length, state.update);
        state.assembly =
          problem.evaluate(state.trial, !state.modified, state.trial_residual);
        state.trial_norm  = state.trial_residual.l2_norm();
        state.trial_valid = !state.assembly.inverted_point_found &&
                            std::isfinite(state.trial_norm);
        const bool descent =
          state.trial_norm < state.norm ||
          (std::isfinite(state.assembly.potential_energy) &&
           state.assembly.potential_energy < state.potential_energy);
        if (state.trial_valid && (!parameters.line_search || descent))
          {
            u                      = state.trial;
            state.residual         = state.trial_residual;
            state.norm             = state.trial_norm;
            state.potential_energy = state.assembly.potential_energy;
            return true;
          }
        state.step_length *= 0.5;
      }
    return false;
  }



  // @sect4{NewtonSolver::accept_stagnated_trial}
  //
  // Stagnation: no step lowers the residual, but it is already six orders
  // of magnitude below the forces that balance in it. This happens when the
  // tolerance asks for more digits than the assembly's round-off leaves
  // (the relative tolerance times the force scale is then below it); the
  // last trial state of the line search is accepted, and the iteration
  // ends.
  bool
  NewtonSolver::accept_stagnated_trial(TrilinosWrappers::MPI::Vector &u,
                                       IterationState &state) const
  {
    if (!state.trial_valid || !(state.norm <= 1e-6 * state.reference))
      return false;
    u              = state.trial;
    state.residual = state.trial_residual;
    state.norm     = state.trial_norm;
    return true;
  }



  // @sect4{NewtonSolver::schedule_tangent_update}
  //
  // After an accepted step of the modified variant: the matrix is no
  // longer the tangent at the iterate, and it is rebuilt in the next
  // iteration if this one left more than `Rebuild threshold` of the
  // residual (by default: reduced it by less than a factor of two), or if
  // it has now served `Max iterations` iterations (counted from the
  // caller's matrix, or from the last rebuilt one).
  void
  NewtonSolver::schedule_tangent_update(IterationState &state,
                                        const double    previous_norm) const
  {
    if (state.tangent_is_current)
      state.iterations_with_tangent = 0;
    ++state.iterations_with_tangent;
    state.tangent_is_current = false;
    state.rebuild_tangent =
      (state.norm > parameters.rebuild_threshold * previous_norm) ||
      (state.iterations_with_tangent >= parameters.newton_max_iterations);
  }



  // @sect4{NewtonSolver::print_iteration}
  //
  // With `Verbose`: the residual after the iteration, the force scale it is
  // measured against, the linear iterations, the step length (after a
  // failed line search the one that would have come next), and whether the
  // step was the accelerated one or came from an old matrix.
  void
  NewtonSolver::print_iteration(const IterationState &state,
                                const unsigned int    linear_iterations,
                                const bool            accelerated) const
  {
    pcout << "    Newton " << state.iterations << ": |r| = " << state.norm
          << " (scale " << state.reference << "), " << linear_iterations
          << " linear iterations, step length " << state.step_length
          << (accelerated ? " (accelerated)" : "")
          << (state.modified && !state.tangent_is_current ? ", old tangent"
                                                          : "")
          << std::endl;
  }
} // namespace SoftRobot
