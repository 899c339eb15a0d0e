// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Tests of the pneumatic load}
//
// The follower pressure, the gas in the cavity and the solver of the
// tangent's rank-one term (include/physics/follower_pressure.h,
// gas_cavity.h, pneumatic_load.h, include/solvers/rank_one_correction.h),
// each against a closed form or an independent computation:
// - the load stiffness and the gas tangent (with its rank-one term) against
//   central differences of the nodal forces;
// - the Sherman-Morrison solve against a dense solve of the full matrix;
// - the cavity volume of the bellows mesh against the revolved section,
//   and of a deformed spherical cavity against the ellipsoid's volume;
// - the static inflation of a thick-walled neo-Hookean sphere against the
//   closed-form pressure-stretch relation of the incompressible solid, with
//   quadratic and with linear hexahedra, and its rate under refinement;
// - a gas cavity driven by a mass inflow: the same pressure history for
//   dt, dt/2 and dt/4 to the second-order error of the time integration;
//   the energy balance with the pressure work, and that work against the
//   isothermal gas's closed form;
// - a mass on the gas spring of a closed cavity: its period against the
//   gas stiffness's.
// Each test says where its tolerance comes from.

#include "solver_test_tools.h"

#include <cmath>
#include <core/soft_robot_dynamics.h>
#include <cstdlib>
#include <deal.II/base/timer.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/grid/grid_in.h>
#include <deal.II/lac/lapack_full_matrix.h>
#include <fstream>
#include <gtest/gtest.h>
#include <random>
#include <solvers/linear_solver.h>
#include <solvers/rank_one_correction.h>

using namespace dealii;
using namespace SoftRobot;
using namespace SoftRobot::Testing;

namespace
{
  // The nodal values of the displacement u = A X (a linear map).
  template <int dim>
  TrilinosWrappers::MPI::Vector
  linear_map(const SimulatorAccess<dim> &body, const Tensor<2, dim> &A)
  {
    TrilinosWrappers::MPI::Vector                 u(body.displacement());
    std::map<types::global_dof_index, Point<dim>> support;
    DoFTools::map_dofs_to_support_points(body.get_mapping(),
                                         body.get_dof_handler(),
                                         support);
    const FiniteElement<dim>            &fe = body.get_dof_handler().get_fe();
    std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
    for (const auto &cell : body.get_dof_handler().active_cell_iterators())
      {
        cell->get_dof_indices(dofs);
        for (unsigned int i = 0; i < dofs.size(); ++i)
          u[dofs[i]] =
            (A * support[dofs[i]])[fe.system_to_component_index(i).first];
      }
    u.compress(VectorOperation::insert);
    return u;
  }

  // The load vector p g(u) of the pneumatics at u: with the gas law if
  // `gas`, else at the pressure p.
  template <int dim>
  TrilinosWrappers::MPI::Vector
  pressure_force(SimulatorAccess<dim>                &body,
                 const TrilinosWrappers::MPI::Vector &u,
                 const bool                           gas,
                 const double                         p = 0.)
  {
    TrilinosWrappers::MPI::Vector g(u);
    const auto                    evaluation =
      gas ? body.get_pneumatics().evaluate(u, 0., g)
                             : body.get_pneumatics().evaluate_at_pressure(u, p, g);
    g *= evaluation.pressure;
    return g;
  }

  // The eighth of a hollow sphere (inner radius A, outer B) of one
  // neo-Hookean material, on the symmetry planes x = 0, y = 0, z = 0 (ids
  // 2, 3, 4), with the pressure on the inner surface (id 0): hexahedra of
  // degree p, `refinements` times refined.
  std::string
  octant_shell(const double       A,
               const double       B,
               const unsigned int degree,
               const unsigned int refinements,
               const double       mu,
               const double       kappa,
               const std::string &pneumatics,
               const std::string &formulation = "displacement")
  {
    std::ostringstream text;
    text << "subsection Geometry\n"
            "  set Generator = quarter_hyper_shell\n"
            "  set Generator arguments = 0, 0, 0 : "
         << A << " : " << B << " : 0 : true\n"
         << "  set Global refinements = " << refinements
         << "\n  set Model fraction = 0.125\nend\n"
         << "subsection Finite element\n  set Polynomial degree = " << degree
         << "\n  set Volumetric formulation = " << formulation << "\nend\n"
         << "subsection Material 1\n  set Name = rubber\n"
         << "  set Shear modulus = " << mu << "\n  set Bulk modulus = " << kappa
         << "\n  set Density = 1e-6\nend\n"
         << "subsection Loads and constraints\n  set Gravity = 0, 0, 0\n"
         << "  set Fixed components = 2: x, 3: y, 4: z\nend\n"
         << "subsection Linear solver\n  set Solver = Direct\nend\n"
         << "subsection Pneumatics\n  set Pressure boundary ids = 0\n"
         << pneumatics << "end\n";
    return parameter_text(3, text.str());
  }

  // The largest entry of x - y over that of y.
  double
  relative_difference(const TrilinosWrappers::MPI::Vector &x,
                      const TrilinosWrappers::MPI::Vector &y)
  {
    TrilinosWrappers::MPI::Vector difference(x);
    difference -= y;
    return difference.linfty_norm() / y.linfty_norm();
  }
} // namespace



// @sect4{The follower load's stiffness}
//
// A box clamped at x = 0, deformed at random, with a pressure on its end
// x = L (an open surface: the load stiffness is not symmetric there, the
// hardest case). The matrix of the simulator with the pressure minus the
// one without is the load stiffness $-p\,\partial\mathbf g/\partial\mathbf
// u$; its product with a random direction must be the central difference
// of the load $p\,\mathbf g$, whose error is $O(h^2)$ times the third
// derivative (relative $\sim 10^{-10}$ at $h = 10^{-5}$ of the
// displacement's scale) plus round-off $\varepsilon/h \sim 10^{-11}$.
template <typename T>
class FollowerPressureTest : public ::testing::Test
{
};
TYPED_TEST_SUITE(FollowerPressureTest, Dimensions2And3);

TYPED_TEST(FollowerPressureTest, LoadStiffnessIsTheDerivativeOfTheLoad)
{
  constexpr int      dim = TypeParam::value;
  std::ostringstream sections;
  sections << "subsection Geometry\n  set Generator = "
              "subdivided_hyper_rectangle\n  set Generator arguments = "
           << box_arguments(dim, 3, 2, 3., 1.)
           << "\n  set Random distortion = 0.15\nend\n"
           << "subsection Finite element\n  set Polynomial degree = 2\nend\n"
           << "subsection Material 1\n  set Name = silicone\n"
              "  set Shear modulus = 10\n  set Bulk modulus = 1000\n"
              "  set Density = 1e-6\nend\n"
           << "subsection Loads and constraints\n  set Gravity = 0, 0, 0\n"
           << "  set Fixed components = 0: "
           << std::string("xyz").substr(0, dim) << "\nend\n"
           << "subsection Linear solver\n  set Solver = Direct\nend\n"
           << "subsection Pneumatics\n  set Pressure boundary ids = 1\n"
              "  set Pressure = 2\nend\n";
  const Parameters::AllParameters parameters =
    read(parameter_text(dim, sections.str()));
  Simulation<dim> body(parameters, MPI_COMM_WORLD);
  body.make_grid();
  body.setup_system();

  const double                        p         = 2.;
  const TrilinosWrappers::MPI::Vector u         = random_vector(body, 0.05, 1);
  const TrilinosWrappers::MPI::Vector direction = random_vector(body, 1., 2);
  TrilinosWrappers::MPI::Vector       with_pressure(u), without(u), load(u);

  pressure_force(body, u, false, p);
  body.tangent_stiffness_matrix(u).vmult(with_pressure, direction);
  pressure_force(body, u, false, 0.);
  body.tangent_stiffness_matrix(u).vmult(without, direction);
  TrilinosWrappers::MPI::Vector stiffness_product(with_pressure);
  stiffness_product -= without;
  // The residual holds -p g: its derivative is the negative of the load's.
  stiffness_product *= -1.;

  const double                  h = 1e-5;
  TrilinosWrappers::MPI::Vector u_plus(u), u_minus(u);
  u_plus.add(h, direction);
  u_minus.add(-h, direction);
  TrilinosWrappers::MPI::Vector difference =
    pressure_force(body, u_plus, false, p);
  difference -= pressure_force(body, u_minus, false, p);
  difference /= 2. * h;
  body.get_constraints().set_zero(difference);
  body.get_constraints().set_zero(stiffness_product);

  const double error = relative_difference(stiffness_product, difference);
  std::cout << dim << "D: |K_p d| = " << stiffness_product.linfty_norm()
            << ", relative difference from the central difference " << error
            << std::endl;
  EXPECT_GT(stiffness_product.linfty_norm(), 1e-3 * p);
  EXPECT_LT(error, 1e-7);
}



// @sect4{The gas cavity's tangent}
//
// The eighth of a hollow sphere holding a gas (adiabatic, 20 kPa above
// ambient at sealing), deformed at random: the derivative of the nodal
// forces $p(V(\mathbf u))\,\mathbf g(\mathbf u)$ is $p\,\partial\mathbf
// g/\partial\mathbf u - s\,\mathbf g\mathbf g^T$, the load stiffness of
// the faces (in the sparse matrix) and the rank-one term. The tolerance
// is that of the central difference, as above. Without the rank-one term
// the product misses by the rank-one part, which is checked to be large.
// (Not typed on the dimension: the reduced models' end load is a
// constant vector and has no load stiffness; its gas term is checked by
// the time-step test below.)
TEST(GasCavity, TangentWithRankOneTermIsTheDerivative)
{
  const Parameters::AllParameters parameters =
    read(octant_shell(10.,
                      15.,
                      2,
                      0,
                      10.,
                      1000.,
                      "  set Pressure model = gas\n"
                      "  set Initial pressure = 20\n"
                      "  set Gas law exponent = 1.4\n"
                      "  set Dead volume = 2000\n"));
  Simulation<3> body(parameters, MPI_COMM_WORLD);
  body.make_grid();
  body.setup_system();
  PneumaticLoad<3> &pneumatics = body.get_pneumatics();
  pneumatics.seal(body.displacement());

  const TrilinosWrappers::MPI::Vector u         = random_vector(body, 0.3, 3);
  const TrilinosWrappers::MPI::Vector direction = random_vector(body, 1., 4);
  TrilinosWrappers::MPI::Vector       g(u), with_pressure(u), without(u);
  const auto evaluation = pneumatics.evaluate(u, 0., g);
  body.tangent_stiffness_matrix(u).vmult(with_pressure, direction);
  pneumatics.evaluate_at_pressure(u, 0., without);
  body.tangent_stiffness_matrix(u).vmult(without, direction);
  // -(K_p d) - s g (g.d)
  TrilinosWrappers::MPI::Vector sparse_part(without);
  sparse_part -= with_pressure;
  TrilinosWrappers::MPI::Vector product(sparse_part);
  product.add(-evaluation.stiffness * (g * direction), g);

  const double                  h = 1e-5;
  TrilinosWrappers::MPI::Vector u_plus(u), u_minus(u);
  u_plus.add(h, direction);
  u_minus.add(-h, direction);
  TrilinosWrappers::MPI::Vector difference = pressure_force(body, u_plus, true);
  difference -= pressure_force(body, u_minus, true);
  difference /= 2. * h;
  body.get_constraints().set_zero(difference);
  body.get_constraints().set_zero(product);
  body.get_constraints().set_zero(sparse_part);

  // dp/dV = -gamma P / V, and s = -(dp/dV) / f.
  const double P = 101.325 + evaluation.pressure;
  EXPECT_NEAR(evaluation.stiffness,
              1.4 * P / evaluation.volume / 0.125,
              1e-12 * evaluation.stiffness);
  const double error         = relative_difference(product, difference);
  const double without_error = relative_difference(sparse_part, difference);
  std::cout << "p = " << evaluation.pressure
            << " kPa, V = " << evaluation.volume
            << " mm^3, s = " << evaluation.stiffness
            << "; relative difference from the central difference " << error
            << ", without the rank-one term " << without_error << std::endl;
  EXPECT_LT(error, 1e-7);
  EXPECT_GT(without_error, 1e-2);
}



// @sect4{Sherman-Morrison against the full matrix}
//
// The tangent of a clamped box (symmetric positive definite on the free
// dofs) plus $c\,\mathbf g\mathbf g^T$ with a random $\mathbf g$:
// RankOneCorrection on the direct solver's factorization against LAPACK's
// solve of the assembled dense matrix. Both are backward stable; their
// difference is the condition number times round-off, about $10^{-12}$ for
// these matrices, and c is chosen so that the rank-one term changes the
// solution at order one.
template <typename T>
class RankOneCorrectionTest : public ::testing::Test
{
};
TYPED_TEST_SUITE(RankOneCorrectionTest, Dimensions);

TYPED_TEST(RankOneCorrectionTest, ShermanMorrisonEqualsTheDirectSolve)
{
  constexpr int      dim = TypeParam::value;
  std::ostringstream sections;
  sections << clamped_bar_sections(dim, 10., 1e-6, 6., 0.)
           << "  set Gravity = 0, 0, 0"
           << "\nend\nsubsection Linear solver\n  set Solver = Direct\nend\n";
  const Parameters::AllParameters parameters =
    read(parameter_text(dim, sections.str()));
  Simulation<dim> body(parameters, MPI_COMM_WORLD);
  body.make_grid();
  body.setup_system();
  const TrilinosWrappers::SparseMatrix &K =
    body.tangent_stiffness_matrix(body.displacement());
  const TrilinosWrappers::MPI::Vector g   = random_vector(body, 1., 5);
  const TrilinosWrappers::MPI::Vector rhs = random_vector(body, 1., 6);
  const double c = K.frobenius_norm() / (g * g); // order one against K

  TimerOutput  timer(MPI_COMM_WORLD,
                    std::cout,
                    TimerOutput::never,
                    TimerOutput::wall_times);
  LinearSolver solver(parameters, 2, MPI_COMM_WORLD, timer);
  solver.prepare(K);
  RankOneCorrection rank_one;
  rank_one.set(g, c);
  rank_one.prepare(solver);
  TrilinosWrappers::MPI::Vector x(rhs), y(rhs);
  rank_one.solve(solver, rhs, x);
  solver.solve(rhs, y);

  const unsigned int       n = rhs.size();
  LAPACKFullMatrix<double> dense(n, n);
  for (unsigned int i = 0; i < n; ++i)
    for (unsigned int j = 0; j < n; ++j)
      dense(i, j) = K.el(i, j) + c * g[i] * g[j];
  Vector<double> dense_x(n);
  for (unsigned int i = 0; i < n; ++i)
    dense_x[i] = rhs[i];
  dense.compute_lu_factorization();
  dense.solve(dense_x);
  TrilinosWrappers::MPI::Vector reference(rhs);
  for (unsigned int i = 0; i < n; ++i)
    reference[i] = dense_x[i];
  reference.compress(VectorOperation::insert);

  const double error  = relative_difference(x, reference);
  const double change = relative_difference(y, reference);
  std::cout << dim << "D: " << n << " dofs, Sherman-Morrison against LAPACK "
            << error << "; the rank-one term changes the solution by " << change
            << std::endl;
  EXPECT_LT(error, 1e-10);
  EXPECT_GT(change, 1e-2);
}



// @sect4{The cavity volume of the bellows}
//
// The quarter and the half model of the coarse bellows mesh, clamped at the
// base, on their symmetry planes: the cavity (boundary 2) closed by the
// program (along x from the base plane x = -15.25), its volume of the
// whole body (the meshed part over the Model fraction)
// - against the sum over the flat cavity triangles of $-(\bar x_T -
//   x_\text{base})\,n_x A_T$ computed here from the mesh's vertices, which
//   is the exact volume of the same polyhedron: to round-off;
// - against the revolved volume of the section's cavity, 15,176.3 mm^3
//   (tests/bellows_meshes.cc; meshes/check_geometry.py computes it from
//   shared/paper/actuator_section.csv). The flat triangles lie inside the
//   curved cavity wall, so the discrete cavity is smaller, by at most the
//   sum of $A_T n_r r_\text{max}(1 - \cos(\Delta\theta_T/2))$ (the bound
//   of tests/bellows_meshes.cc), and by no more than the CSV's rounding
//   (1e-4) larger.
namespace
{
  // The two sums over the cavity triangles: their polyhedron's volume and
  // the bound on how much the curved wall encloses more.
  std::pair<double, double>
  cavity_facets(const Triangulation<3> &triangulation, const double x_base)
  {
    double volume = 0., bound = 0.;
    for (const auto &cell : triangulation.active_cell_iterators())
      for (const unsigned int f : cell->face_indices())
        if (cell->face(f)->at_boundary() && cell->face(f)->boundary_id() == 2)
          {
            const auto     face = cell->face(f);
            const Point<3> a = face->vertex(0), b = face->vertex(1),
                           c         = face->vertex(2);
            Tensor<1, 3> area_vector = 0.5 * cross_product_3d(b - a, c - a);
            // the body's outer normal: away from the cell's centre
            if (area_vector * (face->center() - cell->center()) < 0.)
              area_vector *= -1.;
            volume -= (face->center()[0] - x_base) * area_vector[0];

            double r_min = 1e300, r_max = 0., x_min = 1e300, x_max = -1e300,
                   spread = 0.;
            for (const Point<3> &v : {a, b, c})
              {
                const double r = std::hypot(v[1], v[2]);
                r_min = std::min(r_min, r), r_max = std::max(r_max, r);
                x_min = std::min(x_min, v[0]), x_max = std::max(x_max, v[0]);
                for (const Point<3> &w : {a, b, c})
                  spread =
                    std::max(spread,
                             std::abs(std::remainder(std::atan2(v[2], v[1]) -
                                                       std::atan2(w[2], w[1]),
                                                     2 * numbers::PI)));
              }
            if (x_max - x_min > 1e-9)
              bound += area_vector.norm() * (x_max - x_min) /
                       std::hypot(x_max - x_min, r_max - r_min) * r_max *
                       (1. - std::cos(spread / 2.));
          }
    return {volume, bound};
  }

  std::string
  bellows_cavity(const std::string &mesh_file, const double fraction)
  {
    std::ostringstream text;
    text << "subsection Geometry\n  set Mesh source = file\n"
         << "  set Mesh file = " << mesh_file
         << "\n  set Model fraction = " << fraction << "\nend\n"
         << "subsection Material 1\n  set Name = silicone\n"
            "  set Shear modulus = 100\n  set Bulk modulus = 10000\n"
            "  set Density = 1e-6\nend\n"
            "subsection Material 2\n  set Name = block\n"
            "  set Shear modulus = 1e5\n  set Bulk modulus = 1e7\n"
            "  set Density = 1e-6\nend\n"
         << "subsection Loads and constraints\n  set Fixed components = 1: xyz"
         << (fraction < 1. ? ", 4: z" : "") << (fraction < 0.5 ? ", 3: y" : "")
         << "\nend\n"
         << "subsection Linear solver\n  set Solver = Direct\nend\n"
         << "subsection Pneumatics\n  set Pressure boundary ids = 2\n"
            "  set Pressure model = gas\nend\n";
    return parameter_text(3, text.str());
  }
} // namespace

TEST(CavityVolume, BellowsMeshAgainstTheRevolvedSection)
{
  const double      reference = 15176.3, round_off = 1e-4, x_base = -15.25;
  const char       *source = std::getenv("SOFT_ROBOT_SOURCE_DIR");
  const std::string root   = (source != nullptr) ? source : "..";
  for (const auto &[model, fraction] :
       std::vector<std::pair<std::string, double>>{{"quarter", 0.25},
                                                   {"half", 0.5}})
    {
      const std::string mesh_file =
        root + "/meshes/bellows_" + model + "_coarse.msh";
      const Parameters::AllParameters parameters =
        read(bellows_cavity(mesh_file, fraction));
      Simulation<3> body(parameters, MPI_COMM_WORLD);
      body.make_grid();
      body.setup_system();
      TrilinosWrappers::MPI::Vector g(body.displacement());
      const double                  volume = body.get_pneumatics()
                              .evaluate_at_pressure(body.displacement(), 0., g)
                              .volume;
      Triangulation<3> triangulation;
      {
        GridIn<3>     grid_in(triangulation);
        std::ifstream input(mesh_file);
        grid_in.read_msh(input);
      }
      const auto [facets, facet_bound] = cavity_facets(triangulation, x_base);
      const double polyhedron          = facets / fraction,
                   bound               = facet_bound / fraction;
      std::cout << model << ": cavity volume " << volume
                << " mm^3, the polyhedron's " << polyhedron << " (relative "
                << volume / polyhedron - 1. << "); "
                << 100. * (volume / reference - 1.)
                << " % from the revolved section, bound -"
                << 100. * bound / reference << " %; closed by "
                << body.get_pneumatics().closure().closing_planes << std::endl;
      EXPECT_NEAR(volume / polyhedron, 1., 1e-12);
      EXPECT_LE(volume, reference * (1. + round_off));
      EXPECT_GE(volume, reference * (1. - round_off) - bound);
      EXPECT_EQ(body.get_pneumatics().closure().axis, 0u);
      EXPECT_DOUBLE_EQ(body.get_pneumatics().closure().origin, x_base);
    }
}



// @sect4{The volume of a deformed spherical cavity}
//
// The cavity of the octant shell, under the linear map u = A X: the
// discrete cavity is mapped by the same affine map (P2 reproduces it
// exactly), so its volume is $\det(\mathbf I + \mathbf A)$ times that of
// the undeformed one, to round-off, the ellipsoid's closed form. The
// undeformed volume itself approaches $4\pi R^3/3$ from below, by at most
// the inner surface's area times the sagitta of its faces' largest chord,
// $3(1-\cos(\theta/2))$ relative.
TEST(CavityVolume, DeformedSphereIsTheEllipsoid)
{
  const double R = 10.;
  for (const unsigned int refinements : {0u, 1u})
    {
      const Parameters::AllParameters parameters = read(octant_shell(
        R, 15., 2, refinements, 10., 1000., "  set Pressure = 1\n"));
      Simulation<3>                   body(parameters, MPI_COMM_WORLD);
      body.make_grid();
      body.setup_system();
      PneumaticLoad<3>             &pneumatics = body.get_pneumatics();
      TrilinosWrappers::MPI::Vector g(body.displacement());
      const double                  V0 =
        pneumatics.evaluate_at_pressure(body.displacement(), 0., g).volume;
      // A diagonal map keeps the symmetry planes in place (a shear would
      // move points off them, which the constraints forbid).
      Tensor<2, 3> A;
      A[0][0] = 0.3, A[1][1] = -0.2, A[2][2] = 0.1;
      const double V =
        pneumatics.evaluate_at_pressure(linear_map(body, A), 0., g).volume;
      const double exact_ratio = 1.3 * 0.8 * 1.1;
      const double sphere      = 4. / 3. * numbers::PI * R * R * R;
      // The faces' vertices lie on the sphere; a face whose vertices are at
      // most the angle theta apart lies between the sphere and the plane
      // at R cos(theta) from the centre, so the cavity misses at most its
      // area times R (1 - cos theta).
      double deficit = 0.;
      for (const auto &cell :
           body.get_dof_handler().get_triangulation().active_cell_iterators())
        for (const auto &face : cell->face_iterators())
          if (face->at_boundary() && face->boundary_id() == 0)
            {
              double cos_theta = 1.;
              for (const unsigned int i : face->vertex_indices())
                for (const unsigned int j : face->vertex_indices())
                  cos_theta =
                    std::min(cos_theta,
                             face->vertex(i) * face->vertex(j) / (R * R));
              deficit += face->measure() * R * (1. - cos_theta);
            }
      const double bound = deficit / (0.125 * sphere);
      std::cout << "refinements " << refinements << ": V0 = " << V0 << " mm^3 ("
                << 100. * (V0 / sphere - 1.) << " % from the sphere, bound -"
                << 100. * bound << " %), V/V0 = " << V / V0 << " (exact "
                << exact_ratio << ")" << std::endl;
      EXPECT_NEAR(V / V0, exact_ratio, 1e-12);
      EXPECT_LE(V0, sphere * (1. + 1e-12));
      EXPECT_GE(V0, sphere * (1. - bound));
    }
}



// @sect4{Inflation of a thick-walled neo-Hookean sphere}
//
// The eighth of a hollow sphere, inner radius A = 10 mm, outer B = 15 mm,
// under a prescribed inner pressure p. For the incompressible neo-Hookean
// solid (shear modulus $\mu$) the radial equilibrium $d\sigma_r/dr +
// 2(\sigma_r - \sigma_\theta)/r = 0$ with $\sigma_\theta - \sigma_r =
// \mu(\lambda^2 - \lambda^{-4})$, $\lambda = r/R$, $r^3 - R^3 = a^3 -
// A^3$, integrates to (Ogden, Non-linear elastic deformations, sec. 5.3)
// @f[
//   \frac{p}{\mu} = \frac{1}{2\lambda_b^4} + \frac{2}{\lambda_b}
//   - \frac{1}{2\lambda_a^4} - \frac{2}{\lambda_a},\qquad
//   \lambda_b^3 = 1 + (\lambda_a^3 - 1)\,\frac{A^3}{B^3} .
// @f]
// The inner stretch is measured by the cavity's volume, $\lambda_a^3 =
// V/V_0$ (both of the discrete cavity). The body is compressible with bulk
// modulus $\kappa$: its volume strain is of order $p/\kappa$, which
// changes $\lambda_a$ and so the closed-form p by a relative $O(p/\kappa)$.
// The rest is the mesh's error: the faceted surfaces (the mapping is
// linear) and the displacement's error, both $O(h^2)$ in a volume, so the
// error must fall by about 4 a refinement (asserted: by more than 3) until
// it reaches the compressibility floor.
namespace
{
  // The relative error of the closed-form pressure at the computed stretch,
  // per refinement.
  std::vector<double>
  sphere_inflation_errors(const unsigned int               degree,
                          const std::string               &formulation,
                          const double                     kappa_over_mu,
                          const std::vector<unsigned int> &refinements)
  {
    const double        A = 10., B = 15., mu = 10., p = 3.5;
    std::vector<double> errors;
    for (const unsigned int refinement : refinements)
      {
        std::ostringstream pneumatics;
        pneumatics << "  set Pressure = " << p << "\n";
        Parameters::AllParameters parameters =
          read(octant_shell(A,
                            B,
                            degree,
                            refinement,
                            mu,
                            kappa_over_mu * mu,
                            pneumatics.str(),
                            formulation));
        Simulation<3> body(parameters, MPI_COMM_WORLD);
        body.make_grid();
        body.setup_system();
        TrilinosWrappers::MPI::Vector g(body.displacement());
        const double                  V0 = body.get_pneumatics()
                            .evaluate_at_pressure(body.displacement(), p, g)
                            .volume;
        body.solve_static_equilibrium(0.);
        const double V = body.get_pneumatics()
                           .evaluate_at_pressure(body.displacement(), p, g)
                           .volume;
        const double lambda_a = std::cbrt(V / V0);
        const double lambda_b =
          std::cbrt(1. + (std::pow(lambda_a, 3) - 1.) * std::pow(A / B, 3));
        const double closed_form =
          mu * (0.5 / std::pow(lambda_b, 4) + 2. / lambda_b -
                0.5 / std::pow(lambda_a, 4) - 2. / lambda_a);
        errors.push_back(std::abs(closed_form / p - 1.));
        std::cout << "P" << degree << " " << formulation << ", kappa/mu "
                  << kappa_over_mu << ", refinements " << refinement << ", "
                  << body.get_dof_handler().n_dofs() << " dofs: lambda_a "
                  << lambda_a << ", lambda_b " << lambda_b
                  << ", closed-form pressure " << closed_form
                  << " kPa for the applied " << p << " kPa (relative error "
                  << errors.back() << ")" << std::endl;
      }
    return errors;
  }
} // namespace

// Quadratic hexahedra in the displacement formulation, kappa = 1000 mu, on
// 3 and 24 cells.
TEST(Inflation, ThickWalledNeoHookeanSphere)
{
  const std::vector<double> errors =
    sphere_inflation_errors(2, "displacement", 1000., {0u, 1u});
  EXPECT_GT(errors[0] / errors[1], 3.);
  EXPECT_LT(errors[1], 2e-2);
}

// Linear hexahedra lock in the displacement formulation (on these meshes
// the error is 97 % to 72 % at kappa = 1000 mu, and above 96 % at 1e4 mu);
// with the mean dilatation (constant pressure per cell, Q1-P0) they do
// not. Here with kappa = 1e4 mu, so that the compressibility floor, p/kappa
// = 3.5e-5, lies below the error of the finest of the three meshes.
TEST(Inflation, ThickWalledNeoHookeanSphereLinearElements)
{
  const std::vector<double> errors =
    sphere_inflation_errors(1, "mean dilatation", 1e4, {0u, 1u, 2u});
  for (unsigned int k = 0; k + 1 < errors.size(); ++k)
    EXPECT_GT(errors[k] / errors[k + 1], 3.) << "refinement " << k;
  EXPECT_LT(errors.back(), 2e-2);
}



// @sect4{A gas cavity in time: independent of the time step, and its work}
//
// The reduced models' bellows: a bar clamped at x = 0 whose end carries the
// cavity's pressure through the Equivalent area, with a gas of 200 mm^3
// (the Dead volume) fed by a smooth mass-inflow pulse. The gas law is a
// function of the state, so runs with dt, dt/2 and dt/4 must give the
// same pressure history up to the integrator's error, which for HHT with
// its standard second-order parameters falls by 4 when dt is halved
// (asserted: by more than 3; a pressure updated from the last step's
// volume change, as in SOFA, is first order and falls by 2).
namespace
{
  std::string
  gas_bar(const unsigned int dim,
          const double       dt,
          const double       alpha,
          const std::string &gas,
          const std::string &initial)
  {
    const double       mu = 10., rho = 1e-6, L = 10.;
    std::ostringstream sections;
    sections << clamped_bar_sections(dim, mu, rho, L, 0.)
             << "  set Gravity = 0, 0, 0"
             << "\nend\n"
             << "subsection Pneumatics\n  set Pressure boundary ids = 1\n"
                "  set Pressure model = gas\n  set Equivalent area = 2\n"
                "  set Dead volume = 200\n"
             << gas << "end\n"
             << "subsection Initial conditions\n"
             << initial << "end\n"
             << "subsection Time integration\n  set Alpha = " << alpha
             << "\n  set Time step = " << dt << "\n  set End time = 1e-2\nend\n"
             << "subsection Nonlinear solver\n  set Absolute tolerance = 0\n"
                "  set Relative tolerance = 1e-12\nend\n"
             << "subsection Linear solver\n  set Solver = Direct\nend\n";
    return parameter_text(dim, sections.str());
  }
} // namespace

template <typename T>
class GasCavityInTimeTest : public ::testing::Test
{
};
using ReducedDimensions = ::testing::Types<std::integral_constant<int, 1>,
                                           std::integral_constant<int, 2>>;
TYPED_TEST_SUITE(GasCavityInTimeTest, ReducedDimensions);

TYPED_TEST(GasCavityInTimeTest, PressureHistoryIndependentOfTimeStep)
{
  constexpr int dim = TypeParam::value;
  // m0 = P V / (R T) of the 200 mm^3 at 101.325 kPa and 293.15 K; 2 % of
  // it flows in during the first 4 ms.
  const double       m0      = 101.325 * 200. / (287.05e6 * 293.15);
  const double       t_pulse = 4e-3, rate = 2. * 0.02 * m0 / t_pulse;
  std::ostringstream gas;
  gas << "  set Gas law exponent = 1.4\n  set Mass inflow rate = t < "
      << t_pulse << " ? " << rate << " * sin(3.14159265358979 * t / " << t_pulse
      << ")^2 : 0\n";
  const double                     dt0 = 2e-4;
  std::vector<std::vector<double>> histories;
  for (const unsigned int division : {1u, 2u, 4u})
    {
      const Parameters::AllParameters parameters =
        read(gas_bar(dim, dt0 / division, -0.1, gas.str(), ""));
      Simulation<dim> body(parameters, MPI_COMM_WORLD);
      body.make_grid();
      body.setup_system();
      body.initialize_state();
      std::vector<double> history;
      unsigned int        step = 0;
      while (body.advance_one_step())
        if (++step % division == 0)
          history.push_back(body.pressure());
      histories.push_back(history);
    }
  double largest = 0., e1 = 0., e2 = 0.;
  ASSERT_EQ(histories[0].size(), histories[2].size());
  for (unsigned int k = 0; k < histories[0].size(); ++k)
    {
      largest = std::max(largest, std::abs(histories[2][k]));
      e1      = std::max(e1, std::abs(histories[0][k] - histories[1][k]));
      e2      = std::max(e2, std::abs(histories[1][k] - histories[2][k]));
    }
  std::cout << dim << "D: largest pressure " << largest
            << " kPa; largest difference dt against dt/2 " << e1
            << ", dt/2 against dt/4 " << e2 << " (ratio " << e1 / e2 << ")"
            << std::endl;
  EXPECT_GT(largest, 1.);
  EXPECT_GT(e1 / e2, 3.);
  EXPECT_LT(e2, 1e-2 * largest);
}

// The energy balance with the pressure work: a gas sealed at 5 kPa above
// ambient in the static equilibrium, the bar then set moving. With the
// trapezoidal rule (alpha = 0) the balance $\mathcal B = T + \Pi - W_p -
// (T + \Pi)_0$ vanishes to the scheme's second-order error, and the
// booked pressure work is, to the same order, the work of the isothermal
// gas, $W_p = P_0V_0\ln(V/V_0) - P_a(V - V_0)$. Without the pressure work
// in it, the balance would be of the size of that work.
TYPED_TEST(GasCavityInTimeTest, EnergyBalanceClosesWithPressureWork)
{
  constexpr int      dim = TypeParam::value;
  const double       c   = std::sqrt(3. * 10. / 1e-6);
  std::ostringstream initial;
  initial << "  set Type = static equilibrium\n  set Velocity = " << 0.05 * c
          << " * x / 10"
          << (dim == 1   ? ""
              : dim == 2 ? "; 0"
                         : "; 0; 0")
          << "\n";
  std::vector<double> balances, work_errors;
  double              largest_work = 0.;
  for (const double dt : {2e-4, 1e-4})
    {
      const Parameters::AllParameters parameters = read(
        gas_bar(dim, dt, 0., "  set Initial pressure = 5\n", initial.str()));
      Simulation<dim> body(parameters, MPI_COMM_WORLD);
      body.make_grid();
      body.setup_system();
      body.initialize_state();
      const EnergyAccount &energy = body.energies();
      const double         initial_total =
        energy.kinetic + energy.strain + energy.gravity_potential;
      const double P0 = 101.325 + body.pressure(), V0 = body.gas_volume();
      double       balance = 0., work_error = 0., largest_energy = 0.;
      largest_work = 0.;
      while (body.advance_one_step())
        {
          const double V = body.gas_volume();
          const double exact_work =
            P0 * V0 * std::log(V / V0) - 101.325 * (V - V0);
          balance = std::max(balance, std::abs(energy.balance(initial_total)));
          work_error =
            std::max(work_error, std::abs(energy.pressure_work - exact_work));
          largest_work = std::max(largest_work, std::abs(exact_work));
          largest_energy =
            std::max(largest_energy, energy.kinetic + energy.strain);
        }
      balances.push_back(balance / largest_energy);
      work_errors.push_back(work_error / largest_work);
      std::cout << dim << "D, dt = " << dt << ": largest pressure work "
                << largest_work << ", largest energy " << largest_energy
                << "; largest |balance| relative " << balances.back()
                << ", pressure work against the gas's relative "
                << work_errors.back() << std::endl;
      EXPECT_GT(largest_work, 0.05 * largest_energy);
    }
  EXPECT_LT(balances[1], 1e-3);
  EXPECT_GT(balances[0] / balances[1], 3.);
  EXPECT_LT(work_errors[1], 1e-3);
  EXPECT_GT(work_errors[0] / work_errors[1], 3.);
}



// @sect4{A mass on a gas spring}
//
// A stiff tip block (1 mm, 0.1 g) on a very soft bar (10 mm, shear modulus
// 1e-3 kPa), its end loaded by a closed gas cavity through the Equivalent
// area A = 1 mm^2 (dead volume V = 100 mm^3 at ambient pressure, gamma =
// 1.4): set moving with a small velocity, the block oscillates on the gas
// spring $k = \gamma P A^2/V$ (plus the bar's $3\mu A/L$) at $\omega =
// \sqrt{k/m}$. The trapezoidal rule with 100 steps a period changes the
// period of a single oscillator by $(\omega\Delta t)^2/12 = 3.3\cdot
// 10^{-4}$; the bar's mass (1e-4 of the block's), its own slow motion and
// the amplitude (1e-4 of V/A) are smaller effects. Tolerance 1e-3; a gas
// stiffness off by the model fraction, the exponent or the rank-one term
// misses it by far. (Only in 1D: in 2D and 3D the same model needs a
// meshed piston; the 2D strip's end load is checked by the time-step
// test.)
TEST(GasSpring, MassOscillatesAtTheGasStiffnessFrequency)
{
  const double gamma = 1.4, P = 101.325, A = 1., V = 100., m = 1e-4;
  const double k     = gamma * P * A * A / V + 3. * 1e-3 * A / 10.;
  const double omega = std::sqrt(k / m), period = 2. * numbers::PI / omega;
  std::ostringstream sections;
  sections << "subsection Geometry\n"
              "  set Generator = subdivided_hyper_rectangle\n"
              "  set Generator arguments = 11: 0: 11: true\n"
              "  set Material id function = x > 10 ? 2 : 1\nend\n"
           << "subsection Finite element\n  set Polynomial degree = 1\nend\n"
           << "subsection Material 1\n  set Name = soft bar\n"
              "  set Shear modulus = 1e-3\n  set Density = 1e-9\nend\n"
           << "subsection Material 2\n  set Name = block\n"
              "  set Shear modulus = 1e4\n  set Density = "
           << m << "\nend\n"
           << "subsection Loads and constraints\n  set Gravity = 0, 0, 0\n"
              "  set Fixed components = 0: x\nend\n"
           << "subsection Pneumatics\n  set Pressure boundary ids = 1\n"
              "  set Pressure model = gas\n  set Equivalent area = "
           << A << "\n  set Dead volume = " << V
           << "\n  set Gas law exponent = " << gamma << "\nend\n"
           << "subsection Initial conditions\n  set Velocity = " << 0.01 * omega
           << " * x / 11\nend\n"
           << "subsection Time integration\n  set Alpha = 0\n"
              "  set Time step = "
           << period / 100. << "\n  set End time = " << 3.2 * period
           << "\nend\n"
           << "subsection Nonlinear solver\n  set Absolute tolerance = 0\n"
              "  set Relative tolerance = 1e-12\nend\n"
           << "subsection Linear solver\n  set Solver = Direct\nend\n";
  const Parameters::AllParameters parameters =
    read(parameter_text(1, sections.str()));
  Simulation<1> body(parameters, MPI_COMM_WORLD);
  body.make_grid();
  body.setup_system();
  body.initialize_state();
  // the times at which the tip velocity crosses zero downwards
  std::vector<double> crossings;
  double              t_old = 0., v_old = body.tip_motion().second[0];
  double              largest_pressure = 0.;
  while (body.advance_one_step())
    {
      const double v = body.tip_motion().second[0];
      if (v_old > 0. && v <= 0.)
        crossings.push_back(t_old +
                            (body.time() - t_old) * v_old / (v_old - v));
      t_old            = body.time();
      v_old            = v;
      largest_pressure = std::max(largest_pressure, std::abs(body.pressure()));
    }
  ASSERT_GE(crossings.size(), 3u);
  const double measured =
    (crossings.back() - crossings.front()) / (crossings.size() - 1.);
  std::cout << "gas stiffness " << gamma * P * A * A / V << " mN/mm, period "
            << measured << " s against " << period << " (relative "
            << measured / period - 1. << "); largest gauge pressure "
            << largest_pressure << " kPa" << std::endl;
  EXPECT_GT(largest_pressure, 1e-3);
  EXPECT_NEAR(measured / period, 1., 1e-3);
}
