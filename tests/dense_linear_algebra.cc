// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Tests of the dense least-squares solvers of the analysis}
//
// The spectral analysis hands every least-squares problem to LAPACK
// (source/analysis/dense_linear_algebra.cc). These tests check the two
// solvers against problems whose solution is known in closed form:
// - a residual that is orthogonal to the columns by construction, so that
//   both the coefficients and the residual are known exactly;
// - a rank-deficient matrix, whose minimum-norm solution is known;
// - an ill-conditioned polynomial basis, for which the normal equations
//   would lose about twice as many digits as a QR factorisation;
// - a singular matrix for the full-rank solver, and sizes that do not fit.
// The tolerances are multiples of the machine epsilon times the condition
// number of the problem, as explained next to each.

// Not typed on the dimension: the analysis library (no deal.II) sees no mesh.

#include <analysis/dense_linear_algebra.h>
#include <cmath>
#include <gtest/gtest.h>
#include <limits>
#include <stdexcept>
#include <vector>

namespace
{
  using namespace SoftRobot::Analysis;

  constexpr double epsilon = std::numeric_limits<double>::epsilon();

  // The points $x_i = -1 + 2i/(n-1)$, symmetric about zero.
  std::vector<double>
  symmetric_points(const unsigned int n)
  {
    std::vector<double> x(n);
    for (unsigned int i = 0; i < n; ++i)
      x[i] = -1. + 2. * i / (n - 1.);
    return x;
  }
} // namespace



// @sect3{A line with a known residual}
//
// The data $y_i = 2 + 3x_i + e_i$ with $e_i = c\,(x_i^2 - \overline{x^2})$ on
// points symmetric about zero: $\sum_i e_i = 0$ by the subtraction of the
// mean and $\sum_i x_i e_i = 0$ by symmetry, so $\mathbf e$ is orthogonal to
// both columns $(1)$ and $(x_i)$. The least-squares line is therefore exactly
// $2 + 3x$, and the residual exactly $\mathbf e$. The matrix is well
// conditioned (the columns are orthogonal), so the errors must be a few
// $\epsilon$ relative to the data.
TEST(LeastSquares, LineWithAResidualOrthogonalToTheColumns)
{
  const std::vector<double> x           = symmetric_points(41);
  double                    mean_square = 0.;
  for (const double xi : x)
    mean_square += xi * xi / x.size();

  ColumnMajorMatrix   matrix(x.size(), 2);
  std::vector<double> rhs(x.size()), expected_residual(x.size());
  for (std::size_t i = 0; i < x.size(); ++i)
    {
      matrix(i, 0)         = 1.;
      matrix(i, 1)         = x[i];
      expected_residual[i] = 0.7 * (x[i] * x[i] - mean_square);
      rhs[i]               = 2. + 3. * x[i] + expected_residual[i];
    }

  for (const bool full_rank_solver : {false, true})
    {
      SCOPED_TRACE(full_rank_solver ? "dgels" : "dgelsy");
      std::vector<double> coefficients;
      if (full_rank_solver)
        ASSERT_TRUE(solve_full_rank_least_squares(matrix, rhs, coefficients));
      else
        {
          const LeastSquaresSolution solution =
            solve_least_squares(matrix, rhs);
          EXPECT_EQ(solution.rank, 2u);
          ASSERT_EQ(solution.residual.size(), rhs.size());
          for (std::size_t i = 0; i < rhs.size(); ++i)
            EXPECT_NEAR(solution.residual[i],
                        expected_residual[i],
                        50 * epsilon);
          coefficients = solution.coefficients;
        }
      ASSERT_EQ(coefficients.size(), 2u);
      EXPECT_NEAR(coefficients[0], 2., 50 * epsilon);
      EXPECT_NEAR(coefficients[1], 3., 50 * epsilon);
    }
}



// @sect3{A rank-deficient matrix}
//
// The columns $(\mathbf a, \mathbf a, \mathbf b)$ with
// $\mathbf a = (1)$, $\mathbf b = (x_i)$ and the right-hand side
// $2\mathbf a + \mathbf b$: every $(c_1, c_2, 1)$ with $c_1 + c_2 = 2$ solves
// the problem exactly, and the one of minimal norm is $(1, 1, 1)$. The
// rank-revealing solver must find rank 2, that solution, and a zero
// residual.
TEST(LeastSquares, RankDeficientMatrixGivesTheMinimumNormSolution)
{
  const std::vector<double> x = symmetric_points(30);
  ColumnMajorMatrix         matrix(x.size(), 3);
  std::vector<double>       rhs(x.size());
  for (std::size_t i = 0; i < x.size(); ++i)
    {
      matrix(i, 0) = 1.;
      matrix(i, 1) = 1.;
      matrix(i, 2) = x[i];
      rhs[i]       = 2. + x[i];
    }

  const LeastSquaresSolution solution = solve_least_squares(matrix, rhs);
  EXPECT_EQ(solution.rank, 2u);
  ASSERT_EQ(solution.coefficients.size(), 3u);
  EXPECT_NEAR(solution.coefficients[0], 1., 50 * epsilon);
  EXPECT_NEAR(solution.coefficients[1], 1., 50 * epsilon);
  EXPECT_NEAR(solution.coefficients[2], 1., 50 * epsilon);
  for (const double r : solution.residual)
    EXPECT_NEAR(r, 0., 50 * epsilon);
}



// @sect3{An ill-conditioned basis}
//
// The monomials $1, t, \dots, t^{10}$ on 200 points in $[0,1]$ have the
// condition number $\kappa = 2.2\cdot10^7$ (the ratio of the extreme
// singular values, computed once with LAPACK's dgesvd). A backward-stable QR
// solve of a consistent system recovers coefficients of order one to about
// $\kappa\epsilon \approx 5\cdot10^{-9}$ (measured: $10^{-9}$ for both
// solvers); the normal equations, with the condition number
// $\kappa^2 \approx 5\cdot10^{14}$, are off by $1.4\cdot10^{-2}$ (measured
// with a Cholesky solve of $A^TA$). The tolerance $10^{-6}$ separates the
// two methods by orders of magnitude on both sides.
TEST(LeastSquares, IllConditionedPolynomialBasisKeepsItsDigits)
{
  const unsigned int        n = 200, degree = 10;
  const std::vector<double> exact = {
    1., -2., 0.5, 3., -1., 0.25, 2., -0.75, 1.5, -0.5, 0.125};
  ColumnMajorMatrix   matrix(n, degree + 1);
  std::vector<double> rhs(n, 0.);
  for (unsigned int i = 0; i < n; ++i)
    {
      const double t     = i / (n - 1.);
      double       power = 1.;
      for (unsigned int k = 0; k <= degree; ++k)
        {
          matrix(i, k) = power;
          rhs[i] += exact[k] * power;
          power *= t;
        }
    }

  const LeastSquaresSolution solution = solve_least_squares(matrix, rhs);
  EXPECT_EQ(solution.rank, degree + 1);
  std::vector<double> full_rank;
  ASSERT_TRUE(solve_full_rank_least_squares(matrix, rhs, full_rank));
  for (unsigned int k = 0; k <= degree; ++k)
    {
      EXPECT_NEAR(solution.coefficients[k], exact[k], 1e-6);
      EXPECT_NEAR(full_rank[k], exact[k], 1e-6);
    }
}



// @sect3{Singular matrices and wrong sizes}
//
// The full-rank solver must report an exactly singular matrix (a zero
// column) instead of returning a solution, and leave its output alone; the
// rank-revealing solver gives the zero column a zero coefficient. A matrix
// with fewer rows than columns, or a right-hand side of the wrong length, is
// rejected.
TEST(LeastSquares, SingularMatricesAndWrongSizesAreReported)
{
  ColumnMajorMatrix   matrix(5, 2, 0.);
  std::vector<double> rhs(5);
  for (unsigned int i = 0; i < 5; ++i)
    {
      matrix(i, 0) = i + 1.;
      rhs[i]       = 2. * (i + 1.);
    }

  std::vector<double> untouched = {42.};
  EXPECT_FALSE(solve_full_rank_least_squares(matrix, rhs, untouched));
  EXPECT_EQ(untouched, std::vector<double>{42.});

  const LeastSquaresSolution solution = solve_least_squares(matrix, rhs);
  EXPECT_EQ(solution.rank, 1u);
  EXPECT_NEAR(solution.coefficients[0], 2., 10 * epsilon);
  EXPECT_EQ(solution.coefficients[1], 0.);

  EXPECT_THROW(solve_least_squares(ColumnMajorMatrix(2, 3), {1., 2.}),
               std::invalid_argument);
  EXPECT_THROW(solve_least_squares(matrix, {1., 2.}), std::invalid_argument);
  std::vector<double> solution_vector;
  EXPECT_THROW(solve_full_rank_least_squares(ColumnMajorMatrix(3, 0),
                                             {1., 2., 3.},
                                             solution_vector),
               std::invalid_argument);
}
