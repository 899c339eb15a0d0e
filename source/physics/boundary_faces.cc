// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{The faces of named boundaries}
//
// See include/physics/boundary_faces.h.

#include <core/config.h>
#include <deal.II/fe/fe_values.h>
#include <physics/boundary_faces.h>
#include <set>

namespace SoftRobot
{
  // @sect4{BoundaryFaces::BoundaryFaces}
  template <int dim>
  BoundaryFaces<dim>::BoundaryFaces(
    const Parameters::AllParameters &parameters,
    const CellGeometry<dim>         &geometry,
    const Mapping<dim>              &mapping,
    const DoFHandler<dim>           &dof_handler,
    const Quadrature<dim - 1>       &quadrature,
    const std::vector<unsigned int> &boundary_ids)
  {
    const FiniteElement<dim> &fe = dof_handler.get_fe();
    dofs_per_cell                = fe.n_dofs_per_cell();
    n_q_points                   = quadrature.size();
    components                   = geometry.components;
    if (boundary_ids.empty())
      {
        first_face.assign(geometry.n_cells + 1, 0);
        return;
      }
    first_face.assign(1, 0);
    const std::set<types::boundary_id> ids(boundary_ids.begin(),
                                           boundary_ids.end());
    FEFaceValues<dim>                  fe_face_values(mapping,
                                     fe,
                                     quadrature,
                                     update_values | update_gradients |
                                       update_quadrature_points |
                                       update_normal_vectors |
                                       update_JxW_values);
    unsigned int                       n_faces = 0;
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          const double section =
            parameters.by_id.at(cell->material_id()).section;
          for (const auto face : cell->face_indices())
            if (cell->face(face)->at_boundary() &&
                ids.count(cell->face(face)->boundary_id()) == 1)
              {
                fe_face_values.reinit(cell, face);
                for (const unsigned int q :
                     fe_face_values.quadrature_point_indices())
                  {
                    points.push_back(fe_face_values.quadrature_point(q));
                    normals.push_back(fe_face_values.normal_vector(q));
                    weights.push_back(fe_face_values.JxW(q) * section);
                    for (unsigned int i = 0; i < dofs_per_cell; ++i)
                      {
                        shape_values.push_back(
                          fe_face_values.shape_value_component(i,
                                                               q,
                                                               components[i]));
                        shape_gradients.push_back(
                          fe_face_values.shape_grad_component(i,
                                                              q,
                                                              components[i]));
                      }
                  }
                ++n_faces;
              }
          first_face.push_back(n_faces);
        }
    Assert(first_face.size() == geometry.n_cells + 1, ExcInternalError());
  }



#define SOFT_ROBOT_INSTANTIATE(dim) template class BoundaryFaces<dim>;
  SOFT_ROBOT_FOR_EACH_DIMENSION(SOFT_ROBOT_INSTANTIATE)
#undef SOFT_ROBOT_INSTANTIATE
} // namespace SoftRobot
