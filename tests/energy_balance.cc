// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Test of the energy bookkeeping}
//
// The trajectory's energy balance $\mathcal B = T + \Pi + V_g - W + D -
// (T + \Pi + V_g)_0$ books the work of the tractions and the damping
// dissipation with the forces of HHT's equations of motion, so that what
// remains is the scheme's algorithmic dissipation only (see
// SoftRobotDynamics::update_energies). That remainder can be computed from
// the states alone: summed over the steps,
// @f[
//   \mathcal B_N = \sum_{n<N} \Big[\Delta T_n - \Delta\mathbf u_n\cdot
//   \mathbf M\tfrac12(\mathbf a_n + \mathbf a_{n+1})\Big] + \Big[\Delta\Pi_n -
//   \Delta\mathbf u_n\cdot\tfrac12(\tilde{\mathbf f}_n + \tilde{\mathbf
//   f}_{n+1})\Big],
// @f]
// with the internal forces $\mathbf f_k$ at the converged states and
// $\tilde{\mathbf f}_k = (1+\alpha)\mathbf f_k - \alpha\mathbf f_{k-1}$,
// $\tilde{\mathbf f}_0 = \mathbf f_0$. This test runs a damped bar with
// HHT ($\alpha = -0.2$), a time-dependent traction on its end and a large
// initial velocity, computes that sum from the states and compares it with
// the balance the program books. Booking damping and tractions with any
// other weights (the trapezoidal rule's, say) changes the balance by
// $O(\alpha)$ times their work and fails the comparison; the output shows
// by how much.

#include "solver_test_tools.h"

#include <cmath>
#include <core/soft_robot_dynamics.h>
#include <gtest/gtest.h>

using namespace dealii;
using namespace SoftRobot;
using namespace SoftRobot::Testing;

template <typename T>
class EnergyBalanceTest : public ::testing::Test
{
};
TYPED_TEST_SUITE(EnergyBalanceTest, Dimensions);

TYPED_TEST(EnergyBalanceTest, RemainderIsTheAlgorithmicDissipation)
{
  constexpr int     dim   = TypeParam::value;
  const double      alpha = -0.2;
  const double      mu = 10., rho = 1e-6, L = 10., c = std::sqrt(3. * mu / rho);
  const double      T           = L / c; // time for a wave to cross the bar
  const std::string velocity[3] = {"0.1*c*x/L",
                                   "0.2*c*(x/L)^2",
                                   "-0.1*c*(x/L)^2"};
  const std::string traction[3] = {"2*sin(t/T)",
                                   "(t < 3*T) ? 1 : 0",
                                   "-0.5*sin(2*t/T)"};
  std::ostringstream sections;
  sections << clamped_bar_sections(dim, mu, rho, L, 0.02 * T)
           << "  set Traction boundary ids = 1\n  set Traction = ";
  for (unsigned int d = 0; d < dim; ++d)
    sections << (d > 0 ? "; " : "") << traction[d];
  sections << "\n  set Function constants = c=" << c << ", L=" << L
           << ", T=" << T << "\nend\n"
           << "subsection Initial conditions\n  set Velocity = ";
  for (unsigned int d = 0; d < dim; ++d)
    sections << (d > 0 ? "; " : "") << velocity[d];
  sections << "\nend\n"
           << "subsection Time integration\n  set Alpha = " << alpha
           << "\n  set Time step = " << 0.1 * T
           << "\n  set End time = " << 6. * T << "\nend\n"
           << "subsection Nonlinear solver\n  set Absolute tolerance = 0\n"
              "  set Relative tolerance = 1e-12\nend\n"
           << "subsection Linear solver\n  set Solver = Direct\nend\n";
  Parameters::AllParameters parameters;
  parameters.read_string(parameter_text(dim, sections.str()));
  Simulation<dim> body(parameters, MPI_COMM_WORLD);
  body.make_grid();
  body.setup_system();
  body.initialize_state();

  const TrilinosWrappers::SparseMatrix &M = body.mass_matrix();
  TrilinosWrappers::MPI::Vector         u_old(body.displacement()),
    a_old(body.acceleration()), force(body.displacement()),
    f_old(body.displacement()), f_tilde_old(body.displacement()),
    f_tilde(body.displacement()), increment(body.displacement()),
    mean(body.displacement());
  double strain_old        = body.internal_force(u_old, f_old);
  f_tilde_old              = f_old;
  double       kinetic_old = 0.5 * M.matrix_norm_square(body.velocity()); // T_0
  const double initial_total = body.energies().kinetic +
                               body.energies().strain +
                               body.energies().gravity_potential;

  double remainder = 0., largest_error = 0., largest_energy = 0.,
         largest_balance = 0., work = 0.;
  while (body.advance_one_step())
    {
      const double strain = body.internal_force(body.displacement(), force);
      f_tilde             = force;
      f_tilde.sadd(1. + alpha, -alpha, f_old);
      increment = body.displacement();
      increment -= u_old;
      mean = body.acceleration();
      mean += a_old;
      mean *= 0.5;
      const double kinetic = 0.5 * M.matrix_norm_square(body.velocity());
      TrilinosWrappers::MPI::Vector M_mean(mean);
      M.vmult(M_mean, mean);
      f_tilde_old += f_tilde;
      remainder += (kinetic - kinetic_old - increment * M_mean) +
                   (strain - strain_old - 0.5 * (increment * f_tilde_old));

      const EnergyAccount &energy = body.energies();
      const double         booked = energy.balance(initial_total);
      largest_error  = std::max(largest_error, std::abs(booked - remainder));
      largest_energy = std::max(largest_energy, energy.kinetic + energy.strain);
      largest_balance = std::max(largest_balance, std::abs(booked));
      work            = std::max({work,
                                  std::abs(energy.traction_work),
                                  std::abs(energy.damping_dissipation)});

      u_old       = body.displacement();
      a_old       = body.acceleration();
      f_old       = force;
      f_tilde_old = f_tilde;
      strain_old  = strain;
      kinetic_old = kinetic;
    }
  std::cout << dim << "D: largest |B| " << largest_balance
            << ", largest work or dissipation " << work << ", largest energy "
            << largest_energy
            << "; booked balance minus the algorithmic remainder: "
            << largest_error << " (relative " << largest_error / largest_energy
            << ")" << std::endl;
  // The run must exercise what is checked: tractions and damping that do
  // work, and a scheme that dissipates.
  EXPECT_GT(work, 1e-2 * largest_energy);
  EXPECT_GT(largest_balance, 1e-4 * largest_energy);
  EXPECT_LT(largest_error, 1e-9 * largest_energy);
}
