// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{A cell's sums over its points as matrix products}
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
// its terms into $\mathcal A$ (81 numbers in 3D).
//
// Summed over the points $q$ of a cell, with the pair $(q, J)$ of point
// and direction as one index, the block of the components $(c, k)$ is a
// matrix product:
// @f[
//   K^{ck}_{ab} = \sum_{(q,J)} \partial_J\varphi_a(\mathbf x_q)\;
//   Y_{(q,J),(c,k,b)}, \qquad
//   Y_{(q,J),(c,k,b)} = w_q\sum_L \mathcal A^q_{cJkL}\,
//   \partial_L\varphi_b(\mathbf x_q),
// @f]
// of the $n\times d\,n_q$ matrix of the shape functions' gradients with
// the $d\,n_q\times d^2 n$ matrix $\mathbf Y$, for $n$ shape functions,
// $n_q$ points and dimension $d$. Each point adds its $d$ rows of
// $\mathbf Y$ ($d^3 n$ multiply-adds) and its $d$ columns of gradients to
// a buffer; the product is formed when the block is read (or the buffer is
// full), in loops that keep a tile of the result in vector registers. For
// quadratic hexahedra that is $n^2 d^3 n_q$ = 531,441 multiply-adds per
// cell, as many as adding each point's share to all $n^2 d^2$ entries of
// the block in turn; but that way each entry was loaded and stored once
// per point for three multiply-adds, while the product keeps a tile of
// entries in registers over all points (doc/performance_discussion.md,
// item 39, has the times). A symmetric $\mathcal A$ needs only the pairs
// $b \le a$: about half the product.
//
// Implemented in source/physics/point_tangent.cc.

#ifndef soft_robot_physics_point_tangent_h
#define soft_robot_physics_point_tangent_h

#include <assembly/cell_contribution.h>
#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>
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

  // Adds the point's share $\sum_{J,L}\partial_J\varphi_a\mathcal
  // A_{cJkL}\partial_L\varphi_b\,w$ of every pair of shape functions to
  // `block` (set up by reset_tangent_block()), `grad_phi` being the
  // gradients of the cell's shape functions at the point (indexed by dof).
  // All points of a block must have the same symmetry; with
  // Symmetry::symmetric only the pairs b <= a are formed.
  template <int dim>
  void
  add_point_tangent(const CellGeometry<dim> &geometry,
                    const Tensor<1, dim>    *grad_phi,
                    const Tensor<4, dim>    &A,
                    const double             weight,
                    const Symmetry           symmetry,
                    TangentBlock            &block);

  // A block of the cell's size, zero, with room for the factors of all of
  // the cell's points.
  template <int dim>
  void
  reset_tangent_block(const CellGeometry<dim> &geometry, TangentBlock &block);

  // Adds a block to the cell matrix in dof numbering, all of it; a
  // symmetric block's pairs b > a from their transposes. Multiplies out
  // the points added since the last call first.
  template <int dim>
  void
  add_tangent_block(const CellGeometry<dim> &geometry,
                    TangentBlock            &block,
                    const Symmetry           symmetry,
                    FullMatrix<double>      &matrix);

  // @sect4{The gradients and forces of a cell as products}
  //
  // The same product, with the gradients as either factor, gives the
  // other two sums over a cell's shape functions and points. The gradient
  // of a field at the points is $\sum_a u_{ac}\,\partial_J\varphi_a
  // (\mathbf x_q)$: the $d \times n$ matrix of its nodal values times the
  // $n \times d\,n_q$ matrix of the gradients, for the displacement and
  // the velocity together. The forces of a first Piola-Kirchhoff stress
  // are $f_{ac} = \sum_{(q,J)} \partial_J\varphi_a(\mathbf x_q)\,w_q
  // P^q_{cJ}$: the gradients times the $d\,n_q \times d$ matrix of the
  // weighted stresses, for the elastic and the viscous stress together.
  // Point by point, both were sums with a load and a store per term (they
  // took about 15 % of a run of experiment 1, doc/performance_discussion.md,
  // item 42).
  //
  // With $\partial_J\varphi_a = \sum_K\hat\partial_K\varphi_a\,
  // (\mathbf J^{-1})_{KJ}$ both products can take the gradients on the
  // reference cell, which are the same for every cell (CellGeometry's
  // table by node), and apply the inverse Jacobian point by point: to the
  // product's result for the fields' gradients, to the stresses
  // ($w\,\mathbf P\mathbf J^{-T}$) before the product for the forces. A
  // cell with many shape functions then forms no gradients of its own for
  // them (reset_cell_products() says when; doc/performance_discussion.md,
  // item 50).

  // The number of columns a product's factor with `columns` columns is
  // stored in: a multiple of the width of the tiles.
  unsigned int
  product_stride(const unsigned int columns);

  // The gradients by node for the products (the reference ones and the
  // cell's inverse Jacobians, or the cell's own); the stresses zero.
  template <int dim>
  void
  reset_cell_products(const CellGeometry<dim> &geometry,
                      const unsigned int       cell,
                      CellProducts            &products);

  // The gradients at the cell's points of the fields whose nodal values
  // (in dof numbering) `fields` points to, into `*gradients[f]`.
  template <int dim>
  void
  field_gradients(const CellGeometry<dim>                          &geometry,
                  CellProducts                                     &products,
                  const std::vector<const double *>                &fields,
                  const std::vector<std::vector<Tensor<2, dim>> *> &gradients);

  // Records the stress P of point q with its weight (pulled back to the
  // reference cell where the products take the reference gradients), as
  // the elastic (`column` 0) or the viscous (1) stress.
  template <int dim>
  void
  add_point_stress(const unsigned int    q,
                   const unsigned int    column,
                   const Tensor<2, dim> &P,
                   const double          weight,
                   CellProducts         &products);

  // Adds the forces of the recorded stresses: the elastic ones to `force`,
  // the viscous ones to `second_force`.
  template <int dim>
  void
  add_stress_forces(const CellGeometry<dim> &geometry,
                    CellProducts            &products,
                    Vector<double>          &force,
                    Vector<double>          &second_force);
} // namespace SoftRobot

#endif
