// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{The LAPACK and BLAS routines the analysis calls}
//
// This header is private to source/analysis/dense_linear_algebra.cc, the
// only file that calls LAPACK, and is therefore not in include/. Keeping it
// out of the public headers matters: deal.II declares the same Fortran
// symbols in its own headers with its own argument types, and a translation
// unit of the simulator that saw both declarations would not compile.
//
// LAPACK is written in Fortran, so every argument is passed by address,
// matrices are stored by columns, and the symbols carry the trailing
// underscore of gfortran's name mangling. Debian's liblapack3 and libblas3
// (like OpenBLAS in its default build) use 32-bit integers, which are
// <code>int</code> below.
//
// <i>Hidden string lengths.</i> A Fortran <code>CHARACTER</code> argument
// comes with its length, which gfortran passes as an extra argument of type
// <code>size_t</code> after all the others. The reference routines read
// only the first character, but gfortran 9 and later compile them on the
// assumption that the lengths are there (a tail call may reuse the caller's
// argument area), so a caller that omitted them would risk its stack. The
// declarations below therefore include the lengths, and every call passes 1.

#ifndef soft_robot_analysis_lapack_h
#define soft_robot_analysis_lapack_h

#include <cstddef>

extern "C" {
// Least squares $\min\|A\mathbf x-\mathbf b\|$ for a matrix of full rank
// by a Householder QR factorisation.
void
dgels_(const char *trans,
       const int  *m,
       const int  *n,
       const int  *nrhs,
       double     *a,
       const int  *lda,
       double     *b,
       const int  *ldb,
       double     *work,
       const int  *lwork,
       int        *info,
       std::size_t trans_length);

// Least squares for a matrix of possibly deficient rank, by a QR
// factorisation with column pivoting; the minimum-norm solution on the
// numerical rank.
void
dgelsy_(const int    *m,
        const int    *n,
        const int    *nrhs,
        double       *a,
        const int    *lda,
        double       *b,
        const int    *ldb,
        int          *jpvt,
        const double *rcond,
        int          *rank,
        double       *work,
        const int    *lwork,
        int          *info);

// The BLAS matrix-vector product
// $\mathbf y \leftarrow \alpha A\mathbf x + \beta\mathbf y$.
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
}

#endif
