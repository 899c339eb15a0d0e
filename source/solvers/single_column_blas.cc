// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Back substitutions with one right-hand side}
//
// See include/solvers/single_column_blas.h.

#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <dlfcn.h>
#include <solvers/single_column_blas.h>

namespace SoftRobot
{
  namespace
  {
    thread_local bool          active          = false;
    thread_local std::uint64_t forwarded_calls = 0;

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
    return forwarded_calls;
  }



  namespace
  {
    bool
    forwarding()
    {
      if (!active)
        return false;
      ++forwarded_calls;
      return true;
    }
  } // namespace
} // namespace SoftRobot



// @sect4{The replaced routines}
//
// The Fortran BLAS interface: every argument by address, the matrices by
// columns, and after all others the lengths of the character arguments,
// which gfortran passes and a gfortran-compiled BLAS may assume are there
// (see analysis/lapack.h). MUMPS passes them; the definitions below hand
// them on to the library's routines, and the level-2 calls pass 1. (C++
// callers such as deal.II declare the routines without them; the values
// read then are never used by a routine that reads one character.) The
// routines are replaced in double precision (dgemm, dtrsm) and in single
// precision (sgemm, strsm; SymmetricFactorization's single-precision
// factor), with the same code for both.
extern "C" {
void
dgemv_(const char   *trans,
       const int    *m,
       const int    *n,
       const double *alpha,
       const double *a,
       const int    *lda,
       const double *x,
       const int    *incx,
       const double *beta,
       double       *y,
       const int    *incy,
       std::size_t   trans_length);

void
sgemv_(const char  *trans,
       const int   *m,
       const int   *n,
       const float *alpha,
       const float *a,
       const int   *lda,
       const float *x,
       const int   *incx,
       const float *beta,
       float       *y,
       const int   *incy,
       std::size_t  trans_length);

void
dtrsv_(const char   *uplo,
       const char   *trans,
       const char   *diag,
       const int    *n,
       const double *a,
       const int    *lda,
       double       *x,
       const int    *incx,
       std::size_t   uplo_length,
       std::size_t   trans_length,
       std::size_t   diag_length);

void
strsv_(const char  *uplo,
       const char  *trans,
       const char  *diag,
       const int   *n,
       const float *a,
       const int   *lda,
       float       *x,
       const int   *incx,
       std::size_t  uplo_length,
       std::size_t  trans_length,
       std::size_t  diag_length);
}

namespace SoftRobot
{
  namespace
  {
    template <typename Number>
    using Gemv = void(const char *,
                      const int *,
                      const int *,
                      const Number *,
                      const Number *,
                      const int *,
                      const Number *,
                      const int *,
                      const Number *,
                      Number *,
                      const int *,
                      std::size_t);

    template <typename Number>
    using Gemm = void(const char *,
                      const char *,
                      const int *,
                      const int *,
                      const int *,
                      const Number *,
                      const Number *,
                      const int *,
                      const Number *,
                      const int *,
                      const Number *,
                      Number *,
                      const int *,
                      std::size_t,
                      std::size_t);

    template <typename Number>
    using Trsv = void(const char *,
                      const char *,
                      const char *,
                      const int *,
                      const Number *,
                      const int *,
                      Number *,
                      const int *,
                      std::size_t,
                      std::size_t,
                      std::size_t);

    template <typename Number>
    using Trsm = void(const char *,
                      const char *,
                      const char *,
                      const char *,
                      const int *,
                      const int *,
                      const Number *,
                      const Number *,
                      const int *,
                      Number *,
                      const int *,
                      std::size_t,
                      std::size_t,
                      std::size_t,
                      std::size_t);

    // $\mathbf C \leftarrow \alpha\,\mathrm{op}(\mathbf A)\,\mathrm{op}
    // (\mathbf B) + \beta\mathbf C$, $\mathrm{op}(\mathbf A)$ of $m\times
    // k$. With one column ($n = 1$) that is $\mathbf c \leftarrow \alpha\,
    // \mathrm{op}(\mathbf A)\,\mathbf b + \beta\mathbf c$, where $\mathbf
    // b$ is B's column, or its row (stride ldb) when B is transposed.
    template <typename Number>
    void
    gemm(Gemv<Number> *gemv,
         const char   *name,
         const char   *transa,
         const char   *transb,
         const int    *m,
         const int    *n,
         const int    *k,
         const Number *alpha,
         const Number *a,
         const int    *lda,
         const Number *b,
         const int    *ldb,
         const Number *beta,
         Number       *c,
         const int    *ldc,
         std::size_t   transa_length,
         std::size_t   transb_length)
    {
      if (*n == 1 && *m > 0 && *k > 0 && forwarding())
        {
          const int  one       = 1;
          const int *increment = is_transposed(transb) ? ldb : &one;
          if (is_transposed(transa))
            gemv("T", k, m, alpha, a, lda, b, increment, beta, c, &one, 1);
          else
            gemv("N", m, k, alpha, a, lda, b, increment, beta, c, &one, 1);
          return;
        }
      static Gemm<Number> *const library = library_routine<Gemm<Number>>(name);
      library(transa,
              transb,
              m,
              n,
              k,
              alpha,
              a,
              lda,
              b,
              ldb,
              beta,
              c,
              ldc,
              transa_length,
              transb_length);
    }

    // $\mathrm{op}(\mathbf A)\,\mathbf X = \alpha\mathbf B$ (side L) or
    // $\mathbf X\,\mathrm{op}(\mathbf A) = \alpha\mathbf B$ (side R) with
    // a triangular $\mathbf A$, $\mathbf X$ overwriting the $m\times n$
    // matrix $\mathbf B$. From the left with one column and $\alpha = 1$
    // that is trsv.
    template <typename Number>
    void
    trsm(Trsv<Number> *trsv,
         const char   *name,
         const char   *side,
         const char   *uplo,
         const char   *transa,
         const char   *diag,
         const int    *m,
         const int    *n,
         const Number *alpha,
         const Number *a,
         const int    *lda,
         Number       *b,
         const int    *ldb,
         std::size_t   side_length,
         std::size_t   uplo_length,
         std::size_t   transa_length,
         std::size_t   diag_length)
    {
      if (*n == 1 && *m > 0 && (*side == 'L' || *side == 'l') &&
          *alpha == Number(1) && forwarding())
        {
          const int one = 1;
          trsv(uplo, transa, diag, m, a, lda, b, &one, 1, 1, 1);
          return;
        }
      static Trsm<Number> *const library = library_routine<Trsm<Number>>(name);
      library(side,
              uplo,
              transa,
              diag,
              m,
              n,
              alpha,
              a,
              lda,
              b,
              ldb,
              side_length,
              uplo_length,
              transa_length,
              diag_length);
    }
  } // namespace
} // namespace SoftRobot



extern "C" {
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
       const int    *ldc,
       std::size_t   transa_length,
       std::size_t   transb_length)
{
  SoftRobot::gemm<double>(dgemv_,
                          "dgemm_",
                          transa,
                          transb,
                          m,
                          n,
                          k,
                          alpha,
                          a,
                          lda,
                          b,
                          ldb,
                          beta,
                          c,
                          ldc,
                          transa_length,
                          transb_length);
}

void
sgemm_(const char  *transa,
       const char  *transb,
       const int   *m,
       const int   *n,
       const int   *k,
       const float *alpha,
       const float *a,
       const int   *lda,
       const float *b,
       const int   *ldb,
       const float *beta,
       float       *c,
       const int   *ldc,
       std::size_t  transa_length,
       std::size_t  transb_length)
{
  SoftRobot::gemm<float>(sgemv_,
                         "sgemm_",
                         transa,
                         transb,
                         m,
                         n,
                         k,
                         alpha,
                         a,
                         lda,
                         b,
                         ldb,
                         beta,
                         c,
                         ldc,
                         transa_length,
                         transb_length);
}

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
       const int    *ldb,
       std::size_t   side_length,
       std::size_t   uplo_length,
       std::size_t   transa_length,
       std::size_t   diag_length)
{
  SoftRobot::trsm<double>(dtrsv_,
                          "dtrsm_",
                          side,
                          uplo,
                          transa,
                          diag,
                          m,
                          n,
                          alpha,
                          a,
                          lda,
                          b,
                          ldb,
                          side_length,
                          uplo_length,
                          transa_length,
                          diag_length);
}

void
strsm_(const char  *side,
       const char  *uplo,
       const char  *transa,
       const char  *diag,
       const int   *m,
       const int   *n,
       const float *alpha,
       const float *a,
       const int   *lda,
       float       *b,
       const int   *ldb,
       std::size_t  side_length,
       std::size_t  uplo_length,
       std::size_t  transa_length,
       std::size_t  diag_length)
{
  SoftRobot::trsm<float>(strsv_,
                         "strsm_",
                         side,
                         uplo,
                         transa,
                         diag,
                         m,
                         n,
                         alpha,
                         a,
                         lda,
                         b,
                         ldb,
                         side_length,
                         uplo_length,
                         transa_length,
                         diag_length);
}
}
