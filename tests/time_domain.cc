// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Tests of the turning points and the logarithmic decrement}
//
// The line through the logarithms of the half-cycle amplitudes is a
// least-squares problem that LAPACK solves (source/analysis/time_domain.cc).
// For extrema whose half-cycle amplitudes decay exactly geometrically,
// $h_j = h_0 e^{-\delta j/2}$, the points lie on the line and the fitted
// decrement must be $\delta$ to round-off; the turning points of a sampled
// cosine must lie at its extrema.

// Not typed on the dimension: the decrement is of one signal of time.

#include <analysis/time_domain.h>
#include <cmath>
#include <gtest/gtest.h>
#include <vector>

namespace
{
  using namespace SoftRobot::Analysis;

  constexpr double pi = 3.14159265358979323846;
} // namespace



// @sect3{Exactly geometric extrema}
//
// Extrema $u_j = (-1)^j A e^{-\delta j/2}$, $\delta = 0.2$, ten samples
// apart: successive differences are $h_j = A e^{-\delta j/2}(1 +
// e^{-\delta/2})$, exactly geometric with ratio $e^{-\delta/2}$ per half
// cycle. The run starts at the largest $h_0$ and ends where $h_j$ falls
// below 10 % of it, at $j = 24$, so that 24 half cycles between 25 extrema
// enter the line. The line through $(j/2, \ln h_j)$ is exact,
// so the slope is $-\delta$ to a few $\epsilon$ of the logarithms
// (relative $10^{-13}$), and $\xi = \delta/\sqrt{4\pi^2+\delta^2}$.
TEST(LogarithmicDecrement, GeometricExtremaGiveTheExactDecrement)
{
  const double              delta = 0.2, amplitude = 3.;
  std::vector<TurningPoint> turning_points;
  for (unsigned int j = 0; j < 40; ++j)
    turning_points.push_back(
      {10. * j,
       (j % 2 == 0 ? 1. : -1.) * amplitude * std::exp(-delta * j / 2.)});

  const LogarithmicDecrement decrement =
    logarithmic_decrement_of(turning_points, 10., 0.);
  ASSERT_TRUE(decrement.valid) << decrement.reason;
  EXPECT_EQ(decrement.n_extrema, 25u);
  EXPECT_NEAR(decrement.decrement, delta, 1e-13);
  EXPECT_NEAR(decrement.damping_ratio,
              delta / std::sqrt(4. * pi * pi + delta * delta),
              1e-14);

  // Irregularly spaced extrema end the run: with the third one moved by half
  // a spacing, only the first half cycle qualifies, and the decrement is
  // refused with a reason.
  turning_points[2].position += 5.;
  const LogarithmicDecrement refused =
    logarithmic_decrement_of(turning_points, 10., 0.);
  EXPECT_FALSE(refused.valid);
  EXPECT_TRUE(std::isnan(refused.decrement));
  EXPECT_FALSE(refused.reason.empty());
}



// @sect3{Turning points of a sampled cosine}
//
// $\cos(2\pi t/T_p)$ with 40 samples per period: the extrema after the first
// sample lie at half periods, $i = 20, 40, \dots$, exactly on samples, where
// the parabola through three samples has its vertex on the middle one. The
// last extremum, on the final sample, has no right neighbour and is
// dropped, as is the one at the first sample.
TEST(TurningPoints, SampledCosineHasItsExtremaAtHalfPeriods)
{
  std::vector<double> signal(201);
  for (unsigned int i = 0; i < signal.size(); ++i)
    signal[i] = std::cos(2. * pi * i / 40.);

  const std::vector<TurningPoint> turning_points = find_turning_points(signal);
  ASSERT_EQ(turning_points.size(), 9u);
  for (unsigned int k = 0; k < turning_points.size(); ++k)
    {
      EXPECT_NEAR(turning_points[k].position, 20. * (k + 1), 1e-12);
      EXPECT_NEAR(turning_points[k].value, (k % 2 == 0 ? -1. : 1.), 1e-12);
    }

  EXPECT_TRUE(find_turning_points(std::vector<double>(50, 0.3)).empty());
}
