// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Spectral analysis of a tip trajectory}
//
// The analysis of a whole trajectory combines the pieces of the library in
// their natural order: skip the requested initial interval (with the same
// checks whether or not anything is skipped), make the sampling uniform,
// split the motion into directions, and analyse each direction with the
// same options.

#include <algorithm>
#include <analysis/directions.h>
#include <analysis/spectral_analysis.h>
#include <analysis/uniform_sampling.h>
#include <analysis/utilities.h>
#include <cmath>

namespace SoftRobot
{
  namespace Analysis
  {
    // @sect4{The analysis of a whole trajectory}
    //
    // A motion without a preferred plane (depth and horizontal rms within
    // 30 % of each other) gets a warning, because then the two in-plane
    // directions are an arbitrary choice and their spectra should be read
    // together. All directions share the sample rate, hence the frequency
    // grid of their spectra, which the spectrum file of spectral_report.h
    // relies on.
    TrajectoryAnalysis
    analyse_trajectory(const TipTrajectory   &trajectory,
                       const SpectralOptions &options,
                       const double           skip_seconds)
    {
      const UniformTrajectory uniform =
        resample_uniformly(skip_initial_interval(trajectory, skip_seconds));
      const DirectionalSignals signals = split_into_directions(uniform);

      TrajectoryAnalysis analysis;
      analysis.sample_rate        = uniform.sample_rate;
      analysis.n_samples          = uniform.displacement.size();
      analysis.resampled          = uniform.resampled;
      analysis.plane_angle        = signals.plane_angle;
      analysis.out_of_plane_ratio = signals.out_of_plane_ratio;
      analysis.warnings           = uniform.warnings;
      if (uniform.n_components == 3 && signals.out_of_plane_ratio > 0.7)
        analysis.warnings.push_back(
          "the (y,z) motion has no preferred plane (depth/horizontal rms = " +
          internal::format_number(signals.out_of_plane_ratio, 3) +
          "), so the split into horizontal and depth is arbitrary");

      // The size of the whole motion, against which a direction's range is
      // measured for round-off (analyse_signal()).
      double record_size = 0.;
      for (const auto &u : uniform.displacement)
        for (unsigned int c = 0; c < uniform.n_components; ++c)
          record_size = std::max(record_size, std::abs(u[c]));

      for (std::size_t d = 0; d < signals.names.size(); ++d)
        analysis.directions.push_back({signals.names[d],
                                       analyse_signal(signals.samples[d],
                                                      uniform.sample_rate,
                                                      options,
                                                      record_size)});
      return analysis;
    }
  } // namespace Analysis
} // namespace SoftRobot



// @sect3{Limits and possible extensions}
//
// - <i>Cost of the fit.</i> Each cost evaluation builds and factorises an
//   $N\times(2K+2)$ matrix, and Levenberg--Marquardt with three starts needs
//   a few hundred of them: about 40 ms for 1440 samples and one mode. For
//   records of $10^5$ samples and several modes this becomes seconds;
//   decimating the record to some 20 samples per period of the highest peak
//   before fitting would keep it cheap.
// - <i>Noise.</i> The fit is the maximum-likelihood estimate for white
//   Gaussian noise and degrades gracefully. The logarithmic decrement does
//   not: with noise of 1 % of the initial amplitude it reads a few per cent
//   low, because the largest of several noisy samples overestimates small
//   extrema. Fitting a local cosine instead of a parabola through three
//   samples would reduce this.
// - <i>Amplitude-dependent damping and frequency.</i> A soft robot with
//   large deformations is not linear: damping and stiffness change as the
//   swing decays. The modal fit then returns an average, and the warnings
//   on the fit residual and on the disagreement with the decrement say so;
//   a fit of the decrement over a sliding window of cycles would show the
//   dependence itself.
// - <i>Frequency of the spectral peak.</i> It estimates the damped
//   frequency and, for records of five or six cycles, is shifted by the
//   negative-frequency image by up to about 0.5 %; the fitted natural
//   frequency has neither error and is the one to compare.
