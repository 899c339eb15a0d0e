// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Tests of the damped-mode fit}
//
// fit_damped_modes() (source/analysis/modal_fit.cc) minimises the misfit of
// the model
// @f[
//   u(t) \approx c_0 + c_1\left(\frac tT-\frac12\right)
//     + \sum_k e^{-\sigma_k t}(a_k\cos\omega_k t + b_k\sin\omega_k t)
// @f]
// by variable projection and Levenberg--Marquardt, with every linear solve
// done by LAPACK. For a record that is exactly of this form the minimum is
// the truth with a zero residual, and Levenberg--Marquardt converges to it
// quadratically (a zero-residual problem is Gauss--Newton's best case). The
// fit must therefore recover the parameters to round-off, not merely to the
// accuracy the analysis needs; the tolerances below are $10^{-13}$
// relative, about 450 times the machine epsilon (the errors measured are
// below $10^{-14}$). The fit is called directly here,
// without the spectral peak search, from starting points that are
// deliberately off.

// Not typed on the dimension: the fit is of one signal of time.

#include <analysis/modal_fit.h>
#include <cmath>
#include <gtest/gtest.h>
#include <string>
#include <vector>

namespace
{
  using namespace SoftRobot::Analysis;

  constexpr double pi = 3.14159265358979323846;

  struct Mode
  {
    double decay_rate;        // sigma, 1/s
    double angular_frequency; // omega_d, rad/s
    double amplitude;
    double phase;
  };

  // The record $u(t_i)$, $t_i = i/f_s$, of the model with the given modes, a
  // constant and a linear drift.
  std::vector<double>
  sample(const std::vector<Mode> &modes,
         const double             constant,
         const double             drift,
         const double             duration,
         const double             sample_rate)
  {
    const std::size_t   n = std::lround(duration * sample_rate);
    std::vector<double> samples(n);
    for (std::size_t i = 0; i < n; ++i)
      {
        const double t = i / sample_rate;
        samples[i]     = constant + drift * t;
        for (const Mode &mode : modes)
          samples[i] += mode.amplitude * std::exp(-mode.decay_rate * t) *
                        std::cos(mode.angular_frequency * t + mode.phase);
      }
    return samples;
  }

  // A spectral peak as the peak search would report it: only the frequency
  // and the bandwidth are used by the fit.
  SpectralPeak
  peak_at(const double frequency, const double bandwidth)
  {
    SpectralPeak peak;
    peak.frequency = frequency;
    peak.bandwidth = bandwidth;
    return peak;
  }
} // namespace



// @sect3{One mode with offset and drift}
//
// $f_d = 2$ Hz, $\xi \approx 0.02$, 5.25 s at 240 Hz (the study's record),
// with an offset and a drift that the trend columns must absorb. The fit
// starts 1 % off in frequency and with a bandwidth twice the Lorentzian one.
TEST(ModalFit, RecoversOneDampedModeToRoundOff)
{
  const Mode                mode    = {0.2513, 2. * pi * 2., 0.03, 0.4};
  const double              T       = 5.25;
  const std::vector<double> samples = sample({mode}, 0.12, -4e-3, T, 240.);

  const ModalFit fit =
    fit_damped_modes(samples, 240., {peak_at(2.02, 2. * mode.decay_rate / pi)});
  ASSERT_TRUE(fit.valid) << fit.reason;
  ASSERT_EQ(fit.decay_rates.size(), 1u);
  EXPECT_NEAR(fit.decay_rates[0], mode.decay_rate, 1e-13 * mode.decay_rate);
  EXPECT_NEAR(fit.angular_frequencies[0],
              mode.angular_frequency,
              1e-13 * mode.angular_frequency);
  EXPECT_NEAR(fit.amplitudes[0], mode.amplitude, 1e-13 * mode.amplitude);
  EXPECT_LT(fit.relative_residual, 1e-13);
}



// @sect3{Two modes fitted jointly}
//
// A 2 Hz and a 5.5 Hz mode of half the amplitude and more damping, 6 s at
// 100 Hz, started from peaks that are off by 0.5 % and 1 %. The joint fit
// must separate them to round-off.
TEST(ModalFit, RecoversTwoModesJointly)
{
  const std::vector<Mode>   modes   = {{0.2513, 2. * pi * 2., 0.03, 0.7},
                                       {1.0367, 2. * pi * 5.5, 0.015, -1.2}};
  const std::vector<double> samples = sample(modes, 0.2, 0., 6., 100.);

  const ModalFit fit =
    fit_damped_modes(samples,
                     100.,
                     {peak_at(2.01, 0.18), peak_at(5.445, 0.35)});
  ASSERT_TRUE(fit.valid) << fit.reason;
  ASSERT_EQ(fit.decay_rates.size(), 2u);
  for (unsigned int k = 0; k < 2; ++k)
    {
      SCOPED_TRACE("mode " + std::to_string(k));
      EXPECT_NEAR(fit.decay_rates[k],
                  modes[k].decay_rate,
                  1e-13 * modes[k].decay_rate);
      EXPECT_NEAR(fit.angular_frequencies[k],
                  modes[k].angular_frequency,
                  1e-13 * modes[k].angular_frequency);
      EXPECT_NEAR(fit.amplitudes[k],
                  modes[k].amplitude,
                  1e-13 * modes[k].amplitude);
    }
  EXPECT_LT(fit.relative_residual, 1e-13);
}



// @sect3{A mode that leaves its band}
//
// A strongly damped 2 Hz mode ($\xi = 0.1$) fitted from a "peak" at 2.3 Hz
// with a bandwidth of 0.1 Hz: the fit finds the mode at $f_d = 1.99$ Hz,
// more than the allowed $\max(B, 1/T) = 0.19$ Hz away from where it
// started, and must say so instead of reporting it as the mode of that
// peak.
TEST(ModalFit, RejectsAModeThatMovesOutOfItsBand)
{
  const double omega_n = 2. * pi * 2., xi = 0.1;
  const Mode   mode = {xi * omega_n, omega_n * std::sqrt(1. - xi * xi), 1., 0.};
  const std::vector<double> samples = sample({mode}, 0., 0., 5.25, 240.);

  const ModalFit fit = fit_damped_modes(samples, 240., {peak_at(2.3, 0.1)});
  EXPECT_FALSE(fit.valid);
  EXPECT_NE(fit.reason.find("outside its half-power band"), std::string::npos)
    << fit.reason;
  ASSERT_EQ(fit.angular_frequencies.size(), 1u);
  EXPECT_NEAR(fit.angular_frequencies[0],
              mode.angular_frequency,
              1e-13 * mode.angular_frequency);
}
