// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{The dilatation projected on a few modes per cell}
//
// See include/physics/dilatation_projection.h.

#include <core/config.h>
#include <deal.II/lac/full_matrix.h>
#include <physics/dilatation_projection.h>

namespace SoftRobot
{
  // The centre of the reference cell: (1/2, ...) for the hypercube,
  // (1/(dim+1), ...) for the simplex, told apart by the quadrature points'
  // coordinate sums (at most one inside the simplex).
  template <int dim>
  DilatationProjection<dim>::DilatationProjection(
    const CellGeometry<dim> &geometry,
    const unsigned int       n_modes)
    : geometry(geometry)
    , n(n_modes)
  {
    AssertThrow(n == 0 || n == 1 || n == dim + 1, ExcInternalError());
    AssertThrow(geometry.n_q_points >= n, ExcInternalError());
    bool simplex = true;
    for (const Point<dim> &p : geometry.unit_points)
      {
        double sum = 0.;
        for (unsigned int d = 0; d < dim; ++d)
          sum += p[d];
        simplex = simplex && (sum <= 1. + 1e-12);
      }
    const double centre = simplex ? 1. / (dim + 1) : 0.5;
    for (const Point<dim> &p : geometry.unit_points)
      for (unsigned int m = 0; m < n; ++m)
        values.push_back(m == 0 ? 1. : p[m - 1] - centre);
  }



  template <int dim>
  typename DilatationProjection<dim>::ModeMatrix
  DilatationProjection<dim>::inverse_gram(const unsigned int cell) const
  {
    FullMatrix<double> gram(n, n);
    for (unsigned int q = 0; q < geometry.n_q_points; ++q)
      {
        const double w = geometry.weight(cell, q);
        for (unsigned int m = 0; m < n; ++m)
          for (unsigned int k = 0; k < n; ++k)
            gram(m, k) += mode(q, m) * mode(q, k) * w;
      }
    gram.gauss_jordan();
    ModeMatrix result{};
    for (unsigned int m = 0; m < n; ++m)
      for (unsigned int k = 0; k < n; ++k)
        result[m][k] = gram(m, k);
    return result;
  }



  template <int dim>
  typename DilatationProjection<dim>::ModeVector
  DilatationProjection<dim>::project(const unsigned int         cell,
                                     const ModeMatrix          &inverse_gram,
                                     const std::vector<double> &f) const
  {
    ModeVector moments{}, result{};
    for (unsigned int q = 0; q < geometry.n_q_points; ++q)
      {
        const double w = f[q] * geometry.weight(cell, q);
        for (unsigned int m = 0; m < n; ++m)
          moments[m] += mode(q, m) * w;
      }
    for (unsigned int m = 0; m < n; ++m)
      for (unsigned int k = 0; k < n; ++k)
        result[m] += inverse_gram[m][k] * moments[k];
    return result;
  }



  template <int dim>
  double
  DilatationProjection<dim>::value(const unsigned int q,
                                   const ModeVector  &coefficients) const
  {
    double result = 0.;
    for (unsigned int m = 0; m < n; ++m)
      result += mode(q, m) * coefficients[m];
    return result;
  }



  template <int dim>
  typename DilatationProjection<dim>::ModeMatrix
  DilatationProjection<dim>::weighted_stiffness(
    const unsigned int         cell,
    const ModeMatrix          &inverse_gram,
    const std::vector<double> &g) const
  {
    ModeMatrix weighted{}, product{}, result{};
    for (unsigned int q = 0; q < geometry.n_q_points; ++q)
      {
        const double w = g[q] * geometry.weight(cell, q);
        for (unsigned int m = 0; m < n; ++m)
          for (unsigned int k = 0; k < n; ++k)
            weighted[m][k] += mode(q, m) * mode(q, k) * w;
      }
    for (unsigned int m = 0; m < n; ++m)
      for (unsigned int k = 0; k < n; ++k)
        for (unsigned int l = 0; l < n; ++l)
          product[m][k] += inverse_gram[m][l] * weighted[l][k];
    for (unsigned int m = 0; m < n; ++m)
      for (unsigned int k = 0; k < n; ++k)
        for (unsigned int l = 0; l < n; ++l)
          result[m][k] += product[m][l] * inverse_gram[l][k];
    return result;
  }



  template <int dim>
  void
  DilatationProjection<dim>::add_rank_n_term(const ModeMatrix         &A,
                                             const FullMatrix<double> &G,
                                             FullMatrix<double>       &AG,
                                             FullMatrix<double>       *matrix_1,
                                             const double              scale_1,
                                             FullMatrix<double>       *matrix_2,
                                             const double              scale_2)
  {
    const unsigned int n      = G.m();
    const unsigned int n_dofs = G.n();
    AG.reinit(n, n_dofs);
    for (unsigned int m = 0; m < n; ++m)
      for (unsigned int k = 0; k < n; ++k)
        for (unsigned int j = 0; j < n_dofs; ++j)
          AG(m, j) += A[m][k] * G(k, j);
    for (unsigned int i = 0; i < n_dofs; ++i)
      for (unsigned int j = 0; j <= i; ++j)
        {
          double value = 0.;
          for (unsigned int m = 0; m < n; ++m)
            value += G(m, i) * AG(m, j);
          if (matrix_1)
            (*matrix_1)(i, j) += scale_1 * value;
          if (matrix_2)
            (*matrix_2)(i, j) += scale_2 * value;
        }
  }



  template <int dim>
  void
  DilatationProjection<dim>::add_point_derivatives(
    const Tensor<2, dim>            &T,
    const Tensor<1, dim>            *grad_phi,
    const std::vector<unsigned int> &components,
    const ModeVector                &weights,
    const unsigned int               n_modes,
    FullMatrix<double>              &G)
  {
    for (unsigned int i = 0; i < G.n(); ++i)
      {
        const double g = T[components[i]] * grad_phi[i];
        for (unsigned int m = 0; m < n_modes; ++m)
          G(m, i) += g * weights[m];
      }
  }



#define SOFT_ROBOT_INSTANTIATE(dim) template class DilatationProjection<dim>;
  SOFT_ROBOT_FOR_EACH_DIMENSION(SOFT_ROBOT_INSTANTIATE)
#undef SOFT_ROBOT_INSTANTIATE
} // namespace SoftRobot
