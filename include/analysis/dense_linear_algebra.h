// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Dense linear algebra for the analysis}
//
// Implemented in source/analysis/dense_linear_algebra.cc.
//
// The analysis solves two kinds of small dense problems: linear least
// squares with a tall matrix of a few columns (the linear coefficients of
// the damped-mode model, the line through the logarithms of the extrema),
// and the damped least-squares step of Levenberg--Marquardt. Both go to
// LAPACK through the functions below; nothing else in the analysis
// factorises a matrix. (The principal direction of the motion is the
// eigenvector of a $2\times2$ matrix, which directions.cc computes in
// closed form.)
// The matrices are small (thousands of rows, at most a dozen columns), so
// the point is not speed but that well-tested, backward-stable algorithms
// do the work.

#ifndef soft_robot_analysis_dense_linear_algebra_h
#define soft_robot_analysis_dense_linear_algebra_h

#include <cstddef>
#include <vector>

namespace SoftRobot
{
  namespace Analysis
  {
    // @sect4{A matrix stored by columns}
    //
    // LAPACK expects a matrix as one array in column-major (Fortran) order,
    // entry $(i,j)$ at position $i + j\,n_\text{rows}$. The class holds such
    // an array and hands out its columns, which is how the analysis fills
    // its matrices: one basis function, or one derivative, per column.
    class ColumnMajorMatrix
    {
    public:
      ColumnMajorMatrix(const std::size_t n_rows    = 0,
                        const std::size_t n_columns = 0,
                        const double      value     = 0.)
        : rows(n_rows)
        , columns(n_columns)
        , values(n_rows * n_columns, value)
      {
      }

      std::size_t
      n_rows() const
      {
        return rows;
      }

      std::size_t
      n_columns() const
      {
        return columns;
      }

      double &
      operator()(const std::size_t i, const std::size_t j)
      {
        return values[i + j * rows];
      }

      double
      operator()(const std::size_t i, const std::size_t j) const
      {
        return values[i + j * rows];
      }

      // The <code>n_rows()</code> contiguous entries of column $j$.
      double *
      column(const std::size_t j)
      {
        return values.data() + j * rows;
      }

      const double *
      column(const std::size_t j) const
      {
        return values.data() + j * rows;
      }

      double *
      data()
      {
        return values.data();
      }

      const double *
      data() const
      {
        return values.data();
      }

    private:
      std::size_t         rows;
      std::size_t         columns;
      std::vector<double> values;
    };



    // @sect4{Linear least squares}
    //
    // The minimiser of $\|A\mathbf x - \mathbf b\|_2$ for an $n\times p$
    // matrix with $n\ge p$, and the residual $\mathbf b - A\mathbf x$ in the
    // original coordinates (the Jacobian of the modal fit is built from
    // residuals).
    //
    // <i>Rank.</i> A QR factorisation with column pivoting (LAPACK's
    // <code>dgelsy</code>) determines the numerical rank: the largest
    // leading triangle of $R$ whose estimated condition number stays below
    // $1/$<code>relative_rank_tolerance</code>. Columns beyond that rank,
    // i.e. columns that are linear combinations of others to within the
    // tolerance, do not make the problem ill-posed: the function returns
    // the solution of minimal norm, and the residual is that of the
    // projection onto the numerically independent columns. This is what
    // the modal fit needs when a trial step makes two modes nearly equal.
    struct LeastSquaresSolution
    {
      std::vector<double> coefficients;
      std::vector<double> residual;
      unsigned int        rank = 0;
    };

    LeastSquaresSolution
    solve_least_squares(const ColumnMajorMatrix   &matrix,
                        const std::vector<double> &rhs,
                        const double relative_rank_tolerance = 1e-12);

    // The same problem for a matrix that is known to have full column rank,
    // by a plain Householder QR factorisation (<code>dgels</code>). It
    // returns false, and leaves <code>solution</code> untouched, if a
    // diagonal entry of $R$ is exactly zero, i.e. if the matrix is
    // singular after all. The Levenberg--Marquardt step uses it: its
    // damping rows make the matrix regular, so that no rank decision is
    // needed, and a singular matrix only means that the damping must grow.
    bool
    solve_full_rank_least_squares(ColumnMajorMatrix          matrix,
                                  const std::vector<double> &rhs,
                                  std::vector<double>       &solution);
  } // namespace Analysis
} // namespace SoftRobot

#endif
