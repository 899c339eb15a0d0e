// SPDX-License-Identifier: LGPL-2.1-or-later

// Checks the committed coarse meshes of the bellows actuator
// (meshes/bellows_<model>_coarse.msh, written by meshes/generate_meshes.sh
// from meshes/bellows.geo) as the program reads them: with deal.II's
// GridIn::read_msh into a Triangulation<3> of linear tetrahedra.
//
// For each of the quarter, half and full model the test asserts
//  - the material ids (1 silicone, 2 tip block) and their volumes: the block
//    exactly, the silicone and the cavity within bounds derived below from
//    how far the mesh's flat triangles can stray from the curved surfaces;
//  - the boundary ids present, with every boundary face tagged (an untagged
//    face would read as id 0), and that the faces tagged 1, 3 and 4 lie on the
//    base plane x = -15.25 and the symmetry planes y = 0 and z = 0;
//  - the bounding box.
// The numbers checked against are those of the reference study
// (shared/paper/FACTS.md and the section shared/paper/actuator_section.csv
// beside the project), not the design parameters of bellows.geo, so that the
// test checks the geometry rather than repeating it.

// Not typed on the dimension: the actuator's gmsh meshes are 3D.

#include <array>
#include <cmath>
#include <cstdlib>
#include <deal.II/base/numbers.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>
#include <deal.II/grid/grid_in.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria.h>
#include <fstream>
#include <gtest/gtest.h>
#include <iostream>
#include <set>
#include <string>

namespace
{
  using namespace dealii;

  // @sect3{Facts of the reference geometry (mm)}

  // Revolved volume of the reference section (FACTS.md), and of its cavity,
  // the part enclosed by the cavity surface and the inlet opening
  // (meshes/check_geometry.py computes both from the CSV: 67,482.6 and
  // 15,176.3). Both are given to about 1e-4: the CSV's coordinates are
  // rounded to 1e-3 mm.
  constexpr double reference_volume        = 67483.0;
  constexpr double reference_cavity_volume = 15176.3;
  constexpr double reference_round_off     = 1e-4;

  // The base face, the end face of the cap, and the tip block glued on it.
  constexpr double x_base       = -15.25;
  constexpr double x_end        = 89.25;
  constexpr double block_length = 10.0;
  constexpr double block_width  = 29.0;
  // Outermost radius of the body: the flat tops of the outer crests.
  constexpr double r_outer = 18.622;

  // Material and boundary ids of the project (meshes/README.md).
  constexpr types::material_id silicone = 1, tip_block = 2;
  constexpr types::boundary_id base = 1, cavity = 2, symmetry_y = 3,
                               symmetry_z = 4, block_outer = 5,
                               silicone_outer = 6;

  struct Model
  {
    std::string                  name;
    unsigned int                 quarters;
    std::set<types::boundary_id> boundary_ids;
  };


  std::string
  mesh_path(const std::string &model)
  {
    const char       *source = std::getenv("SOFT_ROBOT_SOURCE_DIR");
    const std::string root   = (source != nullptr) ? source : "..";
    return root + "/meshes/bellows_" + model + "_coarse.msh";
  }


  // @sect3{How far a flat triangle strays from a surface of revolution}
  //
  // Every curved face of the body is a cone or cylinder about the x axis
  // with a straight meridian. A flat triangle whose vertices lie on such a
  // face, span the angle $\Delta\theta$ about the axis and reach the radius
  // $r_\text{max}$ lies inside the surface by at most the sagitta
  // $r_\text{max}(1-\cos(\Delta\theta/2))$ radially, and by that times
  // $n_r$, the radial component of the surface normal, across it. The region
  // inside the outer surface and the region inside the cavity surface are
  // both convex across the axis, so the outer surface's triangles cut
  // silicone off and the cavity's triangles add silicone; the sum of
  // $A_T n_r r_\text{max}(1-\cos(\Delta\theta_T/2))$ over each surface bounds
  // either change. (meshes/check_geometry.py computes the same bounds.)
  double
  inscribed_volume_bound(const std::array<Point<3>, 3> &v)
  {
    if (std::abs(v[0][0] - v[1][0]) < 1e-9 &&
        std::abs(v[0][0] - v[2][0]) < 1e-9)
      return 0.; // a plane x = const is meshed exactly

    const double area = 0.5 * cross_product_3d(v[1] - v[0], v[2] - v[0]).norm();
    double       r_min = 1e300, r_max = 0., x_min = 1e300, x_max = -1e300,
           spread = 0.;
    for (unsigned int i = 0; i < 3; ++i)
      {
        const double r = std::hypot(v[i][1], v[i][2]);
        r_min          = std::min(r_min, r);
        r_max          = std::max(r_max, r);
        x_min          = std::min(x_min, v[i][0]);
        x_max          = std::max(x_max, v[i][0]);
        for (unsigned int j = 0; j < 3; ++j)
          spread =
            std::max(spread,
                     std::abs(std::remainder(std::atan2(v[i][2], v[i][1]) -
                                               std::atan2(v[j][2], v[j][1]),
                                             2 * numbers::PI)));
      }
    const double normal_r =
      (x_max - x_min) / std::hypot(x_max - x_min, r_max - r_min);
    return area * normal_r * r_max * (1. - std::cos(spread / 2.));
  }


  // @sect3{The checks of one mesh}
  void
  check_coarse_mesh(const Model &model)
  {
    const double fraction = model.quarters / 4.;

    Triangulation<3> triangulation;
    {
      GridIn<3> grid_in;
      grid_in.attach_triangulation(triangulation);
      std::ifstream input(mesh_path(model.name));
      ASSERT_TRUE(input.good()) << "cannot open " << mesh_path(model.name);
      grid_in.read_msh(input);
    }
    ASSERT_GT(triangulation.n_active_cells(), 0u);

    double                       silicone_volume = 0., block_volume = 0.;
    double                       cut_off = 0., added = 0., cavity_volume = 0.;
    std::set<types::boundary_id> ids;
    std::set<types::material_id> materials;
    for (const auto &cell : triangulation.active_cell_iterators())
      {
        ASSERT_TRUE(cell->reference_cell() == ReferenceCells::Tetrahedron);
        materials.insert(cell->material_id());
        (cell->material_id() == silicone ? silicone_volume : block_volume) +=
          cell->measure();

        for (const auto f : cell->face_indices())
          {
            if (!cell->face(f)->at_boundary())
              continue;
            const auto               face = cell->face(f);
            const types::boundary_id id   = face->boundary_id();
            ids.insert(id);
            const std::array<Point<3>, 3> v = {
              {face->vertex(0), face->vertex(1), face->vertex(2)}};

            for (const Point<3> &p : v)
              {
                if (id == base)
                  {
                    EXPECT_NEAR(p[0], x_base, 1e-9);
                  }
                else if (id == symmetry_y)
                  {
                    EXPECT_NEAR(p[1], 0., 1e-9);
                  }
                else if (id == symmetry_z)
                  {
                    EXPECT_NEAR(p[2], 0., 1e-9);
                  }
              }

            if (id == silicone_outer)
              cut_off += inscribed_volume_bound(v);
            if (id == cavity)
              {
                added += inscribed_volume_bound(v);
                // Divergence theorem with F = (x - x_base, 0, 0): div F = 1,
                // F.n = 0 on the symmetry planes and the inlet opening, so the
                // cavity's volume is -\int (x - x_base) n_x dA over the cavity
                // faces, n pointing out of the silicone.
                Tensor<1, 3> area_normal =
                  0.5 * cross_product_3d(v[1] - v[0], v[2] - v[0]);
                if (area_normal * (face->center() - cell->center()) < 0)
                  area_normal *= -1.;
                cavity_volume -= (face->center()[0] - x_base) * area_normal[0];
              }
          }
      }

    EXPECT_EQ(materials, (std::set<types::material_id>{silicone, tip_block}));
    EXPECT_EQ(ids, model.boundary_ids);

    // The block is meshed exactly.
    EXPECT_NEAR(block_volume,
                fraction * block_length * block_width * block_width,
                1e-9 * block_volume);

    // The silicone lies between the exact volume less what the outer
    // triangles can cut off and the exact volume plus what the cavity
    // triangles can add. The bounds say something only while they are
    // modest: for the coarse meshes they are 8-15 % and 2-5 % of the
    // silicone, which loses 3-6 % in fact (the fine meshes: 0.1-0.2 %).
    const double exact = fraction * reference_volume;
    EXPECT_GE(silicone_volume, exact * (1 - reference_round_off) - cut_off);
    EXPECT_LE(silicone_volume, exact * (1 + reference_round_off) + added);
    EXPECT_LT(cut_off, 0.25 * exact);
    EXPECT_LT(added, 0.10 * exact);

    // The cavity can only shrink, by at most what the cavity faces add.
    const double exact_cavity = fraction * reference_cavity_volume;
    EXPECT_GE(cavity_volume, exact_cavity * (1 - reference_round_off) - added);
    EXPECT_LE(cavity_volume, exact_cavity * (1 + reference_round_off));

    // Bounding box: from the base to the block's far face; across the axis
    // the outer crests (r_outer) stick out beyond the block (half width
    // 14.5). Nodes lie on the section in the x-y plane, so y reaches r_outer
    // exactly in every model; the lower limits are the symmetry planes.
    const BoundingBox<3> box  = GridTools::compute_bounding_box(triangulation);
    const Point<3>       low  = box.get_boundary_points().first;
    const Point<3>       high = box.get_boundary_points().second;
    EXPECT_NEAR(low[0], x_base, 1e-9);
    EXPECT_NEAR(high[0], x_end + block_length, 1e-9);
    EXPECT_NEAR(high[1], r_outer, 1e-3);
    EXPECT_LE(high[2], r_outer + 1e-3);
    if (model.quarters == 1)
      {
        EXPECT_NEAR(low[1], 0., 1e-9);
      }
    else
      {
        EXPECT_GE(low[1], -r_outer - 1e-3);
      }
    if (model.quarters <= 2)
      {
        EXPECT_NEAR(low[2], 0., 1e-9);
      }
    else
      {
        EXPECT_GE(low[2], -r_outer - 1e-3);
      }
    // The silicone keeps well over 90 % of its cross-section at every angle.
    EXPECT_GT(high[2], 0.9 * r_outer);

    std::cout << model.name << " coarse: " << triangulation.n_active_cells()
              << " cells, " << triangulation.n_used_vertices()
              << " vertices; silicone " << silicone_volume << " mm^3 ("
              << 100. * (silicone_volume / exact - 1.) << " %, bounds -"
              << 100. * cut_off / exact << " % / +" << 100. * added / exact
              << " %), cavity " << cavity_volume << " mm^3 ("
              << 100. * (cavity_volume / exact_cavity - 1.) << " %), block "
              << block_volume << " mm^3" << std::endl;
  }
} // namespace


TEST(BellowsMeshes, QuarterCoarse)
{
  check_coarse_mesh(
    {"quarter",
     1,
     {base, cavity, symmetry_y, symmetry_z, block_outer, silicone_outer}});
}

TEST(BellowsMeshes, HalfCoarse)
{
  check_coarse_mesh(
    {"half", 2, {base, cavity, symmetry_z, block_outer, silicone_outer}});
}

TEST(BellowsMeshes, FullCoarse)
{
  check_coarse_mesh({"full", 4, {base, cavity, block_outer, silicone_outer}});
}
