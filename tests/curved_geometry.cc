// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Tests of second-order meshes and their curved geometry}
//
// A gmsh file of one 6-node triangle (2D) or 10-node tetrahedron (3D) is
// read through create_mesh(), and the curved mapping of CurvedGeometry is
// checked against areas and volumes known in closed form:
//  - a triangle whose edge (0,1) bulges out by d at its middle gains the
//    area between the edge and the parabola through its ends and the
//    mid-edge node, 2/3 L d (the quadratic map's boundary is that
//    parabola, and the area is the boundary's by Green's theorem);
//  - a tetrahedron whose mid-edge node is moved along its straight edge
//    keeps the volume 1/6 (the image of the map is the same tetrahedron),
//    which it would not if a mid-edge node went to the wrong edge;
//  - a globally refined mesh has the same curved geometry, to round-off.
// Then the two input errors: a mid-edge node far from its edge, and a
// distortion asked of a second-order mesh. The 1D program reads no gmsh
// files, so these tests run in 2D and 3D.

#include <core/curved_geometry.h>
#include <core/mesh.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_simplex_p.h>
#include <deal.II/fe/fe_values.h>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <iomanip>
#include <iostream>
#include <sstream>

using namespace dealii;
using namespace SoftRobot;

namespace
{
  // One second-order simplex with its corners at the origin and the unit
  // vectors, the mid-edge node of the edge (0,1) at `bulge` and the others
  // at their edges' midpoints, written as MSH 2.2 in gmsh's node order.
  template <int dim>
  std::string
  write_simplex(const std::string &name, const Point<3> &bulge)
  {
    std::vector<Point<3>> corners(dim + 1);
    for (unsigned int d = 0; d < dim; ++d)
      corners[d + 1][d] = 1.;
    const std::vector<std::pair<unsigned int, unsigned int>> edges =
      (dim == 2) ? std::vector<std::pair<unsigned int, unsigned int>>{{0, 1},
                                                                      {1, 2},
                                                                      {2, 0}}
                 : std::vector<std::pair<unsigned int, unsigned int>>{
                     {0, 1}, {1, 2}, {2, 0}, {3, 0}, {3, 2}, {3, 1}};
    std::vector<Point<3>> nodes = corners;
    for (const auto &[a, b] : edges)
      nodes.push_back(0.5 * (corners[a] + corners[b]));
    nodes[dim + 1] = bulge;

    const std::filesystem::path path =
      std::filesystem::temp_directory_path() /
      ("soft_robot_" + name + "_" + std::to_string(dim) + "d.msh");
    std::ofstream file(path);
    file << std::setprecision(17) << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n"
         << "$Nodes\n"
         << nodes.size() << '\n';
    for (unsigned int i = 0; i < nodes.size(); ++i)
      file << i + 1 << ' ' << nodes[i][0] << ' ' << nodes[i][1] << ' '
           << nodes[i][2] << '\n';
    file << "$EndNodes\n$Elements\n1\n1 " << (dim == 2 ? 9 : 11) << " 2 1 1";
    for (unsigned int i = 0; i < nodes.size(); ++i)
      file << ' ' << i + 1;
    file << "\n$EndElements\n";
    return path.string();
  }

  Parameters::AllParameters
  mesh_parameters(const std::string &file)
  {
    Parameters::AllParameters parameters;
    parameters.mesh_source = Parameters::Geometry::MeshSource::file;
    parameters.mesh_file   = file;
    parameters.distortion  = 0;
    return parameters;
  }

  template <int dim>
  double
  measure(const Triangulation<dim> &triangulation, const Mapping<dim> &mapping)
  {
    const FE_SimplexP<dim> fe(1);
    FEValues<dim>          fe_values(mapping,
                            fe,
                            QGaussSimplex<dim>(4),
                            update_JxW_values);
    double                 sum = 0;
    for (const auto &cell : triangulation.active_cell_iterators())
      {
        fe_values.reinit(cell);
        for (unsigned int q = 0; q < fe_values.n_quadrature_points; ++q)
          sum += fe_values.JxW(q);
      }
    return sum;
  }

  // The simplex's area or volume with its curved geometry, after
  // `refinements` global refinements.
  template <int dim>
  double
  curved_measure(const std::string &file, const unsigned int refinements)
  {
    Triangulation<dim> triangulation;
    MidEdgeNodes<dim>  mid_edge_nodes;
    create_mesh(mesh_parameters(file), triangulation, &mid_edge_nodes);
    EXPECT_EQ(mid_edge_nodes.size(), dim == 2 ? 3u : 6u);
    triangulation.refine_global(refinements);
    const CurvedGeometry<dim> geometry(triangulation, mid_edge_nodes);
    return measure(triangulation, *geometry.create_mapping());
  }
} // namespace

template <typename T>
class CurvedGeometryTest : public ::testing::Test
{
};
using CurvedDimensions = ::testing::Types<std::integral_constant<int, 2>,
                                          std::integral_constant<int, 3>>;
TYPED_TEST_SUITE(CurvedGeometryTest, CurvedDimensions);

TYPED_TEST(CurvedGeometryTest, MeasureOfTheCurvedSimplex)
{
  constexpr int dim = TypeParam::value;
  if constexpr (dim == 2)
    {
      // Edge (0,1) runs from (0,0) to (1,0); the bulge is outwards, -y.
      const double d = 0.1;
      const double area =
        curved_measure<dim>(write_simplex<dim>("bulge", Point<3>(0.5, -d, 0.)),
                            0);
      std::cout << "area " << std::setprecision(15) << area << ", exact "
                << 0.5 + 2. / 3. * d << std::endl;
      EXPECT_NEAR(area, 0.5 + 2. / 3. * 1. * d, 1e-13);
    }
  else
    {
      const double volume =
        curved_measure<dim>(write_simplex<dim>("slide", Point<3>(0.62, 0., 0.)),
                            0);
      std::cout << "volume " << std::setprecision(15) << volume << ", exact "
                << 1. / 6. << std::endl;
      EXPECT_NEAR(volume, 1. / 6., 1e-13);
    }
}

TYPED_TEST(CurvedGeometryTest, RefinementKeepsTheCurvedGeometry)
{
  constexpr int     dim = TypeParam::value;
  const std::string file =
    write_simplex<dim>("refined", Point<3>(0.5, -0.1, -0.05));
  const double coarse = curved_measure<dim>(file, 0);
  // The straight simplex measures 1/2 or 1/6; the bulge must show.
  EXPECT_GT(coarse, (dim == 2 ? 0.5 : 1. / 6.) * 1.01);
  for (unsigned int refinements = 1; refinements <= 2; ++refinements)
    {
      const double refined = curved_measure<dim>(file, refinements);
      std::cout << refinements << " refinement(s): " << std::setprecision(15)
                << refined << ", unrefined " << coarse << std::endl;
      EXPECT_NEAR(refined, coarse, 1e-13);
    }
}

TYPED_TEST(CurvedGeometryTest, InputErrorsNameTheFileAndTheCause)
{
  constexpr int      dim = TypeParam::value;
  Triangulation<dim> triangulation;
  MidEdgeNodes<dim>  mid_edge_nodes;
  const std::string  far = write_simplex<dim>("far", Point<3>(3., 3., 0.));
  try
    {
      create_mesh(mesh_parameters(far), triangulation, &mid_edge_nodes);
      FAIL() << "a mid-edge node far from its edge was accepted";
    }
  catch (const std::exception &error)
    {
      const std::string text = error.what();
      EXPECT_NE(text.find(far), std::string::npos) << text;
      EXPECT_NE(text.find("farther from the edge's midpoint"),
                std::string::npos)
        << text;
    }

  Triangulation<dim>        other;
  Parameters::AllParameters parameters =
    mesh_parameters(write_simplex<dim>("distorted", Point<3>(0.5, -0.1, 0.)));
  parameters.distortion = 0.1;
  try
    {
      create_mesh(parameters, other, &mid_edge_nodes);
      FAIL() << "a distortion of a second-order mesh was accepted";
    }
  catch (const std::exception &error)
    {
      EXPECT_NE(std::string(error.what()).find("Geometry/Distortion"),
                std::string::npos)
        << error.what();
    }
}
