// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Dense linear algebra for the analysis: the calls to LAPACK}
//
// Each function below checks the sizes it is given, converts them to
// LAPACK's 32-bit integers, asks the routine how much work space it wants
// (a call with <code>lwork = -1</code> returns the optimal size in
// <code>work[0]</code> and does nothing else), and then calls it. An
// argument that LAPACK rejects (<code>info < 0</code>) is a programming
// error in this file and raises std::logic_error; a numerical failure
// (<code>info > 0</code>) is reported in the way the respective function
// documents.

#include "lapack.h"

#include <algorithm>
#include <analysis/dense_linear_algebra.h>
#include <analysis/utilities.h>
#include <limits>
#include <stdexcept>
#include <string>

namespace SoftRobot
{
  namespace Analysis
  {
    namespace
    {
      // A size as LAPACK's integer, with a check that it fits: the
      // matrices of the analysis are far smaller than $2^{31}$ entries per
      // dimension, so an overflow would mean a corrupted size.
      int
      lapack_size(const std::size_t size, const char *what)
      {
        if (size > static_cast<std::size_t>(std::numeric_limits<int>::max()))
          throw std::invalid_argument(
            std::string("The ") + what + " of a dense matrix (" +
            std::to_string(size) + ") exceeds LAPACK's integer range.");
        return static_cast<int>(size);
      }



      void
      check_info(const int info, const char *routine)
      {
        if (info < 0)
          throw std::logic_error(std::string("LAPACK's ") + routine +
                                 " rejected its argument " +
                                 std::to_string(-info) + ".");
      }



      // LAPACK's answer to a work-space query, as a size.
      int
      queried_work_size(const double answer)
      {
        return std::max(1, static_cast<int>(answer));
      }



      void
      check_least_squares_sizes(const ColumnMajorMatrix   &matrix,
                                const std::vector<double> &rhs)
      {
        if (matrix.n_columns() == 0 || matrix.n_rows() < matrix.n_columns())
          throw std::invalid_argument(
            "A least-squares problem needs at least one column and at least "
            "as many rows as columns, but the matrix is " +
            std::to_string(matrix.n_rows()) + " x " +
            std::to_string(matrix.n_columns()) + ".");
        if (rhs.size() != matrix.n_rows())
          throw std::invalid_argument(
            "The right-hand side of a least-squares problem has " +
            std::to_string(rhs.size()) + " entries, but the matrix has " +
            std::to_string(matrix.n_rows()) + " rows.");
      }
    } // namespace



    // @sect4{Least squares of possibly deficient rank}
    //
    // <code>dgelsy</code> factorises $AP = QR$ with the column permutation
    // $P$ that brings the largest remaining column to the front at each
    // step, so that $|r_{11}| \ge |r_{22}| \ge \dots$, and takes as rank
    // the largest $r$ for which the incremental condition estimate of the
    // leading $r\times r$ triangle stays below $1/$<code>rcond</code>. The
    // trailing columns of $R$ are then eliminated by orthogonal
    // transformations from the right (a complete orthogonal factorisation),
    // which gives the minimum-norm solution. The routine overwrites the
    // matrix with its factors and the right-hand side with the solution (in
    // its first $p$ entries), so both are copies.
    //
    // The residual is formed afterwards from the unmodified matrix,
    // $\mathbf r = \mathbf b - A\mathbf x$, by the BLAS product
    // <code>dgemv</code> with $\alpha=-1$, $\beta=1$, which subtracts the
    // columns one after the other; <code>dgelsy</code> itself does not
    // return the residual.
    LeastSquaresSolution
    solve_least_squares(const ColumnMajorMatrix   &matrix,
                        const std::vector<double> &rhs,
                        const double               relative_rank_tolerance)
    {
      check_least_squares_sizes(matrix, rhs);
      if (!(relative_rank_tolerance >= 0. && relative_rank_tolerance < 1.))
        throw std::invalid_argument(
          "The relative rank tolerance of a least-squares problem must lie "
          "in [0, 1), but is " +
          internal::format_number(relative_rank_tolerance) + ".");

      const int n_rows    = lapack_size(matrix.n_rows(), "row count");
      const int n_columns = lapack_size(matrix.n_columns(), "column count");
      const int n_rhs     = 1;
      ColumnMajorMatrix   factor   = matrix;
      std::vector<double> solution = rhs;
      std::vector<int>    pivots(n_columns, 0); // all columns may move
      int                 rank = 0, info = 0;

      // The same call twice: first as work-space query, then for real.
      const auto dgelsy = [&](double *work, const int work_size) {
        dgelsy_(&n_rows,
                &n_columns,
                &n_rhs,
                factor.data(),
                &n_rows,
                solution.data(),
                &n_rows,
                pivots.data(),
                &relative_rank_tolerance,
                &rank,
                work,
                &work_size,
                &info);
        check_info(info, "dgelsy");
      };
      double work_size_answer = 0.;
      dgelsy(&work_size_answer, -1);
      std::vector<double> work(queried_work_size(work_size_answer));
      dgelsy(work.data(), static_cast<int>(work.size()));

      LeastSquaresSolution result;
      result.rank = rank;
      result.coefficients.assign(solution.begin(),
                                 solution.begin() + n_columns);

      result.residual        = rhs;
      const double minus_one = -1., one = 1.;
      const int    unit_stride = 1;
      dgemv_("N",
             &n_rows,
             &n_columns,
             &minus_one,
             matrix.data(),
             &n_rows,
             result.coefficients.data(),
             &unit_stride,
             &one,
             result.residual.data(),
             &unit_stride,
             1);
      return result;
    }



    // @sect4{Least squares of full rank}
    //
    // <code>dgels</code> factorises $A = QR$ without pivoting and solves
    // $R\mathbf x = (Q^T\mathbf b)_{1..p}$; it stops with
    // <code>info</code> $= k > 0$ if $r_{kk}$ is exactly zero. Unlike the
    // normal equations $A^TA\mathbf x = A^T\mathbf b$ it works with the
    // condition number of $A$, not its square. The matrix is taken by value
    // because the routine overwrites it with its factors.
    bool
    solve_full_rank_least_squares(ColumnMajorMatrix          matrix,
                                  const std::vector<double> &rhs,
                                  std::vector<double>       &solution)
    {
      check_least_squares_sizes(matrix, rhs);

      const int n_rows    = lapack_size(matrix.n_rows(), "row count");
      const int n_columns = lapack_size(matrix.n_columns(), "column count");
      const int n_rhs     = 1;
      std::vector<double> right_hand_side = rhs;
      int                 info            = 0;

      const auto dgels = [&](double *work, const int work_size) {
        dgels_("N",
               &n_rows,
               &n_columns,
               &n_rhs,
               matrix.data(),
               &n_rows,
               right_hand_side.data(),
               &n_rows,
               work,
               &work_size,
               &info,
               1);
        check_info(info, "dgels");
      };
      double work_size_answer = 0.;
      dgels(&work_size_answer, -1);
      std::vector<double> work(queried_work_size(work_size_answer));
      dgels(work.data(), static_cast<int>(work.size()));
      if (info > 0)
        return false;

      solution.assign(right_hand_side.begin(),
                      right_hand_side.begin() + n_columns);
      return true;
    }
  } // namespace Analysis
} // namespace SoftRobot
