// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Truncation theory of the half-power bandwidth}
//
// The one piece of theory that decides how the numbers of the analysis must
// be read: what truncation does to the half-power bandwidth.
//
// <h4>Truncation of a free decay</h4>
//
// A single mode with natural angular frequency $\omega_n$ and damping ratio
// $\xi$ decays as
// @f[
//   u(t) = A\,e^{-\sigma t}\cos(\omega_d t + \varphi), \qquad
//   \sigma = \xi\omega_n, \quad \omega_d = \omega_n\sqrt{1-\xi^2}.
// @f]
// Recorded for $0\le t\le T$ and away from $\omega=0$, its Fourier transform
// is dominated by the positive-frequency half,
// @f[
//   \hat u(\omega) \approx \frac{A}{2}e^{i\varphi}
//     \int_0^T e^{-(\sigma + i(\omega-\omega_d))t}\,dt
//   = \frac{A T}{2}e^{i\varphi}\,E(s + i w), \qquad
//   E(z) = \frac{1-e^{-z}}{z},
// @f]
// with the dimensionless decay exponent $s = \sigma T$ and frequency offset
// $w = (\omega-\omega_d)T$. For $T\to\infty$, $|E| \propto 1/|s+iw|$ is the
// Lorentzian: it falls to $1/\sqrt2$ at $w=\pm s$, so the half-power
// bandwidth is $B = \sigma/\pi = 2\xi f_n$ and $\xi = B/(2f) = 1/(2Q)$ --
// the study's formula. For finite $T$ the factor $1-e^{-z}$ is the
// convolution of the Lorentzian with the $\operatorname{sinc}$ of the
// rectangular record, and for $s\to0$ the peak keeps the width of the sinc
// main lobe, $B T = 0.886$, however small the damping. The half-power width
// $BT$ depends on $s$ alone (function truncated_decay_half_power_width()
// below); the relative bias of the half-power damping ratio, $\pi BT/s - 1$,
// is
//
// <table>
// <tr><td>$s=\sigma T$</td><td>1</td><td>2</td><td>3</td><td>4</td>
//     <td>5</td><td>6</td></tr>
// <tr><td>$BT$ measured</td><td>0.913</td><td>0.996</td><td>1.138</td>
//     <td>1.343</td><td>1.606</td><td>1.910</td></tr>
// <tr><td>bias of $\xi$, no window</td><td>+187 %</td><td>+56 %</td>
//     <td>+19 %</td><td>+5.5 %</td><td>+0.9 %</td><td>0.0 %</td></tr>
// <tr><td>bias of $\xi$, Hann</td><td>+355 %</td><td>+131 %</td>
//     <td>+58 %</td><td>+23 %</td><td>+2.5 %</td><td>-10 %</td></tr>
// </table>
//
// (for $s\to\infty$ the bias vanishes without window, but with the Hann
// window, which suppresses the early, large part of the decay, it tends to
// $\sqrt{2^{1/3}-1}-1 = -49\,\%$). Since
// $s = \xi\omega_n T \approx 2\pi\xi N_\text{cycles}$ with
// $N_\text{cycles} = f T$, the half-power value is within 5 % only if
// $\xi N_\text{cycles} \gtrsim 0.64$, i.e. if the amplitude has decayed to
// $e^{-4}\approx 2\,\%$ by the end of the record. The study's example
// $f=2$ Hz, $\xi=0.02$, $T=5$ s has $s=1.26$ and its half-power damping
// ratio is 2.3 times too large.
//
// <i>The criterion for the warning.</i> Because $BT$ is a monotone function
// of $s$, the measured bandwidth alone tells whether the record was long
// enough: the half-power damping is biased by less than 5 % only if
// $B \ge 1.34/T$, i.e. if the bandwidth exceeds the resolution $1/T$ of the
// unpadded record by a third; if $B \le 0.886/T$ (the main lobe of an
// undamped record) the damping is not resolved at all. The analysis
// computes the predicted bias for every peak (from the fitted decay, or by
// inverting $BT(s)$) and warns if it exceeds 5 %. It still reports the
// half-power number unchanged, as the study did.
//
// <i>The correction.</i> Inverting $BT(s)$ would correct the bias, but the
// inversion is ill-conditioned exactly where the correction is large
// ($dBT/ds \to 0$ for $s\to0$), and it ignores the negative-frequency image
// and the leakage of the removed offset. The principled correction is to fit
// the truncated model itself: by Parseval's identity, the least-squares
// misfit of the damped-mode model in the time domain over $[0,T]$ equals
// the misfit of its spectrum -- the Lorentzian convolved with the sinc,
// with image and offset -- to the measured complex spectrum. This fit
// (modal_fit.cc) is unbiased for any record length, and it is the
// recommended damping estimate. The logarithmic decrement (time_domain.cc)
// is exact for a single noise-free mode as well, and serves as an
// independent cross check.

#include <algorithm>
#include <analysis/truncation_theory.h>
#include <analysis/utilities.h>
#include <cmath>
#include <complex>
#include <stdexcept>

namespace SoftRobot
{
  namespace Analysis
  {
    using internal::format_number;
    using internal::pi;



    // @sect4{The spectrum of a truncated decay}
    //
    // The dimensionless spectrum of a decay $e^{-s\tau}$ on the unit
    // interval $0\le\tau\le1$, multiplied by the window $w(\tau)$, at the
    // offset $w$ from the carrier is
    // $\int_0^1 w(\tau)\,e^{-(s+iw)\tau}\,d\tau$. Without window this is
    // $E(s+iw)$; the Hann window
    // $w = \tfrac12 - \tfrac14 e^{2\pi i\tau} - \tfrac14 e^{-2\pi i\tau}$
    // gives three shifted copies of $E$. Near $z = 0$ the quotient
    // $(1-e^{-z})/z$ cancels, and the first four terms of its Taylor series
    // are used instead; for $|z| < 10^{-4}$ the omitted term is below
    // $10^{-18}$.
    namespace
    {
      std::complex<double>
      unit_interval_exponential_integral(const std::complex<double> z)
      {
        if (std::abs(z) < 1e-4)
          return 1. - z / 2. + z * z / 6. - z * z * z / 24.;
        return (1. - std::exp(-z)) / z;
      }
    } // namespace



    double
    truncated_decay_spectrum(const double         frequency_offset,
                             const double         decay_exponent,
                             const SpectralWindow window)
    {
      const std::complex<double> z(decay_exponent, frequency_offset);
      if (window == SpectralWindow::none)
        return std::abs(unit_interval_exponential_integral(z));

      const std::complex<double> shift(0., 2. * pi);
      return std::abs(0.5 * unit_interval_exponential_integral(z) -
                      0.25 * unit_interval_exponential_integral(z - shift) -
                      0.25 * unit_interval_exponential_integral(z + shift));
    }



    // @sect4{The half-power width and its inverse}
    //
    // Because the integrand at $w=0$ is non-negative, the magnitude is
    // largest at $w=0$, and the half-power half-width $w_h$ is found by
    // stepping away from $w=0$ and bisecting. The steps are $0.05(1+s)$:
    // small enough not to jump over the main lobe (whose half-width is at
    // least $2.78$, the undamped value, and grows like $s$), and few enough
    // for large $s$. Sixty bisections then fix $w_h$ to round-off. The full
    // width in Hz is $2w_h/(2\pi T)$, so $BT = w_h/\pi$.
    double
    truncated_decay_half_power_width(const double         decay_exponent,
                                     const SpectralWindow window)
    {
      if (!std::isfinite(decay_exponent) || decay_exponent < 0.)
        throw std::invalid_argument(
          "The decay exponent sigma*T must be finite and non-negative, but "
          "is " +
          format_number(decay_exponent) + ".");

      const double level =
        truncated_decay_spectrum(0., decay_exponent, window) / std::sqrt(2.);
      const double step  = 0.05 * (1. + decay_exponent);
      double       below = 0., above = step;
      while (truncated_decay_spectrum(above, decay_exponent, window) > level)
        {
          below = above;
          above += step;
        }
      for (unsigned int i = 0; i < 60; ++i)
        {
          const double middle = 0.5 * (below + above);
          if (truncated_decay_spectrum(middle, decay_exponent, window) > level)
            below = middle;
          else
            above = middle;
        }
      return 0.5 * (below + above) / pi;
    }



    // The bias follows from the width by its definition; it is not defined
    // for $s = 0$, where the exact width vanishes.
    double
    half_power_truncation_bias(const double         decay_exponent,
                               const SpectralWindow window)
    {
      if (!(decay_exponent > 0.))
        throw std::invalid_argument(
          "The truncation bias is defined for a positive decay exponent "
          "sigma*T only, but it is " +
          format_number(decay_exponent) + ".");
      return pi * truncated_decay_half_power_width(decay_exponent, window) /
               decay_exponent -
             1.;
    }



    // The inverse brackets $s$ by doubling and bisects as well; it relies on
    // $BT(s)$ increasing monotonically, which holds for both windows (the
    // table at the top of this file). A width within $10^{-6}$ of the
    // undamped one, or one that would need $s > 10^6$, has no meaningful
    // inverse and gives NaN.
    double
    decay_exponent_from_half_power_width(const double         width,
                                         const SpectralWindow window)
    {
      const double undamped_width =
        truncated_decay_half_power_width(0., window);
      if (!(width > undamped_width * (1. + 1e-6)))
        return internal::not_a_number;

      double lower = 0., upper = 1.;
      while (truncated_decay_half_power_width(upper, window) < width)
        {
          lower = upper;
          upper *= 2.;
          if (upper > 1e6)
            return internal::not_a_number;
        }
      for (unsigned int i = 0; i < 60; ++i)
        {
          const double middle = 0.5 * (lower + upper);
          if (truncated_decay_half_power_width(middle, window) < width)
            lower = middle;
          else
            upper = middle;
        }
      return 0.5 * (lower + upper);
    }



    // @sect4{The envelope of the side lobes}
    //
    // Beyond the main lobe the truncated spectrum is the Lorentzian tail
    // modulated by the ripple $1-e^{-s}e^{-iw}$ of period $2\pi$ in $w$. Its
    // largest value within one period around $w$, relative to the peak, is
    // what a side lobe near $w$ can reach; it is sampled at 65 points
    // across $[|w|-\pi, |w|+\pi]$ (offsets below zero are folded to zero,
    // the peak).
    double
    side_lobe_envelope(const double         frequency_offset,
                       const double         decay_exponent,
                       const SpectralWindow window)
    {
      const double peak_value =
        truncated_decay_spectrum(0., decay_exponent, window);
      const unsigned int n_points = 65;
      double             envelope = 0.;
      for (unsigned int i = 0; i < n_points; ++i)
        {
          const double w =
            std::abs(frequency_offset) + pi * (2. * i / (n_points - 1) - 1.);
          envelope = std::max(envelope,
                              truncated_decay_spectrum(std::max(w, 0.),
                                                       decay_exponent,
                                                       window));
        }
      return envelope / peak_value;
    }
  } // namespace Analysis
} // namespace SoftRobot
