// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{A quadrature point's share of a cell matrix}
//
// Every term of the tangent and damping matrices of this program is, at a
// quadrature point, a bilinear form in the gradients of two vector-valued
// shape functions $\mathbf N_i = \varphi_a\mathbf e_c$ and $\mathbf N_j =
// \varphi_b\mathbf e_k$,
// @f[
//   K_{ij} \mathrel{+}= \sum_{J,L}\partial_J\varphi_a\;
//   \mathcal A_{cJkL}\;\partial_L\varphi_b\;w_q,
// @f]
// with one fourth-order tensor $\mathcal A$ per point: for the
// stiffness of a second Piola-Kirchhoff stress $\mathbf S$ with material
// tangent $\mathcal C$ it is $\mathcal A_{cJkL} = F_{cI}\,\mathcal
// C_{IJKL}\,F_{kK} + \delta_{ck}S_{JL}$ (the derivative of the first
// Piola-Kirchhoff stress), and the viscous and volumetric terms of
// KelvinVoigtDamping have the same form. The point therefore first sums
// its terms into $\mathcal A$ (81 numbers in 3D) and then adds the double
// sum once for all pairs of shape functions, node by node: for each
// $\varphi_a$ the contraction $W_{ckL} = \sum_J\partial_J\varphi_a
// \mathcal A_{cJkL}$, then for each $\varphi_b$ the $3\times3$ block
// $\sum_L W_{ckL}\partial_L\varphi_b$, accumulated per cell in a matrix
// ordered by shape functions and added to the cell matrix once. For
// quadratic hexahedra that is 6,561 multiply-adds per point, in loops the
// compiler vectorizes, where forming each pair's strain variations and
// their products took several times as many
// (doc/performance_discussion.md).
//
// Implemented in source/physics/point_tangent.cc.

#ifndef soft_robot_physics_point_tangent_h
#define soft_robot_physics_point_tangent_h

#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>
#include <deal.II/lac/full_matrix.h>
#include <physics/cell_geometry.h>

namespace SoftRobot
{
  using namespace dealii;

  // $\mathcal A_{cJkL} \mathrel{+}= f\sum_{I,K} X_{cI}\,\mathcal
  // C_{IJKL}\,Y_{kK}$: a material tangent pulled to the first
  // Piola-Kirchhoff form with $\mathbf X = \mathbf Y = \mathbf F$, or, with
  // $\mathbf Y$ another tensor, a term of the viscous stress's tangent.
  template <int dim>
  void
  add_pulled_tangent(const Tensor<2, dim>          &X,
                     const SymmetricTensor<4, dim> &C,
                     const Tensor<2, dim>          &Y,
                     const double                   factor,
                     Tensor<4, dim>                &A);

  // $\mathcal A_{cJcL} \mathrel{+}= S_{JL}$ for every component c: the
  // geometric stiffness of a stress $\mathbf S$.
  template <int dim>
  void
  add_geometric_tangent(const SymmetricTensor<2, dim> &S, Tensor<4, dim> &A);

  // $\mathcal A_{aAbB} \mathrel{+}= f\,\partial^2 J/\partial F_{aA}\partial
  // F_{bB} = f\,\varepsilon_{abk}\varepsilon_{ABK}F_{kK}$ (3D): the
  // stiffness of a pressure $f$ acting on the volume.
  void
  add_volume_hessian(const Tensor<2, 3> &F,
                     const double        factor,
                     Tensor<4, 3>       &A);

  // Whether a point's tensor has the major symmetry $\mathcal A_{cJkL} =
  // \mathcal A_{kLcJ}$ (the second derivative of an energy or of a
  // dissipation potential), so that the block of the pair (a, b) is the
  // transpose of that of (b, a) and only $b \le a$ is formed: half the work.
  enum class Symmetry
  {
    symmetric,
    general
  };

  // The point's share $\sum_{J,L}\partial_J\varphi_a\mathcal
  // A_{cJkL}\partial_L\varphi_b\,w$ of every pair of shape functions,
  // `grad_phi` being the gradients of the cell's shape functions at the
  // point (indexed by dof), added to `block`, the cell's matrix by shape
  // functions: entry ((a dim + c) dim + k) n + b for n shape functions
  // (resized and zeroed by the caller, see reset_tangent_block()). All pairs
  // are formed (with Symmetry::symmetric those with b <= a), in loops over
  // b that the compiler vectorizes.
  template <int dim>
  void
  add_point_tangent(const CellGeometry<dim> &geometry,
                    const Tensor<1, dim>    *grad_phi,
                    const Tensor<4, dim>    &A,
                    const double             weight,
                    const Symmetry           symmetry,
                    std::vector<double>     &block);

  // A block of the cell's size, zero.
  template <int dim>
  void
  reset_tangent_block(const CellGeometry<dim> &geometry,
                      std::vector<double>     &block);

  // Adds a block to the cell matrix in dof numbering, all of it; a
  // symmetric block's pairs b > a from their transposes.
  template <int dim>
  void
  add_tangent_block(const CellGeometry<dim>   &geometry,
                    const std::vector<double> &block,
                    const Symmetry             symmetry,
                    FullMatrix<double>        &matrix);
} // namespace SoftRobot

#endif
