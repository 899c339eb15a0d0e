// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{The motion of the tip}
//
// See include/output/tip_region.h.

#include <core/config.h>
#include <deal.II/fe/fe_values.h>
#include <output/tip_region.h>

namespace SoftRobot
{
  // @sect4{TipRegion::reinit}
  template <int dim>
  void
  TipRegion<dim>::reinit(
    const Parameters::AllParameters                       &parameters,
    const Mapping<dim>                                    &mapping,
    const DoFHandler<dim>                                 &dof_handler,
    const Quadrature<dim>                                 &cell_quadrature,
    const Quadrature<dim - 1>                             &face_quadrature,
    const AffineConstraints<double>                       &constraints,
    const std::function<double(const types::material_id)> &density,
    const MPI_Comm                                         mpi_communicator)
  {
    const FiniteElement<dim> &fe = dof_handler.get_fe();
    weights.assign(dim,
                   TrilinosWrappers::MPI::Vector(
                     dof_handler.locally_owned_dofs(), mpi_communicator));
    double                               weight = 0.;
    const unsigned int                   id     = parameters.tip_region_id;
    const unsigned int                   dofs_per_cell = fe.n_dofs_per_cell();
    std::vector<Vector<double>>          cell_weights(dim,
                                             Vector<double>(dofs_per_cell));
    std::vector<types::global_dof_index> dof_indices(dofs_per_cell);
    const auto                           section = [&](const auto &cell) {
      return parameters.by_id.at(cell->material_id()).section;
    };
    // Adds omega N_i(q) JxW to the weights of a cell.
    const auto add_point =
      [&](const auto &fe_values, const unsigned int q, const double omega) {
        const double w = fe_values.JxW(q) * omega;
        for (unsigned int i = 0; i < dofs_per_cell; ++i)
          {
            const unsigned int c = fe.system_to_component_index(i).first;
            cell_weights[c](i) += w * fe_values.shape_value_component(i, q, c);
          }
        weight += w;
      };
    const auto add_cell = [&](const auto &cell) {
      cell->get_dof_indices(dof_indices);
      for (unsigned int d = 0; d < dim; ++d)
        {
          constraints.distribute_local_to_global(cell_weights[d],
                                                 dof_indices,
                                                 weights[d]);
          cell_weights[d] = 0.;
        }
    };

    if (parameters.tip_region_type ==
        Parameters::Output::TipRegionType::boundary)
      {
        FEFaceValues<dim> fe_face_values(mapping,
                                         fe,
                                         face_quadrature,
                                         update_values | update_JxW_values);
        for (const auto &cell : dof_handler.active_cell_iterators())
          if (cell->is_locally_owned())
            for (const auto face : cell->face_indices())
              if (cell->face(face)->at_boundary() &&
                  cell->face(face)->boundary_id() == id)
                {
                  fe_face_values.reinit(cell, face);
                  for (const unsigned int q :
                       fe_face_values.quadrature_point_indices())
                    add_point(fe_face_values, q, section(cell));
                  add_cell(cell);
                }
      }
    else
      {
        FEValues<dim> fe_values(mapping,
                                fe,
                                cell_quadrature,
                                update_values | update_JxW_values);
        for (const auto &cell : dof_handler.active_cell_iterators())
          if (cell->is_locally_owned() && cell->material_id() == id)
            {
              fe_values.reinit(cell);
              const double rho_A = density(id) * section(cell);
              for (const unsigned int q : fe_values.quadrature_point_indices())
                add_point(fe_values, q, rho_A);
              add_cell(cell);
            }
      }
    for (auto &vector : weights)
      vector.compress(VectorOperation::add);
    total_weight = Utilities::MPI::sum(weight, mpi_communicator);
  }



  // @sect4{TipRegion::motion}
  template <int dim>
  std::pair<Tensor<1, dim>, Tensor<1, dim>>
  TipRegion<dim>::motion(const TrilinosWrappers::MPI::Vector &u,
                         const TrilinosWrappers::MPI::Vector &v) const
  {
    Tensor<1, dim> u_tip, v_tip;
    for (unsigned int d = 0; d < dim; ++d)
      {
        u_tip[d] = (weights[d] * u) / total_weight;
        v_tip[d] = (weights[d] * v) / total_weight;
      }
    return {u_tip, v_tip};
  }



#define SOFT_ROBOT_INSTANTIATE(dim) template class TipRegion<dim>;
  SOFT_ROBOT_FOR_EACH_DIMENSION(SOFT_ROBOT_INSTANTIATE)
#undef SOFT_ROBOT_INSTANTIATE
} // namespace SoftRobot
