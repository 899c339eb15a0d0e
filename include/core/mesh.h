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
// Implemented in source/core/mesh.cc.

#ifndef soft_robot_core_mesh_h
#define soft_robot_core_mesh_h

#include <core/parameters.h>
#include <deal.II/grid/tria.h>

namespace SoftRobot
{
  using namespace dealii;

  // The mesh of the parameter file, with its material ids, into `serial`.
  template <int dim>
  void
  create_mesh(const Parameters::AllParameters &parameters,
              Triangulation<dim>              &serial);

  // Checks that the mesh has what the parameter file names; returns the
  // number of its materials.
  template <int dim>
  unsigned int
  check_mesh_ids(const Parameters::AllParameters &parameters,
                 const Triangulation<dim>        &triangulation);
} // namespace SoftRobot

#endif
