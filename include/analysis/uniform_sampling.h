// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Uniform sampling of a trajectory}
//
// Implemented in source/analysis/uniform_sampling.cc.
//
// The FFT needs equidistant samples. Records whose steps agree to within
// <code>relative_step_tolerance</code> (default 1 %, which absorbs the
// jitter of times printed with few digits) are used as they are, with the
// sample rate $(n-1)/(t_{n-1}-t_0)$. Otherwise (time-step cutbacks of the
// simulator, dropped motion-capture frames) the record is interpolated
// linearly onto a grid with the median step.

#ifndef soft_robot_analysis_uniform_sampling_h
#define soft_robot_analysis_uniform_sampling_h

#include <analysis/trajectory.h>
#include <array>
#include <string>
#include <vector>

namespace SoftRobot
{
  namespace Analysis
  {
    // The samples at the times <code>start_time</code> $+ k$ /
    // <code>sample_rate</code>. <code>resampled</code> says whether they
    // were interpolated, and <code>warnings</code> holds what the
    // interpolation may have lost (a gap of several steps).
    struct UniformTrajectory
    {
      double                             start_time  = 0.;
      double                             sample_rate = 0.;
      std::vector<std::array<double, 3>> displacement;
      unsigned int                       n_components = 1;
      bool                               resampled    = false;
      std::vector<std::string>           warnings;
    };

    UniformTrajectory
    resample_uniformly(const TipTrajectory &trajectory,
                       const double         relative_step_tolerance = 0.01);
  } // namespace Analysis
} // namespace SoftRobot

#endif
