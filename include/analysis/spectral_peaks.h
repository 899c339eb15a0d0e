// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Peaks of the spectrum and their half-power bandwidths}
//
// Implemented in source/analysis/spectral_peaks.cc.
//
// The peaks of a zero-padded magnitude spectrum that are resonances rather
// than noise, shoulders or side lobes of the truncation, each with its
// half-power (-3 dB) crossings, bandwidth, quality factor and half-power
// damping ratio as the reference study computed it,
// @f[
//   Q = \frac{f_\text{peak}}{f_+ - f_-}, \qquad \xi = \frac{1}{2Q}.
// @f]

#ifndef soft_robot_analysis_spectral_peaks_h
#define soft_robot_analysis_spectral_peaks_h

#include <analysis/spectrum.h>
#include <string>
#include <vector>

namespace SoftRobot
{
  namespace Analysis
  {
    // @sect4{A peak}
    //
    // One peak of the magnitude spectrum with its half-power bandwidth,
    // and, if the modal fit succeeded, the damped mode fitted to it (filled
    // in by analyse_signal(), see signal_analysis.h). All frequencies are in
    // Hz; quantities that could not be determined are NaN. The magnitude is
    // that of the amplitude spectrum (a steady sinusoid of amplitude $A$ has
    // a peak of height $A$).
    //
    // <code>frequency</code> is the peak of the spectrum, as the study used
    // it. It estimates the damped frequency $f_d = f_n\sqrt{1-\xi^2}$, and in
    // records of few cycles the leakage of the negative-frequency image
    // shifts it by up to about $0.3/(fT)^2$ relative (0.5 % for 5 cycles);
    // <code>fitted_natural_frequency</code> has neither error and is the
    // recommended frequency.
    struct SpectralPeak
    {
      double frequency                  = 0.;
      double magnitude                  = 0.;
      double lower_half_power_frequency = 0.;
      double upper_half_power_frequency = 0.;
      double bandwidth                  = 0.;
      double quality_factor             = 0.;
      double damping_ratio_half_power   = 0.;

      // Relative error of <code>damping_ratio_half_power</code> that the
      // truncation of the record causes for a single damped mode, i.e.
      // $\xi_\text{half power}/\xi - 1$ predicted by the theory in
      // truncation_theory.cc (from the fitted decay if available, otherwise
      // from the measured bandwidth).
      double half_power_truncation_bias = 0.;

      bool   fit_valid                = false;
      double fitted_damped_frequency  = 0.;
      double fitted_natural_frequency = 0.;
      double fitted_damping_ratio     = 0.;
      double fitted_amplitude         = 0.;
    };



    // @sect4{The search}
    //
    // The peaks of <code>magnitude</code> (bins <code>frequency_step</code>
    // Hz apart, of a record of <code>duration</code> seconds, transformed
    // with <code>window</code>) by decreasing magnitude: the dominant one
    // first, then at most <code>max_secondary_peaks</code> others that reach
    // <code>secondary_peak_threshold</code> times its magnitude and rise
    // above the leakage of the larger ones. Only the spectral quantities of
    // each peak are set. If there is no peak, <code>reason_if_none</code>
    // says why.
    struct PeakSearchResult
    {
      std::vector<SpectralPeak> peaks;
      std::string               reason_if_none;
    };

    PeakSearchResult
    find_spectral_peaks(const std::vector<double> &magnitude,
                        const double               frequency_step,
                        const double               duration,
                        const SpectralWindow       window,
                        const double               secondary_peak_threshold,
                        const unsigned int         max_secondary_peaks);
  } // namespace Analysis
} // namespace SoftRobot

#endif
