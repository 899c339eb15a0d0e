// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{The analysis of one signal}
//
// The steps are those of the study, with the checks that a short record
// needs: remove the offset, transform, check that the signal oscillates at
// all, find the peaks and their bandwidths, and then add the modal fit, the
// logarithmic decrement, the predicted truncation bias, the recommended
// damping ratio and the warnings. Each step is one function below, and
// analyse_signal() at the end of the file calls them in this order.
//
// The methods themselves live in their own files: the spectrum in
// spectrum.cc, the peaks in spectral_peaks.cc, the bias in
// truncation_theory.cc, the decrement in time_domain.cc and the fit in
// modal_fit.cc. This file only combines their results.

#include <algorithm>
#include <analysis/modal_fit.h>
#include <analysis/signal_analysis.h>
#include <analysis/truncation_theory.h>
#include <cmath>
#include <stdexcept>

namespace SoftRobot
{
  namespace Analysis
  {
    namespace
    {
      using internal::format_number;
      using internal::not_a_number;
      using internal::pi;

      // The bias of a damping estimate above which the analysis warns.
      constexpr double tolerated_relative_bias = 0.05;



      // @sect4{Checking the arguments}
      //
      // The arguments are checked first, because a wrong sample rate or a
      // padding factor of zero would otherwise produce plausible-looking
      // nonsense rather than an error. The FFT length, which may still be
      // too large, is checked by zero_padded_fft_length().
      void
      check_arguments(const std::vector<double> &samples,
                      const double               sample_rate,
                      const SpectralOptions     &options)
      {
        const std::size_t n = samples.size();
        if (n < internal::minimal_number_of_samples)
          throw std::invalid_argument(
            "The spectral analysis needs at least " +
            std::to_string(internal::minimal_number_of_samples) +
            " samples, but got " + std::to_string(n) + ".");
        if (!std::isfinite(sample_rate) || !(sample_rate > 0.))
          throw std::invalid_argument(
            "The sample rate must be positive and finite, but is " +
            format_number(sample_rate) + " Hz.");
        for (std::size_t i = 0; i < n; ++i)
          if (!std::isfinite(samples[i]))
            throw std::invalid_argument("Sample " + std::to_string(i) +
                                        " of the signal is not finite.");
        if (options.zero_padding_factor < 1 ||
            options.zero_padding_factor > 1024)
          throw std::invalid_argument(
            "The zero-padding factor must lie in [1, 1024], but is " +
            std::to_string(options.zero_padding_factor) + ".");
        if (!(options.secondary_peak_threshold > 0. &&
              options.secondary_peak_threshold <= 1.))
          throw std::invalid_argument(
            "The secondary-peak threshold must lie in (0, 1], but is " +
            format_number(options.secondary_peak_threshold) + ".");
      }



      // @sect4{The record and its spectrum}
      //
      // The record duration is $T = N/f_s$, the period of the discrete
      // Fourier transform, so that the resolution $1/T$ is the spacing of
      // the unpadded bins and the first zero of the rectangular window's
      // zero-frequency lobe. Subtracting the mean makes the zero-frequency
      // bin vanish exactly; subtracting the final value leaves a residual
      // constant whose leakage stays in that lobe as long as it is small
      // compared with the oscillation. The function returns the signal
      // without its offset and fills in the description of the record and
      // its spectrum, which is available for plotting whatever follows.
      std::vector<double>
      transform_record(const std::vector<double> &samples,
                       const double               sample_rate,
                       const SpectralOptions     &options,
                       const std::size_t          fft_length,
                       SpectralResult            &result)
      {
        const std::size_t n         = samples.size();
        result.damping_ratio        = not_a_number;
        result.n_samples            = n;
        result.fft_length           = fft_length;
        result.sample_rate          = sample_rate;
        result.duration             = n / sample_rate;
        result.frequency_resolution = 1. / result.duration;
        result.removed_offset = (options.offset_removal == OffsetRemoval::mean
                                   ? internal::mean_of(samples)
                                   : samples.back());

        std::vector<double> signal(n);
        for (std::size_t i = 0; i < n; ++i)
          signal[i] = samples[i] - result.removed_offset;

        const WindowedRecord windowed = apply_window(signal, options.window);
        result.magnitudes = zero_padded_magnitude_spectrum(windowed.samples,
                                                           windowed.window_sum,
                                                           fft_length);
        const double frequency_step = sample_rate / fft_length;
        result.frequencies.resize(result.magnitudes.size());
        for (std::size_t k = 0; k < result.frequencies.size(); ++k)
          result.frequencies[k] = k * frequency_step;
        return signal;
      }



      // @sect4{Does the signal oscillate?}
      //
      // A constant (to round-off) has no spectrum to speak of: a signal
      // whose range is below $10^{-12}$ of its size, or of the size of the
      // motion it is a direction of. The depth direction of a motion that is
      // planar by symmetry is such a signal: the difference of two
      // displacements that agree to round-off. A monotone or
      // over-damped decay has at most one turning point; one full cycle
      // needs three. This test comes before the spectral one because the
      // spectrum of a decay $e^{-t/\tau}$ minus its mean does have a broad
      // hump at $f \sim 1/T$ that can pass for a peak; counting turning
      // points decides the question in the time domain, where it is
      // unambiguous. Returns false, with the reason in the result, if the
      // signal does not oscillate.
      bool
      oscillates(const std::vector<double> &samples,
                 const std::vector<double> &signal,
                 const double               record_size,
                 SpectralResult            &result)
      {
        const auto [smallest, largest] =
          std::minmax_element(samples.begin(), samples.end());
        const double own_size =
          std::max(std::abs(*smallest), std::abs(*largest));
        const double size = std::max(own_size, record_size);
        if (!(*largest - *smallest > 1e-12 * size))
          {
            result.no_peak_reason =
              "the signal is constant (its range " +
              format_number(*largest - *smallest) +
              " is at the round-off level of " +
              (size > own_size ? "the record's size " : "its size ") +
              format_number(size) + ")";
            return false;
          }

        const std::vector<TurningPoint> turning_points =
          find_turning_points(signal);
        result.n_turning_points = turning_points.size();
        if (turning_points.size() < 3)
          {
            result.no_peak_reason =
              "the signal does not oscillate: it has " +
              std::to_string(turning_points.size()) +
              " turning points (extrema followed by a reversal of more "
              "than " +
              format_number(100. * turning_point_hysteresis) +
              " % of its range), and one cycle needs 3";
            return false;
          }
        return true;
      }



      // @sect4{The modal fit}
      //
      // The modal fit sees the record without window: the window is a
      // property of the spectral estimate, not of the signal. If the joint
      // fit of all peaks fails, the dominant mode alone is tried. Without
      // the fit (switched off) the result is an invalid fit with a NaN
      // residual.
      ModalFit
      fit_modes(const std::vector<double>       &signal,
                const double                     sample_rate,
                const std::vector<SpectralPeak> &peaks,
                const SpectralOptions           &options,
                SpectralResult                  &result)
      {
        ModalFit fit;
        if (!options.fit_damped_modes)
          return fit;

        fit = fit_damped_modes(signal, sample_rate, peaks);
        if (!fit.valid && peaks.size() > 1)
          {
            const ModalFit single =
              fit_damped_modes(signal, sample_rate, {peaks[0]});
            if (single.valid)
              fit = single;
          }
        result.fit_relative_residual = fit.relative_residual;
        return fit;
      }



      // @sect4{The logarithmic decrement}
      //
      // With the noise level of the fit residual (the signal's rms times the
      // relative residual) and half the period of the dominant peak as the
      // expected spacing of the extrema.
      LogarithmicDecrement
      decrement_of(const std::vector<double> &signal,
                   const double               sample_rate,
                   const double               dominant_frequency,
                   const ModalFit            &fit)
      {
        const std::size_t n           = signal.size();
        double            mean_square = 0.;
        const double      mean        = internal::mean_of(signal);
        for (const double value : signal)
          mean_square += (value - mean) * (value - mean) / n;
        const double noise_level =
          fit.valid ? fit.relative_residual * std::sqrt(mean_square) : 0.;
        return logarithmic_decrement_of(find_turning_points(signal,
                                                            noise_level),
                                        0.5 * sample_rate / dominant_frequency,
                                        noise_level);
      }



      // @sect4{The fitted mode and the bias of each peak}
      //
      // Per peak: the fitted mode, and the truncation bias of its
      // half-power damping, from the fitted decay exponent $\sigma T$ (well
      // conditioned) or else from inverting the measured $BT$. The fitted
      // $\sigma$ and $\omega_d$ give the natural frequency
      // $\omega_n = \sqrt{\sigma^2+\omega_d^2}$ and the damping ratio
      // $\xi = \sigma/\omega_n$; both follow from $\sigma = \xi\omega_n$ and
      // $\omega_d = \omega_n\sqrt{1-\xi^2}$ without approximation.
      void
      complete_peaks(std::vector<SpectralPeak> &peaks,
                     const ModalFit            &fit,
                     const double               duration,
                     const SpectralWindow       window)
      {
        for (std::size_t k = 0; k < peaks.size(); ++k)
          {
            SpectralPeak &peak            = peaks[k];
            peak.fitted_damped_frequency  = not_a_number;
            peak.fitted_natural_frequency = not_a_number;
            peak.fitted_damping_ratio     = not_a_number;
            peak.fitted_amplitude         = not_a_number;
            if (fit.valid && k < fit.decay_rates.size())
              {
                const double sigma            = fit.decay_rates[k];
                const double omega            = fit.angular_frequencies[k];
                const double omega_n          = std::hypot(sigma, omega);
                peak.fit_valid                = true;
                peak.fitted_damped_frequency  = omega / (2. * pi);
                peak.fitted_natural_frequency = omega_n / (2. * pi);
                peak.fitted_damping_ratio     = sigma / omega_n;
                peak.fitted_amplitude         = fit.amplitudes[k];
              }

            const double decay_exponent =
              peak.fit_valid ? fit.decay_rates[k] * duration
                             : decay_exponent_from_half_power_width(
                                 peak.bandwidth * duration, window);
            peak.half_power_truncation_bias =
              (decay_exponent > 0.
                 ? half_power_truncation_bias(decay_exponent, window)
                 : not_a_number);
          }
      }



      // @sect4{The recommended damping ratio}
      //
      // In the order of reliability for short records: the fit is unbiased
      // for any record length and separates modes; the decrement is
      // unbiased for a single mode but mixes modes and suffers from noise at
      // small amplitudes; the half-power value carries the truncation bias.
      void
      choose_damping_ratio(SpectralResult &result)
      {
        const SpectralPeak &dominant = result.dominant_peak;
        if (dominant.fit_valid)
          {
            result.damping_ratio     = dominant.fitted_damping_ratio;
            result.damping_estimator = DampingEstimator::modal_fit;
          }
        else if (result.logarithmic_decrement.valid)
          {
            result.damping_ratio = result.logarithmic_decrement.damping_ratio;
            result.damping_estimator = DampingEstimator::logarithmic_decrement;
          }
        else
          {
            result.damping_ratio     = dominant.damping_ratio_half_power;
            result.damping_estimator = DampingEstimator::half_power;
          }
      }



      // @sect4{Warnings on the half-power damping}
      //
      // Each warning says what is wrong and which number is affected. A
      // record in which the mode decays by less than 10 %
      // ($\sigma T < 0.1$), or whose bandwidth does not exceed that of an
      // undamped record, does not resolve the damping by its bandwidth at
      // all; otherwise the predicted bias is compared with 5 %. A fitted
      // oscillation that grows is reported instead of either.
      void
      warn_about_half_power_damping(const SpectralPeak       &peak,
                                    const double              duration,
                                    const SpectralWindow      window,
                                    std::vector<std::string> &warnings)
      {
        const std::string at   = format_number(peak.frequency, 4) + " Hz: ";
        const double      bias = peak.half_power_truncation_bias;
        const bool        hardly_decays =
          peak.fit_valid && peak.fitted_damping_ratio * 2. * pi *
                                peak.fitted_natural_frequency * duration <
                              0.1;
        if (peak.fit_valid && peak.fitted_damping_ratio < 0.)
          warnings.push_back(
            at + "the fitted oscillation grows instead of decaying");
        else if (std::isnan(bias) || hardly_decays)
          warnings.push_back(
            at + "the oscillation hardly decays within the record of " +
            format_number(duration, 4) + " s, and the half-power bandwidth " +
            format_number(peak.bandwidth, 3) +
            " Hz is that of the record length, not of the damping: "
            "xi_half_power is an upper bound only");
        else if (std::abs(bias) > tolerated_relative_bias)
          warnings.push_back(
            at + "the record is too short for the half-power method (B*T = " +
            format_number(peak.bandwidth * duration, 3) +
            (window == SpectralWindow::none
               ? "; the bias is below 5 % only for B*T >= 1.34"
               : "; with the Hann window the bias exceeds 5 % for almost "
                 "any record length") +
            "): truncation makes xi_half_power " +
            (bias > 1. ? format_number(1. + bias, 3) + " times too large"
                       : format_number(std::abs(100. * bias), 2) +
                           (bias > 0. ? " % too large" : " % too small")));
      }



      // @sect4{Warnings on the time-domain estimates}
      //
      // With secondary peaks the decrement mixes the modes. A failed fit
      // says which estimate replaced it, and a fit that leaves more than
      // 10 % (rms) of the signal unexplained says that the model does not
      // describe the record. Finally the two time-domain estimates are
      // compared on the scale of the decay within the record,
      // $\sigma T \approx 2\pi\xi f_n T$, so that nearly undamped records do
      // not produce large relative differences.
      void
      warn_about_time_domain_estimates(const ModalFit        &fit,
                                       const SpectralOptions &options,
                                       SpectralResult        &result)
      {
        if (!result.secondary_peaks.empty() &&
            result.logarithmic_decrement.valid)
          {
            std::string frequencies;
            for (const SpectralPeak &peak : result.secondary_peaks)
              frequencies += (frequencies.empty() ? "" : ", ") +
                             format_number(peak.frequency, 4) + " Hz";
            result.warnings.push_back(
              "secondary peaks at " + frequencies +
              ": the logarithmic decrement mixes the modes and is not a "
              "modal damping ratio");
          }

        if (options.fit_damped_modes && !fit.valid)
          result.warnings.push_back("the modal fit failed (" + fit.reason +
                                    "); the damping ratio is taken from the " +
                                    to_string(result.damping_estimator));
        else if (options.fit_damped_modes && fit.relative_residual > 0.1)
          result.warnings.push_back(
            "the modal fit leaves " +
            format_number(100. * fit.relative_residual, 2) +
            " % (rms) of the signal unexplained: the record is not a sum of "
            "damped modes (amplitude-dependent damping or frequency, drift, "
            "noise?)");

        const SpectralPeak &dominant = result.dominant_peak;
        if (dominant.fit_valid && result.logarithmic_decrement.valid &&
            result.secondary_peaks.empty())
          {
            const double cycles_scale =
              2. * pi * dominant.fitted_natural_frequency * result.duration;
            const double fitted_decay =
              dominant.fitted_damping_ratio * cycles_scale;
            const double difference =
              (result.logarithmic_decrement.damping_ratio -
               dominant.fitted_damping_ratio) *
              cycles_scale;
            if (std::abs(difference) >
                0.1 * std::max(std::abs(fitted_decay), 1.))
              result.warnings.push_back(
                "the logarithmic decrement (xi = " +
                format_number(result.logarithmic_decrement.damping_ratio, 3) +
                ") and the modal fit (xi = " +
                format_number(dominant.fitted_damping_ratio, 3) +
                ") disagree: the decay is not exponential "
                "(amplitude-dependent damping?), or noise biases the "
                "extrema");
          }
      }
    } // namespace



    std::string
    to_string(const DampingEstimator estimator)
    {
      switch (estimator)
        {
          case DampingEstimator::modal_fit:
            return "modal fit";
          case DampingEstimator::logarithmic_decrement:
            return "logarithmic decrement";
          case DampingEstimator::half_power:
            return "half-power bandwidth";
          case DampingEstimator::none:
          default:
            return "none";
        }
    }



    // @sect4{The analysis of one signal}
    //
    // The phases above in their order. The number of cycles
    // $f_\text{peak}T$ in the record is what decides, with the damping, how
    // much of the decay the record contains; the warnings on the
    // half-power damping come per peak, the dominant one first.
    SpectralResult
    analyse_signal(const std::vector<double> &samples,
                   const double               sample_rate,
                   const SpectralOptions     &options,
                   const double               record_size)
    {
      check_arguments(samples, sample_rate, options);
      const std::size_t fft_length =
        zero_padded_fft_length(samples.size(), options.zero_padding_factor);

      SpectralResult            result;
      const std::vector<double> signal =
        transform_record(samples, sample_rate, options, fft_length, result);
      if (!oscillates(samples, signal, record_size, result))
        return result;

      PeakSearchResult search =
        find_spectral_peaks(result.magnitudes,
                            sample_rate / fft_length,
                            result.duration,
                            options.window,
                            options.secondary_peak_threshold,
                            options.max_secondary_peaks);
      if (search.peaks.empty())
        {
          result.no_peak_reason = search.reason_if_none;
          return result;
        }
      result.has_peak = true;
      result.n_cycles = search.peaks[0].frequency * result.duration;

      const ModalFit fit =
        fit_modes(signal, sample_rate, search.peaks, options, result);
      result.logarithmic_decrement =
        decrement_of(signal, sample_rate, search.peaks[0].frequency, fit);

      complete_peaks(search.peaks, fit, result.duration, options.window);
      result.dominant_peak = search.peaks[0];
      result.secondary_peaks.assign(search.peaks.begin() + 1,
                                    search.peaks.end());
      choose_damping_ratio(result);

      for (const SpectralPeak &peak : search.peaks)
        warn_about_half_power_damping(peak,
                                      result.duration,
                                      options.window,
                                      result.warnings);
      warn_about_time_domain_estimates(fit, options, result);
      return result;
    }
  } // namespace Analysis
} // namespace SoftRobot
