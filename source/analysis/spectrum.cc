// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{The zero-padded magnitude spectrum}
//
// The $N$ (windowed) samples are padded with zeros to the FFT length $L$;
// the padded transform samples the same continuous spectrum of the record
// on the finer grid $f_k = k f_s/L$, which is what the sub-bin
// interpolation of the peak and the crossings needs. The magnitude is
// scaled as an amplitude spectrum, $2|X_k|/\sum_n w_n$, so that a steady
// sinusoid of amplitude $A$ shows a peak of height $A$.
//
// The normalisation follows from the transform of such a sinusoid,
// $x_n = w_n A\cos(\omega n\Delta t)$: at its frequency the
// positive-frequency half contributes $X = \tfrac A2\sum_n w_n$, and the
// negative-frequency half is negligible for many cycles. Without window
// $\sum_n w_n = N$. The real-to-complex transform returns the $L/2+1$
// coefficients for $0 \le f \le f_s/2$; the others are their complex
// conjugates and carry no information.

#include <algorithm>
#include <analysis/spectrum.h>
#include <analysis/utilities.h>
#include <cmath>
#include <fftw3.h>
#include <memory>
#include <new>
#include <stdexcept>
#include <string>

namespace SoftRobot
{
  namespace Analysis
  {
    // @sect4{The window}
    //
    // The symmetric Hann window $w_n = \tfrac12(1-\cos(2\pi n/(N-1)))$
    // vanishes at both ends of the record. Without window all weights are
    // one and their sum is $N$.
    WindowedRecord
    apply_window(const std::vector<double> &signal, const SpectralWindow window)
    {
      const std::size_t n = signal.size();
      WindowedRecord    record;
      record.samples    = signal;
      record.window_sum = n;
      if (window == SpectralWindow::hann)
        {
          record.window_sum = 0.;
          for (std::size_t i = 0; i < n; ++i)
            {
              const double weight =
                0.5 * (1. - std::cos(2. * internal::pi * i / (n - 1.)));
              record.samples[i] *= weight;
              record.window_sum += weight;
            }
        }
      return record;
    }



    // @sect4{The length of the transform}
    //
    // The next power of two above the padded length; a limit of $2^{27}$
    // points (1 GB of work arrays) keeps a typo in the padding factor from
    // exhausting the memory.
    std::size_t
    zero_padded_fft_length(const std::size_t  n_samples,
                           const unsigned int zero_padding_factor)
    {
      std::size_t fft_length = 1;
      while (fft_length < zero_padding_factor * n_samples)
        fft_length *= 2;
      if (fft_length > (std::size_t(1) << 27))
        throw std::invalid_argument(
          "A zero-padding factor of " + std::to_string(zero_padding_factor) +
          " for " + std::to_string(n_samples) +
          " samples needs an FFT longer than 2^27 points; use a smaller "
          "factor.");
      return fft_length;
    }



    // @sect4{The transform}
    //
    // FFTW's planner is not thread-safe; this function plans with
    // FFTW_ESTIMATE (no trial transforms) and must not be called from
    // several threads at once. FFTW's arrays are held by
    // <code>std::unique_ptr</code> with <code>fftw_free</code> as deleter,
    // so that they are released also if an exception leaves the function.
    namespace
    {
      struct FftwDeleter
      {
        void
        operator()(void *pointer) const
        {
          fftw_free(pointer);
        }
      };
    } // namespace



    std::vector<double>
    zero_padded_magnitude_spectrum(const std::vector<double> &weighted,
                                   const double               window_sum,
                                   const unsigned int         fft_length)
    {
      std::unique_ptr<double, FftwDeleter> input(fftw_alloc_real(fft_length));
      std::unique_ptr<fftw_complex, FftwDeleter> output(
        fftw_alloc_complex(fft_length / 2 + 1));
      if (!input || !output)
        throw std::bad_alloc();

      const fftw_plan plan = fftw_plan_dft_r2c_1d(fft_length,
                                                  input.get(),
                                                  output.get(),
                                                  FFTW_ESTIMATE);
      if (plan == nullptr)
        throw std::runtime_error("FFTW could not plan a real-to-complex "
                                 "transform of length " +
                                 std::to_string(fft_length) + ".");

      std::fill(input.get(), input.get() + fft_length, 0.);
      std::copy(weighted.begin(), weighted.end(), input.get());
      fftw_execute(plan);
      fftw_destroy_plan(plan);

      std::vector<double> magnitude(fft_length / 2 + 1);
      for (unsigned int k = 0; k < magnitude.size(); ++k)
        magnitude[k] =
          2. * std::hypot(output.get()[k][0], output.get()[k][1]) / window_sum;
      return magnitude;
    }
  } // namespace Analysis
} // namespace SoftRobot
