// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Solving with a sparse matrix plus a rank-one term}
//
// See include/solvers/rank_one_correction.h.

#include <cmath>
#include <core/exceptions.h>
#include <solvers/rank_one_correction.h>

namespace SoftRobot
{
  void
  RankOneCorrection::set(const TrilinosWrappers::MPI::Vector &vector,
                         const double                         c)
  {
    Assert(c >= 0., ExcMessage("The rank-one term must not be negative."));
    coefficient = c;
    prepared    = false;
    if (c > 0.)
      g = vector;
  }



  void
  RankOneCorrection::clear()
  {
    coefficient = 0.;
    prepared    = false;
  }



  unsigned int
  RankOneCorrection::prepare(LinearSolver &solver)
  {
    if (!active())
      return 0;
    z.reinit(g); // a zero initial guess for the iterative solvers
    const unsigned int iterations = solver.solve(g, z);
    denominator                   = 1. + coefficient * (g * z);
    if (!(std::abs(denominator) > 1e-14))
      throw StepFailure("the rank-one correction of the gas cavity is "
                        "singular (1 + c g.z = " +
                        std::to_string(denominator) + ")");
    prepared = true;
    return iterations;
  }



  unsigned int
  RankOneCorrection::solve(LinearSolver                        &solver,
                           const TrilinosWrappers::MPI::Vector &rhs,
                           TrilinosWrappers::MPI::Vector       &solution) const
  {
    const unsigned int iterations = solver.solve(rhs, solution);
    if (!active())
      return iterations;
    Assert(prepared, ExcMessage("RankOneCorrection::solve() needs prepare()."));
    solution.add(-coefficient * (g * solution) / denominator, z);
    return iterations;
  }
} // namespace SoftRobot
