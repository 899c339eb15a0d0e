// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Newton's method for the time steps and the static equilibrium}
//
// Every nonlinear problem of the program -- a time step of the HHT method,
// a load step of the static equilibrium -- is a system $\mathbf r(\mathbf
// u) = \mathbf 0$ solved by Newton's method with a backtracking line
// search. The class knows nothing about the body: the problem gives it the
// residual (and the tangent matrix, left where the linear solver finds it)
// at a trial displacement, and the linear solve with that matrix, as
// callbacks (NewtonSolver::Problem).
//
// The line search accepts a step that lowers the residual norm or, in
// static problems, the total potential energy: equilibrium is its minimum,
// and the residual norm alone is a poor guide when a slender body rotates
// far; near the solution, where energy differences drown in round-off, the
// residual decides. The iteration has converged when the residual is below
// the absolute tolerance, or below the relative tolerance times a force
// scale: the largest of the external forces, the forces that balance in
// the residual (internal and inertial), and the first residual. The forces
// set the level of round-off, so a relative tolerance of $10^{-12}$ is
// attainable however small the motion; the iteration also stops when the
// update is at round-off level relative to the displacement. Every failure
// -- too many iterations, a linear solver that does not converge, a
// non-finite residual, an inverted element that the line search cannot
// avoid -- throws StepFailure, and the caller decides what to do.
//
// In the modified variant the matrix prepared by the caller (the tangent
// of the last converged state) serves all iterations, and the evaluations
// compute residuals only. When an iteration reduces the residual by less
// than a factor of two (by default; see `Rebuild threshold`), when `Max
// iterations` iterations have used the same old matrix, or when the full
// step fails with it, the tangent is rebuilt at the current iterate. The
// modified variant is allowed twice the iterations of the full one.
//
// The modified iterations are a fixed-point iteration, and Anderson
// acceleration (see AndersonAcceleration) speeds them up: its step is
// tried first; if it does not lower the residual, the plain update (with
// the line search) is taken and the history is dropped, as it is whenever
// the matrix changes. `Acceleration depth` zero turns it off.
//
// Implemented in source/solvers/newton_solver.cc.

#ifndef soft_robot_solvers_newton_solver_h
#define soft_robot_solvers_newton_solver_h

#include <assembly/assembly_result.h>
#include <core/parameters.h>
#include <deal.II/base/conditional_ostream.h>
#include <deal.II/lac/trilinos_vector.h>
#include <functional>

namespace SoftRobot
{
  using namespace dealii;

  class NewtonSolver
  {
  public:
    // What the solver needs of the problem it solves (the time step or the
    // static equilibrium).
    struct Problem
    {
      // The residual at `u` into `residual` (which has the layout of `u`)
      // and, if `with_tangent`, the tangent matrix, left by the problem
      // where prepare_tangent() finds it. The AssemblyResult reports the
      // forces that balance in the residual, the potential energy (static
      // problems; not a number otherwise) and inverted elements.
      std::function<AssemblyResult(const TrilinosWrappers::MPI::Vector &u,
                                   const bool                     with_tangent,
                                   TrilinosWrappers::MPI::Vector &residual)>
        evaluate;
      // Factorizes, or otherwise prepares the linear solver for, the
      // tangent of the last evaluate(u, true, residual).
      std::function<void()> prepare_tangent;
      // Solves tangent * x = rhs with what prepare_tangent() made (x has
      // the layout of rhs; constrained entries are the problem's business);
      // returns the linear iterations. May throw StepFailure.
      std::function<unsigned int(const TrilinosWrappers::MPI::Vector &rhs,
                                 TrilinosWrappers::MPI::Vector       &x)>
        solve;
    };

    // What a converged solve reports: the evaluation of the last state
    // (strain and potential energy, forces), the Newton iterations, the
    // iterations of the linear solves, and the final residual norm.
    struct Result
    {
      AssemblyResult assembly;
      unsigned int   iterations        = 0;
      unsigned int   linear_iterations = 0;
      double         residual          = 0.;
    };

    // The parameters are copied; `pcout` (for the output of `Verbose`) must
    // outlive the solver.
    NewtonSolver(const Parameters::NonlinearSolver &parameters,
                 const ConditionalOStream          &pcout);

    // Iterates `u` to convergence and returns what it found; throws
    // StepFailure if it does not converge, and `u` is then unspecified.
    // `force_scale` is the norm of the external forces. With `modified`,
    // the matrix the caller prepared before the call serves all iterations
    // until it is rebuilt (evaluate(u, true, r) and prepare_tangent()),
    // and the other evaluations ask for no matrix.
    Result
    solve(TrilinosWrappers::MPI::Vector &u,
          const Problem                 &problem,
          const double                   force_scale,
          const bool                     modified) const;

  private:
    // The vectors and numbers that the iterations of one solve() share
    // (defined in the source file).
    struct IterationState;

    // The tests at the top of every iteration: true if converged, throws
    // StepFailure if the iteration cannot converge.
    bool
    converged(IterationState &state) const;

    // The matrix of this iteration: a new tangent in Newton's method
    // proper, and in the modified one when it must be rebuilt.
    void
    prepare_matrix(const TrilinosWrappers::MPI::Vector &u,
                   IterationState                      &state,
                   const Problem                       &problem) const;

    // The Anderson step, tried first in the modified variant; true if it
    // lowered the residual and `u` has become the accelerated iterate.
    bool
    try_accelerated_step(TrilinosWrappers::MPI::Vector &u,
                         IterationState                &state,
                         const Problem                 &problem) const;

    // The backtracking line search along the Newton update; true if a
    // step was accepted and `u` has become the new iterate.
    bool
    line_search(TrilinosWrappers::MPI::Vector &u,
                IterationState                &state,
                const Problem                 &problem) const;

    // Whether the last trial of a failed line search is accepted anyway,
    // because the residual is already at the level of round-off.
    bool
    accept_stagnated_trial(TrilinosWrappers::MPI::Vector &u,
                           IterationState                &state) const;

    // In the modified variant after an accepted step: whether the next
    // iteration rebuilds the matrix.
    void
    schedule_tangent_update(IterationState &state,
                            const double    previous_norm) const;

    // The line of `Verbose` output of one iteration.
    void
    print_iteration(const IterationState &state,
                    const unsigned int    linear_iterations,
                    const bool            accelerated) const;

    const Parameters::NonlinearSolver parameters;
    const ConditionalOStream         &pcout;
  };
} // namespace SoftRobot

#endif
