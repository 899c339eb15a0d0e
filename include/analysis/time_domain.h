// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Time-domain estimates: turning points and the logarithmic decrement}
//
// Implemented in source/analysis/time_domain.cc.
//
// The extrema of a signal, found with a hysteresis, and the logarithmic
// decrement of their successive differences: a damping estimate that needs
// no spectrum and serves as a cross check of the modal fit. The turning
// points also decide, before any spectrum is looked at, whether a signal
// oscillates at all.

#ifndef soft_robot_analysis_time_domain_h
#define soft_robot_analysis_time_domain_h

#include <string>
#include <vector>

namespace SoftRobot
{
  namespace Analysis
  {
    // @sect4{Turning points}
    //
    // A turning point counts only if the signal afterwards reverses by more
    // than this fraction of its range: this keeps noise and round-off
    // wiggles out of the count of oscillations and out of the logarithmic
    // decrement.
    constexpr double turning_point_hysteresis = 0.02;

    // An extremum at the fractional sample index <code>position</code> with
    // the interpolated <code>value</code>.
    struct TurningPoint
    {
      double position;
      double value;
    };

    // The extrema of <code>signal</code>, with a hysteresis of
    // turning_point_hysteresis times its range or six times
    // <code>noise_level</code>, whichever is larger. Empty for a constant
    // signal.
    std::vector<TurningPoint>
    find_turning_points(const std::vector<double> &signal,
                        const double               noise_level = 0.);



    // @sect4{The logarithmic decrement}
    //
    // The logarithmic decrement $\delta$ of the extrema of the signal, from
    // a least-squares line through $\ln$ (peak-to-peak amplitude of each
    // half cycle) against the cycle index, and the damping ratio
    // $\xi = \delta/\sqrt{4\pi^2+\delta^2}$. If too few half cycles qualify,
    // <code>valid</code> is false, the numbers are NaN and
    // <code>reason</code> says why.
    struct LogarithmicDecrement
    {
      bool         valid = false;
      std::string  reason;
      unsigned int n_extrema     = 0;
      double       decrement     = 0.;
      double       damping_ratio = 0.;
    };

    // The decrement of the <code>turning_points</code> of a signal whose
    // extrema are expected <code>half_period_in_samples</code> apart, with
    // half cycles smaller than 20 times <code>noise_level</code> left out.
    LogarithmicDecrement
    logarithmic_decrement_of(const std::vector<TurningPoint> &turning_points,
                             const double half_period_in_samples,
                             const double noise_level);
  } // namespace Analysis
} // namespace SoftRobot

#endif
