// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{A cell matrix by shape functions is the sum of its points' shares}
//
// physics/point_tangent.h forms a cell's matrix
// $K_{(a,c),(b,k)} = \sum_q w_q\sum_{J,L}\partial_J\varphi_a(\mathbf x_q)
// \,\mathcal A^q_{cJkL}\,\partial_L\varphi_b(\mathbf x_q)$ as one matrix
// product over all points, in register tiles with padded rows. The test
// adds random points (random gradients, a random tensor per point, random
// weights) and compares every entry of the matrix that add_tangent_block()
// writes with the sum over the points formed directly in long double:
// - in 1D, 2D and 3D, with the quadratic element's number of shape
//   functions ($3^d$), so that the rows and columns are not multiples of
//   the tiles' sizes, and with the linear simplex's $d + 1$ and one point,
//   whose blocks of at most four columns take narrower tiles;
// - for a general tensor, and for one with the major symmetry $\mathcal
//   A_{cJkL} = \mathcal A_{kLcJ}$, of which only the pairs $b \le a$ are
//   formed and the others taken from their transposes;
// - with as many points as the cell has, with fewer (the buffer is then
//   packed before the product), and with more (the product is then formed
//   twice);
// - with shape functions numbered across the components in an order other
//   than the blocks' (`shape_dofs` reversed).
//
// The tolerance is that of a sum of $m = d^2 n_q$ products of four
// factors, in any order: $\gamma_{m+3}\sum|x|$ per entry, with $\gamma_m =
// mu/(1 - mu)$ and $u = 2^{-53}$ (Higham, Accuracy and Stability of
// Numerical Algorithms, section 3.1), the sum of absolute values formed
// alongside. The symmetric case's entries b > a are those of the
// transposed pair, and must equal the directly formed sum as closely.

#include "solver_test_tools.h"

#include <deal.II/base/tensor.h>
#include <deal.II/lac/full_matrix.h>
#include <gtest/gtest.h>
#include <limits>
#include <physics/point_tangent.h>
#include <random>

using namespace dealii;
using namespace SoftRobot;
using namespace SoftRobot::Testing;

template <typename T>
class PointTangentTest : public ::testing::Test
{
};
TYPED_TEST_SUITE(PointTangentTest, Dimensions);

namespace
{
  template <int dim>
  struct RandomPoint
  {
    std::vector<Tensor<1, dim>> gradients; // by dof
    Tensor<4, dim>              A;
    double                      weight;
  };

  // A cell of n shape functions per component and n_q points, its dofs
  // numbered in reverse of the blocks' order.
  template <int dim>
  CellGeometry<dim>
  test_geometry(const unsigned int n, const unsigned int n_q)
  {
    CellGeometry<dim> geometry;
    geometry.n_shape_functions = n;
    geometry.dofs_per_cell     = n * dim;
    geometry.n_q_points        = n_q;
    geometry.shape_dofs.resize(n * dim);
    for (unsigned int i = 0; i < n * dim; ++i)
      geometry.shape_dofs[i] = n * dim - 1 - i;
    return geometry;
  }

  // Adds `n_points` random points to a block of a cell with `n` shape
  // functions per component and `n_q` points and compares the block with
  // the direct sum; returns the largest ratio of difference to tolerance.
  template <int dim>
  double
  largest_error_ratio(const unsigned int n,
                      const unsigned int n_q,
                      const unsigned int n_points,
                      const Symmetry     symmetry,
                      std::mt19937      &rng)
  {
    const CellGeometry<dim> geometry = test_geometry<dim>(n, n_q);

    std::uniform_real_distribution<double> uniform(-1., 1.);
    std::vector<RandomPoint<dim>>          points(n_points);
    for (RandomPoint<dim> &point : points)
      {
        point.gradients.resize(n * dim);
        // A shape function's gradient is the same for all its components.
        for (unsigned int a = 0; a < n; ++a)
          {
            Tensor<1, dim> g;
            for (unsigned int d = 0; d < dim; ++d)
              g[d] = uniform(rng);
            for (unsigned int c = 0; c < dim; ++c)
              point.gradients[geometry.shape_dofs[a * dim + c]] = g;
          }
        for (unsigned int c = 0; c < dim; ++c)
          for (unsigned int J = 0; J < dim; ++J)
            for (unsigned int k = 0; k < dim; ++k)
              for (unsigned int L = 0; L < dim; ++L)
                point.A[c][J][k][L] = uniform(rng);
        if (symmetry == Symmetry::symmetric)
          for (unsigned int c = 0; c < dim; ++c)
            for (unsigned int J = 0; J < dim; ++J)
              for (unsigned int k = 0; k < dim; ++k)
                for (unsigned int L = 0; L < dim; ++L)
                  point.A[k][L][c][J] = point.A[c][J][k][L];
        point.weight = 0.5 + 0.5 * uniform(rng);
      }

    TangentBlock block;
    reset_tangent_block(geometry, block);
    for (const RandomPoint<dim> &point : points)
      add_point_tangent(geometry,
                        point.gradients.data(),
                        point.A,
                        point.weight,
                        symmetry,
                        block);
    FullMatrix<double> matrix(n * dim, n * dim);
    add_tangent_block(geometry, block, symmetry, matrix);

    const double u     = 0.5 * std::numeric_limits<double>::epsilon();
    const double m     = dim * dim * n_points + 3;
    const double gamma = m * u / (1. - m * u);
    double       worst = 0.;
    for (unsigned int a = 0; a < n; ++a)
      for (unsigned int c = 0; c < dim; ++c)
        for (unsigned int b = 0; b < n; ++b)
          for (unsigned int k = 0; k < dim; ++k)
            {
              long double sum = 0., magnitude = 0.;
              for (const RandomPoint<dim> &point : points)
                {
                  const Tensor<1, dim> &ga =
                    point.gradients[geometry.shape_dofs[a * dim + c]];
                  const Tensor<1, dim> &gb =
                    point.gradients[geometry.shape_dofs[b * dim + k]];
                  for (unsigned int J = 0; J < dim; ++J)
                    for (unsigned int L = 0; L < dim; ++L)
                      {
                        const long double term =
                          static_cast<long double>(ga[J]) *
                          point.A[c][J][k][L] * gb[L] * point.weight;
                        sum += term;
                        magnitude += std::abs(term);
                      }
                }
              const double value     = matrix(geometry.shape_dofs[a * dim + c],
                                          geometry.shape_dofs[b * dim + k]);
              const double tolerance = gamma * static_cast<double>(magnitude);
              worst                  = std::max(worst,
                               std::abs(value - static_cast<double>(sum)) /
                                 tolerance);
            }
    return worst;
  }

  // The cells of the tests, (shape functions, points): the quadratic
  // tensor-product cell ($3^d$ of both) and the linear simplex (d + 1 shape
  // functions, one point), whose narrow blocks take the narrow tiles.
  template <int dim>
  std::vector<std::pair<unsigned int, unsigned int>>
  test_cells()
  {
    unsigned int n_quadratic = 1;
    for (unsigned int d = 0; d < dim; ++d)
      n_quadratic *= 3;
    return {{n_quadratic, n_quadratic}, {dim + 1, 1}};
  }
} // namespace



TYPED_TEST(PointTangentTest, CellProductEqualsTheSumOverPoints)
{
  constexpr int dim = TypeParam::value;
  std::mt19937  rng(2024 + dim);
  for (const auto &[n, n_q] : test_cells<dim>())
    for (const Symmetry symmetry : {Symmetry::general, Symmetry::symmetric})
      for (const unsigned int n_points : {n_q, n_q - 1, 2 * n_q + 1})
        {
          if (n_points == 0)
            continue;
          const double ratio =
            largest_error_ratio<dim>(n, n_q, n_points, symmetry, rng);
          std::cout << dim << "D, "
                    << (symmetry == Symmetry::symmetric ? "symmetric"
                                                        : "general")
                    << ", " << n_points << " points of a cell of " << n_q
                    << " with " << n
                    << " shape functions: largest difference / tolerance = "
                    << ratio << std::endl;
          EXPECT_LE(ratio, 1.) << dim << "D, " << n << " shape functions, "
                               << n_points << " points";
        }
}



// The gradients of two fields and the forces of two stresses of a cell as
// products (reset_cell_products(), field_gradients(), add_point_stress(),
// add_stress_forces()) against the sums formed directly in long double: a
// cell with random reference gradients and inverse Jacobians, random nodal
// values, stresses and weights, the quadratic cell and the linear simplex.
// The gradients, sums of n products in the order of the nodes (the order
// the products keep), must be the same to the bit as those sums formed
// directly in double: of the cell's gradients, or, for a cell with at
// least 4 d shape functions, of the reference gradients, then times the
// inverse Jacobian. The forces, sums of $d^2 n_q$ products of four
// factors, summed over one index of the inverse Jacobian first, must be
// within $\gamma_{d n_q + d + 2}$ times their terms' absolute values.
TYPED_TEST(PointTangentTest, FieldGradientsAndForcesAreTheSumsOverPoints)
{
  constexpr int                          dim = TypeParam::value;
  std::mt19937                           rng(4711 + dim);
  std::uniform_real_distribution<double> uniform(-1., 1.);
  for (const auto &[n, n_q] : test_cells<dim>())
    {
      CellGeometry<dim> geometry = test_geometry<dim>(n, n_q);
      geometry.n_cells           = 1;
      geometry.reference_gradients.resize(n_q * n * dim);
      for (unsigned int q = 0; q < n_q; ++q)
        {
          for (unsigned int a = 0; a < n; ++a)
            {
              Tensor<1, dim> g;
              for (unsigned int d = 0; d < dim; ++d)
                g[d] = uniform(rng);
              for (unsigned int c = 0; c < dim; ++c)
                geometry.reference_gradients[q * n * dim +
                                             geometry.shape_dofs[a * dim + c]] =
                  g;
            }
          Tensor<2, dim> inverse;
          for (unsigned int d = 0; d < dim; ++d)
            for (unsigned int e = 0; e < dim; ++e)
              inverse[d][e] = uniform(rng) + (d == e ? 2. : 0.);
          geometry.inverse_jacobians.push_back(inverse);
        }
      geometry.form_gradients_by_node();
      std::vector<double> u(n * dim), v(n * dim);
      for (unsigned int i = 0; i < n * dim; ++i)
        {
          u[i] = uniform(rng);
          v[i] = uniform(rng);
        }
      std::vector<Tensor<2, dim>> P(n_q), P_v(n_q);
      std::vector<double>         weight(n_q);
      for (unsigned int q = 0; q < n_q; ++q)
        {
          for (unsigned int c = 0; c < dim; ++c)
            for (unsigned int J = 0; J < dim; ++J)
              {
                P[q][c][J]   = uniform(rng);
                P_v[q][c][J] = uniform(rng);
              }
          weight[q] = 0.5 + 0.5 * uniform(rng);
        }

      CellProducts products;
      reset_cell_products(geometry, 0, products);
      std::vector<Tensor<2, dim>> H, L;
      field_gradients(geometry, products, {u.data(), v.data()}, {&H, &L});
      for (unsigned int q = 0; q < n_q; ++q)
        {
          add_point_stress(q, 0, P[q], weight[q], products);
          add_point_stress(q, 1, P_v[q], weight[q], products);
        }
      Vector<double> force(n * dim), second_force(n * dim);
      add_stress_forces(geometry, products, force, second_force);

      // The gradients, in double: the sums over the nodes of the cell's
      // gradients, or, for a cell with at least 4 dim shape functions, of
      // the reference gradients, times the inverse Jacobian.
      const bool pulled_back = n >= 4 * dim;
      EXPECT_EQ(products.pulled_back, pulled_back);
      unsigned int gradient_mismatches = 0;
      for (unsigned int q = 0; q < n_q; ++q)
        for (unsigned int c = 0; c < dim; ++c)
          {
            Tensor<1, dim> reference_u, reference_v;
            for (unsigned int a = 0; a < n; ++a)
              {
                const Tensor<1, dim> &g_ref =
                  geometry.reference_gradients[q * n * dim +
                                               geometry.shape_dofs[a * dim]];
                for (unsigned int K = 0; K < dim; ++K)
                  {
                    reference_u[K] +=
                      u[geometry.shape_dofs[a * dim + c]] * g_ref[K];
                    reference_v[K] +=
                      v[geometry.shape_dofs[a * dim + c]] * g_ref[K];
                  }
              }
            for (unsigned int J = 0; J < dim; ++J)
              {
                double sum_u = 0., sum_v = 0.;
                if (pulled_back)
                  for (unsigned int K = 0; K < dim; ++K)
                    {
                      sum_u +=
                        reference_u[K] * geometry.inverse_jacobians[q][K][J];
                      sum_v +=
                        reference_v[K] * geometry.inverse_jacobians[q][K][J];
                    }
                else
                  for (unsigned int a = 0; a < n; ++a)
                    {
                      const Tensor<1, dim> g = geometry.shape_gradient(0, q, a);
                      sum_u += u[geometry.shape_dofs[a * dim + c]] * g[J];
                      sum_v += v[geometry.shape_dofs[a * dim + c]] * g[J];
                    }
                gradient_mismatches +=
                  (H[q][c][J] != sum_u) + (L[q][c][J] != sum_v);
              }
          }

      // The forces: sums over (q, K, J) of products of four factors,
      // $\hat\partial_K\varphi_a\,(\mathbf J^{-1})_{KJ}\,P_{cJ}\,w$,
      // summed over J first (in the gradient or in the pulled-back
      // stress), then over (q, K) or (q, J).
      const double eps   = 0.5 * std::numeric_limits<double>::epsilon();
      const double m     = dim * n_q + dim + 2;
      const double gamma = m * eps / (1. - m * eps);
      double       worst = 0.;
      for (unsigned int a = 0; a < n; ++a)
        for (unsigned int c = 0; c < dim; ++c)
          {
            long double sums[2] = {0., 0.}, magnitudes[2] = {0., 0.};
            for (unsigned int q = 0; q < n_q; ++q)
              {
                const Tensor<1, dim> &g_ref =
                  geometry.reference_gradients[q * n * dim +
                                               geometry.shape_dofs[a * dim]];
                for (unsigned int K = 0; K < dim; ++K)
                  for (unsigned int J = 0; J < dim; ++J)
                    {
                      const long double g = static_cast<long double>(g_ref[K]) *
                                            geometry.inverse_jacobians[q][K][J];
                      const long double terms[2] = {g * P[q][c][J] * weight[q],
                                                    g * P_v[q][c][J] *
                                                      weight[q]};
                      for (unsigned int s = 0; s < 2; ++s)
                        {
                          sums[s] += terms[s];
                          magnitudes[s] += std::abs(terms[s]);
                        }
                    }
              }
            const unsigned int i         = geometry.shape_dofs[a * dim + c];
            const double       values[2] = {force(i), second_force(i)};
            for (unsigned int s = 0; s < 2; ++s)
              worst =
                std::max(worst,
                         std::abs(values[s] - static_cast<double>(sums[s])) /
                           (gamma * static_cast<double>(magnitudes[s])));
          }
      std::cout << dim << "D, a cell of " << n << " shape functions and " << n_q
                << " points: " << gradient_mismatches
                << " gradients not bit for bit the direct sums; forces' "
                << "largest difference / tolerance = " << worst << std::endl;
      EXPECT_EQ(gradient_mismatches, 0U) << dim << "D, " << n << " nodes";
      EXPECT_LE(worst, 1.) << dim << "D, " << n << " nodes";
    }
}
