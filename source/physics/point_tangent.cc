// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{A quadrature point's share of a cell matrix}
//
// See include/physics/point_tangent.h.

#include <core/config.h>
#include <cstring>
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



  // @sect4{The product}
  //
  // $\mathbf R \mathrel{+}= \mathbf X\mathbf Y$ for the rows a of
  // $\mathbf X$ (gradients, $n \times K$ with $K = d\,n_q$) and the
  // columns of $\mathbf Y$ ($K \times d^2 s$ for the block's stride s, a
  // multiple of the tile's width): tiles of `rows` rows and `width`
  // columns, summed in vector registers over all K. For a lower
  // triangle, in each of the $d^2$ segments of s columns a tile of
  // columns from b0 on is formed only for the rows from b0 on (rounded
  // down to the tile's rows); the few pairs b > a this forms are not
  // read.
  //
  // The vectors are GCC's vector extensions. Every x86-64 processor has
  // two-lane vectors (SSE2), and the tiles are then 4 rows by 4 columns;
  // on processors with AVX2 (`__builtin_cpu_supports`, asked once) they
  // are four-lane vectors in tiles of 3 rows by 8 columns. These sizes
  // were the fastest of those tried on quadratic hexahedra (a throwaway
  // driver, doc/performance_discussion.md, item 39). Blocks of at most four
  // shape functions (linear tetrahedra) take tiles of 4 by 4 there: padded
  // to 8 columns, half of their products were zeros (item 40). Both variants
  // multiply and add (no fused multiply-add) in the same order, so the
  // result does not depend on the processor: the same bits, checked by
  // hand on random blocks.
  namespace
  {
    template <typename Vector, int lanes, int rows, int vectors>
    __attribute__((always_inline)) inline void
    multiply_tile(const unsigned int a,
                  const unsigned int j,
                  const unsigned int n_columns,
                  const unsigned int K,
                  const double *__restrict X,
                  const double *__restrict Y,
                  double *__restrict R)
    {
      Vector sum[rows][vectors];
#pragma GCC unroll 4
      for (int r = 0; r < rows; ++r)
#pragma GCC unroll 4
        for (int v = 0; v < vectors; ++v)
          sum[r][v] = Vector{};
      for (unsigned int k = 0; k < K; ++k)
        {
          Vector y[vectors];
#pragma GCC unroll 4
          for (int v = 0; v < vectors; ++v)
            std::memcpy(&y[v],
                        Y + k * n_columns + j + v * lanes,
                        sizeof(Vector));
#pragma GCC unroll 4
          for (int r = 0; r < rows; ++r)
            {
              const double value = X[(a + r) * K + k];
              Vector       x;
              if constexpr (lanes == 2)
                x = Vector{value, value};
              else
                x = Vector{value, value, value, value};
#pragma GCC unroll 4
              for (int v = 0; v < vectors; ++v)
                sum[r][v] += x * y[v];
            }
        }
      for (int r = 0; r < rows; ++r)
        for (int v = 0; v < vectors; ++v)
          {
            double *target = R + (a + r) * n_columns + j + v * lanes;
            Vector  value;
            std::memcpy(&value, target, sizeof(value));
            value += sum[r][v];
            std::memcpy(target, &value, sizeof(value));
          }
    }

    // The operands of a product: the n rows of $\mathbf X$ and the
    // segments of s columns of $\mathbf Y$ (`stride`), of which the first
    // `columns` are formed, K in between.
    struct Product
    {
      unsigned int  n;
      unsigned int  columns;
      unsigned int  n_segments;
      unsigned int  stride;
      unsigned int  K;
      const double *X;
      const double *Y;
      bool          lower;
      double       *R;
    };

    template <typename Vector, int lanes, int rows, int vectors>
    __attribute__((always_inline)) inline void
    multiply(const Product &p)
    {
      constexpr unsigned int width     = lanes * vectors;
      const unsigned int     n_columns = p.n_segments * p.stride;
      for (unsigned int segment = 0; segment < p.n_segments; ++segment)
        for (unsigned int b0 = 0; b0 < p.columns; b0 += width)
          {
            const unsigned int j = segment * p.stride + b0;
            unsigned int       a = p.lower ? b0 / rows * rows : 0;
            for (; a + rows <= p.n; a += rows)
              multiply_tile<Vector, lanes, rows, vectors>(
                a, j, n_columns, p.K, p.X, p.Y, p.R);
            for (; a < p.n; ++a)
              multiply_tile<Vector, lanes, 1, vectors>(
                a, j, n_columns, p.K, p.X, p.Y, p.R);
          }
    }

    // The block's stride is a multiple of the tiles' width (tile_width()).
    using Vector2 = double __attribute__((vector_size(16)));
    using Vector4 = double __attribute__((vector_size(32)));

    void
    multiply_generic(const Product &p)
    {
      multiply<Vector2, 2, 4, 2>(p);
    }

#if defined(__x86_64__) && defined(__GNUC__)
    __attribute__((target("avx2"))) void
    multiply_avx2(const Product &p)
    {
      if (p.stride == 4)
        multiply<Vector4, 4, 4, 1>(p);
      else
        multiply<Vector4, 4, 3, 2>(p);
    }

    bool
    has_avx2()
    {
      static const bool answer = __builtin_cpu_supports("avx2");
      return answer;
    }
#else
    bool
    has_avx2()
    {
      return false;
    }
#endif

    unsigned int
    tile_width(const unsigned int n)
    {
      return (has_avx2() && n > 4) ? 8 : 4;
    }

    // The stride of `columns` columns: a multiple of their tiles' width.
    unsigned int
    padded(const unsigned int columns)
    {
      const unsigned int width = tile_width(columns);
      return (columns + width - 1) / width * width;
    }

    void
    form_product(const Product &product)
    {
#if defined(__x86_64__) && defined(__GNUC__)
      if (has_avx2())
        multiply_avx2(product);
      else
#endif
        multiply_generic(product);
    }

    // Multiplies out the points added since the last call.
    template <int dim>
    void
    multiply_pending(const CellGeometry<dim> &geometry, TangentBlock &block)
    {
      if (block.pending_points == 0)
        return;
      const unsigned int n = geometry.n_shape_functions;
      const unsigned int K = dim * block.pending_points;
      // The left factor was laid out for all points of a cell; with fewer
      // it is packed to K columns first.
      const unsigned int capacity = dim * geometry.n_q_points;
      if (K < capacity)
        for (unsigned int a = 1; a < n; ++a)
          std::memmove(&block.left[a * K],
                       &block.left[a * capacity],
                       K * sizeof(double));
      const Product product{n,
                            n,
                            dim * dim,
                            block.stride,
                            K,
                            block.left.data(),
                            block.right.data(),
                            block.symmetric,
                            block.values.data()};
      form_product(product);
      block.pending_points = 0;
    }
  } // namespace



  // @sect4{add_point_tangent}
  //
  // The point's columns of the left factor, $\partial_J\varphi_a$, and
  // its rows of the right one, $Y_{(q,J),(c,k,b)} = w\sum_L \mathcal
  // A_{cJkL}\partial_L\varphi_b$ (zero in the padding b >= n).
  template <int dim>
  void
  add_point_tangent(const CellGeometry<dim> &geometry,
                    const Tensor<1, dim>    *grad_phi,
                    const Tensor<4, dim>    &A,
                    const double             weight,
                    const Symmetry           symmetry,
                    TangentBlock            &block)
  {
    const unsigned int               n        = geometry.n_shape_functions;
    const std::vector<unsigned int> &dofs     = geometry.shape_dofs;
    const unsigned int               capacity = dim * geometry.n_q_points;
    const unsigned int               stride   = block.stride;
    Assert(block.values.size() == n * dim * dim * stride, ExcInternalError());
    const bool symmetric = (symmetry == Symmetry::symmetric);
    Assert(block.pending_points == 0 || block.symmetric == symmetric,
           ExcMessage("The points of a block must have the same symmetry."));
    if (block.pending_points == geometry.n_q_points)
      multiply_pending(geometry, block);
    block.symmetric              = symmetric;
    constexpr unsigned int max_n = 64;
    AssertThrow(n <= max_n, ExcInternalError());
    double gradient[dim][max_n];
    for (unsigned int b = 0; b < n; ++b)
      for (unsigned int L = 0; L < dim; ++L)
        gradient[L][b] = grad_phi[dofs[b * dim]][L];
    const unsigned int first = dim * block.pending_points;
    for (unsigned int J = 0; J < dim; ++J)
      {
        for (unsigned int a = 0; a < n; ++a)
          block.left[a * capacity + first + J] = gradient[J][a];
        double *row = &block.right[(first + J) * dim * dim * stride];
        for (unsigned int c = 0; c < dim; ++c)
          for (unsigned int k = 0; k < dim; ++k)
            {
              double W[dim];
              for (unsigned int L = 0; L < dim; ++L)
                W[L] = weight * A[c][J][k][L];
              double *__restrict y = row + (c * dim + k) * stride;
              for (unsigned int b = 0; b < n; ++b)
                {
                  double sum = 0.;
                  for (unsigned int L = 0; L < dim; ++L)
                    sum += W[L] * gradient[L][b];
                  y[b] = sum;
                }
              for (unsigned int b = n; b < stride; ++b)
                y[b] = 0.;
            }
      }
    ++block.pending_points;
  }



  template <int dim>
  void
  reset_tangent_block(const CellGeometry<dim> &geometry, TangentBlock &block)
  {
    const unsigned int n = geometry.n_shape_functions;
    block.stride         = padded(n);
    block.values.assign(n * dim * dim * block.stride, 0.);
    const unsigned int capacity = dim * geometry.n_q_points;
    block.left.resize(n * capacity);
    block.right.resize(capacity * dim * dim * block.stride);
    block.pending_points = 0;
    block.symmetric      = false;
  }



  // A symmetric block holds the pairs $b \le a$; the pair (a c, b k) with
  // $b > a$ is the pair (b k, a c).
  template <int dim>
  void
  add_tangent_block(const CellGeometry<dim> &geometry,
                    TangentBlock            &block,
                    const Symmetry           symmetry,
                    FullMatrix<double>      &matrix)
  {
    Assert(block.pending_points == 0 ||
             block.symmetric == (symmetry == Symmetry::symmetric),
           ExcMessage("The block is read with another symmetry than its "
                      "points were added with."));
    multiply_pending(geometry, block);
    const unsigned int               n      = geometry.n_shape_functions;
    const unsigned int               stride = block.stride;
    const std::vector<unsigned int> &dofs   = geometry.shape_dofs;
    const std::vector<double>       &values = block.values;
    for (unsigned int a = 0; a < n; ++a)
      for (unsigned int c = 0; c < dim; ++c)
        for (unsigned int k = 0; k < dim; ++k)
          {
            const unsigned int i = dofs[a * dim + c];
            const double *row    = &values[((a * dim + c) * dim + k) * stride];
            const unsigned int n_b =
              (symmetry == Symmetry::symmetric) ? a + 1 : n;
            for (unsigned int b = 0; b < n_b; ++b)
              matrix(i, dofs[b * dim + k]) += row[b];
            for (unsigned int b = n_b; b < n; ++b)
              matrix(i, dofs[b * dim + k]) +=
                values[((b * dim + k) * dim + c) * stride + a];
          }
  }



  // @sect4{The gradients and forces of a cell as products}
  unsigned int
  product_stride(const unsigned int columns)
  {
    return padded(columns);
  }



  // The gradients by node: the reference ones, $\hat G_{a,(q,K)} =
  // \hat\partial_K\varphi_a(\hat{\mathbf x}_q)$, which are CellGeometry's
  // (the cell then only copies its inverse Jacobians), or the cell's own,
  // $G_{a,(q,J)} = \partial_J\varphi_a(\mathbf x_q)$. Forming its own
  // costs a cell $n\,n_q d^2$ multiply-adds; the pull-backs of two fields'
  // gradients and two stresses about $4 n_q d^3$. By that count the
  // reference gradients are the cheaper for at least $4d$ shape functions
  // (quadratic hexahedra, not the tetrahedra), and are taken there; the
  // gain was measured on the quadratic hexahedra only
  // (doc/performance_discussion.md, item 50). Either
  // way the rows are padded to a multiple of the tiles' width with zeros,
  // so that they can also serve as the left factor of a product summed
  // over all of a row.
  template <int dim>
  void
  reset_cell_products(const CellGeometry<dim> &geometry,
                      const unsigned int       cell,
                      CellProducts            &products)
  {
    const unsigned int n      = geometry.n_shape_functions;
    const unsigned int n_q    = geometry.n_q_points;
    const unsigned int stride = geometry.node_gradient_stride;
    products.gradient_stride  = stride;
    products.pulled_back      = n >= 4 * dim;
    if (products.pulled_back)
      {
        products.gradients = geometry.reference_gradients_by_node.data();
        products.inverse_jacobians.resize(n_q * dim * dim);
        for (unsigned int q = 0; q < n_q; ++q)
          {
            const Tensor<2, dim> &inverse_jacobian =
              geometry.inverse_jacobians[cell * n_q + q];
            for (unsigned int K = 0; K < dim; ++K)
              for (unsigned int J = 0; J < dim; ++J)
                products.inverse_jacobians[(q * dim + K) * dim + J] =
                  inverse_jacobian[K][J];
          }
      }
    else
      {
        std::vector<double> &gradients = products.cell_gradients;
        gradients.resize(n * stride);
        for (unsigned int a = 0; a < n; ++a)
          for (unsigned int k = dim * n_q; k < stride; ++k)
            gradients[a * stride + k] = 0.;
        // Point by point, with the inverse Jacobian of the point in local
        // numbers (the same products as CellGeometry::shape_gradient()).
        for (unsigned int q = 0; q < n_q; ++q)
          {
            const Tensor<2, dim> &inverse_jacobian =
              geometry.inverse_jacobians[cell * n_q + q];
            double J_inv[dim][dim];
            for (unsigned int i = 0; i < dim; ++i)
              for (unsigned int J = 0; J < dim; ++J)
                J_inv[i][J] = inverse_jacobian[i][J];
            for (unsigned int a = 0; a < n; ++a)
              {
                const double *reference =
                  &geometry.reference_gradients_by_node[a * stride + q * dim];
                double *entry = &gradients[a * stride + q * dim];
                for (unsigned int J = 0; J < dim; ++J)
                  {
                    double sum = 0.;
                    for (unsigned int i = 0; i < dim; ++i)
                      sum += reference[i] * J_inv[i][J];
                    entry[J] = sum;
                  }
              }
          }
        products.gradients = gradients.data();
      }
    products.stress_stride = padded(2 * dim);
    products.stresses.assign(stride * products.stress_stride, 0.);
  }



  // $H^{(f)}_{c,(q,J)} = \sum_a u^{(f)}_{a c}\,G_{a,(q,J)}$ for the fields
  // f: a product of the nodal values (rows (f, c)) with the gradients. With
  // the reference gradients the product is $\hat H^{(f)}_{c,(q,K)}$, and
  // $H^{(f)}_{q,cJ} = \sum_K \hat H^{(f)}_{c,(q,K)} (\mathbf
  // J_q^{-1})_{KJ}$.
  template <int dim>
  void
  field_gradients(const CellGeometry<dim>                          &geometry,
                  CellProducts                                     &products,
                  const std::vector<const double *>                &fields,
                  const std::vector<std::vector<Tensor<2, dim>> *> &gradients)
  {
    const unsigned int n        = geometry.n_shape_functions;
    const unsigned int n_q      = geometry.n_q_points;
    const unsigned int stride   = products.gradient_stride;
    const unsigned int n_fields = fields.size();
    const unsigned int rows     = n_fields * dim;
    products.values.resize(rows * n);
    for (unsigned int f = 0; f < n_fields; ++f)
      for (unsigned int c = 0; c < dim; ++c)
        for (unsigned int a = 0; a < n; ++a)
          products.values[(f * dim + c) * n + a] =
            fields[f][geometry.shape_dofs[a * dim + c]];
    products.result.assign(rows * stride, 0.);
    form_product(Product{rows,
                         dim * n_q,
                         1,
                         stride,
                         n,
                         products.values.data(),
                         products.gradients,
                         false,
                         products.result.data()});
    for (unsigned int f = 0; f < n_fields; ++f)
      {
        std::vector<Tensor<2, dim>> &H = *gradients[f];
        H.resize(n_q);
        if (!products.pulled_back)
          {
            for (unsigned int q = 0; q < n_q; ++q)
              for (unsigned int c = 0; c < dim; ++c)
                for (unsigned int J = 0; J < dim; ++J)
                  H[q][c][J] =
                    products.result[(f * dim + c) * stride + q * dim + J];
            continue;
          }
        for (unsigned int q = 0; q < n_q; ++q)
          {
            const double *J_inv = &products.inverse_jacobians[q * dim * dim];
            for (unsigned int c = 0; c < dim; ++c)
              {
                const double *reference =
                  &products.result[(f * dim + c) * stride + q * dim];
                for (unsigned int J = 0; J < dim; ++J)
                  {
                    double sum = 0.;
                    for (unsigned int K = 0; K < dim; ++K)
                      sum += reference[K] * J_inv[K * dim + J];
                    H[q][c][J] = sum;
                  }
              }
          }
      }
  }



  template <int dim>
  void
  add_point_stress(const unsigned int    q,
                   const unsigned int    column,
                   const Tensor<2, dim> &P,
                   const double          weight,
                   CellProducts         &products)
  {
    if (!products.pulled_back)
      {
        for (unsigned int J = 0; J < dim; ++J)
          {
            double *row =
              &products.stresses[(q * dim + J) * products.stress_stride +
                                 column * dim];
            for (unsigned int c = 0; c < dim; ++c)
              row[c] = weight * P[c][J];
          }
        return;
      }
    const double *J_inv = &products.inverse_jacobians[q * dim * dim];
    for (unsigned int K = 0; K < dim; ++K)
      {
        double *row =
          &products
             .stresses[(q * dim + K) * products.stress_stride + column * dim];
        for (unsigned int c = 0; c < dim; ++c)
          {
            double sum = 0.;
            for (unsigned int J = 0; J < dim; ++J)
              sum += P[c][J] * J_inv[K * dim + J];
            row[c] = weight * sum;
          }
      }
  }



  // $f^{(s)}_{a c} = \sum_{(q,J)} G_{a,(q,J)}\,w_q P^{(s)}_{q,cJ}$ for both
  // stresses at once: the gradients times the stresses' columns (or
  // $\sum_{(q,K)} \hat G_{a,(q,K)}\,w_q (\mathbf P^{(s)}_q\mathbf
  // J_q^{-T})_{cK}$ with the reference gradients).
  template <int dim>
  void
  add_stress_forces(const CellGeometry<dim> &geometry,
                    CellProducts            &products,
                    Vector<double>          &force,
                    Vector<double>          &second_force)
  {
    const unsigned int n      = geometry.n_shape_functions;
    const unsigned int stride = products.stress_stride;
    products.result.assign(n * stride, 0.);
    form_product(Product{n,
                         2 * dim,
                         1,
                         stride,
                         products.gradient_stride,
                         products.gradients,
                         products.stresses.data(),
                         false,
                         products.result.data()});
    for (unsigned int a = 0; a < n; ++a)
      for (unsigned int c = 0; c < dim; ++c)
        {
          const unsigned int i = geometry.shape_dofs[a * dim + c];
          force(i) += products.result[a * stride + c];
          second_force(i) += products.result[a * stride + dim + c];
        }
  }



#define SOFT_ROBOT_INSTANTIATE(dim)                                         \
  template void reset_cell_products<dim>(const CellGeometry<dim> &,         \
                                         const unsigned int,                \
                                         CellProducts &);                   \
  template void field_gradients<dim>(                                       \
    const CellGeometry<dim> &,                                              \
    CellProducts &,                                                         \
    const std::vector<const double *> &,                                    \
    const std::vector<std::vector<Tensor<2, dim>> *> &);                    \
  template void add_point_stress<dim>(const unsigned int,                   \
                                      const unsigned int,                   \
                                      const Tensor<2, dim> &,               \
                                      const double,                         \
                                      CellProducts &);                      \
  template void add_stress_forces<dim>(const CellGeometry<dim> &,           \
                                       CellProducts &,                      \
                                       Vector<double> &,                    \
                                       Vector<double> &);                   \
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
                                       TangentBlock &);                     \
  template void reset_tangent_block<dim>(const CellGeometry<dim> &,         \
                                         TangentBlock &);                   \
  template void add_tangent_block<dim>(const CellGeometry<dim> &,           \
                                       TangentBlock &,                      \
                                       const Symmetry,                      \
                                       FullMatrix<double> &);
  SOFT_ROBOT_FOR_EACH_DIMENSION(SOFT_ROBOT_INSTANTIATE)
#undef SOFT_ROBOT_INSTANTIATE
} // namespace SoftRobot
