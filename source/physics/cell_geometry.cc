// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{The reference geometry of the cells}
//
// See include/physics/cell_geometry.h.

#include <core/config.h>
#include <deal.II/fe/fe_values.h>
#include <physics/cell_geometry.h>

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

    FEValues<dim>                        fe_values(mapping,
                            fe,
                            quadrature,
                            update_gradients | update_JxW_values);
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
              for (unsigned int i = 0; i < dofs_per_cell; ++i)
                shape_gradients.push_back(
                  fe_values.shape_grad_component(i, q, components[i]));
            }
          material_ids.push_back(cell->material_id());
          ++n_cells;
        }
  }



#define SOFT_ROBOT_INSTANTIATE(dim) template struct CellGeometry<dim>;
  SOFT_ROBOT_FOR_EACH_DIMENSION(SOFT_ROBOT_INSTANTIATE)
#undef SOFT_ROBOT_INSTANTIATE
} // namespace SoftRobot
