// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Tests of the solver against closed forms}
//
// Each test sets up a small body through the same parameter interface a
// user has, runs a phase of SoftRobotDynamics<dim>, and compares with a
// solution known in closed form. The tolerances follow from the theory
// that is quoted beside each test.

#include "solver_test_tools.h"

#include <cmath>
#include <core/soft_robot_dynamics.h>
#include <deal.II/base/function_parser.h>
#include <deal.II/base/utilities.h>
#include <deal.II/dofs/dof_tools.h>
#include <functional>
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



// @sect4{Held across its axis: uniaxial strain}
//
// The column and rod tests below run in every dimension. In 2D and 3D the
// body is a bar of square cross-section $A$ (in 2D a width $a$ with the
// thickness $A/a$ as section), held by frictionless walls: $u_y = 0$ on
// the faces $y = 0, a$ and $u_z = 0$ on $z = 0, a$. The motion is then
// $u_x(X)$ alone, every cross-section is in uniaxial strain, $\mathbf F =
// \mathrm{diag}(\lambda, 1, 1)$, and the nominal stress is the function of
// the stretch that each dimension's law gives there,
// @f[
//   P_1(\lambda) = \mu(\lambda - \lambda^{-2}),\quad
//   P_2(\lambda) = \mu(\lambda - \lambda^{-3}),\quad
//   P_3(\lambda) = \tfrac{2\mu}{3}(\lambda^{1/3} - \lambda^{-5/3})
//                + \tfrac{\kappa}{2}(\lambda - \lambda^{-1}),
// @f]
// (the 1D bar's uniaxial stress, the plane-stress sheet's and the
// compressible solid's, see NeoHookeanEnergy), with the small-strain
// moduli $P'(1) = 3\mu$, $4\mu$ and $\kappa + 4\mu/3$. A field $u_x(X)$ is
// also a solution of the discrete equations: each node across the bar
// carries the 1D equations times the integral of its lateral shape
// function, and the lateral equations are integrals of $\partial
// \varphi/\partial y$ across the bar, which vanish. So the finite element
// solution is that of the 1D problem with $P_d$ on the same mesh along the
// axis, and the 1D error estimates hold in every dimension.
namespace
{
  // The walls and the base: 'Fixed components' of the bar in dim
  // dimensions, whose base at x = 0 is fixed in x.
  std::string
  walled_base(const unsigned int dim)
  {
    return dim_list(dim, {"0: x", "2: y, 3: y", "4: z, 5: z"}, ", ");
  }

  // The section factor of a bar of cross-section A and width a.
  double
  section_factor(const unsigned int dim, const double A, const double a)
  {
    return (dim == 1) ? A : (dim == 2) ? A / a : 1.;
  }

  // $P_d(\lambda)$ and $P_d'(\lambda)$ above.
  std::pair<double, double>
  uniaxial_strain_stress(const unsigned int dim,
                         const double       lambda,
                         const double       mu,
                         const double       kappa)
  {
    if (dim == 1)
      return {mu * (lambda - std::pow(lambda, -2.)),
              mu * (1. + 2. * std::pow(lambda, -3.))};
    if (dim == 2)
      return {mu * (lambda - std::pow(lambda, -3.)),
              mu * (1. + 3. * std::pow(lambda, -4.))};
    return {2. * mu / 3. * (std::cbrt(lambda) - std::pow(lambda, -5. / 3.)) +
              0.5 * kappa * (lambda - 1. / lambda),
            2. * mu / 3. *
                (std::pow(lambda, -2. / 3.) / 3. +
                 5. / 3. * std::pow(lambda, -8. / 3.)) +
              0.5 * kappa * (1. + 1. / (lambda * lambda))};
  }

  // The modulus of uniaxial strain at $\lambda = 1$.
  double
  uniaxial_strain_modulus(const unsigned int dim,
                          const double       mu,
                          const double       kappa)
  {
    return uniaxial_strain_stress(dim, 1., mu, kappa).second;
  }
} // namespace



// @sect4{Static sag of a hanging column with a tip mass}
//
// A column of length $L$, cross-section $A$, density $\rho$ hangs from
// $X = 0$ and carries a block of mass $M$ at its end. At the reference
// position $X$ the nominal stress carries the weight of everything below,
// $P(X) = \left(Mg + \rho A g (L - X)\right)/A$ (the walls take no axial
// force), and $P_d(\lambda) = P$ gives the stretch $\lambda(X)$
// pointwise. The end displacement is $\int_0^{L} (\lambda - 1)\,dX$ (plus
// the block's own, here included the same way). Quadratic elements on a
// mesh of 102 cells along the axis resolve this smooth stretch to
// $O(h^4)\approx 10^{-8}$ relative; the stretch at the top is over 1.4 in
// every dimension ($\kappa = 2\mu$ in 3D), well into the nonlinear range.
template <typename T>
class StaticSag : public ::testing::Test
{
protected:
  static constexpr int    dim = T::value;
  static constexpr double L = 100., ell = 2., A = 100., width = 10., g = 9810.;
  static constexpr double mu = 10., kappa = 2. * mu, rho = 1e-6;
  static constexpr double M = 0.1, rho_block = M / (A * ell);
  static constexpr double mu_block = 1e4 * mu, kappa_block = 2. * mu_block;

  // The static equilibrium of the hanging column, reached in `load_steps`
  // load steps, the ones before the last to `load_step_tolerance`, with the
  // Nonlinear solver's `relative_tolerance` and the `equilibrium_tolerance`
  // of the last step: the tip displacement and the matrix factorizations
  // it took.
  static std::pair<Tensor<1, dim>, unsigned int>
  hang(const unsigned int load_steps,
       const double       load_step_tolerance,
       const double       relative_tolerance    = 1e-13,
       const double       equilibrium_tolerance = 0.)
  {
    const double       section = section_factor(dim, A, width);
    std::ostringstream sections;
    sections
      << "subsection Geometry\n  set Generator = subdivided_hyper_rectangle\n"
      << "  set Generator arguments = "
      << box_arguments(dim, 102, 1, 102., width)
      << "\n  set Material id function = x > 100 ? 2 : 1\nend\n"
      << "subsection Finite element\n  set Polynomial degree = 2\nend\n"
      << material(1, mu, kappa, rho, section)
      << material(2, mu_block, kappa_block, rho_block, section)
      << "subsection Loads and constraints\n  set Gravity = " << g << ", 0, 0\n"
      << "  set Fixed components = " << walled_base(dim) << "\nend\n"
      << "subsection Initial conditions\n  set Type = static equilibrium\n"
      << "  set Load steps = " << load_steps << "\n"
      << "  set Load step tolerance = " << load_step_tolerance << "\n"
      << "  set Equilibrium tolerance = " << equilibrium_tolerance << "\nend\n"
      << "subsection Nonlinear solver\n  set Absolute tolerance = 1e-10\n"
      << "  set Relative tolerance = " << relative_tolerance << "\nend\n"
      << "subsection Linear solver\n  set Solver = Direct\nend\n";
    Simulation<dim> column(read(parameter_text(dim, sections.str())),
                           MPI_COMM_WORLD);
    column.make_grid();
    column.setup_system();
    column.solve_static_equilibrium(0.);
    return {column.tip_motion().first, column.n_tangent_updates()};
  }
};
TYPED_TEST_SUITE(StaticSag, Dimensions);

TYPED_TEST(StaticSag, HangingColumnMatchesClosedForm)
{
  using F           = TestFixture;
  constexpr int dim = F::dim;
  const double  L = F::L, ell = F::ell, A = F::A, g = F::g, mu = F::mu,
               kappa = F::kappa, rho = F::rho, M = F::M,
               rho_block = F::rho_block, mu_block = F::mu_block,
               kappa_block = F::kappa_block;
  // The load steps only set the path of Newton's method, not the
  // equilibrium; two keep the 3D case short. The first stops at the
  // default load step tolerance.
  const auto u_tip = F::hang(2, 0.1).first;

  // The stretch where the nominal stress is P, by Newton's method.
  const auto stretch =
    [](const double P, const double shear_modulus, const double bulk_modulus) {
      double lambda = 1.;
      for (unsigned int i = 0; i < 50; ++i)
        {
          const auto [stress, modulus] =
            uniaxial_strain_stress(dim, lambda, shear_modulus, bulk_modulus);
          lambda -= (stress - P) / modulus;
        }
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
            (X < L) ? stretch(weight_below / A, mu, kappa)
                    : stretch(weight_below / A, mu_block, kappa_block);
          exact += 0.5 * (b - a) * gauss_w[q] * (lambda - 1.);
        }
    }
  std::cout << dim << "D static sag: FE " << u_tip[0] << " mm, closed form "
            << exact << " mm, relative error "
            << std::abs(u_tip[0] - exact) / exact << "; lateral "
            << u_tip.norm() - std::abs(u_tip[0]) << " mm" << std::endl;
  EXPECT_GT(stretch((M * g + rho * A * g * L) / A, mu, kappa), 1.4);
  EXPECT_NEAR(u_tip[0], exact, 1e-7 * exact);
  // The walls keep the motion axial.
  EXPECT_LE(u_tip.norm() - std::abs(u_tip[0]), 1e-7 * exact);
}

// The load steps before the last only lead to the equilibrium: stopping
// them at a tenth of the force scale must give the equilibrium of load
// steps converged to the full tolerance, to that tolerance, with fewer
// factorizations.
TYPED_TEST(StaticSag, LooseLoadStepsReachTheSameEquilibrium)
{
  const auto [u_tight, tight_factorizations] = TestFixture::hang(4, 0.);
  const auto [u_loose, loose_factorizations] = TestFixture::hang(4, 0.1);
  std::cout << TestFixture::dim
            << "D static sag in four load steps: " << tight_factorizations
            << " factorizations converging every "
            << "step, " << loose_factorizations << " converging the last; "
            << "tip " << u_tight[0] << " and " << u_loose[0] << " mm"
            << std::endl;
  EXPECT_NEAR((u_loose - u_tight).norm(), 0., 1e-9 * u_tight.norm());
  EXPECT_LT(loose_factorizations, tight_factorizations);
}

// The state the motion starts from can be converged more tightly than the
// time steps (`Equilibrium tolerance`): with the steps' relative tolerance
// at 1e-4, the last load step at 1e-13 must give the equilibrium of the
// tight solve, and without it the equilibrium must be visibly off (else
// this test could not tell the two apart).
TYPED_TEST(StaticSag, EquilibriumToleranceTightensTheLastLoadStep)
{
  const Tensor<1, TestFixture::dim> u_tight = TestFixture::hang(2, 0.1).first;
  const Tensor<1, TestFixture::dim> u_loose =
    TestFixture::hang(2, 0.1, 1e-4).first;
  const Tensor<1, TestFixture::dim> u_start =
    TestFixture::hang(2, 0.1, 1e-4, 1e-13).first;
  const double loose = (u_loose - u_tight).norm() / u_tight.norm();
  const double start = (u_start - u_tight).norm() / u_tight.norm();
  std::cout << TestFixture::dim
            << "D static sag, steps' tolerance 1e-4: tip off the tight "
            << "solve's by " << loose << " (relative), with the equilibrium "
            << "at 1e-13 by " << start << std::endl;
  EXPECT_LE(start, 1e-11);
  EXPECT_GE(loose, 1e3 * std::max(start, 1e-14));
}



// @sect4{Axial vibration of a rod with a tip mass}
//
// A rod (length $L$, the modulus $E = P_d'(1)$ of uniaxial strain above,
// density $\rho$) fixed at $X = 0$ carries a block of length $\ell$ at its
// end. With the block's own modulus $E_2$ and density $\rho_2$, the exact
// first axial mode of the two-segment rod satisfies
// @f[
//   E_1 k_1 \cos(k_1 L)\cos(k_2\ell) = E_2 k_2 \sin(k_1 L)\sin(k_2\ell),
//   \qquad k_i = \omega\sqrt{\rho_i/E_i},
// @f]
// which for a rigid block of mass $M$ becomes the classical
// $\beta\tan\beta = m/M$, $\beta = \omega L/c$, $m = \rho A L$. The
// eigenfrequency of Lagrange elements of degree $p$ converges at the rate
// $h^{2p}$. In 2D and 3D the walls make the axial mode an exact
// eigenvector of the discrete problem (see above), whose eigenvalue is
// that of the 1D elements with the modulus $E$; the lateral modes of the
// quadratic elements' interior nodes across the bar are of the order of
// the shear wave's frequency across its width, far above the axial mode.
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

  template <int dim>
  double
  rod_frequency(const unsigned int degree,
                const unsigned int n_cells,
                const double       mu,
                const double       kappa,
                const double       rho,
                const double       mu_block,
                const double       kappa_block,
                const double       rho_block,
                const double       A,
                const double       a)
  {
    std::ostringstream geometry;
    geometry
      << "subsection Geometry\n  set Generator = subdivided_hyper_rectangle\n  set Generator arguments = "
      << box_arguments(dim, n_cells, 1, 125., a)
      << "\n  set Material id function = x > 100 ? 2 : 1\nend\n"
      << "subsection Finite element\n  set Polynomial degree = " << degree
      << "\nend\n";
    const double      section = section_factor(dim, A, a);
    const std::string text    = parameter_text(
      dim,
      geometry.str() + material(1, mu, kappa, rho, section) +
        material(2, mu_block, kappa_block, rho_block, section) +
        "subsection Loads and constraints\n  set Fixed components = " +
        walled_base(dim) + "\nend\n");
    Simulation<dim> rod(read(text), MPI_COMM_WORLD);
    rod.make_grid();
    rod.setup_system();
    return linearised_frequencies(rod)[0];
  }
} // namespace

template <typename T>
class RodWithTipMass : public ::testing::Test
{
};
TYPED_TEST_SUITE(RodWithTipMass, Dimensions);

TYPED_TEST(RodWithTipMass, FrequencyConvergesAtRateTwoP)
{
  constexpr int dim = TypeParam::value;
  const double  mu = 10., kappa = 10. * mu, rho = 1e-6, L = 100., ell = 25.,
               A = 100., a = 10.;
  const double M = 0.01, rho_block = M / (A * ell), mu_block = 1e3 * mu,
               kappa_block = 10. * mu_block;
  const double E           = uniaxial_strain_modulus(dim, mu, kappa);
  const double E_block = uniaxial_strain_modulus(dim, mu_block, kappa_block);
  const double exact =
    two_segment_rod_frequency(E, rho, L, E_block, rho_block, ell);

  // The stiff block is nearly rigid: the exact frequency is within
  // ell E_1 / (L E_2) ~ 3e-4 of the rigid-mass formula's.
  const double c     = std::sqrt(E / rho);
  const double rigid = rod_tip_mass_root(rho * A * L / M) * c / L;
  EXPECT_NEAR(exact / rigid, 1., 3e-4);

  for (const unsigned int degree : {1u, 2u})
    {
      std::vector<double> errors;
      for (unsigned int level = 0; level < (degree == 1 ? 4u : 3u); ++level)
        {
          const double omega = rod_frequency<dim>(degree,
                                                  5u << level,
                                                  mu,
                                                  kappa,
                                                  rho,
                                                  mu_block,
                                                  kappa_block,
                                                  rho_block,
                                                  A,
                                                  a);
          errors.push_back(std::abs(omega - exact) / exact);
        }
      for (unsigned int k = 0; k + 1 < errors.size(); ++k)
        {
          const double rate = std::log2(errors[k] / errors[k + 1]);
          std::cout << dim << "D, p = " << degree << ", h = " << 25. / (1 << k)
                    << ": frequency error " << errors[k] << ", rate " << rate
                    << std::endl;
          // The rate 2p is reached up to the next term of the error
          // expansion, O(h^2) relative: 0.3 covers it on these meshes.
          EXPECT_NEAR(rate, 2. * degree, 0.3);
        }
      EXPECT_LT(errors.back(), degree == 1 ? 1e-3 : 1e-7);
    }
}



// @sect4{Axial vibration of a slender column with lateral inertia}
//
// A column of square cross-section (3D) or a strip (2D) of width 2a = 10
// mm and length L = 100 mm, of which the half y > 0 (and in 3D the quarter
// y, z > 0) is modelled with symmetry conditions, its base free to
// contract laterally (only u_x fixed there), and a dense end segment of
// the same material. The symmetry planes forbid bending and torsion, so
// the first mode is the axial one, and a slender column vibrates axially
// as a rod with Young's modulus $E$ and Poisson's ratio $\nu$ of uniaxial
// stress: $E = 9\kappa\mu/(3\kappa + \mu)$ in 3D, $E = 3\mu$ and $\nu =
// 1/2$ for the plane-stress sheet of incompressible material in 2D. The
// Rayleigh-Love correction for lateral inertia lowers the frequency by
// about $\nu^2 k^2 r_p^2 / 2 \approx 10^{-5}$, $r_p$ the radius of
// gyration of the lateral motion ($r_p^2 = (dim - 1)(2a)^2/12$: the
// lateral contraction is along y in 2D and along y and z in 3D); the jump
// in density at the end segment and the base add end effects of the same
// order, so the frequency must agree with rod theory to a few times the
// Love correction, and quadratic elements must have converged to that
// level already on the coarse mesh. (In 1D there is no lateral motion:
// the rod test above is the 1D case.)
template <typename T>
class SlenderColumn : public ::testing::Test
{
};
TYPED_TEST_SUITE(SlenderColumn, Dimensions2And3);

TYPED_TEST(SlenderColumn, AxialFrequencyMatchesRodTheory)
{
  constexpr int dim = TypeParam::value;
  const double  mu = 10., kappa = 100., rho = 1e-6, L = 100., ell = 25.,
               half_side = 5.;
  const double rho_block = 40. * rho;
  const double E = (dim == 3) ? 9. * kappa * mu / (3. * kappa + mu) : 3. * mu;
  const double nu =
    (dim == 3) ? (3. * kappa - 2. * mu) / (2. * (3. * kappa + mu)) : 0.5;
  const double exact = two_segment_rod_frequency(E, rho, L, E, rho_block, ell);

  std::vector<double> errors;
  for (const unsigned int n : {5u, 10u})
    {
      std::ostringstream sections;
      sections
        << "subsection Geometry\n  set Generator = subdivided_hyper_rectangle\n  set Generator arguments = "
        << box_arguments(dim, n, n / 5, L + ell, half_side)
        << "\n  set Material id function = x > 100 ? 2 : 1\nend\n"
        << "subsection Finite element\n  set Polynomial degree = 2\nend\n"
        << material(1, mu, kappa, rho, 1.)
        << material(2, mu, kappa, rho_block, 1.)
        << "subsection Loads and constraints\n  set Fixed components = "
        << dim_list(dim, {"0: x", "2: y", "4: z"}, ", ") << "\nend\n";
      Simulation<dim> column(read(parameter_text(dim, sections.str())),
                             MPI_COMM_WORLD);
      column.make_grid();
      column.setup_system();
      errors.push_back(std::abs(linearised_frequencies(column)[0] - exact) /
                       exact);
      std::cout << dim << "D column, " << n
                << " cells along the axis: frequency error " << errors.back()
                << std::endl;
    }
  // Rayleigh-Love: k^2 r_p^2 nu^2 / 2 with k = omega/c.
  const double love = 0.5 * nu * nu * std::pow(exact * std::sqrt(rho / E), 2) *
                      (dim - 1) * std::pow(2. * half_side, 2) / 12.;
  std::cout << dim << "D: Rayleigh-Love correction estimate: " << love
            << std::endl;
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



// The largest difference between a nodal vector of the body and a field
// given per component at the nodes' positions in the mesh.
template <int dim>
double
largest_nodal_difference(
  const SimulatorAccess<dim>                                    &body,
  const TrilinosWrappers::MPI::Vector                           &values,
  const std::function<double(const Point<dim> &, unsigned int)> &exact)
{
  std::map<types::global_dof_index, Point<dim>> support_points;
  DoFTools::map_dofs_to_support_points(body.get_mapping(),
                                       body.get_dof_handler(),
                                       support_points);
  double largest = 0.;
  for (const auto &cell : body.get_dof_handler().active_cell_iterators())
    {
      std::vector<types::global_dof_index> dofs(
        cell->get_fe().n_dofs_per_cell());
      cell->get_dof_indices(dofs);
      for (unsigned int i = 0; i < dofs.size(); ++i)
        {
          const unsigned int c =
            cell->get_fe().system_to_component_index(i).first;
          largest = std::max(largest,
                             std::abs(values[dofs[i]] -
                                      exact(support_points[dofs[i]], c)));
        }
    }
  return largest;
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

  const double largest_error = largest_nodal_difference<dim>(
    body, body.displacement(), [&](const Point<dim> &X, const unsigned int c) {
      return (stretches[c] - 1.) * X[c];
    });
  std::cout << dim << "D patch test ("
            << (simplices ? "simplices" : "hypercubes") << ", p = " << degree
            << ", " << formulation << "): largest nodal error " << largest_error
            << " mm" << std::endl;
  EXPECT_LT(largest_error, 1e-10);
}

TYPED_TEST(SolverTest, PatchTestHypercubes)
{
  check_patch_test<TypeParam::value>(false, 1);
  check_patch_test<TypeParam::value>(false, 2);
  if (TypeParam::value == 3)
    {
      check_patch_test<TypeParam::value>(false, 2, "mean dilatation");
      check_patch_test<TypeParam::value>(false, 2, "linear dilatation");
    }
}

// Initial conditions/Velocity coordinates: with 'initial state' the
// velocity expression is evaluated where the nodes are after the initial
// displacement, with 'reference' where they are in the mesh. The velocity
// v = x (the position itself) then gives every node its reference position
// plus its initial displacement, or its reference position alone; the
// initial displacement is linear, so exact at the nodes of the distorted
// quadratic mesh.
TYPED_TEST(SolverTest, InitialVelocityAtInitialStatePositions)
{
  constexpr int     dim = TypeParam::value;
  const std::string displacement =
    dim_list(dim, {"0.1*x", "0.05*x - 0.02*y", "0.03*z + 0.01*x"}, "; ");
  FunctionParser<dim> initial_displacement(dim);
  initial_displacement.initialize(FunctionParser<dim>::default_variable_names(),
                                  displacement,
                                  {});
  for (const bool at_initial_state : {false, true})
    {
      std::ostringstream sections;
      sections
        << "subsection Geometry\n  set Generator = subdivided_hyper_rectangle\n"
        << "  set Generator arguments = " << box_arguments(dim, 3, 2, 2., 1.)
        << "\n  set Random distortion = 0.2\nend\n"
        << "subsection Finite element\n  set Polynomial degree = 2\nend\n"
        << material(1, 10., 50., 1e-6, 1.)
        << "subsection Initial conditions\n  set Displacement = "
        << displacement
        << "\n  set Velocity = " << dim_list(dim, {"x", "y", "z"}, "; ")
        << "\n  set Velocity coordinates = "
        << (at_initial_state ? "initial state" : "reference") << "\nend\n";
      Simulation<dim> body(read(parameter_text(dim, sections.str())),
                           MPI_COMM_WORLD);
      body.make_grid();
      body.setup_system();
      body.initialize_state();

      const double largest_error = largest_nodal_difference<dim>(
        body, body.velocity(), [&](const Point<dim> &X, const unsigned int c) {
          return X[c] +
                 (at_initial_state ? initial_displacement.value(X, c) : 0.);
        });
      std::cout << dim << "D initial velocity at the "
                << (at_initial_state ? "initial state's" : "reference")
                << " positions: largest nodal difference " << largest_error
                << " mm/s" << std::endl;
      EXPECT_LT(largest_error, 1e-12);
    }
}

// In 1D a simplex is a line, the hypercube of the test above: the simplex
// patch test is typed on 2D and 3D.
template <typename T>
class SimplexSolverTest : public ::testing::Test
{
};
TYPED_TEST_SUITE(SimplexSolverTest, Dimensions2And3);

TYPED_TEST(SimplexSolverTest, PatchTestSimplices)
{
  check_patch_test<TypeParam::value>(true, 1);
  check_patch_test<TypeParam::value>(true, 2);
  if (TypeParam::value == 3)
    check_patch_test<TypeParam::value>(true, 2, "mean dilatation");
}
