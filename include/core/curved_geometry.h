// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Curved cells from a second-order mesh}
//
// A mesh of linear tetrahedra approximates a curved surface by flat facets:
// the coarse quarter of the bellows, whose circumferential arcs have two or
// three facets, holds 4.4 % less silicone than the revolved section
// (meshes/README.md). gmsh can write the same tetrahedra with a node in the
// middle of each edge, placed on the CAD surfaces (`-order 2`, the 10-node
// tetrahedron). The mesh reader (create_mesh()) hands deal.II the linear
// cells and keeps those mid-edge nodes; this class turns them into the
// geometry of the computation: a continuous quadratic vector field of
// positions, $\mathbf X(\hat{\mathbf x}) = \sum_j \mathbf X_j
// \hat\varphi_j(\hat{\mathbf x})$ with the ten quadratic shape functions on
// each cell, used as the mapping (deal.II's MappingFEField). Every module
// takes the mapping, not the vertices, so the stiffness, mass, loads and
// output all see the curved cells.
//
// After global refinement a cell's quadratic geometry is that of its
// coarsest ancestor: the ancestor's quadratic map is evaluated at the
// child's support points, which the refinement placed affinely inside the
// ancestor. The refined geometry is then the same curved body, not the
// facets of the coarse one.

#ifndef soft_robot_core_curved_geometry_h
#define soft_robot_core_curved_geometry_h

#include <core/mesh.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/vector.h>
#include <memory>

namespace SoftRobot
{
  using namespace dealii;

  template <int dim>
  class CurvedGeometry
  {
  public:
    // The triangulation is the one the mid-edge nodes were read for (its
    // coarsest level has the file's vertex numbering), possibly refined.
    CurvedGeometry(const Triangulation<dim> &triangulation,
                   const MidEdgeNodes<dim>  &mid_edge_nodes);
    ~CurvedGeometry();

    // The mapping of the positions field; it refers to this object, which
    // must outlive it.
    std::unique_ptr<Mapping<dim>>
    create_mapping() const;

    // How far the mid-edge nodes lie from the straight edges' midpoints,
    // largest over the mesh, in mesh units (reported at start-up).
    double
    largest_offset() const
    {
      return max_offset;
    }

  private:
    FESystem<dim>   fe;
    DoFHandler<dim> dof_handler;
    Vector<double>  positions;
    double          max_offset = 0.;
  };
} // namespace SoftRobot

#endif
