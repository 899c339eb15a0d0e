// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{The reference geometry of the cells}
//
// In the total Lagrangian formulation the shape-function gradients and the
// quadrature weights refer to the undeformed mesh and never change.
// CellGeometry computes them once for the locally owned cells, so that the
// integrals over the cells, which run in every Newton iteration, do no
// FEValues::reinit(), which for linear tetrahedra would take about a third
// of their time. A vector-valued shape function $\mathbf N_i = \varphi_i\mathbf
// e_{c_i}$ of the FESystem has one nonzero component $c_i$; only the
// gradient of $\varphi_i$ is needed.
//
// Every cell has the same shape functions on the reference cell, so the
// gradients at point q of a cell are $\nabla_0\varphi_i =
// \mathbf J_q^{-T}\hat\nabla\varphi_i(\hat{\mathbf x}_q)$, with the
// Jacobian $\mathbf J_q$ of the mapping at that point. What is stored per
// point is $\mathbf J_q^{-1}$ and the weight; the reference gradients are
// stored once. cell_gradients() forms a cell's gradients when an integral
// over it begins. This stores dim^2 numbers per point instead of dim per
// shape function (30 of them for quadratic tetrahedra), and costs no
// measurable time (doc/performance_discussion.md, item 28).
//
// The cells are numbered in the order in which a loop over the locally
// owned cells of the DoFHandler visits them; every per-cell array of the
// program (here, in HyperelasticSolid, in the global addition) uses that
// numbering.
//
// Implemented in source/physics/cell_geometry.cc.

#ifndef soft_robot_physics_cell_geometry_h
#define soft_robot_physics_cell_geometry_h

#include <deal.II/base/quadrature.h>
#include <deal.II/base/tensor.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/mapping.h>
#include <functional>
#include <vector>

namespace SoftRobot
{
  using namespace dealii;

  template <int dim>
  struct CellGeometry
  {
    // Computes the data below for the locally owned cells. `section` gives
    // the factor that turns an integral over the model into one over the
    // body it stands for (the cross-section area of the 1D column, the
    // thickness of the 2D strip, one in 3D), per material id.
    void
    reinit(const Mapping<dim>                                    &mapping,
           const DoFHandler<dim>                                 &dof_handler,
           const Quadrature<dim>                                 &quadrature,
           const std::function<double(const types::material_id)> &section);

    unsigned int n_cells       = 0;
    unsigned int dofs_per_cell = 0;
    unsigned int n_q_points    = 0;
    // The component $c_i$ of each shape function of a cell.
    std::vector<unsigned int> components;
    // The FESystem is dim copies of one scalar element: the number of that
    // element's shape functions $\varphi_a$, and the dof of component c of
    // each, [a * dim + c].
    unsigned int              n_shape_functions = 0;
    std::vector<unsigned int> shape_dofs;
    // Per cell: the global dof indices, [cell][i].
    std::vector<types::global_dof_index> dof_indices;
    // The quadrature points on the reference cell, [q].
    std::vector<Point<dim>> unit_points;
    // Per reference point: the gradients of the scalar shape functions on
    // the reference cell, [q][i].
    std::vector<Tensor<1, dim>> reference_gradients;
    // The same by node, [a][(q, K)], in rows of `node_gradient_stride`
    // columns (dim n_q, padded with zeros to the width of the products'
    // tiles, see physics/point_tangent.h), formed from
    // `reference_gradients` by form_gradients_by_node().
    std::vector<double> reference_gradients_by_node;
    unsigned int        node_gradient_stride = 0;
    // Per cell and point: the inverse Jacobian of the mapping, [cell][q],
    // and the weight times the section factor, [cell][q].
    std::vector<Tensor<2, dim>> inverse_jacobians;
    std::vector<double>         JxW;
    // Per cell: its material id.
    std::vector<types::material_id> material_ids;

    // Forms `reference_gradients_by_node` (reinit() does; for a geometry
    // set up by hand, after its reference gradients).
    void
    form_gradients_by_node();

    // The gradients of the shape functions at every point of a cell,
    // [q][i] (`gradients` is resized to n_q_points * dofs_per_cell).
    void
    cell_gradients(const unsigned int           cell,
                   std::vector<Tensor<1, dim>> &gradients) const;

    // The gradient of the scalar shape function a at point q of a cell.
    Tensor<1, dim>
    shape_gradient(const unsigned int cell,
                   const unsigned int q,
                   const unsigned int a) const
    {
      return reference_gradients[q * dofs_per_cell + shape_dofs[a * dim]] *
             inverse_jacobians[cell * n_q_points + q];
    }

    // The weight of point q of a cell (times the section factor).
    double
    weight(const unsigned int cell, const unsigned int q) const
    {
      return JxW[cell * n_q_points + q];
    }
  };
} // namespace SoftRobot

#endif
