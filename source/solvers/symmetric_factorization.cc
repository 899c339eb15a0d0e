// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{The symmetric factorization}
//
// See include/solvers/symmetric_factorization.h.

#include <Epetra_CrsMatrix.h>
#include <Epetra_Map.h>
#include <algorithm>
#include <deal.II/base/exceptions.h>
#include <dmumps_c.h>
#include <mpi.h>
#include <smumps_c.h>
#include <solvers/single_column_blas.h>
#include <solvers/symmetric_factorization.h>
#include <string>

namespace SoftRobot
{
  // MUMPS's control and information arrays are indexed from one in its
  // documentation (ICNTL(8), INFOG(1)) and from zero here. MUMPS has one
  // library per arithmetic, with the same structure in each: dmumps_c on
  // DMUMPS_STRUC_C for double precision, smumps_c on SMUMPS_STRUC_C for
  // single precision. Mumps is the part of the class that does not depend
  // on it; Instance<> the one that does.
  struct SymmetricFactorization::Mumps
  {
    virtual ~Mumps() = default;

    // The control and information arrays of either structure.
    virtual int *
    icntl() = 0;
    virtual const int *
    infog() const = 0;

    // Job -1 (initialisation), 1 (analysis), 2 (factorization),
    // 3 (back substitution), -2 (end), on the pattern, values and
    // right-hand side handed over below.
    virtual void
    run(const int job) = 0;

    // The pattern in MUMPS's coordinates; the arrays must outlive the
    // instance's use of them.
    virtual void
    set_pattern(const int n, const int nnz, int *rows, int *columns) = 0;

    // The values of the lower triangle, in the instance's arithmetic:
    // entry e is the mean of the matrix's entries at positions[e] and
    // mirror_positions[e].
    virtual void
    set_values(const double           *entries,
               const std::vector<int> &positions,
               const std::vector<int> &mirror_positions) = 0;

    // The back substitution: b and x hold the locally stored rows, whose
    // global indices (MUMPS's order) are row_indices.
    virtual void
    solve(const double *b, const std::vector<int> &row_indices, double *x) = 0;

    int
    error() const
    {
      return infog()[0];
    }

    std::string
    describe() const
    {
      return "MUMPS returned INFOG(1) = " + std::to_string(infog()[0]) +
             ", INFOG(2) = " + std::to_string(infog()[1]);
    }
  };



  namespace
  {
    template <typename Structure, typename Number, void (*call)(Structure *)>
    struct Instance : public SymmetricFactorization::Mumps
    {
      Structure           data = {};
      std::vector<Number> values, rhs;

      // A MUMPS instance on this process alone, symmetric (SYM = 2), the
      // host working too (PAR = 1).
      Instance()
      {
        data.comm_fortran = static_cast<MUMPS_INT>(MPI_Comm_c2f(MPI_COMM_SELF));
        data.par          = 1;
        data.sym          = 2;
        run(-1);
      }

      ~Instance() override
      {
        run(-2);
      }

      int *
      icntl() override
      {
        return data.icntl;
      }

      const int *
      infog() const override
      {
        return data.infog;
      }

      void
      run(const int job) override
      {
        data.job = job;
        call(&data);
      }

      void
      set_pattern(const int n, const int nnz, int *rows, int *columns) override
      {
        data.n   = n;
        data.nnz = nnz;
        data.irn = rows;
        data.jcn = columns;
        values.resize(nnz);
        rhs.resize(n);
        data.a    = values.data();
        data.rhs  = rhs.data();
        data.nrhs = 1;
        data.lrhs = n;
      }

      void
      set_values(const double           *entries,
                 const std::vector<int> &positions,
                 const std::vector<int> &mirror_positions) override
      {
        for (std::size_t e = 0; e < values.size(); ++e)
          values[e] =
            0.5 * (entries[positions[e]] + entries[mirror_positions[e]]);
      }

      void
      solve(const double           *b,
            const std::vector<int> &row_indices,
            double                 *x) override
      {
        for (std::size_t i = 0; i < row_indices.size(); ++i)
          rhs[row_indices[i]] = b[i];
        {
          const SingleColumnBlas single_column;
          run(3);
        }
        for (std::size_t i = 0; i < row_indices.size(); ++i)
          x[i] = rhs[row_indices[i]];
      }
    };

    using DoubleInstance = Instance<DMUMPS_STRUC_C, double, dmumps_c>;
    using SingleInstance = Instance<SMUMPS_STRUC_C, float, smumps_c>;
  } // namespace



  // @sect4{SymmetricFactorization::SymmetricFactorization}
  //
  // A MUMPS instance on this process alone, symmetric (SYM = 2), the host
  // working too (PAR = 1), without output, without scaling.
  SymmetricFactorization::SymmetricFactorization(const Precision precision)
  {
    if (precision == Precision::single_precision)
      mumps = std::make_unique<SingleInstance>();
    else
      mumps = std::make_unique<DoubleInstance>();
    AssertThrow(mumps->error() == 0,
                ExcMessage("MUMPS could not be initialised: " +
                           mumps->describe()));
    int *const icntl = mumps->icntl();
    icntl[0]         = -1;
    icntl[1]         = -1;
    icntl[2]         = -1;
    icntl[3]         = 0;
    icntl[7]         = 0;
  }



  SymmetricFactorization::~SymmetricFactorization() = default;



  // @sect4{SymmetricFactorization::analyse}
  //
  // The entries of the lower triangle and the positions of their mirrors,
  // found through each row's entries sorted by column.
  void
  SymmetricFactorization::analyse(const TrilinosWrappers::SparseMatrix &matrix)
  {
    const Epetra_CrsMatrix &A = matrix.trilinos_matrix();
    AssertThrow(A.Comm().NumProc() == 1,
                ExcMessage("The symmetric factorization needs the matrix on "
                           "one process."));
    int    *offsets = nullptr, *local_columns = nullptr;
    double *entries = nullptr;
    const_cast<Epetra_CrsMatrix &>(A).ExtractCrsDataPointers(offsets,
                                                             local_columns,
                                                             entries);
    const int n = A.NumMyRows();
    row_indices.resize(n);
    // The global row of each local row, and the local row of each global
    // index (all rows are on this process).
    std::vector<int> local_row(n, -1);
    for (int i = 0; i < n; ++i)
      {
        row_indices[i] = A.RowMap().GID(i);
        AssertThrow(row_indices[i] >= 0 && row_indices[i] < n,
                    ExcInternalError());
        local_row[row_indices[i]] = i;
      }
    // Per local row, its positions sorted by global column.
    std::vector<int> global_column(offsets[n]);
    for (int k = 0; k < offsets[n]; ++k)
      global_column[k] = A.ColMap().GID(local_columns[k]);
    std::vector<int> sorted(offsets[n]);
    for (int i = 0; i < n; ++i)
      {
        for (int k = offsets[i]; k < offsets[i + 1]; ++k)
          sorted[k] = k;
        std::sort(sorted.begin() + offsets[i],
                  sorted.begin() + offsets[i + 1],
                  [&](const int a, const int b) {
                    return global_column[a] < global_column[b];
                  });
      }
    const auto position_in_row = [&](const int i, const int column) {
      const auto begin = sorted.begin() + offsets[i];
      const auto end   = sorted.begin() + offsets[i + 1];
      const auto found =
        std::lower_bound(begin, end, column, [&](const int k, const int c) {
          return global_column[k] < c;
        });
      AssertThrow(found != end && global_column[*found] == column,
                  ExcMessage("The symmetric factorization needs a matrix "
                             "with a symmetric sparsity pattern."));
      return *found;
    };

    rows.clear();
    columns.clear();
    positions.clear();
    mirror_positions.clear();
    for (int i = 0; i < n; ++i)
      for (int k = offsets[i]; k < offsets[i + 1]; ++k)
        {
          const int row = row_indices[i], column = global_column[k];
          if (column > row)
            continue;
          rows.push_back(row + 1);
          columns.push_back(column + 1);
          positions.push_back(k);
          mirror_positions.push_back(
            column == row ? k : position_in_row(local_row[column], row));
        }

    mumps->set_pattern(n, rows.size(), rows.data(), columns.data());
    mumps->run(1);
    AssertThrow(mumps->error() >= 0,
                ExcMessage("The symmetric analysis failed: " +
                           mumps->describe()));
    analysed   = true;
    factorized = false;
  }



  // @sect4{SymmetricFactorization::factorize}
  //
  // When MUMPS's estimate of its working memory was too small (INFOG(1) =
  // -8, -9 or -14: more pivoting than the analysis foresaw), the memory
  // relaxation ICNTL(14) is doubled and the factorization repeated.
  bool
  SymmetricFactorization::factorize(
    const TrilinosWrappers::SparseMatrix &matrix)
  {
    Assert(analysed, ExcMessage("factorize() needs analyse() first."));
    int    *offsets = nullptr, *local_columns = nullptr;
    double *entries = nullptr;
    const_cast<Epetra_CrsMatrix &>(matrix.trilinos_matrix())
      .ExtractCrsDataPointers(offsets, local_columns, entries);
    AssertThrow(static_cast<std::size_t>(
                  offsets[matrix.trilinos_matrix().NumMyRows()]) >=
                  positions.size(),
                ExcInternalError());
    mumps->set_values(entries, positions, mirror_positions);
    factorized = false;
    for (unsigned int attempt = 0; attempt < 4; ++attempt)
      {
        mumps->run(2);
        const int error = mumps->error();
        if (error >= 0)
          {
            factorized = true;
            return true;
          }
        if (error == -10)
          return false;
        if (error != -8 && error != -9 && error != -14)
          break;
        mumps->icntl()[13] = 2 * std::max(mumps->icntl()[13], 20);
      }
    AssertThrow(false,
                ExcMessage("The symmetric factorization failed: " +
                           mumps->describe()));
    return false;
  }



  // @sect4{SymmetricFactorization::solve}
  //
  // MUMPS's back substitution with one right-hand side, its level-3 BLAS
  // calls handed to the level-2 routines (SingleColumnBlas).
  void
  SymmetricFactorization::solve(const TrilinosWrappers::MPI::Vector &rhs,
                                TrilinosWrappers::MPI::Vector       &solution)
  {
    AssertThrow(factorized,
                ExcMessage("solve() needs a successful factorize()."));
    mumps->solve(rhs.trilinos_vector()[0],
                 row_indices,
                 solution.trilinos_vector()[0]);
    AssertThrow(mumps->error() >= 0,
                ExcMessage("The symmetric back substitution failed: " +
                           mumps->describe()));
  }
} // namespace SoftRobot
