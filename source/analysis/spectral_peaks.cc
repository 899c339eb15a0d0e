// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Peaks of the spectrum and their half-power bandwidths}
//
// <i>Sub-bin peak.</i> Through the largest bin $k$ and its neighbours a
// parabola $y(p)$, $p\in[-1,1]$ in bins, is laid; its vertex is at
// @f[
//   p^\ast = \frac{y_{-1}-y_{+1}}{2(y_{-1}-2y_0+y_{+1})}, \qquad
//   y^\ast = y_0 - \tfrac14(y_{-1}-y_{+1})p^\ast.
// @f]
// With 16-fold padding the main lobe spans dozens of bins and the parabola
// is accurate to a tiny fraction of a bin.
//
// <i>Half-power crossings.</i> From the peak the spectrum is followed bin by
// bin to both sides until it falls below $y^\ast/\sqrt2$; the crossing is
// interpolated linearly between the last two bins. If the spectrum rises
// above $y^\ast$ before (another, larger peak) or the end of the spectrum is
// reached, that crossing does not exist.
//
// <i>Which local maxima are resonances.</i> A zero-padded spectrum of a
// short record has many local maxima; a maximum is taken as a peak only if
// - it stands at least 20 dB (a factor 10) above the noise floor, the
//   median of the spectrum above the zero-frequency lobe: for white noise
//   the magnitudes are Rayleigh distributed, and a bin exceeds ten times
//   their median with probability $e^{-(10\cdot1.177)^2/2} \approx
//   10^{-30}$, whereas for a noise-free free decay the median is the far
//   tail of the Lorentzian, orders of magnitude lower;
// - it lies above the zero-frequency neighbourhood, i.e. beyond the first
//   zero of the window's main lobe around $f=0$ ($1/T$ without window,
//   $2/T$ with Hann): the residual of the removed offset leaks into that
//   lobe, and a maximum there is less than one cycle in the record, which
//   cannot be told apart from a drift;
// - the spectrum falls by 3 dB on both sides before it rises above the
//   maximum again (otherwise it is a shoulder of a larger peak); and
// - its half-power width is at least 0.8 times the width of the main lobe
//   of an undamped record ($0.886/T$, resp. $1.441/T$): no oscillation
//   recorded for $T$ seconds can have a narrower peak, whereas the side
//   lobes of an undamped record are only $0.5/T$ wide; and
// - it rises above the leakage of every larger peak. A damped mode's side
//   lobes are its Lorentzian tail modulated by the ripple
//   $1-e^{-s}e^{-iw}$; for $s < 1.76$ they dip by more than 3 dB and,
//   broadened by the image at $-f$, can be as wide as a resonance. The
//   leakage of a peak of magnitude $M_j$ at $f_j$ is at most
//   $M_j\,[g(2\pi T(f-f_j)) + g(2\pi T(f+f_j))]$, where $g(w)$ is the
//   largest normalised magnitude of the truncated-decay spectrum within one
//   ripple period ($\pm\pi$) of $w$ (side_lobe_envelope() in
//   truncation_theory.cc) and the second term is the image; the decay
//   exponent $s_j$ is taken from the peak's bandwidth, and $M_j$ is divided
//   by $1-g(4\pi T f_j)$ because the image may have lowered the measured
//   peak by that much. A maximum below that bound is a side lobe, not a
//   second mode.
//
// The search runs in three phases, one function each: the tests that a
// single maximum must pass, the selection among the maxima that passed
// (dominant peak, threshold, leakage), and, if nothing passed, the
// explanation why.

#include <algorithm>
#include <analysis/spectral_peaks.h>
#include <analysis/truncation_theory.h>
#include <analysis/utilities.h>
#include <cmath>

namespace SoftRobot
{
  namespace Analysis
  {
    namespace
    {
      using internal::format_number;
      using internal::not_a_number;
      using internal::pi;



      // @sect4{A half-power crossing}
      //
      // The frequency at which the spectrum, followed from
      // <code>peak_bin</code> in <code>direction</code> ($\pm1$), first
      // falls below <code>level</code>; NaN if it rises above the peak
      // value first or the spectrum ends.
      double
      half_power_crossing(const std::vector<double> &magnitude,
                          const std::size_t          peak_bin,
                          const int                  direction,
                          const double               level,
                          const double               peak_value,
                          const double               frequency_step)
      {
        std::size_t bin = peak_bin;
        while (true)
          {
            if ((direction < 0 && bin == 0) ||
                (direction > 0 && bin + 1 >= magnitude.size()))
              return not_a_number;
            const std::size_t next = bin + direction;
            if (magnitude[next] > peak_value)
              return not_a_number;
            if (magnitude[next] < level)
              {
                const double fraction =
                  (magnitude[bin] - level) / (magnitude[bin] - magnitude[next]);
                return (bin + direction * fraction) * frequency_step;
              }
            bin = next;
          }
      }



      // @sect4{The tests of a single maximum}
      //
      // Each local maximum above the zero-frequency lobe is tested in turn
      // against the noise floor, the two half-power crossings and the
      // narrowest possible resonance; the counters remember why maxima
      // were rejected, to explain a "no peak" result. A maximum that
      // passes gets its sub-bin frequency and magnitude, its crossings,
      // bandwidth, $Q$ and half-power damping ratio. A flat top (zero
      // curvature of the parabola) keeps the bin itself.
      struct ResonanceCandidates
      {
        std::vector<SpectralPeak> peaks;
        unsigned int              n_local_maxima = 0;
        unsigned int              n_in_noise     = 0;
        unsigned int              n_shoulders    = 0;
        unsigned int              n_side_lobes   = 0;
      };



      ResonanceCandidates
      find_resonance_candidates(const std::vector<double> &magnitude,
                                const double               frequency_step,
                                const std::size_t          first_bin,
                                const double               noise_floor,
                                const double               narrowest_resonance)
      {
        ResonanceCandidates candidates;
        for (std::size_t k = first_bin; k + 1 < magnitude.size(); ++k)
          {
            if (!(magnitude[k] > magnitude[k - 1] &&
                  magnitude[k] >= magnitude[k + 1]))
              continue;
            ++candidates.n_local_maxima;
            if (magnitude[k] < 10. * noise_floor)
              {
                ++candidates.n_in_noise;
                continue;
              }

            const double below = magnitude[k - 1], centre = magnitude[k],
                         above     = magnitude[k + 1];
            const double curvature = below - 2. * centre + above;
            const double offset =
              (curvature < 0. ? 0.5 * (below - above) / curvature : 0.);

            SpectralPeak peak;
            peak.frequency = (k + offset) * frequency_step;
            peak.magnitude = centre - 0.25 * (below - above) * offset;

            const double level              = peak.magnitude / std::sqrt(2.);
            peak.lower_half_power_frequency = half_power_crossing(
              magnitude, k, -1, level, peak.magnitude, frequency_step);
            peak.upper_half_power_frequency = half_power_crossing(
              magnitude, k, +1, level, peak.magnitude, frequency_step);
            if (std::isnan(peak.lower_half_power_frequency) ||
                std::isnan(peak.upper_half_power_frequency))
              {
                ++candidates.n_shoulders;
                continue;
              }

            peak.bandwidth =
              peak.upper_half_power_frequency - peak.lower_half_power_frequency;
            if (peak.bandwidth < narrowest_resonance)
              {
                ++candidates.n_side_lobes;
                continue;
              }

            peak.quality_factor           = peak.frequency / peak.bandwidth;
            peak.damping_ratio_half_power = 0.5 / peak.quality_factor;
            candidates.peaks.push_back(peak);
          }
        return candidates;
      }



      // @sect4{The selection of the peaks}
      //
      // The candidates by decreasing magnitude: the first is the dominant
      // peak. The others are kept, up to the requested number, if they
      // reach the threshold relative to the dominant peak and rise above
      // the leakage of all peaks kept before them. The decay exponent of
      // each kept peak (from its bandwidth, zero where the bandwidth does
      // not resolve one) is computed once, when it is first needed.
      std::vector<SpectralPeak>
      select_peaks(std::vector<SpectralPeak> candidates,
                   const double              duration,
                   const SpectralWindow      window,
                   const double              secondary_peak_threshold,
                   const unsigned int        max_secondary_peaks)
      {
        std::sort(candidates.begin(),
                  candidates.end(),
                  [](const SpectralPeak &a, const SpectralPeak &b) {
                    return a.magnitude > b.magnitude;
                  });

        const double smallest_magnitude =
          secondary_peak_threshold * candidates[0].magnitude;
        std::vector<SpectralPeak> kept = {candidates[0]};
        std::vector<double>       decay_exponents;
        for (std::size_t i = 1;
             i < candidates.size() && kept.size() <= max_secondary_peaks;
             ++i)
          {
            const SpectralPeak &candidate = candidates[i];
            if (candidate.magnitude < smallest_magnitude)
              break;

            double leakage = 0.;
            for (std::size_t j = 0; j < kept.size(); ++j)
              {
                if (decay_exponents.size() <= j)
                  {
                    const double s = decay_exponent_from_half_power_width(
                      kept[j].bandwidth * duration, window);
                    decay_exponents.push_back(std::isnan(s) ? 0. : s);
                  }
                // The image at $-f_j$ may lower the measured peak itself by
                // up to its envelope at $2f_j$.
                const double image_at_peak =
                  side_lobe_envelope(4. * pi * duration * kept[j].frequency,
                                     decay_exponents[j],
                                     window);
                leakage += kept[j].magnitude /
                           (1. - std::min(0.5, image_at_peak)) *
                           (side_lobe_envelope(2. * pi * duration *
                                                 (candidate.frequency -
                                                  kept[j].frequency),
                                               decay_exponents[j],
                                               window) +
                            side_lobe_envelope(2. * pi * duration *
                                                 (candidate.frequency +
                                                  kept[j].frequency),
                                               decay_exponents[j],
                                               window));
              }
            if (candidate.magnitude > leakage)
              kept.push_back(candidate);
          }
        return kept;
      }



      // @sect4{Why there is no peak}
      //
      // Either the spectrum has no local maximum above the zero-frequency
      // lobe at all, or every maximum failed one of the tests; the message
      // gives the counts per test and the thresholds.
      std::string
      no_peak_reason(const ResonanceCandidates &candidates,
                     const double               dc_lobe_edge,
                     const double               noise_floor,
                     const double               narrowest_resonance,
                     const double               duration)
      {
        if (candidates.n_local_maxima == 0)
          return "the magnitude spectrum has no local maximum above " +
                 format_number(dc_lobe_edge, 3) +
                 " Hz, the edge of the zero-frequency lobe";
        return "none of the " + std::to_string(candidates.n_local_maxima) +
               " local maxima of the spectrum above " +
               format_number(dc_lobe_edge, 3) +
               " Hz is a resonance: " + std::to_string(candidates.n_in_noise) +
               " are less than 20 dB above the noise floor (the median "
               "magnitude " +
               format_number(noise_floor, 3) + "), " +
               std::to_string(candidates.n_shoulders) +
               " do not fall by 3 dB on both sides, and " +
               std::to_string(candidates.n_side_lobes) + " are narrower than " +
               format_number(narrowest_resonance, 3) +
               " Hz, less than the main lobe of an undamped oscillation "
               "recorded for " +
               format_number(duration, 4) + " s (side lobes of the truncation)";
      }
    } // namespace



    // @sect4{The search}
    //
    // The thresholds that depend on the record: the edge of the
    // zero-frequency lobe, the narrowest resonance, and the noise floor,
    // the median (by <code>nth_element</code>, the upper median for an even
    // count) of the bins above that edge.
    PeakSearchResult
    find_spectral_peaks(const std::vector<double> &magnitude,
                        const double               frequency_step,
                        const double               duration,
                        const SpectralWindow       window,
                        const double               secondary_peak_threshold,
                        const unsigned int         max_secondary_peaks)
    {
      const double dc_lobe_edge =
        (window == SpectralWindow::none ? 1. : 2.) / duration;
      const double narrowest_resonance =
        0.8 * truncated_decay_half_power_width(0., window) / duration;
      const std::size_t first_bin = std::max<std::size_t>(
        1, static_cast<std::size_t>(std::ceil(dc_lobe_edge / frequency_step)));

      std::vector<double> above_dc_lobe(magnitude.begin() + first_bin,
                                        magnitude.end());
      std::nth_element(above_dc_lobe.begin(),
                       above_dc_lobe.begin() + above_dc_lobe.size() / 2,
                       above_dc_lobe.end());
      const double noise_floor = above_dc_lobe[above_dc_lobe.size() / 2];

      const ResonanceCandidates candidates = find_resonance_candidates(
        magnitude, frequency_step, first_bin, noise_floor, narrowest_resonance);

      PeakSearchResult search;
      if (!candidates.peaks.empty())
        search.peaks = select_peaks(candidates.peaks,
                                    duration,
                                    window,
                                    secondary_peak_threshold,
                                    max_secondary_peaks);
      else
        search.reason_if_none = no_peak_reason(
          candidates, dc_lobe_edge, noise_floor, narrowest_resonance, duration);
      return search;
    }
  } // namespace Analysis
} // namespace SoftRobot
