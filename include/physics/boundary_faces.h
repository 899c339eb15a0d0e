// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{The faces of named boundaries}
//
// The loads that act on the body's surface (the aerodynamic drag, the
// pressure of a cavity) integrate over the faces of the cells that lie on
// some boundary ids. BoundaryFaces collects, once, what they need of these
// faces in the reference configuration: for each face and quadrature point
// the position, the outward normal, the weight times the material's
// section factor (the cross-section of the 1D column, the thickness of the
// 2D strip), and the values and gradients of the scalar shape functions.
// The classes of the loads derive from it and read these arrays in their
// cell integrals.
//
// Implemented in source/physics/boundary_faces.cc.

#ifndef soft_robot_physics_boundary_faces_h
#define soft_robot_physics_boundary_faces_h

#include <core/parameters.h>
#include <deal.II/base/point.h>
#include <deal.II/base/quadrature.h>
#include <deal.II/base/tensor.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/mapping.h>
#include <physics/cell_geometry.h>
#include <vector>

namespace SoftRobot
{
  using namespace dealii;

  template <int dim>
  class BoundaryFaces
  {
  public:
    // The faces of the locally owned cells on the boundary ids `ids`, in the
    // cell numbering of `geometry`. With no ids no cell has faces.
    BoundaryFaces(const Parameters::AllParameters &parameters,
                  const CellGeometry<dim>         &geometry,
                  const Mapping<dim>              &mapping,
                  const DoFHandler<dim>           &dof_handler,
                  const Quadrature<dim - 1>       &quadrature,
                  const std::vector<unsigned int> &ids);

    // Whether the cell (in the numbering of CellGeometry) has such faces.
    bool
    has_faces(const unsigned int cell) const
    {
      return first_face[cell] != first_face[cell + 1];
    }

  protected:
    unsigned int              n_q_points    = 0;
    unsigned int              dofs_per_cell = 0;
    std::vector<unsigned int> components;
    // The faces of each cell, [first_face[cell], first_face[cell + 1]), and
    // per face and point (index face * n_q_points + q) the reference
    // position and normal, the weight times the section factor, and (index
    // point * dofs_per_cell + i) the values and gradients of the scalar
    // shape functions.
    std::vector<unsigned int>   first_face;
    std::vector<Point<dim>>     points;
    std::vector<Tensor<1, dim>> normals;
    std::vector<double>         weights;
    std::vector<double>         shape_values;
    std::vector<Tensor<1, dim>> shape_gradients;
  };
} // namespace SoftRobot

#endif
