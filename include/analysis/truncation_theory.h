// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Truncation theory of the half-power bandwidth}
//
// Implemented in source/analysis/truncation_theory.cc, which also explains
// the theory.
//
// For a single mode $e^{-\sigma t}\cos(\omega_d t)$ recorded for $T$ seconds
// the half-power bandwidth $B$ depends only on the decay exponent
// $s = \sigma T$ and on the window; the exact (Lorentzian) value would be
// $B T = s/\pi$. For $s \to 0$, $BT \to 0.886$ (no window) and $1.441$
// (Hann): the width of the main lobe of an undamped record. The functions
// below evaluate this dependence, invert it, and describe the side lobes of
// the same truncated spectrum, which the peak search needs to tell a second
// mode from leakage.

#ifndef soft_robot_analysis_truncation_theory_h
#define soft_robot_analysis_truncation_theory_h

#include <analysis/spectrum.h>

namespace SoftRobot
{
  namespace Analysis
  {
    // The dimensionless half-power width $B\,T$ of a truncated decay with
    // the decay exponent $s = \sigma T \ge 0$.
    double
    truncated_decay_half_power_width(const double         decay_exponent,
                                     const SpectralWindow window);

    // The relative bias $\pi B T / s - 1$ of the half-power damping ratio,
    // for $s > 0$.
    double
    half_power_truncation_bias(const double         decay_exponent,
                               const SpectralWindow window);

    // The inverse of truncated_decay_half_power_width(): the decay exponent
    // $s$ whose half-power width is the measured $BT$, or NaN if $BT$ does
    // not exceed the width of an undamped record.
    double
    decay_exponent_from_half_power_width(const double         width,
                                         const SpectralWindow window);

    // The magnitude of the dimensionless spectrum
    // $\int_0^1 w(\tau)\,e^{-(s+iw)\tau}\,d\tau$ of a decay on the unit
    // interval at the frequency offset $w$ from the carrier.
    double
    truncated_decay_spectrum(const double         frequency_offset,
                             const double         decay_exponent,
                             const SpectralWindow window);

    // The largest magnitude of that spectrum within one ripple period
    // ($\pm\pi$) of the offset $w$, relative to its peak at $w = 0$: the
    // envelope of the side lobes there.
    double
    side_lobe_envelope(const double         frequency_offset,
                       const double         decay_exponent,
                       const SpectralWindow window);
  } // namespace Analysis
} // namespace SoftRobot

#endif
