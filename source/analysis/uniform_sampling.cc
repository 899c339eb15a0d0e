// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Uniform sampling of a trajectory}
//
// A simulator that cuts its time step back for a while, or a motion capture
// system that drops frames, produces non-uniform records. They are
// interpolated linearly onto a grid with the median step -- the regular
// step of the simulator, unaffected by a few cutbacks. Linear interpolation
// of a signal with angular frequency $\omega$ on steps of length $h$ has an
// error of at most $h^2\max|u''|/8 = (\omega h)^2A/8$, 1.8 % of the
// amplitude for 6 Hz and $h=0.01$ s; since this error follows the envelope,
// it changes the amplitude but hardly the decay.
//
// A record whose steps agree within the tolerance is left alone; its sample
// rate is taken from the total duration, which is more accurate than any
// single printed step. Times printed with six significant digits change a
// step of $1/240$ s by up to 0.24 % for $t<10$ s, which the default
// tolerance of 1 % absorbs. Classifying a nearly uniform record as
// non-uniform would do no harm either: the interpolation uses the recorded
// times, so it cannot shift a frequency, it only moves the samples onto a
// grid.

#include <algorithm>
#include <analysis/uniform_sampling.h>
#include <analysis/utilities.h>
#include <cmath>
#include <stdexcept>

namespace SoftRobot
{
  namespace Analysis
  {
    namespace
    {
      using internal::format_number;



      // @sect4{The steps of the record}
      //
      // The differences of successive times, which must all be positive;
      // resample_uniformly() may be called on a trajectory that was not
      // read by read_tip_trajectory(), so the order is checked again here,
      // with the times to 17 digits because neighbouring times can agree
      // in the first six.
      std::vector<double>
      time_steps(const TipTrajectory &trajectory)
      {
        const std::size_t   n = trajectory.time.size();
        std::vector<double> steps(n - 1);
        for (std::size_t i = 0; i + 1 < n; ++i)
          {
            steps[i] = trajectory.time[i + 1] - trajectory.time[i];
            if (!(steps[i] > 0.))
              throw std::invalid_argument(
                "The times of a trajectory must increase strictly, but "
                "sample " +
                std::to_string(i + 1) + " is at " +
                format_number(trajectory.time[i + 1], 17) + " s after " +
                format_number(trajectory.time[i], 17) + " s.");
          }
        return steps;
      }



      // @sect4{Linear interpolation onto the grid}
      //
      // The interpolation sweeps once through the original intervals: the
      // uniform times increase, so the interval $[t_i, t_{i+1}]$ that
      // contains the next uniform time is found by moving forward, and
      // $u(t) = (1-\lambda)u_i + \lambda u_{i+1}$ with
      // $\lambda = (t-t_i)/(t_{i+1}-t_i)$, clipped to $[0,1]$ against
      // round-off at the ends. The number of uniform samples is the
      // largest that still fits into the recorded interval (with a relative
      // allowance of $10^{-12}$, so that a last time that lies on the grid
      // up to round-off is kept).
      std::vector<std::array<double, 3>>
      interpolate_onto_grid(const TipTrajectory       &trajectory,
                            const std::vector<double> &steps,
                            const double               uniform_step)
      {
        const std::size_t n          = trajectory.time.size();
        const double      start_time = trajectory.time.front();
        const std::size_t n_uniform =
          static_cast<std::size_t>(
            std::floor((trajectory.time.back() - trajectory.time.front()) /
                       uniform_step * (1. + 1e-12))) +
          1;

        std::vector<std::array<double, 3>> displacement(n_uniform);
        std::size_t                        interval = 0;
        for (std::size_t k = 0; k < n_uniform; ++k)
          {
            const double time = start_time + k * uniform_step;
            while (interval + 2 < n && trajectory.time[interval + 1] < time)
              ++interval;
            const double weight =
              std::min(1.,
                       std::max(0.,
                                (time - trajectory.time[interval]) /
                                  steps[interval]));
            for (unsigned int d = 0; d < 3; ++d)
              displacement[k][d] =
                (1. - weight) * trajectory.displacement[interval][d] +
                weight * trajectory.displacement[interval + 1][d];
          }
        return displacement;
      }
    } // namespace



    // @sect4{Uniform sampling}
    //
    // The largest relative deviation of a step from the mean step decides
    // whether the record is kept. If not, the grid step is the median of
    // the steps (found by <code>nth_element</code>, the upper median for
    // an even count), and a gap of more than four grid steps, which the
    // straight line across it cuts any oscillation out of, gets a warning.
    UniformTrajectory
    resample_uniformly(const TipTrajectory &trajectory,
                       const double         relative_step_tolerance)
    {
      const std::size_t n = trajectory.time.size();
      if (n < 2 || trajectory.displacement.size() != n)
        throw std::invalid_argument(
          "A trajectory to resample needs at least two samples with one "
          "displacement each, but has " +
          std::to_string(n) + " times and " +
          std::to_string(trajectory.displacement.size()) + " displacements.");
      if (!(relative_step_tolerance > 0. && relative_step_tolerance < 1.))
        throw std::invalid_argument(
          "The relative step tolerance must lie in (0, 1), but is " +
          format_number(relative_step_tolerance) + ".");

      const std::vector<double> steps = time_steps(trajectory);

      UniformTrajectory uniform;
      uniform.start_time   = trajectory.time.front();
      uniform.n_components = trajectory.n_components;

      const double mean_step =
        (trajectory.time.back() - trajectory.time.front()) / (n - 1);
      double largest_deviation = 0.;
      for (const double step : steps)
        largest_deviation =
          std::max(largest_deviation, std::abs(step - mean_step) / mean_step);

      if (largest_deviation <= relative_step_tolerance)
        {
          uniform.sample_rate  = 1. / mean_step;
          uniform.displacement = trajectory.displacement;
          uniform.resampled    = false;
          return uniform;
        }

      std::vector<double> sorted_steps = steps;
      std::nth_element(sorted_steps.begin(),
                       sorted_steps.begin() + sorted_steps.size() / 2,
                       sorted_steps.end());
      const double uniform_step = sorted_steps[sorted_steps.size() / 2];

      uniform.displacement =
        interpolate_onto_grid(trajectory, steps, uniform_step);
      uniform.sample_rate = 1. / uniform_step;
      uniform.resampled   = true;

      const auto longest_step = std::max_element(steps.begin(), steps.end());
      if (*longest_step > 4. * uniform_step)
        uniform.warnings.push_back(
          "the record has a gap of " + format_number(*longest_step) +
          " s after t = " +
          format_number(trajectory.time[longest_step - steps.begin()]) +
          " s (" + format_number(*longest_step / uniform_step, 3) +
          " times the median step), bridged by linear interpolation");
      return uniform;
    }
  } // namespace Analysis
} // namespace SoftRobot
