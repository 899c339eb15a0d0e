// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Back substitutions with one right-hand side}
//
// MUMPS's back substitution walks through the factor's fronts with the
// level-3 BLAS routines gemm and trsm, written for several right-hand
// sides, also when there is only one. OpenBLAS 0.3.21 (Debian 12's) then
// copies every panel of the factor into its packed buffers before it
// multiplies it with the single column; the copies cost more than the
// products (doc/performance_discussion.md, item 46). While a
// SingleColumnBlas object lives on a thread, the calls of that thread with
// one right-hand side go to the level-2 routines gemv and trsv instead,
// which read each panel once: gemm with one column of B, and trsm from
// the left with one column and the factor one. All other calls, and all
// calls outside such a scope, go to the BLAS the program is linked with.
// Both precisions are handled: dgemm and dtrsm for the double-precision
// factor, sgemm and strsm for the single-precision one
// (SymmetricFactorization).
//
// This works through the dynamic linker: the program defines these
// routines itself (in the source file, like the analysis's LAPACK
// declarations kept out of the public headers, analysis/lapack.h), the
// linker resolves MUMPS's calls to the program's definitions first, and
// these find the BLAS library's own through dlsym(RTLD_NEXT).
// SymmetricFactorization::solve() opens the scope around MUMPS's back
// substitution.
//
// Implemented in source/solvers/single_column_blas.cc.

#ifndef soft_robot_solvers_single_column_blas_h
#define soft_robot_solvers_single_column_blas_h

#include <cstdint>

namespace SoftRobot
{
  class SingleColumnBlas
  {
  public:
    SingleColumnBlas();
    ~SingleColumnBlas();
    SingleColumnBlas(const SingleColumnBlas &) = delete;
    SingleColumnBlas &
    operator=(const SingleColumnBlas &) = delete;

    // The number of calls the calling thread has handed to the level-2
    // routines so far (for the tests: the program's definitions must be the
    // ones MUMPS calls).
    static std::uint64_t
    n_forwarded_calls();

  private:
    // Whether the thread was inside a scope already when this one opened.
    bool was_active;
  };
} // namespace SoftRobot

#endif
