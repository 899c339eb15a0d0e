// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Implementation of AndersonAcceleration}
//
// The history, the least-squares problem for the coefficients and the
// accelerated step; see include/solvers/anderson_acceleration.h for what
// they are for.
//
// Why it works: for a linear problem $\mathbf A\mathbf u = \mathbf b$,
// and a history that is never truncated, the method is GMRES on the
// preconditioned system $\mathbf K^{-1}\mathbf A$ in disguise: the
// accelerated iterate is the fixed-point map $g(\mathbf u) = \mathbf u +
// \mathbf d(\mathbf u)$ applied to the GMRES iterate of the same Krylov
// space (Walker and Ni, theorem 2.2), so it reaches the solution after at
// most $n+1$ iterations, and in practice after as many as the spectrum of
// $\mathbf K^{-1}\mathbf A$ needs. For a nonlinear problem it learns,
// from the iterates, how the tangent has changed since $\mathbf K$ was
// built. A depth of two or three captures most of that in the modified
// Newton iterations of the time steps, which take few iterations anyway.

#include <cmath>
#include <deal.II/base/exceptions.h>
#include <deal.II/lac/full_matrix.h>
#include <solvers/anderson_acceleration.h>

namespace SoftRobot
{
  AndersonAcceleration::AndersonAcceleration(const unsigned int depth)
    : max_depth(depth)
  {
  }



  void
  AndersonAcceleration::clear()
  {
    clear_differences();
    have_last_update = false;
  }



  void
  AndersonAcceleration::clear_differences()
  {
    iterate_differences.clear();
    update_differences.clear();
  }



  unsigned int
  AndersonAcceleration::depth() const
  {
    return max_depth;
  }



  unsigned int
  AndersonAcceleration::n_differences() const
  {
    return update_differences.size();
  }



  // @sect4{AndersonAcceleration::accelerated_step}
  //
  // Records the iterate $\mathbf u_k$ and its update $\mathbf d_k$, and if
  // there is a history, computes $\mathbf d_k - \sum_j\gamma_j(\Delta\mathbf
  // u_j + \Delta\mathbf d_j)$ into `step`. When the differences are close to
  // linearly dependent (see compute_coefficients()), the oldest pair is
  // dropped and the coefficients are computed again from the others;
  // round-off near convergence would otherwise make them meaningless. If no
  // pair is left, there is no accelerated step.
  bool
  AndersonAcceleration::accelerated_step(
    const TrilinosWrappers::MPI::Vector &iterate,
    const TrilinosWrappers::MPI::Vector &update,
    TrilinosWrappers::MPI::Vector       &step)
  {
    AssertDimension(iterate.size(), update.size());
    AssertDimension(step.size(), update.size());
    record(iterate, update);

    Vector<double> gamma;
    while (!update_differences.empty())
      {
        if (!compute_coefficients(update, gamma))
          {
            iterate_differences.pop_front();
            update_differences.pop_front();
            continue;
          }
        step = update;
        for (unsigned int j = 0; j < update_differences.size(); ++j)
          step.add(-gamma(j),
                   iterate_differences[j],
                   -gamma(j),
                   update_differences[j]);
        return true;
      }
    return false;
  }



  // @sect4{AndersonAcceleration::record}
  //
  // The differences need the previous iterate and update, so the first call
  // after clear() only remembers them. Beyond the depth the oldest pair
  // goes; the window of the last $m$ iterations moves with the iteration.
  void
  AndersonAcceleration::record(const TrilinosWrappers::MPI::Vector &iterate,
                               const TrilinosWrappers::MPI::Vector &update)
  {
    if (have_last_update)
      {
        iterate_differences.push_back(iterate);
        iterate_differences.back() -= last_iterate;
        update_differences.push_back(update);
        update_differences.back() -= last_update;
        if (update_differences.size() > max_depth)
          {
            iterate_differences.pop_front();
            update_differences.pop_front();
          }
      }
    last_iterate     = iterate;
    last_update      = update;
    have_last_update = true;
    Assert(iterate_differences.size() == update_differences.size(),
           ExcInternalError());
  }



  // @sect4{AndersonAcceleration::compute_coefficients}
  //
  // The least-squares problem $\min_\gamma\|\mathbf d_k -
  // \sum_j\gamma_j\Delta\mathbf d_j\|$ is solved through its normal
  // equations $\mathbf G\gamma = \mathbf b$, $G_{ij} = \Delta\mathbf
  // d_i\cdot\Delta\mathbf d_j$, $b_i = \Delta\mathbf d_i\cdot\mathbf d_k$,
  // which are at most `depth` by `depth`: a handful of scalar products of
  // distributed vectors, and a tiny dense problem that every process solves
  // alike. (The normal equations square the condition number; the test
  // below keeps it in check, and the accelerated step is only ever a trial
  // that NewtonSolver rejects if it does not lower the residual.)
  //
  // The Cholesky factorization $\mathbf G = \mathbf L\mathbf L^T$ is
  // computed in the lower triangle of `gram`. A pivot below $10^{-10}$ of
  // its diagonal entry means that $\Delta\mathbf d_j$ is, to some ten
  // digits, a combination of the earlier differences: the history is then
  // numerically singular, and false is returned. Otherwise the forward and
  // backward substitutions give $\gamma$.
  bool
  AndersonAcceleration::compute_coefficients(
    const TrilinosWrappers::MPI::Vector &update,
    Vector<double>                      &gamma) const
  {
    const unsigned int m = update_differences.size();
    FullMatrix<double> gram(m, m);
    gamma.reinit(m);
    for (unsigned int i = 0; i < m; ++i)
      {
        for (unsigned int j = 0; j <= i; ++j)
          gram(i, j) = update_differences[i] * update_differences[j];
        gamma(i) = update_differences[i] * update;
      }

    for (unsigned int j = 0; j < m; ++j)
      {
        const double diagonal = gram(j, j);
        double       pivot    = diagonal;
        for (unsigned int k = 0; k < j; ++k)
          pivot -= gram(j, k) * gram(j, k);
        // (Written so that a pivot that is not a number also fails.)
        if (!(pivot > 1e-10 * diagonal))
          return false;
        gram(j, j) = std::sqrt(pivot);
        for (unsigned int i = j + 1; i < m; ++i)
          {
            double value = gram(i, j);
            for (unsigned int k = 0; k < j; ++k)
              value -= gram(i, k) * gram(j, k);
            gram(i, j) = value / gram(j, j);
          }
      }

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
    return true;
  }
} // namespace SoftRobot
