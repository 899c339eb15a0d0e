// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{The mesh}
//
// The mesh comes either from one of deal.II's generators or from a gmsh
// file (see Parameters::Geometry). It is built in a serial triangulation,
// where it can be converted to simplices or distorted, and then copied into
// the simulator's shared triangulation, which partitions it. Every material
// id of the mesh must have its `Material <id>` subsection, and every
// boundary id the parameter file names must exist: both mistakes are caught
// before anything is written.
//
// A gmsh file of second-order cells (MSH 2.2, 6-node triangles, 10-node
// tetrahedra) is read as its linear cells, and the positions of its
// mid-edge nodes are handed back, from which CurvedGeometry makes the
// curved mapping.
//
// Implemented in source/core/mesh.cc.

#ifndef soft_robot_core_mesh_h
#define soft_robot_core_mesh_h

#include <core/parameters.h>
#include <deal.II/base/point.h>
#include <deal.II/grid/tria.h>
#include <map>
#include <utility>

namespace SoftRobot
{
  using namespace dealii;

  // The mesh of the parameter file, with its material ids, into `serial`.
  // The mid-edge nodes of a second-order mesh, by the vertex indices of
  // the edge's ends, the smaller first.
  template <int dim>
  using MidEdgeNodes =
    std::map<std::pair<unsigned int, unsigned int>, Point<dim>>;

  // Fills mid_edge_nodes, if given, for a second-order mesh file; it stays
  // empty for a linear mesh or a generated one.
  template <int dim>
  void
  create_mesh(const Parameters::AllParameters &parameters,
              Triangulation<dim>              &serial,
              MidEdgeNodes<dim>               *mid_edge_nodes = nullptr);

  // Checks that the mesh has what the parameter file names; returns the
  // number of its materials.
  template <int dim>
  unsigned int
  check_mesh_ids(const Parameters::AllParameters &parameters,
                 const Triangulation<dim>        &triangulation);
} // namespace SoftRobot

#endif
