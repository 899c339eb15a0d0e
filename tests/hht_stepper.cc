// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Tests of the HHT-alpha time stepper on the model problem}
//
// Every property of a linear time integrator shows on the single-degree-of-
// freedom oscillator
// @f[
//   \ddot u + 2\xi\omega\dot u + \omega^2 u = 0 .
// @f]
// One step maps the scaled state $\mathbf x_n = (u_n, \Delta t\,v_n,
// \Delta t^2 a_n)$ linearly to $\mathbf x_{n+1} = \mathbf A(\Omega,
// \xi)\,\mathbf x_n$, $\Omega = \omega\Delta t$. The tests below check the
// matrix HHTStepper::amplification_matrix() against theory (spectral radius,
// period error, algorithmic damping, stability), and check the matrix itself
// against an independent implementation of the step built from the stepper's
// own kinematic relations (HHTStepper::predict_displacement() and
// HHTStepper::update_kinematics()).
//
// The principal eigenvalues of $\mathbf A$ are written as
// @f[
//   \lambda_{1,2} = e^{\bar\Omega(-\bar\xi\pm i)},\qquad
//   \bar\Omega = \arg\lambda_1,\qquad
//   \bar\xi = -\frac{\ln|\lambda_1|}{\bar\Omega},
// @f]
// so that $\bar T/T - 1 = \Omega/\bar\Omega - 1$ is the relative period
// error and $\bar\xi$ the algorithmic damping ratio (Hilber, Hughes and
// Taylor 1977; Hughes, The Finite Element Method, section 9.3).
//
// @sect4{The series expansions the tests rely on}
//
// For the standard family, $\beta = (1-\alpha)^2/4$ and $\gamma =
// 1/2-\alpha$, we inserted $\lambda_1 = \exp(i\Omega + \sum_{k\ge2}
// a_k\Omega^k)$ into the characteristic polynomial of $\mathbf A(\Omega,
// 0)$ and solved for the $a_k$ order by order (with a computer algebra
// system; the tests below confirm the result numerically, including the
// second terms). This gives
// @f{align*}{
//   \frac{\Omega}{\bar\Omega} - 1 &= p_2\Omega^2 + p_4\Omega^4
//     + p_6\Omega^6 + O(\Omega^8),
//   \\ p_2 &= \tfrac{1}{12} - \tfrac{\alpha}{4} - \tfrac{3\alpha^2}{8},
//   \quad p_4 = -\tfrac{405\alpha^4 + 180\alpha^3 - 720\alpha^2
//                 - 480\alpha + 32}{5760},
//   \\ p_6 &= \tfrac{12285\alpha^6 + 168210\alpha^5 + 391230\alpha^4
//            + 304920\alpha^3 + 44352\alpha^2 - 24192\alpha + 704}{967680},
//   \\ \bar\xi &= d_3\Omega^3 + d_5\Omega^5 + d_7\Omega^7 + O(\Omega^9),
//   \\ d_3 &= -\tfrac{\alpha(1+\alpha)^2}{8},
//   \quad d_5 = -\tfrac{\alpha(1+\alpha)^2(27\alpha^2 + 18\alpha - 10)}{192},
//   \\ d_7 &= -\tfrac{\alpha(1+\alpha)^2(6075\alpha^4 + 6300\alpha^3
//            - 5400\alpha^2 - 4800\alpha + 808)}{46080}.
// @f}
// The leading terms are the ones of the issue that asked for these tests:
// the period error is $(1/12 - \alpha/4 - 3\alpha^2/8)\,\Omega^2$ and the
// damping ratio $-\alpha(1+\alpha)^2\Omega^3/8$. (The amplitude lost per step,
// $1-|\lambda_1| = \bar\xi\bar\Omega + \ldots$, is therefore $O(\Omega^4)$.)
// For $\alpha = 0$, the trapezoidal rule, $\lambda_{1,2} = (1 - \Omega^2/4
// \pm i\Omega)/(1+\Omega^2/4)$ exactly, so $|\lambda_{1,2}| = 1$ and
// $\bar\Omega = 2\arctan(\Omega/2)$.
//
// When $\Omega\to\infty$ the characteristic polynomial of the standard
// family tends to one with the double root $-(1+\alpha)/(1-\alpha)$ and the
// simple root $\alpha/(1+\alpha)$, whose modulus never exceeds the former
// for $-1/3\le\alpha\le 0$: $\rho_\infty = (1+\alpha)/(1-\alpha)$.
//
// @sect4{Round-off in the eigenvalues}
//
// The tolerances below are set by two effects. The truncation of the series
// is bounded by the first neglected term. The round-off comes from the
// eigenvalue solver: LAPACK returns the exact eigenvalues of a matrix
// perturbed by $\epsilon\|\mathbf A\|$, $\epsilon\approx 2.2\cdot10^{-16}$,
// and a simple eigenvalue moves by that perturbation times its condition
// number. As $\Omega\to 0$ the principal pair coalesces into a Jordan block
// at $\lambda = 1$, and the condition number grows like
// $1/|\lambda_1-\lambda_2| = 1/(2\Omega)$. At $\Omega = 0.01$ the
// eigenvalues are therefore accurate to about $50\epsilon\approx
// 10^{-14}$, which has to be compared with $1-|\lambda_1|\approx
// d_3\Omega^4$, only $6\cdot 10^{-11}$ for $\alpha = -0.05$.

// Not typed on the dimension: the model problem is a scalar oscillator.

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <deal.II/base/numbers.h>
#include <deal.II/base/tensor.h>
#include <deal.II/lac/lapack_full_matrix.h>
#include <deal.II/lac/vector.h>
#include <gtest/gtest.h>
#include <iomanip>
#include <iostream>
#include <time_integration/hht_stepper.h>
#include <vector>

namespace
{
  using namespace dealii;
  using SoftRobot::HHTStepper;

  // The standard family over its whole range, including both ends.
  const std::vector<double> standard_alphas =
    {0., -0.05, -0.1, -0.2, -0.25, -1. / 3.};

  // The reference study's parameters: $\gamma = 1/2-\alpha$, but $\beta =
  // 0.4 > (1-\alpha)^2/4 = 0.390625$.
  constexpr double reference_alpha = -0.25;
  constexpr double reference_beta  = 0.4;
  constexpr double reference_gamma = 0.75;



  // @sect4{Eigenvalues of the amplification matrix}
  //
  // The three eigenvalues of a $3\times 3$ matrix, computed by LAPACK.
  std::array<std::complex<double>, 3>
  eigenvalues(const Tensor<2, 3> &A)
  {
    LAPACKFullMatrix<double> matrix(3, 3);
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        matrix(i, j) = A[i][j];
    matrix.compute_eigenvalues();
    std::array<std::complex<double>, 3> values;
    for (unsigned int i = 0; i < 3; ++i)
      values[i] = matrix.eigenvalue(i);
    return values;
  }



  double
  spectral_radius_of(const Tensor<2, 3> &A)
  {
    double radius = 0.;
    for (const std::complex<double> &lambda : eigenvalues(A))
      radius = std::max(radius, std::abs(lambda));
    return radius;
  }



  // The principal pair: the eigenvalue with the largest positive imaginary
  // part (the spurious root is real). From it the algorithmic frequency
  // $\bar\Omega$ and damping ratio $\bar\xi$ as defined above.
  struct PrincipalRoot
  {
    double Omega_bar;
    double xi_bar;
  };

  PrincipalRoot
  principal_root(const HHTStepper &stepper, const double Omega)
  {
    std::complex<double> principal(0., 0.);
    for (const std::complex<double> &lambda :
         eigenvalues(stepper.amplification_matrix(Omega)))
      if (lambda.imag() > principal.imag())
        principal = lambda;
    EXPECT_GT(principal.imag(), 0.) << "no complex principal pair";

    const double Omega_bar = std::arg(principal);
    return {Omega_bar, -std::log(std::abs(principal)) / Omega_bar};
  }



  double
  period_error(const HHTStepper &stepper, const double Omega)
  {
    return Omega / principal_root(stepper, Omega).Omega_bar - 1.;
  }



  // The coefficients of the series expansions above.
  double
  period_error_coefficient_2(const double a)
  {
    return 1. / 12. - a / 4. - 3. * a * a / 8.;
  }

  double
  period_error_coefficient_4(const double a)
  {
    return -(405. * std::pow(a, 4) + 180. * std::pow(a, 3) - 720. * a * a -
             480. * a + 32.) /
           5760.;
  }

  double
  period_error_coefficient_6(const double a)
  {
    return (12285. * std::pow(a, 6) + 168210. * std::pow(a, 5) +
            391230. * std::pow(a, 4) + 304920. * std::pow(a, 3) +
            44352. * a * a - 24192. * a + 704.) /
           967680.;
  }

  double
  damping_coefficient_3(const double a)
  {
    return -a * (1. + a) * (1. + a) / 8.;
  }

  double
  damping_coefficient_5(const double a)
  {
    return -a * (1. + a) * (1. + a) * (27. * a * a + 18. * a - 10.) / 192.;
  }

  double
  damping_coefficient_7(const double a)
  {
    return -a * (1. + a) * (1. + a) *
           (6075. * std::pow(a, 4) + 6300. * std::pow(a, 3) - 5400. * a * a -
            4800. * a + 808.) /
           46080.;
  }



  // @sect4{One step of the oscillator, independently of the matrix}
  //
  // The HHT equation of the oscillator at $t_{n+1}$,
  // @f[
  //   R(u_{n+1}) = a_{n+1} + (1+\alpha)\left(2\xi\omega v_{n+1}
  //     + \omega^2 u_{n+1}\right) - \alpha\left(2\xi\omega v_n
  //     + \omega^2 u_n\right) = 0,
  // @f]
  // is linear in $u_{n+1}$ once $v_{n+1}$ and $a_{n+1}$ are expressed by
  // Newmark's relations (HHTStepper::update_kinematics()). One Newton step
  // from the predictor, with the derivative $\partial R/\partial u_{n+1} =
  // c_a + (1+\alpha)(2\xi\omega c_v + \omega^2)$ built from the stepper's
  // coefficients $c_a$, $c_v$, solves it exactly: this also checks that
  // the coefficients are the derivatives of update_kinematics().
  struct OscillatorState
  {
    double u, v, a;
  };

  OscillatorState
  step_oscillator(const HHTStepper     &stepper,
                  const double          omega,
                  const double          xi,
                  const double          dt,
                  const OscillatorState old_state)
  {
    Vector<double> u_old(1), v_old(1), a_old(1);
    u_old[0] = old_state.u;
    v_old[0] = old_state.v;
    a_old[0] = old_state.a;

    const double damping   = 2. * xi * omega;
    const double stiffness = omega * omega;
    const double alpha     = stepper.alpha();

    Vector<double> u_new(1), v_new(1), a_new(1);
    stepper.predict_displacement(u_old, v_old, a_old, dt, u_new);
    stepper.update_kinematics(u_new, u_old, v_old, a_old, dt, v_new, a_new);
    const double residual_at_predictor =
      a_new[0] +
      stepper.new_force_weight() * (damping * v_new[0] + stiffness * u_new[0]) +
      alpha * (-damping * v_old[0] - stiffness * u_old[0]);
    const double derivative =
      stepper.acceleration_coefficient(dt) +
      stepper.new_force_weight() *
        (damping * stepper.velocity_coefficient(dt) + stiffness);

    u_new[0] -= residual_at_predictor / derivative;
    stepper.update_kinematics(u_new, u_old, v_old, a_old, dt, v_new, a_new);
    return {u_new[0], v_new[0], a_new[0]};
  }
} // namespace



// @sect3{The tests}

// @sect4{Spectral radius at infinity}
//
// For $\Omega\to\infty$, $\rho = (1+\alpha)/(1-\alpha)$. The eigenvalues of
// $\mathbf A(\Omega)$ differ from their limits by $O(\Omega^{-2})$ for a
// simple root, but a $k$-fold root with a Jordan block moves by the $k$-th
// root of the perturbation: by $O(\Omega^{-1})$ for the double root
// $-\rho_\infty$ (the modulus of the complex pair still converges like
// $\Omega^{-2}$) and, at $\alpha=-1/3$ where all three roots meet at
// $-1/2$, by $O(\Omega^{-2/3})$ and by the cube root of the round-off,
// $\epsilon^{1/3}\approx 6\cdot 10^{-6}$. At $\Omega = 10^6$ we therefore
// require $10^{-6}$ for $-1/3 < \alpha\le 0$, and only $3\Omega^{-2/3} =
// 3\cdot 10^{-4}$ for $\alpha = -1/3$. For every $\alpha$ the well-conditioned
// coefficients of the characteristic polynomial $\lambda^3 - I_1\lambda^2 +
// I_2\lambda - I_3$ (trace, sum of principal minors, determinant) converge
// to those of $(\lambda+\rho_\infty)^2(\lambda - \alpha/(1+\alpha))$ like
// $c\,\Omega^{-2}$. The trace of the trapezoidal rule, $2(1-\Omega^2/4)/(1 +
// \Omega^2/4) = -2 + 16\Omega^{-2} + \ldots$, shows that $c\approx 16$,
// i.e. $1.6\cdot 10^{-11}$ at $\Omega = 10^6$; we require $10^{-10}$.
TEST(HHTStepper, SpectralRadiusAtInfinity)
{
  const double Omega                 = 1e6;
  double       worst_radius_error    = 0.;
  double       worst_invariant_error = 0.;
  for (const double alpha : standard_alphas)
    {
      SCOPED_TRACE("alpha = " + std::to_string(alpha));
      const HHTStepper   stepper(alpha);
      const double       rho_infinity = (1. + alpha) / (1. - alpha);
      const Tensor<2, 3> A            = stepper.amplification_matrix(Omega);

      const bool   triple_root = (alpha == -1. / 3.);
      const double tolerance =
        triple_root ? 3. * std::pow(Omega, -2. / 3.) : 1e-6;
      const double radius_error =
        std::abs(spectral_radius_of(A) - rho_infinity);
      EXPECT_LE(radius_error, tolerance);
      EXPECT_LE(std::abs(stepper.spectral_radius(Omega) - rho_infinity),
                tolerance);
      if (!triple_root)
        worst_radius_error = std::max(worst_radius_error, radius_error);

      const double spurious_root = alpha / (1. + alpha);
      const double I1            = A[0][0] + A[1][1] + A[2][2];
      const double I2            = A[0][0] * A[1][1] - A[0][1] * A[1][0] +
                        A[0][0] * A[2][2] - A[0][2] * A[2][0] +
                        A[1][1] * A[2][2] - A[1][2] * A[2][1];
      const double I3 = determinant(A);
      const double invariant_error =
        std::max({std::abs(I1 - (-2. * rho_infinity + spurious_root)),
                  std::abs(I2 - (rho_infinity * rho_infinity -
                                 2. * rho_infinity * spurious_root)),
                  std::abs(I3 - rho_infinity * rho_infinity * spurious_root)});
      EXPECT_LE(invariant_error, 1e-10);
      worst_invariant_error = std::max(worst_invariant_error, invariant_error);
    }
  std::cout << "  rho(1e6): worst error (alpha > -1/3) " << worst_radius_error
            << ", alpha = -1/3 "
            << std::abs(spectral_radius_of(
                          HHTStepper(-1. / 3.).amplification_matrix(Omega)) -
                        0.5)
            << ", worst invariant error " << worst_invariant_error << std::endl;
}



// @sect4{Period error and algorithmic damping for small $\Omega$}
//
// At $\Omega = 0.01$ the numbers must agree with the leading terms
// $p_2\Omega^2$ and $d_3\Omega^3$. The relative truncation error of the
// leading term is $|p_4/p_2|\Omega^2\le 1.6\cdot10^{-5}$ and
// $|d_5/d_3|\Omega^2 \le 5.5\cdot 10^{-5}$ for the $\alpha$ tested; the
// round-off in $\bar\xi$ is about $10^{-14}/(d_3\Omega^4) \le 2\cdot 10^{-4}$
// (for $\alpha = -0.05$, see the introduction). The tolerance $10^{-3}$
// covers both with a margin of five.
//
// The two-term expansions $p_2\Omega^2 + p_4\Omega^4$ and $d_3\Omega^3 +
// d_5\Omega^5$ are checked at $\Omega = 0.1$, where the next-order terms are
// large enough to be seen and the round-off is small: the error must be
// below twice the first neglected term, $2|p_6|\Omega^6$ and $2|d_7|\Omega^7$
// (the terms after it are smaller by another factor $\approx\Omega^2$),
// plus $10^{-14}$ for the round-off.
TEST(HHTStepper, PeriodErrorAndDampingAsymptotics)
{
  double worst_period_ratio_error    = 0.;
  double worst_damping_ratio_error   = 0.;
  double worst_period_two_term_error = 0.;
  double worst_damp_two_term_error   = 0.;
  for (const double alpha : standard_alphas)
    {
      SCOPED_TRACE("alpha = " + std::to_string(alpha));
      const HHTStepper stepper(alpha);

      const double small_Omega = 0.01;
      const double period_ratio =
        period_error(stepper, small_Omega) /
        (period_error_coefficient_2(alpha) * std::pow(small_Omega, 2));
      EXPECT_NEAR(period_ratio, 1., 1e-3);
      worst_period_ratio_error =
        std::max(worst_period_ratio_error, std::abs(period_ratio - 1.));
      if (alpha != 0.)
        {
          const double damping_ratio =
            principal_root(stepper, small_Omega).xi_bar /
            (damping_coefficient_3(alpha) * std::pow(small_Omega, 3));
          EXPECT_NEAR(damping_ratio, 1., 1e-3);
          worst_damping_ratio_error =
            std::max(worst_damping_ratio_error, std::abs(damping_ratio - 1.));
        }

      const double Omega = 0.1;
      const double period_two_term =
        period_error_coefficient_2(alpha) * std::pow(Omega, 2) +
        period_error_coefficient_4(alpha) * std::pow(Omega, 4);
      const double period_two_term_error =
        std::abs(period_error(stepper, Omega) - period_two_term);
      EXPECT_LE(period_two_term_error,
                2. * std::abs(period_error_coefficient_6(alpha)) *
                    std::pow(Omega, 6) +
                  1e-14);
      worst_period_two_term_error =
        std::max(worst_period_two_term_error, period_two_term_error);

      const double damping_two_term =
        damping_coefficient_3(alpha) * std::pow(Omega, 3) +
        damping_coefficient_5(alpha) * std::pow(Omega, 5);
      const double damping_two_term_error =
        std::abs(principal_root(stepper, Omega).xi_bar - damping_two_term);
      EXPECT_LE(damping_two_term_error,
                2. * std::abs(damping_coefficient_7(alpha)) *
                    std::pow(Omega, 7) +
                  1e-14);
      worst_damp_two_term_error =
        std::max(worst_damp_two_term_error, damping_two_term_error);
    }
  std::cout << "  Omega = 0.01: worst |numeric/asymptote - 1|: period "
            << worst_period_ratio_error << ", damping "
            << worst_damping_ratio_error << std::endl
            << "  Omega = 0.1: worst error of the two-term series: period "
            << worst_period_two_term_error << ", damping "
            << worst_damp_two_term_error << std::endl;
}



// @sect4{The trapezoidal rule}
//
// For $\alpha = 0$ the period error is exactly $\Omega/(2\arctan(\Omega/2))
// - 1$ and there is no damping. The eigenvalues are accurate to $\epsilon$
// times their condition number $\approx 1/(2\Omega)$, so $\bar\Omega$ to
// $\approx 10^{-14}$ and the period error, $\Omega/\bar\Omega^2$ times that,
// to $\approx 10^{-12}$ over $0.01\le\Omega\le 100$: we require
// $10^{-10}$. $\bar\xi = -\ln|\lambda_1|/\bar\Omega$ has the round-off
// $10^{-14}/\bar\Omega$, below $10^{-12}$ for $\Omega\ge 0.1$, where we
// require $10^{-12}$.
TEST(HHTStepper, TrapezoidalRuleIsExact)
{
  const HHTStepper stepper(0.);
  double           worst_period_error  = 0.;
  double           worst_damping_ratio = 0.;
  for (const double Omega : {0.01, 0.03, 0.1, 0.3, 1., 2., 3., 10., 100.})
    {
      SCOPED_TRACE("Omega = " + std::to_string(Omega));
      const double exact_period_error =
        Omega / (2. * std::atan(Omega / 2.)) - 1.;
      const double error =
        std::abs(period_error(stepper, Omega) - exact_period_error);
      EXPECT_LE(error, 1e-10);
      worst_period_error = std::max(worst_period_error, error);
      if (Omega >= 0.1)
        {
          const double xi_bar = principal_root(stepper, Omega).xi_bar;
          EXPECT_LE(std::abs(xi_bar), 1e-12);
          worst_damping_ratio = std::max(worst_damping_ratio, std::abs(xi_bar));
        }
    }
  std::cout << "  alpha = 0: worst period error deviation "
            << worst_period_error << ", worst |xi_bar| " << worst_damping_ratio
            << std::endl;
}



// @sect4{One step equals the amplification matrix}
//
// The stepping of step_oscillator() and $\mathbf A(\Omega, \xi)$ applied to
// the scaled state must agree up to round-off: both evaluate the same
// rational functions of $\Omega$ with a handful of operations, and the
// conditioning of the scalar solve is benign (the effective stiffness is
// dominated by $1/(\beta\Delta t^2)$ for small and by $(1+\alpha)\omega^2$ for
// large $\Omega$, both without cancellation). We require $10^{-12}$ relative
// to the norm of the scaled state, several hundred $\epsilon$. Tested for
// unit states and a generic one, for the standard family, the reference
// study's parameters and a conditionally stable Newmark scheme, with and
// without physical damping, $10^{-2}\le\Omega\le 10^6$.
TEST(HHTStepper, OneStepEqualsAmplificationMatrix)
{
  std::vector<HHTStepper> steppers;
  for (const double alpha : standard_alphas)
    steppers.emplace_back(alpha);
  steppers.emplace_back(reference_alpha, reference_beta, reference_gamma);
  steppers.emplace_back(0., 0.2, 0.75);

  const double                       omega  = 2. * numbers::PI * 3.; // 3 Hz
  const std::vector<OscillatorState> states = {{1., 0., 0.},
                                               {0., 1., 0.},
                                               {0., 0., 1.},
                                               {0.3, -1.7, 25.}};
  double                             worst_error = 0.;
  for (const HHTStepper &stepper : steppers)
    for (const double Omega : {0.01, 0.3, 1., 4., 100., 1e6})
      for (const double xi : {0., 0.05, 0.7})
        for (const OscillatorState &state : states)
          {
            SCOPED_TRACE(stepper.description() +
                         ", Omega = " + std::to_string(Omega) +
                         ", xi = " + std::to_string(xi));
            const double dt = Omega / omega;

            const OscillatorState new_state =
              step_oscillator(stepper, omega, xi, dt, state);
            const Tensor<1, 3> stepped{
              {new_state.u, dt * new_state.v, dt * dt * new_state.a}};

            const Tensor<1, 3> old_scaled{
              {state.u, dt * state.v, dt * dt * state.a}};
            const Tensor<1, 3> predicted =
              stepper.amplification_matrix(Omega, xi) * old_scaled;

            const double error = (stepped - predicted).norm() /
                                 std::max(old_scaled.norm(), predicted.norm());
            EXPECT_LE(error, 1e-12);
            worst_error = std::max(worst_error, error);
          }
  std::cout << "  one step vs amplification matrix: worst relative error "
            << worst_error << std::endl;
}



// @sect4{Stability}
//
// The standard family is unconditionally stable for $-1/3\le\alpha\le 0$
// (Hughes, section 9.3). The reference study keeps $\gamma = 1/2-\alpha$
// and takes $\beta = 0.4$ slightly above $(1-\alpha)^2/4 = 0.390625$, the
// analogue of Newmark's condition $\beta\ge(\gamma+1/2)^2/4$ for complex
// high-frequency roots; it should stay unconditionally stable (with
// $\rho_\infty \approx 0.612$ instead of $0.6$), which the matrix
// must confirm. Newmark's method ($\alpha = 0$) with $2\beta < \gamma$ is
// only conditionally stable: a real eigenvalue passes $-1$ at the undamped
// critical step $\Omega_\text{crit} = (\gamma/2-\beta)^{-1/2}$, which is
// $2.39$ for $\beta = 0.2$, $\gamma = 0.75$. With $\alpha = -0.25$ the same
// $\beta$, $\gamma$ are unstable as well ($\rho\to 4.3$ for
// $\Omega\to\infty$).
//
// Besides the stepper's own verdict we scan the spectral radius over
// $10^{-4}\le\Omega\le 10^6$, 50 points per decade, and accept $1 +
// 10^{-9}$. The round-off in the moduli is largest for the nearly defective
// principal pairs at both ends of the range, where the condition number of
// the pair is the inverse of its separation: $1/(2\Omega) = 5\cdot 10^3$ at
// $\Omega = 10^{-4}$, and $\Omega/8\approx 10^5$ at $\Omega = 10^6$ for
// the trapezoidal rule, whose pair $-1\pm 4i/\Omega$ closes in on $-1$. The
// bound $10^5\epsilon\approx 2\cdot 10^{-11}$ is well below the
// tolerance.
TEST(HHTStepper, Stability)
{
  const auto scanned_maximal_radius = [](const HHTStepper &stepper) {
    double radius = 0.;
    for (int i = -200; i <= 300; ++i)
      radius = std::max(radius,
                        spectral_radius_of(stepper.amplification_matrix(
                          std::pow(10., i / 50.))));
    return radius;
  };

  for (const double alpha : standard_alphas)
    {
      SCOPED_TRACE("alpha = " + std::to_string(alpha));
      const HHTStepper stepper(alpha);
      EXPECT_TRUE(stepper.is_standard_family());
      EXPECT_TRUE(stepper.is_unconditionally_stable());
      EXPECT_LE(scanned_maximal_radius(stepper), 1. + 1e-9);

      const HHTStepper explicit_standard(alpha,
                                         (1. - alpha) * (1. - alpha) / 4.,
                                         0.5 - alpha);
      EXPECT_TRUE(explicit_standard.is_standard_family());
    }

  const HHTStepper reference(reference_alpha, reference_beta, reference_gamma);
  EXPECT_FALSE(reference.is_standard_family());
  EXPECT_TRUE(reference.is_unconditionally_stable());
  EXPECT_LE(scanned_maximal_radius(reference), 1. + 1e-9);

  const HHTStepper newmark(0., 0.2, 0.75);
  EXPECT_FALSE(newmark.is_standard_family());
  EXPECT_FALSE(newmark.is_unconditionally_stable());
  const double Omega_critical = 1. / std::sqrt(0.75 / 2. - 0.2);
  EXPECT_LE(spectral_radius_of(
              newmark.amplification_matrix(0.99 * Omega_critical)),
            1.);
  EXPECT_GT(spectral_radius_of(
              newmark.amplification_matrix(1.01 * Omega_critical)),
            1.);

  const HHTStepper damped_newmark(reference_alpha, 0.2, 0.75);
  EXPECT_FALSE(damped_newmark.is_unconditionally_stable());
  EXPECT_GT(spectral_radius_of(damped_newmark.amplification_matrix(1e6)), 1.);

  std::cout
    << std::setprecision(16) << "  scanned max spectral radius: alpha = 0: "
    << scanned_maximal_radius(HHTStepper(0.))
    << ", alpha = -1/3: " << scanned_maximal_radius(HHTStepper(-1. / 3.))
    << ", reference study: " << scanned_maximal_radius(reference)
    << "; Newmark beta = 0.2, gamma = 0.75: rho(0.99 Omega_crit) = "
    << spectral_radius_of(newmark.amplification_matrix(0.99 * Omega_critical))
    << ", rho(1.01 Omega_crit) = "
    << spectral_radius_of(newmark.amplification_matrix(1.01 * Omega_critical))
    << std::setprecision(6) << std::endl;
}



// @sect4{The constructor checks $\alpha$}
TEST(HHTStepper, ConstructorRejectsAlphaOutsideRange)
{
  EXPECT_NO_THROW(HHTStepper(0.));
  EXPECT_NO_THROW(HHTStepper(-1. / 3.));
  EXPECT_NO_THROW(HHTStepper(reference_alpha, reference_beta, reference_gamma));
  for (const double alpha : {0.01, 0.5, -0.34, -0.5, -1.})
    {
      SCOPED_TRACE("alpha = " + std::to_string(alpha));
      EXPECT_ANY_THROW(HHTStepper{alpha});
      EXPECT_ANY_THROW(HHTStepper(alpha, 0.25, 0.5));
    }
}



// @sect4{Orders of the period error and the damping}
//
// The local slopes $s = \ln(e(0.02)/e(0.01))/\ln 2$ of the period error and
// of $\bar\xi$ must be 2 and 3. With $e = c\,\Omega^q(1 + r\Omega^2)$ the
// next-order term shifts the slope by $r\,(0.02^2 - 0.01^2)/\ln 2$, at most
// $7\cdot 10^{-5}$ ($r = p_4/p_2$) and $2.4\cdot 10^{-4}$ ($r = d_5/d_3$)
// for the $\alpha$ tested; the round-off of $\bar\xi$ at $\Omega = 0.01$
// (relative $2\cdot 10^{-4}$, see above) by $3\cdot 10^{-4}$. The
// tolerance $\pm 0.05$ is generous, but it is what separates the orders.
TEST(HHTStepper, OrdersOfPeriodErrorAndDamping)
{
  double worst_period_slope_error  = 0.;
  double worst_damping_slope_error = 0.;
  for (const double alpha : standard_alphas)
    {
      SCOPED_TRACE("alpha = " + std::to_string(alpha));
      const HHTStepper stepper(alpha);
      const double     coarse = 0.02, fine = 0.01;

      const double period_slope =
        std::log(period_error(stepper, coarse) / period_error(stepper, fine)) /
        std::log(coarse / fine);
      EXPECT_NEAR(period_slope, 2., 0.05);
      worst_period_slope_error =
        std::max(worst_period_slope_error, std::abs(period_slope - 2.));

      if (alpha != 0.)
        {
          const double damping_slope =
            std::log(principal_root(stepper, coarse).xi_bar /
                     principal_root(stepper, fine).xi_bar) /
            std::log(coarse / fine);
          EXPECT_NEAR(damping_slope, 3., 0.05);
          worst_damping_slope_error =
            std::max(worst_damping_slope_error, std::abs(damping_slope - 3.));
        }
    }
  std::cout << "  log-log slopes: worst |slope - 2| (period) "
            << worst_period_slope_error << ", worst |slope - 3| (damping) "
            << worst_damping_slope_error << std::endl;
}
