// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{The zero-padded magnitude spectrum}
//
// Implemented in source/analysis/spectrum.cc.
//
// The window applied to a record before its transform, the length of the
// zero-padded FFT, and the magnitude (amplitude) spectrum itself, computed
// with FFTW3. The peaks of this spectrum and their half-power widths are
// found in spectral_peaks.h; what truncation does to those widths is
// explained in truncation_theory.h.

#ifndef soft_robot_analysis_spectrum_h
#define soft_robot_analysis_spectrum_h

#include <cstddef>
#include <vector>

namespace SoftRobot
{
  namespace Analysis
  {
    // @sect4{The window}
    //
    // None (default) or Hann. A window lowers the side lobes but widens the
    // main lobe of every peak (for an undamped record from $0.886/T$ to
    // $1.44/T$), so it inflates the half-power bandwidth of a lightly
    // damped short record; for a record in which the oscillation decays it
    // even does the opposite, because it suppresses the large early part of
    // the free decay. Damping estimates must therefore be made without a
    // window; Hann is only useful to see weak secondary peaks next to a
    // strong one.
    enum class SpectralWindow
    {
      none,
      hann
    };

    // The record multiplied by the window, and the sum of the window's
    // weights, which normalises the amplitude spectrum.
    struct WindowedRecord
    {
      std::vector<double> samples;
      double              window_sum = 0.;
    };

    WindowedRecord
    apply_window(const std::vector<double> &signal,
                 const SpectralWindow       window);



    // @sect4{The length of the transform}
    //
    // The smallest power of two that is at least
    // <code>zero_padding_factor</code> times the number of samples, so that
    // the peak and the -3 dB crossings are interpolated on a fine grid.
    // Throws std::invalid_argument if that exceeds $2^{27}$ points.
    std::size_t
    zero_padded_fft_length(const std::size_t  n_samples,
                           const unsigned int zero_padding_factor);



    // @sect4{The magnitude spectrum}
    //
    // The magnitudes $2|X_k|/$<code>window_sum</code> at the frequencies
    // $k f_s/L$, $k = 0,\dots,L/2$, of the windowed record padded with
    // zeros to the length $L$ = <code>fft_length</code>: a steady sinusoid
    // of amplitude $A$ has a peak of height $A$. Not thread-safe (FFTW's
    // planner is not).
    std::vector<double>
    zero_padded_magnitude_spectrum(const std::vector<double> &weighted,
                                   const double               window_sum,
                                   const unsigned int         fft_length);
  } // namespace Analysis
} // namespace SoftRobot

#endif
