// SPDX-License-Identifier: LGPL-2.1-or-later

// Checks the hexahedral mesh of the bellows (core/bellows_mesh.h) against
// the reference geometry, independently of how it is built:
//  - the section of quadrilaterals covers the reference polygon: its area
//    and its volume of revolution are those of the polygon (computed here
//    from the reference numbers, not from the generator's design);
//  - the 3D mesh of the quarter, half and full model, integrated with the
//    program's mapping of degree 2, holds the revolved volume of the
//    silicone and of the cylindrical block, within the error of a
//    quadratic arc (bounded below);
//  - every boundary face has an id, the faces of ids 1, 3 and 4 lie on the
//    base plane and the symmetry planes, those of id 2 enclose the
//    reference cavity volume (by the divergence theorem), and every cell
//    has a positive Jacobian at every quadrature point;
//  - global refinement keeps the volume (the manifold places new points on
//    the surfaces of revolution).
// Not typed on the dimension: the bellows mesh is 3D.

#include <cmath>
#include <core/bellows_mesh.h>
#include <cstdlib>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_nothing.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/grid/grid_tools.h>
#include <gtest/gtest.h>
#include <iostream>
#include <map>
#include <string>

namespace
{
  using namespace dealii;
  using namespace SoftRobot;

  // @sect3{Facts of the reference geometry (mm)}
  //
  // The revolved volume of the reference polygon and of its cavity (the
  // region enclosed by the cavity surface and the inlet opening), as in
  // tests/bellows_meshes.cc, and the block of the reference study.
  constexpr double reference_volume        = 67483.0;
  constexpr double reference_cavity_volume = 15176.3;
  constexpr double reference_round_off     = 1e-4;
  constexpr double x_base                  = -15.25;
  constexpr double x_end                   = 89.25;
  constexpr double block_length            = 10.0;
  constexpr double block_width             = 29.0;

  std::string
  design_file()
  {
    const char       *source = std::getenv("SOFT_ROBOT_SOURCE_DIR");
    const std::string root   = (source != nullptr) ? source : "..";
    return root + "/meshes/bellows.geo";
  }

  // The volume of each material of a mesh, the flux of x e_x through the
  // faces of each boundary id (with the mesh's outward normals), and the
  // smallest Jacobian at the quadrature points.
  struct Measured
  {
    std::map<types::material_id, double> volume;
    std::map<types::boundary_id, double> x_flux;
    double                               smallest_jacobian = 1e300;
  };

  Measured
  measure(const Triangulation<3> &triangulation)
  {
    const MappingQ<3>   mapping(2);
    const FE_Nothing<3> fe;
    DoFHandler<3>       dof_handler(triangulation);
    dof_handler.distribute_dofs(fe);
    const QGauss<3> quadrature(4);
    const QGauss<2> face_quadrature(4);
    FEValues<3>     fe_values(mapping,
                          fe,
                          quadrature,
                          update_JxW_values | update_jacobians);
    FEFaceValues<3> fe_face_values(mapping,
                                   fe,
                                   face_quadrature,
                                   update_JxW_values | update_normal_vectors |
                                     update_quadrature_points);
    Measured        result;
    for (const auto &cell : dof_handler.active_cell_iterators())
      {
        fe_values.reinit(cell);
        for (unsigned int q = 0; q < quadrature.size(); ++q)
          {
            result.volume[cell->material_id()] += fe_values.JxW(q);
            result.smallest_jacobian =
              std::min(result.smallest_jacobian,
                       determinant(Tensor<2, 3>(fe_values.jacobian(q))));
          }
        for (const unsigned int f : cell->face_indices())
          if (cell->face(f)->at_boundary())
            {
              fe_face_values.reinit(cell, f);
              for (unsigned int q = 0; q < face_quadrature.size(); ++q)
                result.x_flux[cell->face(f)->boundary_id()] +=
                  fe_face_values.quadrature_point(q)[0] *
                  fe_face_values.normal_vector(q)[0] * fe_face_values.JxW(q);
            }
      }
    return result;
  }

  // @sect3{The section}
  TEST(BellowsHexMesh, SectionCoversTheReferencePolygon)
  {
    const BellowsDesign design = BellowsDesign::read(design_file());
    for (const unsigned int through : {1u, 2u})
      {
        BellowsResolution resolution;
        resolution.cells_through_wall = through;
        resolution.cells_along_flank  = 3 * through;
        const BellowsSection section = make_bellows_section(design, resolution);
        std::cout << "cells through the wall " << through << ": "
                  << section.quads.size() << " quadrilaterals, silicone "
                  << 100. * (section.revolved_volume(1) / reference_volume - 1.)
                  << " %" << std::endl;
        // The silicone: the polygon's revolved volume to its round-off.
        EXPECT_NEAR(section.revolved_volume(1) / reference_volume,
                    1.,
                    reference_round_off)
          << "cells through the wall: " << through;
        // The block: a cylinder of radius w / sqrt(3).
        const double radius = block_width / std::sqrt(3.);
        EXPECT_NEAR(section.revolved_volume(2),
                    numbers::PI * radius * radius * block_length,
                    1e-9 * block_length * radius * radius);
        // No quadrilateral is inverted or degenerate: all have one sense
        // (the shoelace area in deal.II's vertex order) and each has its
        // four corners convex, which a positive Jacobian needs.
        for (unsigned int q = 0; q < section.quads.size(); ++q)
          {
            const auto                       &v = section.quads[q];
            const std::array<unsigned int, 4> loop{{v[0], v[1], v[3], v[2]}};
            unsigned int                      left = 0, right = 0;
            for (unsigned int i = 0; i < 4; ++i)
              {
                const Point<2> &a = section.vertices[loop[(i + 3) % 4]];
                const Point<2> &b = section.vertices[loop[i]];
                const Point<2> &c = section.vertices[loop[(i + 1) % 4]];
                const double    turn =
                  (b[0] - a[0]) * (c[1] - b[1]) - (b[1] - a[1]) * (c[0] - b[0]);
                left += (turn > 0.);
                right += (turn < 0.);
              }
            EXPECT_TRUE(left == 4 || right == 4)
              << "quadrilateral " << q << " is not convex";
          }
      }
  }

  // @sect3{The body}
  //
  // A quadratic arc through three points of a circle of radius r over an
  // angle h deviates from it by about r h^4 / 512 at most; over the
  // coarsest turn of 45 degrees that is 7e-4 r, and the volume error is at
  // most that relative to the volume: the bound below is 1e-3.
  TEST(BellowsHexMesh, VolumesIdsAndJacobians)
  {
    const BellowsDesign design = BellowsDesign::read(design_file());
    for (const unsigned int quarters : {1u, 2u, 4u})
      {
        Triangulation<3> triangulation;
        make_bellows_mesh(design, BellowsResolution(), quarters, triangulation);
        const double   fraction = quarters / 4.;
        const Measured measured = measure(triangulation);
        const double   radius   = block_width / std::sqrt(3.);
        const double   cavity =
          -measured.x_flux.at(2) - fraction * numbers::PI * 2.5 * 2.5 * x_base;
        std::cout
          << quarters << " quarter(s): " << triangulation.n_active_cells()
          << " cells; silicone "
          << 100. * (measured.volume.at(1) / (fraction * reference_volume) - 1.)
          << " %, cavity "
          << 100. * (cavity / (fraction * reference_cavity_volume) - 1.)
          << " %, block " << measured.volume.at(2) << " mm^3" << std::endl;
        EXPECT_NEAR(measured.volume.at(1) / (fraction * reference_volume),
                    1.,
                    1e-3)
          << quarters << " quarter(s)";
        EXPECT_NEAR(measured.volume.at(2) /
                      (fraction * numbers::PI * radius * radius * block_length),
                    1.,
                    1e-3)
          << quarters << " quarter(s)";
        EXPECT_GT(measured.smallest_jacobian, 0.);

        // Ids: all there, none other, and the planar ones on their planes.
        std::set<types::boundary_id> ids;
        for (const auto &face : triangulation.active_face_iterators())
          if (face->at_boundary())
            {
              ids.insert(face->boundary_id());
              for (const unsigned int v : face->vertex_indices())
                {
                  const Point<3> &p = face->vertex(v);
                  if (face->boundary_id() == 1)
                    {
                      EXPECT_NEAR(p[0], x_base, 1e-9);
                    }
                  else if (face->boundary_id() == 3)
                    {
                      EXPECT_NEAR(p[1], 0., 1e-9);
                    }
                  else if (face->boundary_id() == 4)
                    {
                      EXPECT_NEAR(p[2], 0., 1e-9);
                    }
                }
            }
        std::set<types::boundary_id> expected{1, 2, 5, 6};
        if (quarters == 1)
          expected.insert(3);
        if (quarters < 4)
          expected.insert(4);
        EXPECT_EQ(ids, expected) << quarters << " quarter(s)";

        // The cavity's volume is the flux of x e_x out of it (divergence
        // theorem): through the cavity faces, whose normals point out of
        // the silicone and so into the cavity, minus their flux; through
        // the inlet opening (the disc of radius 2.5 at x = x_base, outward
        // normal -e_x) -x_base times its area; the symmetry planes contain
        // e_x and add nothing.
        EXPECT_NEAR(cavity / (fraction * reference_cavity_volume), 1., 1e-3)
          << quarters << " quarter(s)";
      }
  }

  TEST(BellowsHexMesh, RefinementKeepsTheVolume)
  {
    const BellowsDesign design = BellowsDesign::read(design_file());
    Triangulation<3>    triangulation;
    make_bellows_mesh(design, BellowsResolution(), 1, triangulation);
    const double coarse = measure(triangulation).volume.at(1);
    triangulation.refine_global(1);
    const Measured fine = measure(triangulation);
    // Halving the arcs' angle divides their error by about 16.
    std::cout << "silicone, coarse: "
              << 100. * (coarse / (0.25 * reference_volume) - 1.)
              << " %, refined once: "
              << 100. * (fine.volume.at(1) / (0.25 * reference_volume) - 1.)
              << " %" << std::endl;
    EXPECT_NEAR(coarse / (0.25 * reference_volume), 1., 1e-3);
    EXPECT_NEAR(fine.volume.at(1) / (0.25 * reference_volume), 1., 2e-4);
    EXPECT_GT(fine.smallest_jacobian, 0.);
  }

  TEST(BellowsHexMesh, DesignErrorsNameTheFileAndEntry)
  {
    const std::string missing = "/nonexistent/bellows.geo";
    try
      {
        BellowsDesign::read(missing);
        FAIL() << "no exception for a missing file";
      }
    catch (const ExceptionBase &error)
      {
        EXPECT_NE(std::string(error.what()).find(missing), std::string::npos);
      }
  }
} // namespace
