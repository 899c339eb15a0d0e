// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{The symmetric factorization}
//
// The effective tangent of the time steps is symmetric when the
// non-symmetric parts of the damping's tangent are left out (as for CG,
// see KelvinVoigtDamping), and the modified Newton method does not need
// them: the matrix only has to be close enough to the true tangent for
// the iterations to converge, and the residual decides the answer. A
// symmetric matrix can be factorized as $\mathbf L\mathbf D\mathbf L^T$,
// from its lower triangle: about half the arithmetic of the $\mathbf
// L\mathbf U$ factorization and half the factor to read in every back
// substitution.
//
// Trilinos 13.2's Amesos always hands MUMPS a general matrix (setting its
// matrix property to symmetric changes nothing,
// doc/performance_discussion.md, item 32), so this class calls MUMPS
// directly, with SYM = 2 (symmetric, not necessarily definite: MUMPS
// pivots with 1x1 and 2x2 blocks). It takes $(\mathbf A + \mathbf A^T)/2$
// of the matrix it is given, entry by entry from the lower triangle and
// its mirror, so that a matrix that is symmetric only to round-off is
// factorized as the symmetric matrix nearest to it.
//
// The factor can be kept in single precision (`Factorization precision =
// single`; MUMPS's single-precision library, the matrix and right-hand
// side converted on the way in, the solution on the way out). A back
// substitution then solves only to single precision: the usual bound on
// its relative error is single precision's unit round-off ($6\cdot
// 10^{-8}$) times the matrix's condition number. That is enough where the
// solution is a correction of Newton's method: the next iteration's
// residual, computed in double precision, carries the error of this one
// and the iterations absorb it as they absorb the error of a matrix kept
// from earlier iterates. The factor's entries take half the bytes; what that
// saves in time is measured in doc/performance_discussion.md, item 47.
//
// For a matrix on one process only (MUMPS's centralized input and
// right-hand side); LinearSolver uses Amesos for the others. As in
// LinearSolver, the symmetric analysis is done once per matrix object and
// sparsity pattern, the numerical factorization for every new matrix, and
// MUMPS's scaling of rows and columns is off (item 31 of the discussion).
//
// Implemented in source/solvers/symmetric_factorization.cc.

#ifndef soft_robot_solvers_symmetric_factorization_h
#define soft_robot_solvers_symmetric_factorization_h

#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>
#include <memory>
#include <vector>

namespace SoftRobot
{
  using namespace dealii;

  class SymmetricFactorization
  {
  public:
    // The arithmetic of the factor: double precision, or single precision
    // (see the class's description).
    enum class Precision
    {
      double_precision,
      single_precision
    };

    explicit SymmetricFactorization(
      const Precision precision = Precision::double_precision);
    ~SymmetricFactorization();
    SymmetricFactorization(const SymmetricFactorization &) = delete;
    SymmetricFactorization &
    operator=(const SymmetricFactorization &) = delete;

    // The symmetric analysis (the fill-reducing ordering) of the matrix's
    // sparsity pattern, which must be symmetric. The matrix must be on one
    // process.
    void
    analyse(const TrilinosWrappers::SparseMatrix &matrix);

    // The numerical factorization of a matrix with the analysed pattern.
    // Returns false if MUMPS finds it singular.
    bool
    factorize(const TrilinosWrappers::SparseMatrix &matrix);

    // The solution of the factorized system for one right-hand side.
    void
    solve(const TrilinosWrappers::MPI::Vector &rhs,
          TrilinosWrappers::MPI::Vector       &solution);

    // MUMPS's data structure in one of its arithmetics, declared in
    // source/solvers/symmetric_factorization.cc so that its headers stay
    // there.
    struct Mumps;

  private:
    std::unique_ptr<Mumps> mumps;

    // The lower triangle in MUMPS's coordinates (from one): for entry e
    // its row and column, its position in the matrix's value array and
    // that of its mirror (the same for a diagonal entry).
    std::vector<int> rows, columns;
    std::vector<int> positions, mirror_positions;
    // The global index of each locally stored row.
    std::vector<int> row_indices;
    bool             analysed   = false;
    bool             factorized = false;
  };
} // namespace SoftRobot

#endif
