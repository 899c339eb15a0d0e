// @sect3{Tests of the solver against closed forms}
//
// Each test sets up a small body through the same parameter interface a
// user has, runs a phase of SoftRobotDynamics<dim>, and compares with a
// solution known in closed form. The tolerances follow from the theory
// that is quoted beside each test.

#include "solver_test_tools.h"

#include <cmath>
#include <core/soft_robot_dynamics.h>
#include <deal.II/base/utilities.h>
#include <deal.II/dofs/dof_tools.h>
#include <gtest/gtest.h>
#include <iomanip>

using namespace dealii;
using namespace SoftRobot;
using namespace SoftRobot::Testing;

template <typename T>
class SolverTest : public ::testing::Test
{
};
TYPED_TEST_SUITE(SolverTest, Dimensions);

namespace
{
  Parameters::AllParameters
  read(const std::string &text)
  {
    Parameters::AllParameters parameters;
    parameters.read_string(text);
    return parameters;
  }

  // A material subsection.
  std::string
  material(const unsigned int id,
           const double       mu,
           const double       kappa,
           const double       density,
           const double       section,
           const double       zeta = 0.)
  {
    std::ostringstream text;
    text << "subsection Material " << id << "\n  set Name = m" << id
         << "\n  set Shear modulus = " << mu
         << "\n  set Bulk modulus = " << kappa
         << "\n  set Density = " << density << "\n  set Section = " << section
         << "\n  set Damping coefficient = " << zeta << "\nend\n";
    return text.str();
  }

  // The x-components of the axis letters for 'Fixed components' and
  // 'Traction' in dim dimensions.
  std::string
  dim_list(const unsigned int              dim,
           const std::vector<std::string> &items,
           const char                     *sep)
  {
    std::string out;
    for (unsigned int d = 0; d < dim; ++d)
      out += (d > 0 ? sep : "") + items[d];
    return out;
  }
} // namespace



// @sect4{Static sag of a hanging column with a tip mass}
//
// A column of length $L$, cross-section $A$, density $\rho$ hangs from
// $X = 0$ and carries a block of mass $M$ at its end. At the reference
// position $X$ the nominal stress carries the weight of everything below,
// $P(X) = \left(Mg + \rho A g (L - X)\right)/A$, and the uniaxial
// incompressible neo-Hookean law $P = \mu(\lambda - \lambda^{-2})$ gives
// the stretch $\lambda(X)$ pointwise. The end displacement is $\int_0^{L}
// (\lambda - 1)\,dX$ (plus the block's own, here included the same way).
// Quadratic elements on a mesh of 102 cells resolve this smooth stretch to
// $O(h^4)\approx 10^{-8}$ relative; the stretch at the top is about 1.5,
// well into the nonlinear range.
TEST(StaticSag, HangingColumnMatchesClosedForm)
{
  const double L = 100., ell = 2., A = 100., mu = 10., rho = 1e-6, g = 9810.;
  const double M = 0.1, mu_block = 1e4 * mu, rho_block = M / (A * ell);
  const std::string text = parameter_text(
    1,
    "subsection Geometry\n  set Generator = subdivided_hyper_rectangle\n  set Generator arguments = 102: 0: 102: true\n"
    "  set Material id function = x > 100 ? 2 : 1\nend\n"
    "subsection Finite element\n  set Polynomial degree = 2\nend\n" +
      material(1, mu, 100., rho, A) +
      material(2, mu_block, 100., rho_block, A) +
      "subsection Loads and constraints\n  set Gravity = 9810, 0, 0\n"
      "  set Fixed components = 0: x\nend\n"
      "subsection Initial conditions\n  set Type = static equilibrium\n"
      "  set Load steps = 8\nend\n"
      "subsection Nonlinear solver\n  set Absolute tolerance = 1e-10\n"
      "  set Relative tolerance = 1e-13\nend\n"
      "subsection Linear solver\n  set Solver = Direct\nend\n");
  Simulation<1> column(read(text), MPI_COMM_WORLD);
  column.make_grid();
  column.setup_system();
  column.solve_static_equilibrium(0.);
  const double u_tip = column.tip_motion().first[0];

  // The stretch where the nominal stress is P, by Newton's method on the
  // cubic mu (lambda^3 - 1) = P lambda^2.
  const auto stretch = [](const double P, const double shear_modulus) {
    double lambda = 1.;
    for (unsigned int i = 0; i < 50; ++i)
      lambda -= (shear_modulus * (lambda - 1. / (lambda * lambda)) - P) /
                (shear_modulus * (1. + 2. / (lambda * lambda * lambda)));
    return lambda;
  };
  // Composite 5-point Gauss-Legendre quadrature of lambda - 1.
  const double gauss_x[5] = {-0.9061798459386640,
                             -0.5384693101056831,
                             0.,
                             0.5384693101056831,
                             0.9061798459386640};
  const double gauss_w[5] = {0.2369268850561891,
                             0.4786286704993665,
                             0.5688888888888889,
                             0.4786286704993665,
                             0.2369268850561891};
  // The stretch jumps at X = L, so the column and the block are integrated
  // separately.
  double             exact  = 0.;
  const unsigned int panels = 1000;
  for (unsigned int k = 0; k < 2 * panels; ++k)
    {
      const double start  = (k < panels) ? 0. : L,
                   length = (k < panels) ? L : ell;
      const double a      = start + length * (k % panels) / panels,
                   b      = start + length * (k % panels + 1) / panels;
      for (unsigned int q = 0; q < 5; ++q)
        {
          const double X = 0.5 * (a + b) + 0.5 * (b - a) * gauss_x[q];
          const double weight_below = (X < L)
                                        ? M * g + rho * A * g * (L - X)
                                        : rho_block * A * g * (L + ell - X);
          const double lambda =
            stretch(weight_below / A, X < L ? mu : mu_block);
          exact += 0.5 * (b - a) * gauss_w[q] * (lambda - 1.);
        }
    }
  std::cout << "static sag: FE " << u_tip << " mm, closed form " << exact
            << " mm, relative error " << std::abs(u_tip - exact) / exact
            << std::endl;
  EXPECT_GT(stretch((M * g + rho * A * g * L) / A, mu), 1.4);
  EXPECT_NEAR(u_tip, exact, 1e-7 * exact);
}



// @sect4{Axial vibration of a rod with a tip mass}
//
// A rod (length $L$, Young's modulus $E = 3\mu$ of the uniaxial
// incompressible law, density $\rho$) fixed at $X = 0$ carries a block of
// length $\ell$ at its end. With the block's own modulus $E_2$ and density
// $\rho_2$, the exact first axial mode of the two-segment rod satisfies
// @f[
//   E_1 k_1 \cos(k_1 L)\cos(k_2\ell) = E_2 k_2 \sin(k_1 L)\sin(k_2\ell),
//   \qquad k_i = \omega\sqrt{\rho_i/E_i},
// @f]
// which for a rigid block of mass $M$ becomes the classical
// $\beta\tan\beta = m/M$, $\beta = \omega L/c$, $m = \rho A L$. The
// eigenfrequency of Lagrange elements of degree $p$ converges at the rate
// $h^{2p}$.
namespace
{
  // Smallest root of the two-segment frequency equation, bracketed from
  // below by a scan and refined by bisection.
  double
  two_segment_rod_frequency(const double E1,
                            const double rho1,
                            const double L,
                            const double E2,
                            const double rho2,
                            const double ell)
  {
    const auto f = [&](const double omega) {
      const double k1 = omega * std::sqrt(rho1 / E1),
                   k2 = omega * std::sqrt(rho2 / E2);
      return E1 * k1 * std::cos(k1 * L) * std::cos(k2 * ell) -
             E2 * k2 * std::sin(k1 * L) * std::sin(k2 * ell);
    };
    double low = 1e-6, high = low;
    while (f(high) > 0.)
      {
        low = high;
        high *= 1.01;
        if (high == low)
          high = 1e-3;
      }
    for (unsigned int i = 0; i < 200; ++i)
      {
        const double mid           = 0.5 * (low + high);
        (f(mid) > 0. ? low : high) = mid;
      }
    return 0.5 * (low + high);
  }

  double
  rod_frequency_1d(const unsigned int degree,
                   const unsigned int n_cells,
                   const double       mu,
                   const double       rho,
                   const double       mu_block,
                   const double       rho_block)
  {
    std::ostringstream geometry;
    geometry
      << "subsection Geometry\n  set Generator = subdivided_hyper_rectangle\n  set Generator arguments = "
      << n_cells
      << ": 0: 125: true\n  set Material id function = x > 100 ? 2 : 1\nend\n"
      << "subsection Finite element\n  set Polynomial degree = " << degree
      << "\nend\n";
    const std::string text = parameter_text(
      1,
      geometry.str() + material(1, mu, 100., rho, 100.) +
        material(2, mu_block, 100., rho_block, 100.) +
        "subsection Loads and constraints\n  set Fixed components = 0: x\nend\n");
    Simulation<1> rod(read(text), MPI_COMM_WORLD);
    rod.make_grid();
    rod.setup_system();
    return linearised_frequencies(rod)[0];
  }
} // namespace

TEST(RodWithTipMass, FrequencyConvergesAtRateTwoP)
{
  const double mu = 10., rho = 1e-6, L = 100., ell = 25., A = 100.;
  const double M = 0.01, rho_block = M / (A * ell), mu_block = 1e3 * mu;
  const double exact =
    two_segment_rod_frequency(3 * mu, rho, L, 3 * mu_block, rho_block, ell);

  // The stiff block is nearly rigid: the exact frequency is within
  // ell E_1 / (L E_2) ~ 3e-4 of the rigid-mass formula's.
  const double c     = std::sqrt(3. * mu / rho);
  const double rigid = rod_tip_mass_root(rho * A * L / M) * c / L;
  EXPECT_NEAR(exact / rigid, 1., 3e-4);

  for (const unsigned int degree : {1u, 2u})
    {
      std::vector<double> errors;
      for (unsigned int level = 0; level < (degree == 1 ? 4u : 3u); ++level)
        {
          const double omega =
            rod_frequency_1d(degree, 5u << level, mu, rho, mu_block, rho_block);
          errors.push_back(std::abs(omega - exact) / exact);
        }
      for (unsigned int k = 0; k + 1 < errors.size(); ++k)
        {
          const double rate = std::log2(errors[k] / errors[k + 1]);
          std::cout << "p = " << degree << ", h = " << 25. / (1 << k)
                    << ": frequency error " << errors[k] << ", rate " << rate
                    << std::endl;
          // The rate 2p is reached up to the next term of the error
          // expansion, O(h^2) relative: 0.3 covers it on these meshes.
          EXPECT_NEAR(rate, 2. * degree, 0.3);
        }
      EXPECT_LT(errors.back(), degree == 1 ? 1e-3 : 1e-7);
    }
}



// @sect4{Axial vibration of a slender 3D column}
//
// The quarter of a square column (side 2a = 10 mm, length L = 100 mm),
// symmetric about y = 0 and z = 0, with its base free to contract laterally
// (only u_x fixed there), and a dense end segment of the same material.
// The symmetry planes forbid bending and torsion, so the first mode is the
// axial one, and a slender column vibrates axially as a rod with Young's
// modulus $E = 9\kappa\mu/(3\kappa + \mu)$. The Rayleigh-Love correction
// for lateral inertia lowers the frequency by about $\nu^2 k^2 r_p^2 / 2
// \approx 2\cdot10^{-5}$ ($r_p$ the polar radius of gyration); the
// jump in density at the end segment and the base add three-dimensional
// end effects of the same order, so the 3D frequency must agree with rod
// theory to a few times the Love correction, and quadratic hexahedra must
// have converged to that level already on the coarse mesh.
TEST(SlenderColumn3D, AxialFrequencyMatchesRodTheory)
{
  const double mu = 10., kappa = 100., rho = 1e-6, L = 100., ell = 25.,
               half_side = 5.;
  const double rho_block = 40. * rho;
  const double E         = 9. * kappa * mu / (3. * kappa + mu);
  const double nu        = (3. * kappa - 2. * mu) / (2. * (3. * kappa + mu));
  const double exact = two_segment_rod_frequency(E, rho, L, E, rho_block, ell);

  std::vector<double> errors;
  for (const unsigned int n : {5u, 10u})
    {
      std::ostringstream sections;
      sections
        << "subsection Geometry\n  set Generator = subdivided_hyper_rectangle\n  set Generator arguments = "
        << box_arguments(3, n, n / 5, L + ell, half_side)
        << "\n  set Material id function = x > 100 ? 2 : 1\nend\n"
        << material(1, mu, kappa, rho, 1.)
        << material(2, mu, kappa, rho_block, 1.)
        << "subsection Loads and constraints\n  set Fixed components = 0: x, 2: y, "
           "4: z\nend\n";
      Simulation<3> column(read(parameter_text(3, sections.str())),
                                  MPI_COMM_WORLD);
      column.make_grid();
      column.setup_system();
      errors.push_back(std::abs(linearised_frequencies(column)[0] - exact) /
                       exact);
      std::cout << "3D column, " << n
                << " cells along the axis: frequency error " << errors.back()
                << std::endl;
    }
  // Rayleigh-Love: k^2 r_p^2 nu^2 / 2 with k = omega/c and r_p^2 = (2a)^2/6.
  const double love = 0.5 * nu * nu * std::pow(exact * std::sqrt(rho / E), 2) *
                      std::pow(2. * half_side, 2) / 6.;
  std::cout << "Rayleigh-Love correction estimate: " << love << std::endl;
  EXPECT_LT(errors.back(), 5. * love);
  EXPECT_LT(std::abs(errors.back() - errors.front()), love);
}



// @sect4{Energy conservation of the trapezoidal rule}
//
// Without damping and with $\alpha = 0$ (the trapezoidal rule) the discrete
// energy $\tfrac12\mathbf v^T\mathbf M\mathbf v + \Psi(\mathbf u)$ of a
// linear system is conserved exactly. At a strain amplitude of $10^{-9}$ the
// nonlinearity changes the energy by a relative $O(10^{-9})$ at most, so
// the total must stay constant to $10^{-8}$ over 1,000 steps. With
// $\alpha < 0$ the scheme dissipates, and the energy must never grow.
template <int dim>
std::vector<double>
energy_history(const double alpha)
{
  const double mu = 10., rho = 1e-6, L = 10., c = std::sqrt(3. * mu / rho);
  std::ostringstream sections;
  sections
    << "subsection Geometry\n  set Generator = subdivided_hyper_rectangle\n  set Generator arguments = "
    << box_arguments(dim, 4, 2, L, 2.) << "\nend\n"
    << "subsection Finite element\n  set Polynomial degree = 1\nend\n"
    << material(1, mu, 10. * mu, rho, 1.)
    << "subsection Loads and constraints\n  set Fixed components = 0: "
    << std::string("xyz").substr(0, dim)
    << "\n  set Function constants = c=" << c << ", L=" << L << "\nend\n"
    << "subsection Initial conditions\n  set Velocity = "
    << dim_list(dim, {"1e-9*c*x/L", "0.5e-9*c*x/L", "-0.3e-9*c*x/L"}, "; ")
    << "\nend\n"
    << "subsection Time integration\n  set Alpha = " << alpha
    << "\n  set Time step = " << 0.02 * L / c
    << "\n  set End time = " << 20. * L / c << "\nend\n"
    << "subsection Nonlinear solver\n  set Absolute tolerance = 0\n"
       "  set Relative tolerance = 1e-11\nend\n"
    << "subsection Linear solver\n  set Solver = Direct\nend\n";
  Simulation<dim> body(read(parameter_text(dim, sections.str())),
                              MPI_COMM_WORLD);
  body.make_grid();
  body.setup_system();
  body.initialize_state();
  std::vector<double> energy{body.energies().kinetic + body.energies().strain};
  while (body.advance_one_step())
    energy.push_back(body.energies().kinetic + body.energies().strain);
  return energy;
}

TYPED_TEST(SolverTest, TrapezoidalRuleConservesEnergy)
{
  constexpr int             dim    = TypeParam::value;
  const std::vector<double> energy = energy_history<dim>(0.);
  ASSERT_EQ(energy.size(), 1001u);
  double drift = 0.;
  for (const double e : energy)
    drift = std::max(drift, std::abs(e / energy[0] - 1.));
  std::cout << dim
            << "D: largest relative energy change over 1000 steps: " << drift
            << std::endl;
  EXPECT_LT(drift, 1e-8);
}

TYPED_TEST(SolverTest, HHTNeverGainsEnergy)
{
  constexpr int             dim     = TypeParam::value;
  const std::vector<double> energy  = energy_history<dim>(-0.1);
  double                    largest = 0.;
  for (const double e : energy)
    largest = std::max(largest, e / energy[0]);
  std::cout << dim << "D, alpha = -0.1: largest E/E0 = " << largest
            << ", final E/E0 = " << energy.back() / energy[0] << std::endl;
  EXPECT_LE(largest, 1. + 1e-8);
  EXPECT_LT(energy.back(), energy[0]);
}



// @sect4{Patch test: a uniform stretch on a distorted mesh}
//
// The unit square or cube, its interior vertices moved at random, symmetry
// conditions on the faces x = 0, y = 0, z = 0 and the nominal tractions
// $\mathbf P(\mathbf F_0)\mathbf N$ of the uniform stretch $\mathbf F_0 =
// \mathrm{diag}(1.3, 0.8, 1.1)$ on the others: the exact solution $\mathbf
// u = (\mathbf F_0 - \mathbf I)\mathbf X$ is in the finite element space of
// every mesh, so it must be reproduced up to round-off and the tolerance of
// Newton's method.
template <int dim>
void
check_patch_test(const bool         simplices,
                 const unsigned int degree,
                 const std::string &formulation = "displacement")
{
  const double   mu = 10., kappa = 50.;
  Tensor<2, dim> F0;
  const double   stretches[3] = {1.3, 0.8, 1.1};
  for (unsigned int d = 0; d < dim; ++d)
    F0[d][d] = stretches[d];
  const Tensor<2, dim> P0 =
    NeoHookeanEnergy<dim>(mu, kappa).first_piola_closed_form(F0);
  std::string traction_constants;
  for (unsigned int d = 0; d < dim; ++d)
    {
      std::ostringstream constant;
      constant << (d > 0 ? ", P" : "P") << d << '=' << std::setprecision(17)
               << P0[d][d];
      traction_constants += constant.str();
    }

  std::ostringstream sections;
  sections
    << "subsection Geometry\n  set Generator = subdivided_hyper_rectangle\n  set Generator arguments = "
    << box_arguments(dim, simplices ? 2 : 4, simplices ? 2 : 4, 1., 1.)
    << "\n  set Random distortion = 0.25\n"
    << "  set Convert to simplices = " << (simplices ? "true" : "false")
    << "\nend\n"
    << "subsection Finite element\n  set Polynomial degree = " << degree
    << "\n  set Volumetric formulation = " << formulation << "\nend\n"
    << material(1, mu, kappa, 1e-6, 1.)
    << "subsection Loads and constraints\n  set Fixed components = "
    << dim_list(dim, {"0: x", "2: y", "4: z"}, ", ")
    << "\n  set Traction boundary ids = "
    << dim_list(dim, {"1", "3", "5"}, ", ") << "\n  set Traction = "
    << dim_list(dim,
                {"x > 0.999 ? P0 : 0",
                 "y > 0.999 ? P1 : 0",
                 "z > 0.999 ? P2 : 0"},
                "; ")
    << "\n  set Function constants = " << traction_constants << "\nend\n"
    << "subsection Initial conditions\n  set Load steps = 4\nend\n"
    << "subsection Nonlinear solver\n  set Absolute tolerance = 1e-11\n"
       "  set Relative tolerance = 0\nend\n"
    << "subsection Linear solver\n  set Solver = Direct\nend\n";
  Simulation<dim> body(read(parameter_text(dim, sections.str())),
                              MPI_COMM_WORLD);
  body.make_grid();
  body.setup_system();
  body.solve_static_equilibrium(0.);

  std::map<types::global_dof_index, Point<dim>> support_points;
  DoFTools::map_dofs_to_support_points(body.get_mapping(),
                                       body.get_dof_handler(),
                                       support_points);
  double largest_error = 0.;
  for (const auto &cell : body.get_dof_handler().active_cell_iterators())
    {
      std::vector<types::global_dof_index> dofs(
        cell->get_fe().n_dofs_per_cell());
      cell->get_dof_indices(dofs);
      for (unsigned int i = 0; i < dofs.size(); ++i)
        {
          const unsigned int c =
            cell->get_fe().system_to_component_index(i).first;
          const double exact = (stretches[c] - 1.) * support_points[dofs[i]][c];
          largest_error =
            std::max(largest_error,
                     std::abs(body.displacement()[dofs[i]] - exact));
        }
    }
  std::cout << dim << "D patch test ("
            << (simplices ? "simplices" : "hypercubes") << ", p = " << degree
            << ", " << formulation << "): largest nodal error " << largest_error << " mm" << std::endl;
  EXPECT_LT(largest_error, 1e-10);
}

TYPED_TEST(SolverTest, PatchTestHypercubes)
{
  check_patch_test<TypeParam::value>(false, 1);
  check_patch_test<TypeParam::value>(false, 2);
  if (TypeParam::value == 3)
    check_patch_test<TypeParam::value>(false, 2, "mean dilatation");
}

TYPED_TEST(SolverTest, PatchTestSimplices)
{
  if (TypeParam::value > 1)
    {
      check_patch_test<TypeParam::value>(true, 1);
      check_patch_test<TypeParam::value>(true, 2);
      if (TypeParam::value == 3)
        check_patch_test<TypeParam::value>(true, 2, "mean dilatation");
    }
}
