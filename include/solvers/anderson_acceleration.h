// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Anderson acceleration of a fixed-point iteration}
//
// The modified Newton iterations of a time step are a fixed-point
// iteration $\mathbf u_{k+1} = \mathbf u_k + \mathbf d_k$ with the update
// $\mathbf d_k = -\mathbf K^{-1}\mathbf r(\mathbf u_k)$ of a fixed matrix
// $\mathbf K$. Anderson acceleration (Walker and Ni, SIAM J. Numer. Anal.
// 49, 2011) speeds up such iterations cheaply: from the differences
// @f[
//   \Delta\mathbf u_j = \mathbf u_{j+1} - \mathbf u_j,\qquad
//   \Delta\mathbf d_j = \mathbf d_{j+1} - \mathbf d_j
// @f]
// of the last $m$ iterates and of their updates, the coefficients
// $\gamma$ minimize $\|\mathbf d_k - \sum_j\gamma_j\Delta\mathbf d_j\|$,
// and the accelerated step is
// @f[
//   \mathbf s_k = \mathbf d_k - \sum_j\gamma_j(\Delta\mathbf u_j +
//   \Delta\mathbf d_j).
// @f]
// The depth $m$ is the parameter `Nonlinear solver/Acceleration depth`.
//
// The class keeps the history (the differences, and the last iterate and
// update from which the next differences are taken) and computes the step;
// whether the step is taken, and when the history is forgotten, is the
// business of its user, NewtonSolver. It forgets in two ways: clear() drops
// everything (the matrix changed, and the old updates belong to another
// iteration), clear_differences() keeps the last iterate and update as the
// start of a new history (the accelerated step was not better than the
// plain one, but the iteration goes on with the same matrix).
//
// Implemented in source/solvers/anderson_acceleration.cc.

#ifndef soft_robot_solvers_anderson_acceleration_h
#define soft_robot_solvers_anderson_acceleration_h

#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>
#include <deque>

namespace SoftRobot
{
  using namespace dealii;

  class AndersonAcceleration
  {
  public:
    // At most `depth` pairs of differences are kept; with zero there is
    // never an accelerated step.
    explicit AndersonAcceleration(const unsigned int depth);

    // Forgets the differences and the last iterate and update.
    void
    clear();

    // Forgets the differences; the last iterate and update stay and start
    // the new history.
    void
    clear_differences();

    // Records the iterate $\mathbf u_k$ and its update $\mathbf d_k$. If
    // there is a history, writes the accelerated step $\mathbf s_k$ into
    // `step` and returns true; otherwise leaves `step` alone and returns
    // false. `step` must have the layout of `update`.
    bool
    accelerated_step(const TrilinosWrappers::MPI::Vector &iterate,
                     const TrilinosWrappers::MPI::Vector &update,
                     TrilinosWrappers::MPI::Vector       &step);

    // The maximal number of pairs of differences.
    unsigned int
    depth() const;

    // The pairs of differences held now (at most depth()).
    unsigned int
    n_differences() const;

  private:
    // Appends the differences to the last iterate and update, dropping the
    // oldest pair beyond the depth, and remembers the new ones.
    void
    record(const TrilinosWrappers::MPI::Vector &iterate,
           const TrilinosWrappers::MPI::Vector &update);

    // The coefficients $\gamma$ of the least-squares problem for the
    // current history; false if its Gram matrix is numerically singular.
    bool
    compute_coefficients(const TrilinosWrappers::MPI::Vector &update,
                         Vector<double>                      &gamma) const;

    const unsigned int max_depth;

    std::deque<TrilinosWrappers::MPI::Vector> iterate_differences;
    std::deque<TrilinosWrappers::MPI::Vector> update_differences;
    TrilinosWrappers::MPI::Vector             last_iterate;
    TrilinosWrappers::MPI::Vector             last_update;
    bool                                      have_last_update = false;
  };
} // namespace SoftRobot

#endif
