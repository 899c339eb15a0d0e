// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Time-domain estimates: turning points and the logarithmic decrement}
//
// The extrema of a single damped mode lie half a damped period apart, and
// their distances from the equilibrium $c$ shrink by the factor
// $e^{-\sigma T_d/2}$ from one to the next. The difference of two successive
// extrema, the peak-to-peak amplitude of a half cycle,
// @f[
//   h_j = |u_{j+1} - u_j| \propto e^{-\sigma T_d\,j/2},
// @f]
// does not contain $c$ at all, so it is insensitive to the offset estimate.
// A least-squares line through $\ln h_j$ against the cycle index $j/2$ has
// the slope $-\delta$, the logarithmic decrement
// $\delta = \sigma T_d = 2\pi\xi/\sqrt{1-\xi^2}$, and hence
// $\xi = \delta/\sqrt{4\pi^2+\delta^2}$.
//
// Extrema are found with a hysteresis of 2 % of the signal range (a maximum
// is confirmed only when the signal has fallen by that much below it),
// which ignores small wiggles. Extrema at the first sample are boundary
// values, not turning points, and are dropped. The value of each extremum
// comes from the parabola through the largest sample and its neighbours;
// its error, of order $(\omega\Delta t)^4$, is below $10^{-3}$ of the
// amplitude at 16 samples per cycle.
//
// Which half cycles enter the line: the run starts at the largest amplitude
// $h_j$ and continues while successive extrema are half a period of the
// spectral peak apart (within 25 %) and $h_j$ is at least 10 % of the
// largest one and 20 times the noise level $\sigma_n$. These conditions end
// the run where noise begins to dominate: extrema of noise are irregularly
// spaced, and each extremum carries an error of order $\sigma_n$, i.e. 10 %
// of $\ln h_j$ at $h_j = 20\sigma_n$. For the same reason the hysteresis is
// raised to $6\sigma_n$ if that is larger, since a pair of noise samples
// reverses by that much with probability $3\cdot10^{-5}$. The noise level
// is the rms residual of the modal fit (zero without a valid fit); an
// estimate from the spectrum would mistake the $1/f$ tail of the truncation
// for noise. Without these limits, a record that decays into a noise of 1 %
// of its initial amplitude has its decrement underestimated by several per
// cent.

#include <algorithm>
#include <analysis/dense_linear_algebra.h>
#include <analysis/time_domain.h>
#include <analysis/utilities.h>
#include <cmath>

namespace SoftRobot
{
  namespace Analysis
  {
    namespace
    {
      // @sect4{Confirming extrema}
      //
      // The search is a small state machine. At first the direction is
      // unknown and the running minimum and maximum are tracked; as soon as
      // they are a hysteresis apart, the earlier of the two is the first
      // turning point, and the later one becomes the candidate for the
      // next. From then on the search alternates: while looking for a
      // maximum (direction +1), a larger value replaces the candidate, and
      // a value that lies a hysteresis below it confirms the candidate as a
      // maximum and starts the search for a minimum (direction -1), and
      // vice versa. A candidate that is not confirmed by the end of the
      // record is dropped. The function returns the sample indices of the
      // confirmed extrema.
      std::vector<std::size_t>
      confirmed_extrema(const std::vector<double> &signal,
                        const double               hysteresis)
      {
        std::vector<std::size_t> indices;
        int                      direction = 0;
        std::size_t              lowest = 0, highest = 0, candidate = 0;
        for (std::size_t i = 1; i < signal.size(); ++i)
          {
            if (direction == 0)
              {
                if (signal[i] > signal[highest])
                  highest = i;
                if (signal[i] < signal[lowest])
                  lowest = i;
                if (signal[highest] - signal[lowest] >= hysteresis)
                  {
                    const bool rising = (highest > lowest);
                    indices.push_back(rising ? lowest : highest);
                    candidate = rising ? highest : lowest;
                    direction = rising ? +1 : -1;
                  }
              }
            else if (direction > 0)
              {
                if (signal[i] > signal[candidate])
                  candidate = i;
                else if (signal[candidate] - signal[i] >= hysteresis)
                  {
                    indices.push_back(candidate);
                    candidate = i;
                    direction = -1;
                  }
              }
            else
              {
                if (signal[i] < signal[candidate])
                  candidate = i;
                else if (signal[i] - signal[candidate] >= hysteresis)
                  {
                    indices.push_back(candidate);
                    candidate = i;
                    direction = +1;
                  }
              }
          }
        return indices;
      }
    } // namespace



    // @sect4{Turning points}
    //
    // The hysteresis, then the confirmed extrema, then the vertex of the
    // parabola through each extremum and its neighbours (the same formula
    // as for the spectral peak, see spectral_peaks.cc). Extrema at the
    // first or the last sample have no two neighbours and are dropped.
    std::vector<TurningPoint>
    find_turning_points(const std::vector<double> &signal,
                        const double               noise_level)
    {
      const auto [smallest, largest] =
        std::minmax_element(signal.begin(), signal.end());
      const double hysteresis =
        std::max(turning_point_hysteresis * (*largest - *smallest),
                 6. * noise_level);
      if (!(hysteresis > 0.))
        return {};

      std::vector<TurningPoint> turning_points;
      for (const std::size_t i : confirmed_extrema(signal, hysteresis))
        {
          if (i == 0 || i + 1 >= signal.size())
            continue;
          const double below = signal[i - 1], centre = signal[i],
                       above     = signal[i + 1];
          const double curvature = below - 2. * centre + above;
          const double offset =
            (curvature != 0. ? 0.5 * (below - above) / curvature : 0.);
          turning_points.push_back(
            {i + offset, centre - 0.25 * (below - above) * offset});
        }
      return turning_points;
    }



    // @sect4{The logarithmic decrement}
    //
    // The half-cycle amplitudes $h_j$, the run of qualifying ones that
    // starts at the largest, and the line
    // $\ln h_j \approx c_0 + c_1\,\tfrac j2$ through them. The line is the
    // least-squares solution of the $m\times2$ system with the columns
    // $(1)$ and $(j/2)$, computed by LAPACK (dense_linear_algebra.cc); the
    // decrement is $\delta = -c_1$. At least three half cycles are
    // required, one more than a line needs.
    LogarithmicDecrement
    logarithmic_decrement_of(const std::vector<TurningPoint> &turning_points,
                             const double half_period_in_samples,
                             const double noise_level)
    {
      LogarithmicDecrement decrement;
      decrement.decrement     = internal::not_a_number;
      decrement.damping_ratio = internal::not_a_number;

      std::vector<double> amplitudes;
      std::vector<bool>   regularly_spaced;
      for (std::size_t j = 0; j + 1 < turning_points.size(); ++j)
        {
          amplitudes.push_back(
            std::abs(turning_points[j + 1].value - turning_points[j].value));
          const double spacing =
            turning_points[j + 1].position - turning_points[j].position;
          regularly_spaced.push_back(
            std::abs(spacing - half_period_in_samples) <=
            0.25 * half_period_in_samples);
        }

      std::vector<double> log_amplitudes;
      if (!amplitudes.empty())
        {
          const std::size_t largest =
            std::max_element(amplitudes.begin(), amplitudes.end()) -
            amplitudes.begin();
          for (std::size_t j = largest;
               j < amplitudes.size() && regularly_spaced[j] &&
               amplitudes[j] >= 0.1 * amplitudes[largest] &&
               amplitudes[j] >= 20. * noise_level;
               ++j)
            log_amplitudes.push_back(std::log(amplitudes[j]));
        }

      decrement.n_extrema =
        log_amplitudes.empty() ? 0 : log_amplitudes.size() + 1;
      if (log_amplitudes.size() < 3)
        {
          decrement.reason =
            "only " + std::to_string(log_amplitudes.size()) +
            " successive half cycles are regularly spaced and above 10 % "
            "of the largest amplitude and 20 times the noise level; at "
            "least 3 are needed";
          return decrement;
        }

      const std::size_t m = log_amplitudes.size();
      ColumnMajorMatrix line(m, 2);
      for (std::size_t j = 0; j < m; ++j)
        {
          line(j, 0) = 1.;
          line(j, 1) = 0.5 * j;
        }
      const LeastSquaresSolution fit =
        solve_least_squares(line, log_amplitudes);

      decrement.valid     = true;
      decrement.decrement = -fit.coefficients[1];
      decrement.damping_ratio =
        decrement.decrement /
        std::sqrt(4. * internal::pi * internal::pi +
                  decrement.decrement * decrement.decrement);
      return decrement;
    }
  } // namespace Analysis
} // namespace SoftRobot
