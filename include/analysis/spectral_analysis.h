// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Spectral analysis of a tip trajectory}
//
// Implemented in source/analysis/spectral_analysis.cc.
//
// A soft robot that is released from a deflected state, or that stops being
// actuated, swings back to rest. The frequency of that swing and how fast it
// dies out are the two numbers by which a simulator is compared with the
// real robot: a reference study judged a simulator by the peak frequency of
// the Fourier transform of the tip displacement and by the damping ratio
// from the half-power (-3 dB) bandwidth of that peak,
// @f[
//   Q = \frac{f_\text{peak}}{f_+ - f_-}, \qquad \xi = \frac{1}{2Q},
// @f]
// where $f_\pm$ are the frequencies at which the magnitude spectrum has
// fallen to $1/\sqrt2$ of its peak value.
//
// The records are short (5--6 s, i.e. 10--30 cycles at 2--6 Hz), and for
// such records the half-power bandwidth is dominated by the finite record
// length rather than by the damping (see truncation_theory.cc). The
// analysis therefore reports three damping estimates side by side:
// - the half-power value exactly as the study computed it, together with the
//   bias that truncation theory predicts for it,
// - the logarithmic decrement of the successive extrema (a time-domain cross
//   check that needs no spectrum), and
// - a least-squares fit of damped modes to the record (the recommended
//   result: it is the Fourier-domain fit of the truncated Lorentzian, done
//   in the time domain, and it is unbiased for short records).
//
// The analysis is a library of its own, <code>soft_robot_analysis</code>:
// plain C++17 with FFTW3 for the transform and LAPACK for the dense linear
// algebra, without deal.II, so that it can be used on motion-capture data
// without the solver. Its files, one task each, in the order of the
// analysis:
// - trajectory.h: the record, its CSV reader, skipping an initial interval;
// - uniform_sampling.h: interpolation of non-uniform records;
// - directions.h: vertical, horizontal and depth motion;
// - spectrum.h: window and zero-padded magnitude spectrum;
// - spectral_peaks.h: peaks and their half-power bandwidths;
// - truncation_theory.h: what truncation does to those bandwidths;
// - time_domain.h: turning points and the logarithmic decrement;
// - modal_fit.h: the least-squares fit of damped modes;
// - dense_linear_algebra.h: the calls to LAPACK;
// - signal_analysis.h: all of this for one signal;
// - this file: all of this for a whole trajectory;
// - spectral_report.h: the results as CSV and as a summary.
//
// This header includes what a program needs to read and analyse a
// trajectory; the other headers are included where their functions are
// called directly.

#ifndef soft_robot_analysis_spectral_analysis_h
#define soft_robot_analysis_spectral_analysis_h

#include <analysis/signal_analysis.h>
#include <analysis/trajectory.h>
#include <string>
#include <vector>

namespace SoftRobot
{
  namespace Analysis
  {
    // @sect4{Analysis of a whole trajectory}
    //
    // Skip the initial interval, make the sampling uniform, split into
    // directions and analyse each. The result per direction carries the
    // direction's name; the trajectory as a whole has the common sample
    // rate and count, whether it was resampled, the plane of the $(y,z)$
    // motion and the warnings that concern all directions.
    struct DirectionalAnalysis
    {
      std::string    direction;
      SpectralResult result;
    };

    struct TrajectoryAnalysis
    {
      double                           sample_rate        = 0.;
      unsigned int                     n_samples          = 0;
      bool                             resampled          = false;
      double                           plane_angle        = 0.;
      double                           out_of_plane_ratio = 0.;
      std::vector<std::string>         warnings;
      std::vector<DirectionalAnalysis> directions;
    };

    TrajectoryAnalysis
    analyse_trajectory(const TipTrajectory   &trajectory,
                       const SpectralOptions &options      = SpectralOptions(),
                       const double           skip_seconds = 0.);
  } // namespace Analysis
} // namespace SoftRobot

#endif
