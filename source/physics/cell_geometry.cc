// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{The reference geometry of the cells}
//
// See include/physics/cell_geometry.h.

#include <core/config.h>
#include <deal.II/fe/fe_values.h>
#include <physics/cell_geometry.h>
#include <physics/point_tangent.h>

namespace SoftRobot
{
  // @sect4{CellGeometry::reinit}
  template <int dim>
  void
  CellGeometry<dim>::reinit(
    const Mapping<dim>                                    &mapping,
    const DoFHandler<dim>                                 &dof_handler,
    const Quadrature<dim>                                 &quadrature,
    const std::function<double(const types::material_id)> &section)
  {
    const FiniteElement<dim> &fe = dof_handler.get_fe();
    *this                        = CellGeometry();
    dofs_per_cell                = fe.n_dofs_per_cell();
    n_q_points                   = quadrature.size();
    for (unsigned int i = 0; i < dofs_per_cell; ++i)
      components.push_back(fe.system_to_component_index(i).first);
    AssertThrow(fe.n_components() == dim && dofs_per_cell % dim == 0,
                ExcInternalError());
    n_shape_functions = dofs_per_cell / dim;
    shape_dofs.assign(dofs_per_cell, numbers::invalid_unsigned_int);
    for (unsigned int i = 0; i < dofs_per_cell; ++i)
      {
        const auto [c, a]       = fe.system_to_component_index(i);
        shape_dofs[a * dim + c] = i;
      }

    unit_points = quadrature.get_points();
    for (unsigned int q = 0; q < n_q_points; ++q)
      for (unsigned int i = 0; i < dofs_per_cell; ++i)
        reference_gradients.push_back(
          fe.shape_grad_component(i, quadrature.point(q), components[i]));
    // cell_gradients(), shape_gradient() and the sums node by node of the
    // physics (the products of physics/point_tangent.h) rely on the
    // components of a node sharing their scalar shape function.
    for (unsigned int q = 0; q < n_q_points; ++q)
      for (unsigned int a = 0; a < n_shape_functions; ++a)
        for (unsigned int c = 1; c < dim; ++c)
          AssertThrow(
            reference_gradients[q * dofs_per_cell + shape_dofs[a * dim + c]] ==
              reference_gradients[q * dofs_per_cell + shape_dofs[a * dim]],
            ExcInternalError());

    form_gradients_by_node();

    FEValues<dim>                        fe_values(mapping,
                            fe,
                            quadrature,
                            update_inverse_jacobians | update_JxW_values);
    std::vector<types::global_dof_index> cell_dofs(dofs_per_cell);
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          cell->get_dof_indices(cell_dofs);
          dof_indices.insert(dof_indices.end(),
                             cell_dofs.begin(),
                             cell_dofs.end());
          const double factor = section(cell->material_id());
          for (unsigned int q = 0; q < n_q_points; ++q)
            {
              JxW.push_back(fe_values.JxW(q) * factor);
              inverse_jacobians.push_back(
                Tensor<2, dim>(fe_values.inverse_jacobian(q)));
            }
          material_ids.push_back(cell->material_id());
          ++n_cells;
        }
  }



  // @sect4{CellGeometry::form_gradients_by_node}
  template <int dim>
  void
  CellGeometry<dim>::form_gradients_by_node()
  {
    node_gradient_stride = product_stride(dim * n_q_points);
    reference_gradients_by_node.assign(n_shape_functions * node_gradient_stride,
                                       0.);
    for (unsigned int a = 0; a < n_shape_functions; ++a)
      for (unsigned int q = 0; q < n_q_points; ++q)
        for (unsigned int K = 0; K < dim; ++K)
          reference_gradients_by_node[a * node_gradient_stride + q * dim + K] =
            reference_gradients[q * dofs_per_cell + shape_dofs[a * dim]][K];
  }



  // @sect4{CellGeometry::cell_gradients}
  //
  // $(\nabla_0\varphi_i)_k = \sum_l \hat\partial_l\varphi_i\,
  // (\mathbf J^{-1})_{lk}$, the transformation FEValues applies. The dim
  // shape functions of a node share one scalar function, so the gradient
  // is transformed once per node and copied to its components.
  template <int dim>
  void
  CellGeometry<dim>::cell_gradients(
    const unsigned int           cell,
    std::vector<Tensor<1, dim>> &gradients) const
  {
    gradients.resize(n_q_points * dofs_per_cell);
    for (unsigned int q = 0; q < n_q_points; ++q)
      {
        Tensor<1, dim> *result = &gradients[q * dofs_per_cell];
        for (unsigned int a = 0; a < n_shape_functions; ++a)
          {
            const Tensor<1, dim> gradient = shape_gradient(cell, q, a);
            for (unsigned int c = 0; c < dim; ++c)
              result[shape_dofs[a * dim + c]] = gradient;
          }
      }
  }



#define SOFT_ROBOT_INSTANTIATE(dim) template struct CellGeometry<dim>;
  SOFT_ROBOT_FOR_EACH_DIMENSION(SOFT_ROBOT_INSTANTIATE)
#undef SOFT_ROBOT_INSTANTIATE
} // namespace SoftRobot
