// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Fitting damped modes}
//
// Implemented in source/analysis/modal_fit.cc, which also explains the
// method.
//
// A least-squares fit of a sum of exponentially damped sinusoids, plus a
// constant and a linear trend, to a uniformly sampled record. It is the
// time-domain form of fitting the truncated Lorentzian to the complex
// spectrum, unbiased for short records, and therefore the recommended
// damping estimate of the analysis.

#ifndef soft_robot_analysis_modal_fit_h
#define soft_robot_analysis_modal_fit_h

#include <analysis/spectral_peaks.h>
#include <analysis/utilities.h>
#include <string>
#include <vector>

namespace SoftRobot
{
  namespace Analysis
  {
    // The fitted modes, one per spectral peak that the fit started from and
    // in the same order: decay rate $\sigma_k$ (1/s), damped angular
    // frequency $\omega_k$ (rad/s) and amplitude
    // $\sqrt{a_k^2+b_k^2}$ of $e^{-\sigma_k t}(a_k\cos\omega_k t +
    // b_k\sin\omega_k t)$ at $t = 0$, in the units of the signal.
    // <code>relative_residual</code> is the root mean square of the
    // residual over that of the signal about its mean. If a mode left its
    // peak or the fit broke down, <code>valid</code> is false and
    // <code>reason</code> says why; the numbers are then still those of the
    // best minimum found.
    struct ModalFit
    {
      bool                valid = false;
      std::string         reason;
      std::vector<double> decay_rates;
      std::vector<double> angular_frequencies;
      std::vector<double> amplitudes;
      double              relative_residual = internal::not_a_number;
    };

    // Fit one damped mode per entry of <code>peaks</code> (of which only the
    // frequency and the bandwidth are used, as the starting point and to
    // check the result) to <code>signal</code>, sampled at
    // <code>sample_rate</code> Hz from $t = 0$.
    ModalFit
    fit_damped_modes(const std::vector<double>       &signal,
                     const double                     sample_rate,
                     const std::vector<SpectralPeak> &peaks);
  } // namespace Analysis
} // namespace SoftRobot

#endif
