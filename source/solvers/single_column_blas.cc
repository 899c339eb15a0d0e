// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Back substitutions with one right-hand side}
//
// See include/solvers/single_column_blas.h.

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <dlfcn.h>
#include <solvers/single_column_blas.h>

namespace SoftRobot
{
  namespace
  {
    thread_local bool          active = false;
    std::atomic<std::uint64_t> forwarded_calls{0};

    bool
    is_transposed(const char *flag)
    {
      return *flag == 'T' || *flag == 't' || *flag == 'C' || *flag == 'c';
    }

    // The BLAS library's definition of a routine the program replaces.
    template <typename Function>
    Function *
    library_routine(const char *name)
    {
      void *symbol = dlsym(RTLD_NEXT, name);
      if (symbol == nullptr)
        {
          std::fprintf(stderr,
                       "The BLAS routine %s was not found in a shared "
                       "library the program is linked with.\n",
                       name);
          std::abort();
        }
      return reinterpret_cast<Function *>(symbol);
    }
  } // namespace



  SingleColumnBlas::SingleColumnBlas()
    : was_active(active)
  {
    active = true;
  }



  SingleColumnBlas::~SingleColumnBlas()
  {
    active = was_active;
  }



  std::uint64_t
  SingleColumnBlas::n_forwarded_calls()
  {
    return forwarded_calls.load();
  }



  namespace
  {
    bool
    forwarding()
    {
      if (!active)
        return false;
      forwarded_calls.fetch_add(1, std::memory_order_relaxed);
      return true;
    }
  } // namespace
} // namespace SoftRobot



// @sect4{The replaced routines}
//
// Declared in the header; the level-2 routines they hand calls to are
// declared here. gfortran's hidden lengths of the character arguments are
// left out, as in the C declarations of deal.II and of the BLAS libraries
// themselves: the routines read one character.
extern "C" {
void
dgemv_(const char *,
       const int *,
       const int *,
       const double *,
       const double *,
       const int *,
       const double *,
       const int *,
       const double *,
       double *,
       const int *);

void
dtrsv_(const char *,
       const char *,
       const char *,
       const int *,
       const double *,
       const int *,
       double *,
       const int *);

// With one column ($n = 1$) dgemm is $\mathbf c \leftarrow \alpha\,
// \mathrm{op}(\mathbf A)\,\mathbf b + \beta\mathbf c$, where $\mathbf b$
// is B's column, or its row (stride ldb) when B is transposed.
void
dgemm_(const char   *transa,
       const char   *transb,
       const int    *m,
       const int    *n,
       const int    *k,
       const double *alpha,
       const double *a,
       const int    *lda,
       const double *b,
       const int    *ldb,
       const double *beta,
       double       *c,
       const int    *ldc)
{
  if (*n == 1 && *m > 0 && *k > 0 && SoftRobot::forwarding())
    {
      const int  one       = 1;
      const int *increment = SoftRobot::is_transposed(transb) ? ldb : &one;
      if (SoftRobot::is_transposed(transa))
        dgemv_("T", k, m, alpha, a, lda, b, increment, beta, c, &one);
      else
        dgemv_("N", m, k, alpha, a, lda, b, increment, beta, c, &one);
      return;
    }
  using Dgemm                 = decltype(dgemm_);
  static Dgemm *const library = SoftRobot::library_routine<Dgemm>("dgemm_");
  library(transa, transb, m, n, k, alpha, a, lda, b, ldb, beta, c, ldc);
}

// From the left with one column and $\alpha = 1$, dtrsm is dtrsv.
void
dtrsm_(const char   *side,
       const char   *uplo,
       const char   *transa,
       const char   *diag,
       const int    *m,
       const int    *n,
       const double *alpha,
       const double *a,
       const int    *lda,
       double       *b,
       const int    *ldb)
{
  if (*n == 1 && *m > 0 && (*side == 'L' || *side == 'l') && *alpha == 1. &&
      SoftRobot::forwarding())
    {
      const int one = 1;
      dtrsv_(uplo, transa, diag, m, a, lda, b, &one);
      return;
    }
  using Dtrsm                 = decltype(dtrsm_);
  static Dtrsm *const library = SoftRobot::library_routine<Dtrsm>("dtrsm_");
  library(side, uplo, transa, diag, m, n, alpha, a, lda, b, ldb);
}
}
