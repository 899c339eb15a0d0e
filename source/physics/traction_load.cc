// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Nominal tractions on the boundary}
//
// See include/physics/traction_load.h.

#include <core/config.h>
#include <core/expression_function.h>
#include <deal.II/fe/fe_values.h>
#include <physics/traction_load.h>
#include <set>

namespace SoftRobot
{
  template <int dim>
  TractionLoad<dim>::TractionLoad(const Parameters::AllParameters &parameters)
    : parameters(parameters)
    , boundary_ids(parameters.traction_boundary_ids)
    , traction(dim)
  {
    initialize_vector_function(traction,
                               parameters.traction_expression,
                               parameters.constants,
                               "Loads and constraints/Traction");
  }



  // @sect4{TractionLoad::reinit}
  template <int dim>
  void
  TractionLoad<dim>::reinit(const Mapping<dim>        &mapping,
                            const DoFHandler<dim>     &dof_handler,
                            const Quadrature<dim - 1> &quadrature)
  {
    n_faces = 0;
    dof_indices.clear();
    points.clear();
    weighted_shape_values.clear();
    if (boundary_ids.empty())
      return;
    const FiniteElement<dim> &fe = dof_handler.get_fe();
    dofs_per_cell                = fe.n_dofs_per_cell();
    n_q_points                   = quadrature.size();
    components.clear();
    for (unsigned int i = 0; i < dofs_per_cell; ++i)
      components.push_back(fe.system_to_component_index(i).first);
    const std::set<types::boundary_id>   ids(boundary_ids.begin(),
                                           boundary_ids.end());
    FEFaceValues<dim>                    fe_face_values(mapping,
                                     fe,
                                     quadrature,
                                     update_values | update_quadrature_points |
                                       update_JxW_values);
    std::vector<types::global_dof_index> cell_dofs(dofs_per_cell);
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const auto face : cell->face_indices())
          if (cell->face(face)->at_boundary() &&
              ids.count(cell->face(face)->boundary_id()) == 1)
            {
              fe_face_values.reinit(cell, face);
              cell->get_dof_indices(cell_dofs);
              dof_indices.insert(dof_indices.end(),
                                 cell_dofs.begin(),
                                 cell_dofs.end());
              const double section =
                parameters.by_id.at(cell->material_id()).section;
              for (const unsigned int q :
                   fe_face_values.quadrature_point_indices())
                {
                  points.push_back(fe_face_values.quadrature_point(q));
                  for (const unsigned int i : fe_face_values.dof_indices())
                    weighted_shape_values.push_back(
                      fe_face_values.shape_value_component(i,
                                                           q,
                                                           components[i]) *
                      fe_face_values.JxW(q) * section);
                }
              ++n_faces;
            }
  }



  // @sect4{TractionLoad::add_forces}
  template <int dim>
  void
  TractionLoad<dim>::add_forces(const double                     time,
                                const AffineConstraints<double> &constraints,
                                TrilinosWrappers::MPI::Vector   &force) const
  {
    Vector<double>                       cell_force(dofs_per_cell);
    std::vector<types::global_dof_index> cell_dofs(dofs_per_cell);
    Vector<double>                       value(dim);
    traction.set_time(time);
    for (unsigned int face = 0; face < n_faces; ++face)
      {
        bool loaded = false;
        cell_force  = 0.;
        for (unsigned int q = 0; q < n_q_points; ++q)
          {
            traction.vector_value(points[face * n_q_points + q], value);
            if (value.l2_norm() == 0.)
              continue;
            loaded = true;
            const double *shape =
              &weighted_shape_values[(face * n_q_points + q) * dofs_per_cell];
            for (unsigned int i = 0; i < dofs_per_cell; ++i)
              cell_force(i) += shape[i] * value[components[i]];
          }
        if (!loaded)
          continue;
        std::copy_n(&dof_indices[face * dofs_per_cell],
                    dofs_per_cell,
                    cell_dofs.begin());
        constraints.distribute_local_to_global(cell_force, cell_dofs, force);
      }
  }



#define SOFT_ROBOT_INSTANTIATE(dim) template class TractionLoad<dim>;
  SOFT_ROBOT_FOR_EACH_DIMENSION(SOFT_ROBOT_INSTANTIATE)
#undef SOFT_ROBOT_INSTANTIATE
} // namespace SoftRobot
