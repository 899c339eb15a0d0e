// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{A quadrature point's share of a cell matrix}
//
// See include/physics/point_tangent.h.

#include <core/config.h>
#include <physics/point_tangent.h>

namespace SoftRobot
{
  // @sect4{add_pulled_tangent}
  //
  // In two contractions of three indices each: $T_{cJKL} = \sum_I X_{cI}
  // \mathcal C_{IJKL}$, then $\sum_K T_{cJKL}Y_{kK}$.
  template <int dim>
  void
  add_pulled_tangent(const Tensor<2, dim>          &X,
                     const SymmetricTensor<4, dim> &C,
                     const Tensor<2, dim>          &Y,
                     const double                   factor,
                     Tensor<4, dim>                &A)
  {
    double T[dim][dim][dim][dim] = {};
    for (unsigned int c = 0; c < dim; ++c)
      for (unsigned int I = 0; I < dim; ++I)
        {
          const double x = X[c][I];
          for (unsigned int J = 0; J < dim; ++J)
            for (unsigned int K = 0; K < dim; ++K)
              for (unsigned int L = 0; L < dim; ++L)
                T[c][J][K][L] += x * C[I][J][K][L];
        }
    for (unsigned int c = 0; c < dim; ++c)
      for (unsigned int J = 0; J < dim; ++J)
        for (unsigned int k = 0; k < dim; ++k)
          for (unsigned int L = 0; L < dim; ++L)
            {
              double sum = 0.;
              for (unsigned int K = 0; K < dim; ++K)
                sum += T[c][J][K][L] * Y[k][K];
              A[c][J][k][L] += factor * sum;
            }
  }



  template <int dim>
  void
  add_geometric_tangent(const SymmetricTensor<2, dim> &S, Tensor<4, dim> &A)
  {
    for (unsigned int c = 0; c < dim; ++c)
      for (unsigned int J = 0; J < dim; ++J)
        for (unsigned int L = 0; L < dim; ++L)
          A[c][J][c][L] += S[J][L];
  }



  // The Levi-Civita symbol's products: for $a \ne b$ the one $k$ with
  // $\varepsilon_{abk} \ne 0$ is $3 - a - b$, with the sign of the cyclic
  // order.
  void
  add_volume_hessian(const Tensor<2, 3> &F,
                     const double        factor,
                     Tensor<4, 3>       &A)
  {
    for (unsigned int a = 0; a < 3; ++a)
      for (unsigned int b = 0; b < 3; ++b)
        if (a != b)
          {
            const unsigned int k    = 3 - a - b;
            const double       sign = ((a + 1) % 3 == b) ? 1. : -1.;
            for (unsigned int I = 0; I < 3; ++I)
              for (unsigned int J = 0; J < 3; ++J)
                if (I != J)
                  {
                    const unsigned int K       = 3 - I - J;
                    const double       sign_IJ = ((I + 1) % 3 == J) ? 1. : -1.;
                    A[a][I][b][J] += factor * sign * sign_IJ * F[k][K];
                  }
          }
  }



  // @sect4{add_point_tangent}
  //
  // Node by node (see the header), with the gradients of the shape
  // functions copied into one array per direction so that the innermost
  // loop runs over b with unit stride; for a symmetric $\mathcal A$ only
  // over $b \le a$.
  template <int dim>
  void
  add_point_tangent(const CellGeometry<dim> &geometry,
                    const Tensor<1, dim>    *grad_phi,
                    const Tensor<4, dim>    &A,
                    const double             weight,
                    const Symmetry           symmetry,
                    std::vector<double>     &block)
  {
    const unsigned int               n    = geometry.n_shape_functions;
    const std::vector<unsigned int> &dofs = geometry.shape_dofs;
    Assert(block.size() == n * n * dim * dim, ExcInternalError());
    constexpr unsigned int max_n = 64;
    AssertThrow(n <= max_n, ExcInternalError());
    double gradient[dim][max_n];
    for (unsigned int b = 0; b < n; ++b)
      for (unsigned int L = 0; L < dim; ++L)
        gradient[L][b] = grad_phi[dofs[b * dim]][L];
    for (unsigned int a = 0; a < n; ++a)
      for (unsigned int c = 0; c < dim; ++c)
        for (unsigned int k = 0; k < dim; ++k)
          {
            const unsigned int n_b =
              (symmetry == Symmetry::symmetric) ? a + 1 : n;
            double W[dim];
            for (unsigned int L = 0; L < dim; ++L)
              {
                double sum = 0.;
                for (unsigned int J = 0; J < dim; ++J)
                  sum += gradient[J][a] * A[c][J][k][L];
                W[L] = weight * sum;
              }
            double *__restrict row = &block[((a * dim + c) * dim + k) * n];
            if constexpr (dim == 3)
              {
                const double *__restrict g0 = gradient[0];
                const double *__restrict g1 = gradient[1];
                const double *__restrict g2 = gradient[2];
                for (unsigned int b = 0; b < n_b; ++b)
                  row[b] += W[0] * g0[b] + W[1] * g1[b] + W[2] * g2[b];
              }
            else
              for (unsigned int L = 0; L < dim; ++L)
                for (unsigned int b = 0; b < n_b; ++b)
                  row[b] += W[L] * gradient[L][b];
          }
  }



  template <int dim>
  void
  reset_tangent_block(const CellGeometry<dim> &geometry,
                      std::vector<double>     &block)
  {
    block.assign(geometry.dofs_per_cell * geometry.dofs_per_cell, 0.);
  }



  // A symmetric block holds the pairs $b \le a$; the pair (a c, b k) with
  // $b > a$ is the pair (b k, a c).
  template <int dim>
  void
  add_tangent_block(const CellGeometry<dim>   &geometry,
                    const std::vector<double> &block,
                    const Symmetry             symmetry,
                    FullMatrix<double>        &matrix)
  {
    const unsigned int               n    = geometry.n_shape_functions;
    const std::vector<unsigned int> &dofs = geometry.shape_dofs;
    for (unsigned int a = 0; a < n; ++a)
      for (unsigned int c = 0; c < dim; ++c)
        for (unsigned int k = 0; k < dim; ++k)
          {
            const unsigned int i   = dofs[a * dim + c];
            const double      *row = &block[((a * dim + c) * dim + k) * n];
            const unsigned int n_b =
              (symmetry == Symmetry::symmetric) ? a + 1 : n;
            for (unsigned int b = 0; b < n_b; ++b)
              matrix(i, dofs[b * dim + k]) += row[b];
            for (unsigned int b = n_b; b < n; ++b)
              matrix(i, dofs[b * dim + k]) +=
                block[((b * dim + k) * dim + c) * n + a];
          }
  }



#define SOFT_ROBOT_INSTANTIATE(dim)                                         \
  template void add_pulled_tangent<dim>(const Tensor<2, dim> &,             \
                                        const SymmetricTensor<4, dim> &,    \
                                        const Tensor<2, dim> &,             \
                                        const double,                       \
                                        Tensor<4, dim> &);                  \
  template void add_geometric_tangent<dim>(const SymmetricTensor<2, dim> &, \
                                           Tensor<4, dim> &);               \
  template void add_point_tangent<dim>(const CellGeometry<dim> &,           \
                                       const Tensor<1, dim> *,              \
                                       const Tensor<4, dim> &,              \
                                       const double,                        \
                                       const Symmetry,                      \
                                       std::vector<double> &);              \
  template void reset_tangent_block<dim>(const CellGeometry<dim> &,         \
                                         std::vector<double> &);            \
  template void add_tangent_block<dim>(const CellGeometry<dim> &,           \
                                       const std::vector<double> &,         \
                                       const Symmetry,                      \
                                       FullMatrix<double> &);
  SOFT_ROBOT_FOR_EACH_DIMENSION(SOFT_ROBOT_INSTANTIATE)
#undef SOFT_ROBOT_INSTANTIATE
} // namespace SoftRobot
