// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{The analysis of one signal}
//
// Implemented in source/analysis/signal_analysis.cc.
//
// Frequency and damping of one uniformly sampled signal (one direction of a
// tip trajectory): the spectral peaks with their half-power bandwidths as
// the reference study computed them, the bias that truncation theory
// predicts for those, the logarithmic decrement, and the modal fit, with a
// recommendation which damping ratio to use and warnings where a number
// should not be trusted.

#ifndef soft_robot_analysis_signal_analysis_h
#define soft_robot_analysis_signal_analysis_h

#include <analysis/spectral_peaks.h>
#include <analysis/spectrum.h>
#include <analysis/time_domain.h>
#include <analysis/utilities.h>
#include <string>
#include <vector>

namespace SoftRobot
{
  namespace Analysis
  {
    // @sect4{Options of the analysis}
    //
    // <code>OffsetRemoval</code>: the static offset that is subtracted
    // before the transform, either the mean of the record (default; it makes
    // the zero-frequency bin vanish exactly) or its final value (the
    // equilibrium position, if the oscillation has died out by the end of
    // the record).
    //
    // <code>window</code>: see SpectralWindow in spectrum.h; damping
    // estimates must be made without a window.
    //
    // <code>zero_padding_factor</code>: the FFT length is the smallest power
    // of two that is at least this factor times the number of samples, so
    // that the peak and the -3 dB crossings are interpolated on a fine grid.
    //
    // <code>secondary_peak_threshold</code>: a spectral peak other than the
    // dominant one is reported (and fitted) if its magnitude is at least
    // this fraction of the dominant one; at most
    // <code>max_secondary_peaks</code> such peaks are kept.
    //
    // <code>fit_damped_modes</code>: fit a damped mode to every reported
    // peak (the recommended damping estimate; switch it off only to save
    // time on long records).
    enum class OffsetRemoval
    {
      mean,
      final_value
    };

    struct SpectralOptions
    {
      OffsetRemoval  offset_removal           = OffsetRemoval::mean;
      SpectralWindow window                   = SpectralWindow::none;
      unsigned int   zero_padding_factor      = 16;
      double         secondary_peak_threshold = 0.1;
      unsigned int   max_secondary_peaks      = 3;
      bool           fit_damped_modes         = true;
    };



    // @sect4{Results}
    //
    // Which estimate <code>SpectralResult::damping_ratio</code> holds.
    enum class DampingEstimator
    {
      none,
      modal_fit,
      logarithmic_decrement,
      half_power
    };

    std::string
    to_string(const DampingEstimator estimator);

    // The result of the analysis of one signal. If the signal does not
    // oscillate, <code>has_peak</code> is false and
    // <code>no_peak_reason</code> says why; the spectrum is still filled in.
    // Otherwise the dominant peak and any secondary peaks (by decreasing
    // magnitude) are given, and <code>damping_ratio</code> is the
    // recommended estimate: the modal fit if it is valid, else the
    // logarithmic decrement, else the half-power value.
    struct SpectralResult
    {
      bool        has_peak = false;
      std::string no_peak_reason;

      SpectralPeak              dominant_peak;
      std::vector<SpectralPeak> secondary_peaks;
      LogarithmicDecrement      logarithmic_decrement;

      double           damping_ratio     = internal::not_a_number;
      DampingEstimator damping_estimator = DampingEstimator::none;

      // Root mean square of the fit residual over that of the signal.
      double fit_relative_residual = 0.;

      unsigned int n_samples            = 0;
      unsigned int fft_length           = 0;
      unsigned int n_turning_points     = 0;
      double       sample_rate          = 0.;
      double       duration             = 0.; // T = n_samples / sample_rate
      double       frequency_resolution = 0.; // 1/T
      double       n_cycles             = 0.; // f_peak T
      double       removed_offset       = 0.;

      std::vector<std::string> warnings;

      // The zero-padded magnitude (amplitude) spectrum for plotting.
      std::vector<double> frequencies;
      std::vector<double> magnitudes;
    };



    // @sect4{The analysis}
    //
    // Analyse one uniformly sampled signal. Throws std::invalid_argument for
    // fewer than 16 samples, a non-positive sample rate, non-finite samples
    // or options out of range. A signal that is one direction of a larger
    // motion is constant when its range is at the round-off level of that
    // motion's size, <code>record_size</code> (the largest displacement of
    // the record; zero for a signal on its own).
    SpectralResult
    analyse_signal(const std::vector<double> &samples,
                   const double               sample_rate,
                   const SpectralOptions     &options     = SpectralOptions(),
                   const double               record_size = 0.);
  } // namespace Analysis
} // namespace SoftRobot

#endif
