// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Solving with a sparse matrix plus a rank-one term}
//
// The tangent of a gas cavity is the sparse matrix $\mathbf S$ of the body
// and the load plus the gas's stiffness, $c\,\mathbf g\mathbf g^T$ with $c
// \ge 0$ and the volume gradient $\mathbf g$, which couples every pair of
// degrees of freedom on the cavity wall: assembled, it would fill the
// matrix with $n_c^2$ entries for $n_c$ wall dofs (some $10^6$ for the
// medium bellows mesh) and ruin the factorization. The Sherman-Morrison
// formula solves with the sum using $\mathbf S$ alone:
// @f[
//   (\mathbf S + c\,\mathbf g\mathbf g^T)^{-1}\mathbf r
//   = \mathbf y - \frac{c\,\mathbf g^T\mathbf y}{1 + c\,\mathbf g^T\mathbf z}
//     \,\mathbf z,
//   \qquad \mathbf y = \mathbf S^{-1}\mathbf r,\quad
//   \mathbf z = \mathbf S^{-1}\mathbf g .
// @f]
// $\mathbf z$ costs one solve per preparation of $\mathbf S$ (a
// factorization or a multigrid set-up), every solve one more inner
// product and vector update. With the direct solvers the result is the
// solution of the full tangent to round-off. With CG or GMRES both inner
// solves are inexact (to the linear solver's relative tolerance), and so
// is the corrected one; Newton's method, which checks the true residual,
// tolerates that as it tolerates any inexact solve. The formula needs $1 +
// c\,\mathbf g^T\mathbf z \ne 0$, which holds whenever $\mathbf S$ is
// positive definite ($\mathbf g^T\mathbf z = \mathbf g^T\mathbf
// S^{-1}\mathbf g > 0$).
//
// Implemented in source/solvers/rank_one_correction.cc.

#ifndef soft_robot_solvers_rank_one_correction_h
#define soft_robot_solvers_rank_one_correction_h

#include <deal.II/lac/trilinos_vector.h>
#include <solvers/linear_solver.h>

namespace SoftRobot
{
  using namespace dealii;

  class RankOneCorrection
  {
  public:
    // The term $c\,\mathbf g\mathbf g^T$ of the next matrix the linear
    // solver prepares; c = 0 (or clear()) leaves the matrix as it is.
    void
    set(const TrilinosWrappers::MPI::Vector &g, const double c);
    void
    clear();
    bool
    active() const
    {
      return coefficient > 0.;
    }

    // The term's vector and coefficient (for a checkpoint).
    const TrilinosWrappers::MPI::Vector &
    vector() const
    {
      return g;
    }
    double
    factor() const
    {
      return coefficient;
    }

    // After solver.prepare(S): $\mathbf z = \mathbf S^{-1}\mathbf g$ and
    // the denominator; returns the linear iterations of that solve.
    unsigned int
    prepare(LinearSolver &solver);

    // The solution of $(\mathbf S + c\,\mathbf g\mathbf g^T)\mathbf x =
    // \mathbf r$; returns the linear iterations.
    unsigned int
    solve(LinearSolver                        &solver,
          const TrilinosWrappers::MPI::Vector &rhs,
          TrilinosWrappers::MPI::Vector       &solution) const;

  private:
    TrilinosWrappers::MPI::Vector g, z;
    double                        coefficient = 0.;
    double                        denominator = 1.;
    bool                          prepared    = false;
  };
} // namespace SoftRobot

#endif
