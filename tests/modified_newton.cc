// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Tests of the accelerated modified Newton method}
//
// The time steps' modified Newton method keeps one matrix per step and
// speeds up its iterations in two ways (see NewtonSolver and
// SoftRobotDynamics::prepare_step_tangent): the matrix is built from the stiffness
// extrapolated from the last two converged states, and Anderson
// acceleration combines the last iterates. Neither changes the residual,
// so all variants must converge to the same motion as Newton's method
// proper, to the tolerance, and the accelerated one must need fewer
// iterations than the plain one. The body is a clamped bar set swinging
// (or, in 1D, stretching) by an initial velocity large enough for strains
// of about 20 %, with stiffness-proportional damping, so that its tangent
// changes from step to step as it does in the bellows.

#include "solver_test_tools.h"

#include <cmath>
#include <core/soft_robot_dynamics.h>
#include <deal.II/base/function.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/mapping_q1.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/numerics/vector_tools.h>
#include <gtest/gtest.h>
#include <solvers/rotated_tangent.h>

using namespace dealii;
using namespace SoftRobot;
using namespace SoftRobot::Testing;

template <typename T>
class ModifiedNewtonTest : public ::testing::Test
{
};
TYPED_TEST_SUITE(ModifiedNewtonTest, Dimensions);

namespace
{
  struct Run
  {
    std::vector<std::vector<double>> tip;
    unsigned int                     newton_iterations = 0;
    unsigned int                     factorizations    = 0;
    unsigned int                     linear_iterations = 0;
    std::string                      linear_solver;
    double                           operator_complexity = 0.;
  };

  // The tip displacement after every step, for the given entries of the
  // subsections "Nonlinear solver" and "Linear solver"; `more_sections`
  // may replace earlier entries.
  template <int dim>
  Run
  swing(const std::string &nonlinear_solver,
        const std::string &linear_solver          = "  set Solver = Direct\n"
                                                    "  set Direct solver = KLU\n",
        const double       end_time_in_wave_times = 8.,
        const std::string &more_sections          = "")
  {
    const double mu = 10., rho = 1e-6, L = 10., c = std::sqrt(3. * mu / rho);
    const std::string velocity[3] = {dim == 1 ? "0.4*c*x/L" : "0.15*c*x/L",
                                     "0.3*c*(x/L)^2",
                                     "-0.2*c*(x/L)^2"};
    std::ostringstream sections;
    sections << clamped_bar_sections(dim, mu, rho, L, 2e-3 * L / c)
             << "  set Function constants = c=" << c << ", L=" << L << "\nend\n"
             << "subsection Initial conditions\n  set Velocity = ";
    for (unsigned int d = 0; d < dim; ++d)
      sections << (d > 0 ? "; " : "") << velocity[d];
    sections << "\nend\n"
             << "subsection Time integration\n  set Alpha = -0.1\n"
             << "  set Time step = " << 0.1 * L / c
             << "\n  set End time = " << end_time_in_wave_times * L / c
             << "\nend\n"
             << "subsection Nonlinear solver\n  set Absolute tolerance = 0\n"
                "  set Relative tolerance = 1e-11\n"
             << nonlinear_solver << "end\n"
             << "subsection Linear solver\n"
             << linear_solver << "end\n"
             << more_sections;
    Parameters::AllParameters parameters;
    parameters.read_string(parameter_text(dim, sections.str()));
    Simulation<dim> body(parameters, MPI_COMM_WORLD);
    body.make_grid();
    body.setup_system();
    body.initialize_state();
    Run run;
    while (body.advance_one_step())
      {
        const Tensor<1, dim> u = body.tip_motion().first;
        run.tip.emplace_back(u.begin_raw(), u.end_raw());
      }
    run.newton_iterations   = body.n_newton_iterations();
    run.factorizations      = body.n_tangent_updates();
    run.linear_iterations   = body.n_linear_iterations();
    run.linear_solver       = body.linear_solver_in_use();
    run.operator_complexity = body.multigrid_operator_complexity();
    return run;
  }

  // The largest difference between two tip histories, relative to the
  // largest tip displacement.
  double
  difference(const Run &a, const Run &b)
  {
    EXPECT_EQ(a.tip.size(), b.tip.size());
    double largest = 0., scale = 0.;
    for (unsigned int n = 0; n < std::min(a.tip.size(), b.tip.size()); ++n)
      for (unsigned int d = 0; d < a.tip[n].size(); ++d)
        {
          largest = std::max(largest, std::abs(a.tip[n][d] - b.tip[n][d]));
          scale   = std::max(scale, std::abs(a.tip[n][d]));
        }
    return largest / scale;
  }
} // namespace

TYPED_TEST(ModifiedNewtonTest, AccelerationKeepsTheMotionAndSavesIterations)
{
  constexpr int dim   = TypeParam::value;
  const Run     full  = swing<dim>("  set Tangent update = every iteration\n");
  const Run     plain = swing<dim>("  set Tangent update = every step\n"
                                   "  set Acceleration depth = 0\n"
                                   "  set Tangent extrapolation = false\n");
  const Run     extrapolated = swing<dim>("  set Tangent update = every step\n"
                                          "  set Acceleration depth = 0\n"
                                          "  set Tangent extrapolation = true\n");
  const Run     accelerated  = swing<dim>("  set Tangent update = every step\n"
                                          "  set Acceleration depth = 2\n"
                                          "  set Tangent extrapolation = true\n");
  double        largest_tip  = 0.;
  for (const auto &u : full.tip)
    for (const double value : u)
      largest_tip = std::max(largest_tip, std::abs(value));
  std::cout << dim << "D: largest tip displacement " << largest_tip
            << " mm; Newton iterations (factorizations): every iteration "
            << full.newton_iterations << " (" << full.factorizations
            << "), plain modified " << plain.newton_iterations << " ("
            << plain.factorizations << "), extrapolated "
            << extrapolated.newton_iterations << " ("
            << extrapolated.factorizations << "), extrapolated and "
            << "accelerated " << accelerated.newton_iterations << " ("
            << accelerated.factorizations << ")" << std::endl;
  std::cout << "  differences to Newton's method proper: plain "
            << difference(full, plain) << ", extrapolated "
            << difference(full, extrapolated) << ", accelerated "
            << difference(full, accelerated) << std::endl;

  // The motion is large: the tip moves by a fifth of the bar's length or
  // more. The iterations stop at a residual of 1e-11 of the forces, and
  // the motions agree to about that.
  EXPECT_GT(largest_tip, 2.);
  EXPECT_LT(difference(full, plain), 1e-9);
  EXPECT_LT(difference(full, extrapolated), 1e-9);
  EXPECT_LT(difference(full, accelerated), 1e-9);
  // The accelerated variant needs fewer iterations and no more
  // factorizations than the plain one. (Extrapolation alone saves
  // iterations in 1D and 2D, factorizations in 3D; it is not checked
  // separately.)
  EXPECT_LT(accelerated.newton_iterations, plain.newton_iterations);
  EXPECT_LE(accelerated.factorizations, plain.factorizations);
}


// With `Tangent update = when needed` the matrix and its factorization
// are kept from step to step, and rebuilt only when the iterations slow
// down; the end of a step then assembles no matrices, only the forces and
// the viscosity of the new state (from the material tangent at the
// points). The residual is the same, so the motion must be that of
// Newton's method proper to the tolerance, with fewer factorizations than
// steps and than the modified method that rebuilds every step. CG with
// multigrid, whose operator is the kept matrix itself, must give the same
// motion too.
TYPED_TEST(ModifiedNewtonTest, KeptMatrixGivesTheMotionWithFewerFactorizations)
{
  constexpr int dim  = TypeParam::value;
  const Run     full = swing<dim>("  set Tangent update = every iteration\n");
  const Run     every_step = swing<dim>("  set Tangent update = every step\n");
  const Run     kept       = swing<dim>("  set Tangent update = when needed\n");
  const Run     kept_cg =
    swing<dim>("  set Tangent update = when needed\n",
               "  set Solver = CG\n  set Relative tolerance = 1e-3\n");
  std::cout << dim << "D: " << kept.tip.size()
            << " steps; factorizations (Newton iterations): every step "
            << every_step.factorizations << " (" << every_step.newton_iterations
            << "), when needed " << kept.factorizations << " ("
            << kept.newton_iterations << "), when needed with CG "
            << kept_cg.factorizations << " (" << kept_cg.newton_iterations
            << "); differences to Newton's method proper "
            << difference(full, kept) << " (direct), "
            << difference(full, kept_cg) << " (CG)" << std::endl;
  EXPECT_LT(difference(full, kept), 1e-9);
  EXPECT_LT(difference(full, kept_cg), 1e-9);
  EXPECT_LT(kept.factorizations, kept.tip.size());
  EXPECT_LT(kept.factorizations, every_step.factorizations);
}


// The two sparse direct solvers factorize the same matrices, so the motion
// must be the same to the tolerance of the Newton iterations.
TYPED_TEST(ModifiedNewtonTest, MumpsGivesTheMotionOfKlu)
{
  constexpr int dim = TypeParam::value;
  const Run     klu =
    swing<dim>("", "  set Solver = Direct\n  set Direct solver = KLU\n", 2.);
  const Run mumps =
    swing<dim>("", "  set Solver = Direct\n  set Direct solver = MUMPS\n", 2.);
  std::cout << dim << "D: KLU " << klu.newton_iterations
            << " Newton iterations (" << klu.factorizations
            << " factorizations), MUMPS " << mumps.newton_iterations << " ("
            << mumps.factorizations << "); difference "
            << difference(klu, mumps) << std::endl;
  EXPECT_GT(klu.tip.size(), 10u);
  EXPECT_LT(difference(klu, mumps), 1e-9);
  // The two runs used the solvers they were given (the class of the solver
  // object Amesos created), so the comparison above is not KLU with itself.
  EXPECT_EQ(klu.linear_solver, "Amesos_Klu");
  EXPECT_EQ(mumps.linear_solver, "Amesos_Mumps");
}


// CG with algebraic multigrid solves the linear systems only to the
// default relative tolerance (1e-2), as the inner iteration of an inexact
// Newton method: the Newton iterations still stop on the true residual, so
// the motion must be that of the direct solver to the Newton tolerance,
// with few more Newton iterations than with nearly exact solves and far
// fewer CG iterations.
//
// Multigrid needs a mesh with more unknowns than ML's coarsest level (2,000)
// to be more than a direct solver: 1,200 cells in 1D, 48 x 6 in 2D and
// 16 x 2 x 2 in 3D (2,401, 2,522 and 2,475 unknowns).
TYPED_TEST(ModifiedNewtonTest, InexactSolvesGiveTheMotionOfExactOnes)
{
  constexpr int      dim  = TypeParam::value;
  const unsigned int n[3] = {1200, 48, 16}, m[3] = {1, 6, 2};
  const std::string mesh = "subsection Geometry\n  set Generator arguments = " +
                           box_arguments(dim, n[dim - 1], m[dim - 1], 10., 2.) +
                           "\nend\n";
  const Run direct = swing<dim>("", "  set Solver = Direct\n", 0.6, mesh);
  const Run inexact =
    swing<dim>("", "  set Solver = CG\n", 0.6, mesh); // the default tolerance
  const Run tight = swing<dim>(
    "", "  set Solver = CG\n  set Relative tolerance = 1e-10\n", 0.6, mesh);
  std::cout << dim << "D: Newton iterations (CG iterations): direct "
            << direct.newton_iterations << ", CG to 1e-2 "
            << inexact.newton_iterations << " (" << inexact.linear_iterations
            << "), CG to 1e-10 " << tight.newton_iterations << " ("
            << tight.linear_iterations << "); differences to the direct "
            << "solver " << difference(direct, inexact) << ", "
            << difference(direct, tight) << std::endl;
  EXPECT_GE(direct.tip.size(), 6u);
  EXPECT_EQ(direct.linear_solver, "Amesos_Klu");
  EXPECT_EQ(inexact.linear_solver, "CG with ML");
  // The hierarchy has a coarse level below the finest, and its matrices
  // together hold fewer nonzeros than three times the finest.
  EXPECT_EQ(direct.operator_complexity, 0.);
  EXPECT_GT(inexact.operator_complexity, 1.);
  EXPECT_LT(inexact.operator_complexity, 3.);
  EXPECT_LT(difference(direct, inexact), 1e-9);
  EXPECT_LT(difference(direct, tight), 1e-9);
  EXPECT_LE(inexact.newton_iterations, 1.25 * tight.newton_iterations);
  EXPECT_LT(2 * inexact.linear_iterations, tight.linear_iterations);
}


// The kept matrix rotated with the body (`Rotated tangent`, see
// RotatedTangent) changes only the linear solves, so the motion must be
// that of the unrotated kept matrix to the tolerance. The swinging bar
// turns by tens of degrees, which the unrotated matrix answers with
// rebuilds: in 2D and 3D the rotated one must need fewer factorizations.
// In 1D there is no rotation, and the option changes nothing.
TYPED_TEST(ModifiedNewtonTest, RotatedKeptMatrixGivesTheMotionWithFewerRebuilds)
{
  constexpr int dim     = TypeParam::value;
  const Run     kept    = swing<dim>("  set Tangent update = when needed\n");
  const Run     rotated = swing<dim>("  set Tangent update = when needed\n"
                                     "  set Rotated tangent = true\n");
  std::cout << dim << "D: " << kept.tip.size()
            << " steps; factorizations (Newton iterations): kept "
            << kept.factorizations << " (" << kept.newton_iterations
            << "), rotated " << rotated.factorizations << " ("
            << rotated.newton_iterations << "); difference "
            << difference(kept, rotated) << std::endl;
  EXPECT_LT(difference(kept, rotated), 1e-9);
  if (dim == 1)
    EXPECT_EQ(rotated.factorizations, kept.factorizations);
  else
    EXPECT_LT(rotated.factorizations, kept.factorizations);
}


// The rotations themselves: for a rigid rotation Q of the whole body from
// the matrix state, every node's rotation is Q, so that a solve returns
// Q times the solve of Q^T rhs, to round-off.
template <typename T>
class RotatedTangentTest : public ::testing::Test
{
};

namespace
{
  // A displacement field given by a function of the point.
  template <int dim>
  class DisplacementField : public Function<dim>
  {
  public:
    explicit DisplacementField(
      const std::function<Tensor<1, dim>(const Point<dim> &)> &field)
      : Function<dim>(dim)
      , field(field)
    {
    }
    double
    value(const Point<dim> &p, const unsigned int component) const override
    {
      return field(p)[component];
    }

  private:
    const std::function<Tensor<1, dim>(const Point<dim> &)> field;
  };
} // namespace
TYPED_TEST_SUITE(RotatedTangentTest, Dimensions2And3);

TYPED_TEST(RotatedTangentTest, RigidRotationIsFoundAtEveryNode)
{
  constexpr int      dim = TypeParam::value;
  Triangulation<dim> triangulation;
  GridGenerator::subdivided_hyper_rectangle(triangulation,
                                            std::vector<unsigned int>(dim, 2),
                                            Point<dim>(),
                                            dim == 2 ? Point<dim>(3., 1.)
                                                     : Point<dim>(3., 1., 2.));
  const FESystem<dim> fe(FE_Q<dim>(2), dim);
  DoFHandler<dim>     dof_handler(triangulation);
  dof_handler.distribute_dofs(fe);
  const MappingQ1<dim> mapping;

  // Q: 40 degrees about the axis (1, 2, 2) / 3 (the z axis in 2D).
  const double   angle = 40. * numbers::PI / 180.;
  Tensor<1, 3>   axis;
  Tensor<2, dim> Q;
  axis[0] = dim == 3 ? 1. / 3. : 0.;
  axis[1] = dim == 3 ? 2. / 3. : 0.;
  axis[2] = dim == 3 ? 2. / 3. : 1.;
  for (unsigned int i = 0; i < dim; ++i)
    for (unsigned int j = 0; j < dim; ++j)
      {
        double cross = 0.;
        for (unsigned int k = 0; k < 3; ++k)
          cross -= (i == j                                   ? 0.
                    : ((i + 1) % 3 == j && (j + 1) % 3 == k) ? 1.
                    : ((j + 1) % 3 == i && (i + 1) % 3 == k) ? -1.
                                                             : 0.) *
                   axis[k];
        Q[i][j] = (i == j ? std::cos(angle) : 0.) +
                  (1. - std::cos(angle)) * axis[i] * axis[j] +
                  std::sin(angle) * cross;
      }
  ASSERT_NEAR(determinant(Q), 1., 1e-14);

  // u0: a stretch; u1: the same, then rotated (x1 = Q x0).
  const auto stretch = [](const Point<dim> &p) {
    Tensor<1, dim> u;
    for (unsigned int d = 0; d < dim; ++d)
      u[d] = (d == 0 ? 0.1 * p[0] : 0.) + 0.05 * p[d] * p[0];
    return u;
  };
  const DisplacementField<dim> stretched(stretch);
  const DisplacementField<dim> rotated(
    [&](const Point<dim> &p) { return Q * (p + stretch(p)) - p; });
  TrilinosWrappers::MPI::Vector u0(dof_handler.locally_owned_dofs(),
                                   MPI_COMM_WORLD);
  TrilinosWrappers::MPI::Vector u1(u0), rhs(u0), x(u0), seen(u0);
  VectorTools::interpolate(mapping, dof_handler, stretched, u0);
  VectorTools::interpolate(mapping, dof_handler, rotated, u1);

  RotatedTangent<dim> rotation(mapping, dof_handler);
  rotation.set_matrix_state(u0);
  rotation.set_iterate(u1);
  for (unsigned int i = 0; i < rhs.size(); ++i)
    rhs[i] = std::sin(1. + i);
  rotation.solve(rhs,
                 x,
                 [&](const TrilinosWrappers::MPI::Vector &b,
                     TrilinosWrappers::MPI::Vector       &solution) {
                   seen     = b;
                   solution = b;
                   return 1u;
                 });
  EXPECT_NEAR(rotation.largest_angle(), angle, 1e-12);
  // The solve saw Q^T rhs at every node, and x = Q Q^T rhs = rhs.
  double largest = 0.;
  for (unsigned int i = 0; i < rhs.size(); ++i)
    largest = std::max(largest, std::abs(x[i] - rhs[i]));
  EXPECT_LT(largest, 1e-13);
  std::vector<Point<dim>> support(dof_handler.n_dofs());
  DoFTools::map_dofs_to_support_points(mapping, dof_handler, support);
  std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
  double                               error = 0.;
  for (const auto &cell : dof_handler.active_cell_iterators())
    {
      cell->get_dof_indices(dofs);
      for (unsigned int k = 0; k < fe.base_element(0).n_dofs_per_cell(); ++k)
        {
          Tensor<1, dim> b, expected;
          for (unsigned int d = 0; d < dim; ++d)
            b[d] = rhs[dofs[fe.component_to_system_index(d, k)]];
          expected = b * Q; // Q^T b
          for (unsigned int d = 0; d < dim; ++d)
            error =
              std::max(error,
                       std::abs(seen[dofs[fe.component_to_system_index(d, k)]] -
                                expected[d]));
        }
    }
  std::cout << dim << "D: largest node rotation " << rotation.largest_angle()
            << " rad (Q: " << angle << " rad); largest error of Q^T rhs "
            << error << ", of x - rhs " << largest << std::endl;
  EXPECT_LT(error, 1e-12);
}
