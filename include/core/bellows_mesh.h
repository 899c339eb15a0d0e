// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{A hexahedral mesh of the bellows}
//
// The bellows actuator is a solid of revolution: a folded wall of constant
// thickness, a base ring and an end cap (meshes/bellows.geo describes it
// and meshes/README.md gives its numbers). Its thin walls are what an
// unstructured tetrahedral mesh resolves badly: the 3 mm wall of the coarse
// gmsh meshes is one or two tetrahedra thick, with cells of every
// orientation, and quadratic tetrahedra need some 30,000 unknowns on a
// quarter of the body before the frequency of the vertical oscillation is
// within 1 % of its converged value (doc/reference.md). This file builds
// the mesh that the shape asks for: hexahedra that follow the wall, made by
// revolving a mesh of quadrilaterals of the section about the axis.
//
// <h4>The section</h4>
//
// The section in the $(x, r)$ half plane is the polygon of bellows.geo:
// each convolution is a wall of thickness $t$ folded about a mid-line of
// circular arcs (the folds) and straight flanks, and each fold's two sides
// are arcs about one centre sampled by a few chords (the reference
// polygon's vertices). The wall becomes a strip of quadrilaterals between
// "stations", segments across the wall:
// - in a fold, one station at each vertex of the side with the larger
//   radius (its chords), ending on the side with the smaller radius at
//   points spaced evenly along its chords, so that every vertex of the
//   polygon is a vertex of the mesh and the polygon is represented
//   exactly;
//   (`Cells per chord` stations per chord of that side);
// - on a flank, whose two sides are parallel, `Cells along a flank`
//   cells between the stations at its ends, which are normal to it.
// The strip has `Cells through the wall` cells across. The base ring and
// the end cap, thicker parts, are small structured blocks joined to the
// strip at the first and the last fold; the neck where the outermost flank
// meets the ring gets a patch of its own, so that the neck's corner is a
// vertex too.
//
// <h4>Revolving, and the axis</h4>
//
// Every quadrilateral whose vertices lie off the axis is revolved through
// the model's angle (90 degrees for the quarter model, 180 for the half,
// 360 for the full body) in `Cells per quarter turn` steps per 90 degrees:
// one hexahedron per step. The end cap and the tip block reach the axis,
// where revolving would give degenerate cells. There the section has a
// column of quadrilaterals from the axis to the radius of the inlet
// channel, and each of them becomes an "O-grid" in 3D instead: a square
// core of hexahedra about the axis, surrounded by one ring of hexahedra
// whose outer faces lie on the cylinder and share their vertices with the
// revolved cells.
//
// <h4>Geometry</h4>
//
// The revolved cells carry a CylindricalManifold about the x axis, so the
// mapping of degree 2 that the program uses on such a mesh, and every
// global refinement, place new points on the exact surfaces of revolution
// (the section's straight chords stay straight: they are the reference
// geometry). The square cores are flat.
//
// <h4>The tip block</h4>
//
// The study's tip block is a 29 x 29 x 10 mm box glued over the end cap,
// whose end disc (radius 14.5 mm) touches the box's sides: a box and a
// disc cannot share a hexahedral mesh without cells that degenerate at
// the four points of contact. The block is a rigid body for all purposes
// of the motion (its stiffness is chosen only to be large, see the
// protocol files), and a rigid body's motion depends on its mass, centre of
// mass and tensor of inertia alone. A cylinder of the same length and mass
// about the same axis has the box's tensor of inertia when its radius is
// $a/\sqrt3$ for the box's width $a$: about the axis $m a^2/6 = m R^2/2$,
// and about a transverse axis through the centre of mass $m(a^2 + l^2)/12
// = m(3R^2 + l^2)/12$. This mesh therefore has a cylindrical block of
// radius $29/\sqrt3 = 16.74$ mm, glued over the same disc; its density
// follows from the same mass (`Material 2/Mass`). How much that changes
// the computed motion, through the block's finite stiffness, is measured
// in doc/reference_discussion.md.
//
// <h4>Ids</h4>
//
// Material and boundary ids are those of the gmsh meshes (meshes/README.md):
// material 1 the silicone, 2 the block; boundary 1 the clamped base face,
// 2 the cavity (inlet channel, convolutions and the disc closing the
// cavity), 3 and 4 the symmetry planes y = 0 and z = 0, 5 the block's free
// faces, 6 the rest of the silicone. The glued joint is interior.
//
// Implemented in source/core/bellows_mesh.cc.

#ifndef soft_robot_core_bellows_mesh_h
#define soft_robot_core_bellows_mesh_h

#include <array>
#include <deal.II/base/point.h>
#include <deal.II/grid/tria.h>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace SoftRobot
{
  using namespace dealii;

  // @sect4{The design}
  //
  // The design numbers of the body, read from the gmsh geometry
  // meshes/bellows.geo (its lines `Name = number;`), which is their one
  // home: the tetrahedral meshes and this generator build the same body.
  struct BellowsDesign
  {
    double       x_base;
    double       end_wall;
    double       inlet_radius;
    double       ring_radius;
    double       neck_radius;
    double       neck_length;
    unsigned int n_convolutions;
    double       pitch;
    double       inner_crest_radius;
    double       wall_thickness;
    double       fold_radius;
    unsigned int chords_cavity_valley;
    unsigned int chords_cavity_crest;
    unsigned int chords_outer_crest;
    unsigned int chords_outer_valley;
    double       block_length;
    double       block_width;

    // Reads the numbers; an entry that is missing or out of its range is an
    // error that names the file and the entry.
    static BellowsDesign
    read(const std::string &geo_file);

    // The radius of the cylindrical block with the box's tensor of inertia.
    double
    block_radius() const;

    // The end of the cap (the glued joint), x_base + 2 end_wall +
    // n_convolutions pitch.
    double
    x_end() const;
  };

  // @sect4{Resolution}
  struct BellowsResolution
  {
    unsigned int cells_through_wall     = 1;
    unsigned int cells_along_flank      = 3;
    unsigned int cells_per_chord        = 1;
    unsigned int cells_per_quarter_turn = 2;
  };

  // @sect4{The section}
  //
  // Quadrilaterals in the $(x, r)$ half plane, vertices in deal.II's order
  // (lexicographic in the cell's two directions). Boundary edges, by the
  // indices of their ends (the smaller first), carry the boundary id their
  // revolved faces get; edges on the axis carry none. `on_axis` marks the
  // quadrilaterals that reach the axis, which become O-grids.
  struct BellowsSection
  {
    std::vector<Point<2>>                    vertices;
    std::vector<std::array<unsigned int, 4>> quads;
    std::vector<types::material_id>          materials;
    std::vector<bool>                        on_axis;
    std::map<std::pair<unsigned int, unsigned int>, types::boundary_id>
           boundary_edges;
    double core_radius;

    // The area and the volume of revolution (full turn) of the quadrilaterals
    // of one material, by the shoelace formula and Pappus' theorem: checks.
    double
    area(const types::material_id material) const;
    double
    revolved_volume(const types::material_id material) const;
  };

  BellowsSection
  make_bellows_section(const BellowsDesign     &design,
                       const BellowsResolution &resolution);

  // @sect4{The body}
  //
  // The section revolved through `quarters` times 90 degrees (1, 2 or 4),
  // with the O-grids at the axis, the ids, and the CylindricalManifold
  // (manifold id 1) on the revolved cells, into an empty triangulation.
  void
  make_bellows_mesh(const BellowsDesign     &design,
                    const BellowsResolution &resolution,
                    const unsigned int       quarters,
                    Triangulation<3>        &triangulation);
} // namespace SoftRobot

#endif
