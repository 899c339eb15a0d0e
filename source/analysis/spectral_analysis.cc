// @sect3{Spectral analysis of a tip trajectory: implementation}
//
// This file turns a recorded tip trajectory into frequencies and damping
// ratios. The steps, in the order in which they are implemented below, are
// - reading the CSV file and making the sampling uniform,
// - splitting the motion into a vertical, a horizontal and a depth
//   direction,
// - the zero-padded magnitude spectrum and its peaks with their half-power
//   bandwidths,
// - the logarithmic decrement of the extrema, and
// - a least-squares fit of damped modes, which is the recommended damping
//   estimate for short records.
//
// Before any code, the one piece of theory that decides how the numbers
// must be read: what truncation does to the half-power bandwidth.
//
// <h4>Truncation of a free decay</h4>
//
// A single mode with natural angular frequency $\omega_n$ and damping ratio
// $\xi$ decays as
// @f[
//   u(t) = A\,e^{-\sigma t}\cos(\omega_d t + \varphi), \qquad
//   \sigma = \xi\omega_n, \quad \omega_d = \omega_n\sqrt{1-\xi^2}.
// @f]
// Recorded for $0\le t\le T$ and away from $\omega=0$, its Fourier transform
// is dominated by the positive-frequency half,
// @f[
//   \hat u(\omega) \approx \frac{A}{2}e^{i\varphi}
//     \int_0^T e^{-(\sigma + i(\omega-\omega_d))t}\,dt
//   = \frac{A T}{2}e^{i\varphi}\,E(s + i w), \qquad
//   E(z) = \frac{1-e^{-z}}{z},
// @f]
// with the dimensionless decay exponent $s = \sigma T$ and frequency offset
// $w = (\omega-\omega_d)T$. For $T\to\infty$, $|E| \propto 1/|s+iw|$ is the
// Lorentzian: it falls to $1/\sqrt2$ at $w=\pm s$, so the half-power
// bandwidth is $B = \sigma/\pi = 2\xi f_n$ and $\xi = B/(2f) = 1/(2Q)$ --
// the study's formula. For finite $T$ the factor $1-e^{-z}$ is the
// convolution of the Lorentzian with the $\operatorname{sinc}$ of the
// rectangular record, and for $s\to0$ the peak keeps the width of the sinc
// main lobe, $B T = 0.886$, however small the damping. The half-power
// width $BT$ depends on $s$ alone (function
// truncated_decay_half_power_width() below); the relative bias of the
// half-power damping ratio, $\pi BT/s - 1$, is
//
// <table>
// <tr><td>$s=\sigma T$</td><td>1</td><td>2</td><td>3</td><td>4</td>
//     <td>5</td><td>6</td></tr>
// <tr><td>$BT$ measured</td><td>0.913</td><td>0.996</td><td>1.138</td>
//     <td>1.343</td><td>1.606</td><td>1.910</td></tr>
// <tr><td>bias of $\xi$, no window</td><td>+187 %</td><td>+56 %</td>
//     <td>+19 %</td><td>+5.5 %</td><td>+0.9 %</td><td>0.0 %</td></tr>
// <tr><td>bias of $\xi$, Hann</td><td>+355 %</td><td>+131 %</td>
//     <td>+58 %</td><td>+23 %</td><td>+2.5 %</td><td>-10 %</td></tr>
// </table>
//
// (for $s\to\infty$ the bias vanishes without window, but with the Hann
// window, which suppresses the early, large part of the decay, it tends to
// $\sqrt{2^{1/3}-1}-1 = -49\,\%$). Since
// $s = \xi\omega_n T \approx 2\pi\xi N_\text{cycles}$ with
// $N_\text{cycles} = f T$, the half-power value is within 5 % only
// if $\xi N_\text{cycles} \gtrsim 0.64$, i.e. if the amplitude has decayed
// to $e^{-4}\approx 2\,\%$ by the end of the record. The study's example
// $f=2$ Hz, $\xi=0.02$, $T=5$ s has $s=1.26$ and its half-power damping
// ratio is 2.3 times too large.
//
// <i>The criterion for the warning.</i> Because $BT$ is a monotone function
// of $s$, the measured bandwidth alone tells whether the record was long
// enough: the half-power damping is biased by less than 5 % only if
// $B \ge 1.34/T$, i.e. if the bandwidth exceeds the resolution $1/T$ of the
// unpadded record by a third; if $B \le 0.886/T$ (the main lobe of an
// undamped record) the damping is not resolved at all. The analysis
// computes the predicted bias for every peak (from the fitted decay, or by
// inverting $BT(s)$) and warns if it exceeds 5 %. It still reports the
// half-power number unchanged, as the study did.
//
// <i>The correction.</i> Inverting $BT(s)$ would correct the bias, but the
// inversion is ill-conditioned exactly where the correction is large
// ($dBT/ds \to 0$ for $s\to0$), and it ignores the negative-frequency image
// and the leakage of the removed offset. The principled correction is to fit
// the truncated model itself: by Parseval's identity, the least-squares
// misfit of the damped-mode model in the time domain over $[0,T]$ equals the
// misfit of its spectrum -- the Lorentzian convolved with the sinc, with
// image and offset -- to the measured complex spectrum. This fit (section
// "Fitting damped modes" below) is unbiased for any record length, and it is
// the recommended damping estimate. The logarithmic decrement is exact for
// a single noise-free mode as well, and serves as an independent cross
// check.

#include <algorithm>
#include <analysis/spectral_analysis.h>
#include <cmath>
#include <complex>
#include <cstdlib>
#include <fftw3.h>
#include <fstream>
#include <limits>
#include <memory>
#include <numeric>
#include <sstream>
#include <stdexcept>

namespace SoftRobot
{
  namespace Analysis
  {
    namespace
    {
      constexpr double pi           = 3.14159265358979323846;
      constexpr double not_a_number = std::numeric_limits<double>::quiet_NaN();

      // The smallest record the analysis accepts; below this neither a
      // spectrum nor a decrement means anything.
      constexpr unsigned int minimal_number_of_samples = 16;

      // A turning point counts only if the signal afterwards reverses by
      // more than this fraction of its range: this keeps noise and
      // round-off wiggles out of the count of oscillations and out of the
      // logarithmic decrement.
      constexpr double turning_point_hysteresis = 0.02;

      // The bias of a damping estimate above which the analysis warns.
      constexpr double tolerated_relative_bias = 0.05;



      std::string
      trim(const std::string &text)
      {
        const auto first = text.find_first_not_of(" \t\r\n");
        if (first == std::string::npos)
          return "";
        const auto last = text.find_last_not_of(" \t\r\n");
        return text.substr(first, last - first + 1);
      }



      std::vector<std::string>
      split_at_commas(const std::string &line)
      {
        std::vector<std::string> fields;
        std::string::size_type   begin = 0;
        while (true)
          {
            const auto comma = line.find(',', begin);
            fields.push_back(trim(line.substr(begin, comma - begin)));
            if (comma == std::string::npos)
              break;
            begin = comma + 1;
          }
        return fields;
      }



      std::string
      format_number(const double value, const int precision = 6)
      {
        std::ostringstream stream;
        stream.precision(precision);
        stream << value;
        return stream.str();
      }



      double
      mean_of(const std::vector<double> &values)
      {
        return std::accumulate(values.begin(), values.end(), 0.) /
               values.size();
      }
    } // namespace



    // @sect4{Reading the trajectory}
    //
    // The reader finds its columns by name, so that the simulator and the
    // motion-capture scripts may write further columns in any order. Every
    // error names the file, the line and, where there is one, the column,
    // because a trajectory is usually produced by a different program than
    // the one that complains about it.
    //
    // A file looks like
    // @code
    // # tip of the finger, scene "release", time step 0.01 s
    // t,u_x,u_y,u_z,v_x,kinetic_energy
    // 0,0.0123,0,0,0,0
    // 0.01,0.0121,0.0004,0.0001,-0.02,1.3e-05
    // @endcode
    // and the rules, in the order in which they are checked, are:
    // - blank lines, and lines whose first non-blank character is
    //   <code>#</code>, are skipped anywhere in the file;
    // - the first other line is the header. Names are trimmed and may be
    //   quoted. A name that appears twice is an error, since it would be
    //   ambiguous which column is meant; so is <code>u_z</code> without
    //   <code>u_y</code>, which is more likely a mistake than a planar
    //   record in the $x$-$z$ plane;
    // - every data line has as many fields as the header. Only the columns
    //   that are used are parsed, so the others may hold anything;
    // - a number is read with <code>strtod</code> (the C locale's decimal
    //   point), must fill its whole field and must be finite: a diverged
    //   simulation that wrote <code>nan</code> should stop the analysis, not
    //   feed it;
    // - times increase strictly. A repeated time, e.g. from a restart that
    //   appended to the file, would make the sampling ambiguous.
    TipTrajectory
    read_tip_trajectory(const std::string &csv_file)
    {
      std::ifstream input(csv_file);
      if (!input)
        throw std::runtime_error("Cannot open the tip trajectory file '" +
                                 csv_file + "' for reading.");

      const auto location = [&csv_file](const unsigned int line_number) {
        return "In the tip trajectory file '" + csv_file + "', line " +
               std::to_string(line_number) + ": ";
      };

      const std::array<std::string, 3> displacement_names = {
        {"u_x", "u_y", "u_z"}};

      std::vector<std::string> column_names;
      unsigned int             header_line_number   = 0;
      int                      time_column          = -1;
      std::array<int, 3>       displacement_columns = {{-1, -1, -1}};

      TipTrajectory trajectory;
      std::string   previous_time_text;
      std::string   line;
      unsigned int  line_number = 0;
      while (std::getline(input, line))
        {
          ++line_number;
          const std::string content = trim(line);
          if (content.empty() || content.front() == '#')
            continue;
          const std::vector<std::string> fields = split_at_commas(content);

          // The first line that is not a comment is the header. Column names
          // may be quoted, as spreadsheet programs write them.
          if (column_names.empty())
            {
              header_line_number = line_number;
              for (std::string name : fields)
                {
                  if (name.size() >= 2 && name.front() == '"' &&
                      name.back() == '"')
                    name = trim(name.substr(1, name.size() - 2));
                  column_names.push_back(name);
                }

              std::string listed_names;
              for (unsigned int c = 0; c < column_names.size(); ++c)
                {
                  listed_names += (c > 0 ? ", '" : "'") + column_names[c] + "'";
                  for (unsigned int d = 0; d < c; ++d)
                    if (column_names[d] == column_names[c])
                      throw std::runtime_error(
                        location(line_number) + "the column '" +
                        column_names[c] + "' appears twice in the header.");
                  if (column_names[c] == "t")
                    time_column = c;
                  for (unsigned int i = 0; i < 3; ++i)
                    if (column_names[c] == displacement_names[i])
                      displacement_columns[i] = c;
                }

              if (time_column < 0 || displacement_columns[0] < 0)
                throw std::runtime_error(
                  location(line_number) +
                  "the header must name the columns 't' and 'u_x' "
                  "(optionally also 'u_y' and 'u_z'), but it names " +
                  listed_names + ".");
              if (displacement_columns[2] >= 0 && displacement_columns[1] < 0)
                throw std::runtime_error(
                  location(line_number) +
                  "the header names a column 'u_z' but no column 'u_y'; "
                  "a record has the components u_x, (u_x, u_y) or "
                  "(u_x, u_y, u_z).");
              trajectory.n_components = (displacement_columns[2] >= 0   ? 3
                                         : displacement_columns[1] >= 0 ? 2
                                                                        : 1);
              continue;
            }

          if (fields.size() != column_names.size())
            throw std::runtime_error(
              location(line_number) + "found " + std::to_string(fields.size()) +
              " comma-separated fields, but the header on line " +
              std::to_string(header_line_number) + " names " +
              std::to_string(column_names.size()) + " columns.");

          const auto parse = [&](const int column) {
            const std::string &text  = fields[column];
            char              *end   = nullptr;
            const double       value = std::strtod(text.c_str(), &end);
            if (text.empty() || end != text.c_str() + text.size() ||
                !std::isfinite(value))
              throw std::runtime_error(
                location(line_number) + "column '" + column_names[column] +
                "' (field " + std::to_string(column + 1) + ") holds '" + text +
                "', which is not a finite number.");
            return value;
          };

          const double time = parse(time_column);
          if (!trajectory.time.empty() && !(time > trajectory.time.back()))
            throw std::runtime_error(
              location(line_number) + "column 't' holds the time " +
              fields[time_column] + ", which is not larger than the time " +
              previous_time_text +
              " on the previous data line; times must increase strictly.");
          previous_time_text = fields[time_column];

          std::array<double, 3> displacement = {{0., 0., 0.}};
          for (unsigned int i = 0; i < trajectory.n_components; ++i)
            displacement[i] = parse(displacement_columns[i]);

          trajectory.time.push_back(time);
          trajectory.displacement.push_back(displacement);
        }

      if (input.bad())
        throw std::runtime_error("Reading the tip trajectory file '" +
                                 csv_file + "' failed after line " +
                                 std::to_string(line_number) + ".");
      if (column_names.empty())
        throw std::runtime_error("The tip trajectory file '" + csv_file +
                                 "' has no header line (it is empty or "
                                 "holds only comments).");
      if (trajectory.time.size() < 2)
        throw std::runtime_error("The tip trajectory file '" + csv_file +
                                 "' has " +
                                 std::to_string(trajectory.time.size()) +
                                 " data lines; at least two are needed.");
      return trajectory;
    }



    // @sect4{Skipping an initial interval}
    //
    // Samples up to a millionth of a time step before the requested start
    // are kept, so that a start time that is printed with fewer digits than
    // the times in the file does not lose the first sample.
    TipTrajectory
    skip_initial_interval(const TipTrajectory &trajectory, const double seconds)
    {
      const std::size_t n = trajectory.time.size();
      if (n < minimal_number_of_samples || trajectory.displacement.size() != n)
        throw std::invalid_argument("The trajectory has " + std::to_string(n) +
                                    " samples; at least " +
                                    std::to_string(minimal_number_of_samples) +
                                    " with one displacement each are needed.");

      const double longest_skip =
        trajectory.time[n - minimal_number_of_samples] - trajectory.time[0];
      if (!std::isfinite(seconds) || seconds < 0. || seconds > longest_skip)
        throw std::invalid_argument(
          "The initial interval to skip must lie in [0, " +
          format_number(longest_skip) + "] s, so that at least " +
          std::to_string(minimal_number_of_samples) +
          " samples remain, but it is " + format_number(seconds) + " s.");

      const double mean_step =
        (trajectory.time.back() - trajectory.time.front()) / (n - 1);
      const double start = trajectory.time.front() + seconds - 1e-6 * mean_step;

      TipTrajectory remaining;
      remaining.n_components = trajectory.n_components;
      for (std::size_t i = 0; i < n; ++i)
        if (trajectory.time[i] >= start)
          {
            remaining.time.push_back(trajectory.time[i]);
            remaining.displacement.push_back(trajectory.displacement[i]);
          }
      return remaining;
    }



    // @sect4{Uniform sampling}
    //
    // A simulator that cuts its time step back for a while, or a motion
    // capture system that drops frames, produces non-uniform records. They
    // are interpolated linearly onto a grid with the median step -- the
    // regular step of the simulator, unaffected by a few cutbacks. Linear
    // interpolation of a signal with angular frequency $\omega$ on steps of
    // length $h$ has an error of at most $h^2\max|u''|/8 = (\omega h)^2A/8$,
    // 1.8 % of the amplitude for 6 Hz and $h=0.01$ s; since this error
    // follows the envelope, it changes the amplitude but hardly the decay.
    //
    // A record whose steps agree within the tolerance is left alone; its
    // sample rate is taken from the total duration, which is more accurate
    // than any single printed step. Times printed with six significant
    // digits change a step of $1/240$ s by up to 0.24 % for $t<10$ s, which
    // the default tolerance of 1 % absorbs. Classifying a nearly uniform
    // record as non-uniform would do no harm either: the interpolation uses
    // the recorded times, so it cannot shift a frequency, it only moves the
    // samples onto a grid.
    //
    // The interpolation sweeps once through the original intervals: the
    // uniform times increase, so the interval $[t_i, t_{i+1}]$ that
    // contains the next uniform time is found by moving forward, and
    // $u(t) = (1-\lambda)u_i + \lambda u_{i+1}$ with
    // $\lambda = (t-t_i)/(t_{i+1}-t_i)$. The number of uniform samples is
    // the largest that still fits into the recorded interval.
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

      std::vector<double> steps(n - 1);
      for (std::size_t i = 0; i + 1 < n; ++i)
        {
          steps[i] = trajectory.time[i + 1] - trajectory.time[i];
          if (!(steps[i] > 0.))
            throw std::invalid_argument(
              "The times of a trajectory must increase strictly, but sample " +
              std::to_string(i + 1) + " is at " +
              format_number(trajectory.time[i + 1], 17) + " s after " +
              format_number(trajectory.time[i], 17) + " s.");
        }

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

      const std::size_t n_uniform =
        static_cast<std::size_t>(
          std::floor((trajectory.time.back() - trajectory.time.front()) /
                     uniform_step * (1. + 1e-12))) +
        1;
      uniform.displacement.resize(n_uniform);

      // One sweep through the original intervals: the uniform times are
      // increasing, so the interval that contains them only moves forward.
      std::size_t interval = 0;
      for (std::size_t k = 0; k < n_uniform; ++k)
        {
          const double time = uniform.start_time + k * uniform_step;
          while (interval + 2 < n && trajectory.time[interval + 1] < time)
            ++interval;
          const double weight = std::min(
            1.,
            std::max(0., (time - trajectory.time[interval]) / steps[interval]));
          for (unsigned int d = 0; d < 3; ++d)
            uniform.displacement[k][d] =
              (1. - weight) * trajectory.displacement[interval][d] +
              weight * trajectory.displacement[interval + 1][d];
        }
      uniform.sample_rate = 1. / uniform_step;
      uniform.resampled   = true;

      // A gap of several steps is bridged by a straight line, which cuts off
      // any oscillation inside it; that deserves a warning.
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



    // @sect4{Directions of motion}
    //
    // A pendulum swing of the robot happens in a plane through its vertical
    // axis. Among the planes through the $x$ axis, the one with normal
    // $\mathbf n = (0,-\sin\theta,\cos\theta)$ fits the motion best if it
    // minimises the mean square of the out-of-plane displacement
    // $\mathbf n\cdot\mathbf u$, i.e. if $\mathbf n$ is the eigenvector of
    // the smaller eigenvalue of the $(y,z)$ covariance
    // $C = \begin{pmatrix}C_{yy}&C_{yz}\\C_{yz}&C_{zz}\end{pmatrix}$. The
    // in-plane (horizontal) direction $(\cos\theta,\sin\theta)$ is then the
    // principal direction, at the angle
    // @f[
    //   \theta = \tfrac12\operatorname{atan2}(2C_{yz},\,C_{yy}-C_{zz})
    //   \in (-\pi/2, \pi/2].
    // @f]
    // The covariance is taken about the mean, i.e. about the static offset
    // that the spectral analysis removes anyway; for a swing about the axis
    // this is the same as the second moment about the axis.
    //
    // The eigenvalues $\lambda_\pm = \tfrac12(C_{yy}+C_{zz}) \pm
    // \sqrt{\tfrac14(C_{yy}-C_{zz})^2 + C_{yz}^2}$ are the mean squares of
    // the horizontal and the depth motion; their ratio tells how planar the
    // motion is. The sign of the horizontal direction is fixed by the range
    // of $\theta$: its $y$ component is positive (or, for $\theta=\pi/2$,
    // it points along $+z$). The depth direction
    // $(-\sin\theta, \cos\theta)$ is the horizontal one turned by
    // $+90^\circ$ about $x$, so that $\mathbf e_x \times
    // \mathbf e_\text{horizontal} = \mathbf e_\text{depth}$. Without any
    // $(y,z)$ motion, or for a circular one, the angle is arbitrary
    // (<code>atan2(0,0)</code> gives $\theta = 0$); the ratio then says so.
    DirectionalSignals
    split_into_directions(const UniformTrajectory &trajectory)
    {
      const std::size_t n = trajectory.displacement.size();
      if (trajectory.n_components < 1 || trajectory.n_components > 3)
        throw std::invalid_argument(
          "A trajectory has one, two or three displacement components, not " +
          std::to_string(trajectory.n_components) + ".");

      DirectionalSignals signals;
      const auto         component = [&](const unsigned int d) {
        std::vector<double> values(n);
        for (std::size_t i = 0; i < n; ++i)
          values[i] = trajectory.displacement[i][d];
        return values;
      };

      signals.names.push_back("vertical");
      signals.samples.push_back(component(0));
      if (trajectory.n_components == 1)
        return signals;

      const std::vector<double> u_y = component(1);
      if (trajectory.n_components == 2)
        {
          signals.names.push_back("horizontal");
          signals.samples.push_back(u_y);
          return signals;
        }

      const std::vector<double> u_z    = component(2);
      const double              mean_y = mean_of(u_y);
      const double              mean_z = mean_of(u_z);
      double                    c_yy = 0., c_zz = 0., c_yz = 0.;
      for (std::size_t i = 0; i < n; ++i)
        {
          c_yy += (u_y[i] - mean_y) * (u_y[i] - mean_y) / n;
          c_zz += (u_z[i] - mean_z) * (u_z[i] - mean_z) / n;
          c_yz += (u_y[i] - mean_y) * (u_z[i] - mean_z) / n;
        }

      const double theta      = 0.5 * std::atan2(2. * c_yz, c_yy - c_zz);
      const double half_trace = 0.5 * (c_yy + c_zz);
      const double radius =
        std::sqrt(0.25 * (c_yy - c_zz) * (c_yy - c_zz) + c_yz * c_yz);
      const double major = half_trace + radius;
      const double minor = std::max(0., half_trace - radius);

      signals.plane_angle        = theta;
      signals.out_of_plane_ratio = (major > 0. ? std::sqrt(minor / major) : 0.);

      std::vector<double> horizontal(n), depth(n);
      for (std::size_t i = 0; i < n; ++i)
        {
          horizontal[i] = std::cos(theta) * u_y[i] + std::sin(theta) * u_z[i];
          depth[i]      = -std::sin(theta) * u_y[i] + std::cos(theta) * u_z[i];
        }
      signals.names.push_back("horizontal");
      signals.samples.push_back(horizontal);
      signals.names.push_back("depth");
      signals.samples.push_back(depth);
      return signals;
    }



    // @sect4{Truncation theory}
    //
    // The dimensionless spectrum of a decay $e^{-s\tau}$ on the unit interval
    // $0\le\tau\le1$, multiplied by the window $w(\tau)$, at the offset $w$
    // from the carrier is $\int_0^1 w(\tau)\,e^{-(s+iw)\tau}\,d\tau$. Without
    // window this is $E(s+iw)$; the Hann window
    // $w = \tfrac12 - \tfrac14 e^{2\pi i\tau} - \tfrac14 e^{-2\pi i\tau}$
    // gives three shifted copies of $E$. Because the integrand at $w=0$ is
    // non-negative, the magnitude is largest at $w=0$, and the half-power
    // half-width $w_h$ is found by stepping away from $w=0$ and bisecting.
    //
    // The steps are $0.05(1+s)$: small enough not to jump over the main lobe
    // (whose half-width is at least $2.78$, the undamped value, and grows
    // like $s$), and few enough for large $s$. Sixty bisections then fix
    // $w_h$ to round-off. The inverse function brackets $s$ by doubling and
    // bisects as well; it relies on $BT(s)$ increasing monotonically, which
    // holds for both windows (the table at the top of this file).
    namespace
    {
      std::complex<double>
      unit_interval_exponential_integral(const std::complex<double> z)
      {
        // Series for small $|z|$, where $1-e^{-z}$ would cancel.
        if (std::abs(z) < 1e-4)
          return 1. - z / 2. + z * z / 6. - z * z * z / 24.;
        return (1. - std::exp(-z)) / z;
      }



      double
      truncated_decay_spectrum(const double         frequency_offset,
                               const double         decay_exponent,
                               const SpectralWindow window)
      {
        const std::complex<double> z(decay_exponent, frequency_offset);
        if (window == SpectralWindow::none)
          return std::abs(unit_interval_exponential_integral(z));

        const std::complex<double> shift(0., 2. * pi);
        return std::abs(0.5 * unit_interval_exponential_integral(z) -
                        0.25 * unit_interval_exponential_integral(z - shift) -
                        0.25 * unit_interval_exponential_integral(z + shift));
      }



      // The inverse of truncated_decay_half_power_width(): the decay
      // exponent $s$ whose half-power width is the measured $BT$, or NaN if
      // $BT$ does not exceed the width of an undamped record.
      double
      decay_exponent_from_half_power_width(const double         width,
                                           const SpectralWindow window)
      {
        const double undamped_width =
          truncated_decay_half_power_width(0., window);
        if (!(width > undamped_width * (1. + 1e-6)))
          return not_a_number;

        double lower = 0., upper = 1.;
        while (truncated_decay_half_power_width(upper, window) < width)
          {
            lower = upper;
            upper *= 2.;
            if (upper > 1e6)
              return not_a_number;
          }
        for (unsigned int i = 0; i < 60; ++i)
          {
            const double middle = 0.5 * (lower + upper);
            if (truncated_decay_half_power_width(middle, window) < width)
              lower = middle;
            else
              upper = middle;
          }
        return 0.5 * (lower + upper);
      }
    } // namespace



    double
    truncated_decay_half_power_width(const double         decay_exponent,
                                     const SpectralWindow window)
    {
      if (!std::isfinite(decay_exponent) || decay_exponent < 0.)
        throw std::invalid_argument(
          "The decay exponent sigma*T must be finite and non-negative, but "
          "is " +
          format_number(decay_exponent) + ".");

      const double level =
        truncated_decay_spectrum(0., decay_exponent, window) / std::sqrt(2.);
      const double step  = 0.05 * (1. + decay_exponent);
      double       below = 0., above = step;
      while (truncated_decay_spectrum(above, decay_exponent, window) > level)
        {
          below = above;
          above += step;
        }
      for (unsigned int i = 0; i < 60; ++i)
        {
          const double middle = 0.5 * (below + above);
          if (truncated_decay_spectrum(middle, decay_exponent, window) > level)
            below = middle;
          else
            above = middle;
        }

      // The full width in Hz is $2w_h/(2\pi T)$, so $BT = w_h/\pi$.
      return 0.5 * (below + above) / pi;
    }



    double
    half_power_truncation_bias(const double         decay_exponent,
                               const SpectralWindow window)
    {
      if (!(decay_exponent > 0.))
        throw std::invalid_argument(
          "The truncation bias is defined for a positive decay exponent "
          "sigma*T only, but it is " +
          format_number(decay_exponent) + ".");
      return pi * truncated_decay_half_power_width(decay_exponent, window) /
               decay_exponent -
             1.;
    }



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



    // @sect4{The zero-padded magnitude spectrum}
    //
    // The $N$ (windowed) samples are padded with zeros to the FFT length $L$;
    // the padded transform samples the same continuous spectrum of the
    // record on the finer grid $f_k = k f_s/L$, which is what the sub-bin
    // interpolation of the peak and the crossings needs. The magnitude is
    // scaled as an amplitude spectrum, $2|X_k|/\sum_n w_n$, so that a steady
    // sinusoid of amplitude $A$ shows a peak of height $A$.
    //
    // The normalisation follows from the transform of such a sinusoid,
    // $x_n = w_n A\cos(\omega n\Delta t)$: at its frequency the
    // positive-frequency half contributes $X = \tfrac A2\sum_n w_n$, and the
    // negative-frequency half is negligible for many cycles. Without window
    // $\sum_n w_n = N$. The real-to-complex transform returns the
    // $L/2+1$ coefficients for $0 \le f \le f_s/2$; the others are their
    // complex conjugates and carry no information.
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
          magnitude[k] = 2. *
                         std::hypot(output.get()[k][0], output.get()[k][1]) /
                         window_sum;
        return magnitude;
      }
    } // namespace



    // @sect4{Peaks and their half-power bandwidths}
    //
    // <i>Sub-bin peak.</i> Through the largest bin $k$ and its neighbours a
    // parabola $y(p)$, $p\in[-1,1]$ in bins, is laid; its vertex is at
    // @f[
    //   p^\ast = \frac{y_{-1}-y_{+1}}{2(y_{-1}-2y_0+y_{+1})}, \qquad
    //   y^\ast = y_0 - \tfrac14(y_{-1}-y_{+1})p^\ast.
    // @f]
    // With 16-fold padding the main lobe spans dozens of bins and the
    // parabola is accurate to a tiny fraction of a bin.
    //
    // <i>Half-power crossings.</i> From the peak the spectrum is followed
    // bin by bin to both sides until it falls below $y^\ast/\sqrt2$; the
    // crossing is interpolated linearly between the last two bins. If the
    // spectrum rises above $y^\ast$ before (another, larger peak) or the end
    // of the spectrum is reached, that crossing does not exist.
    //
    // <i>Which local maxima are resonances.</i> A zero-padded spectrum of a
    // short record has many local maxima; a maximum is taken as a peak only
    // if
    // - it stands at least 20 dB (a factor 10) above the noise floor, the
    //   median of the spectrum above the zero-frequency lobe: for white
    //   noise the magnitudes are Rayleigh distributed, and a bin exceeds ten
    //   times their median with probability $e^{-(10\cdot1.177)^2/2}
    //   \approx 10^{-30}$, whereas for a noise-free free decay the median is
    //   the far tail of the Lorentzian, orders of magnitude lower;
    // - it lies above the zero-frequency neighbourhood, i.e. beyond the
    //   first zero of the window's main lobe around $f=0$ ($1/T$ without
    //   window, $2/T$ with Hann): the residual of the removed offset leaks
    //   into that lobe, and a maximum there is less than one cycle in the
    //   record, which cannot be told apart from a drift;
    // - the spectrum falls by 3 dB on both sides before it rises above the
    //   maximum again (otherwise it is a shoulder of a larger peak); and
    // - its half-power width is at least 0.8 times the width of the main
    //   lobe of an undamped record ($0.886/T$, resp. $1.441/T$): no
    //   oscillation recorded for $T$ seconds can have a narrower peak,
    //   whereas the side lobes of an undamped record are only $0.5/T$ wide;
    //   and
    // - it rises above the leakage of every larger peak. A damped mode's
    //   side lobes are its Lorentzian tail modulated by the ripple
    //   $1-e^{-s}e^{-iw}$; for $s < 1.76$ they dip by more than 3 dB and,
    //   broadened by the image at $-f$, can be as wide as a resonance. The
    //   leakage of a peak of magnitude $M_j$ at $f_j$ is at most
    //   $M_j\,[g(2\pi T(f-f_j)) + g(2\pi T(f+f_j))]$, where $g(w)$ is the
    //   largest normalised magnitude of the truncated-decay spectrum within
    //   one ripple period ($\pm\pi$) of $w$ and the second term is the image;
    //   the decay exponent $s_j$ is taken from the peak's bandwidth, and
    //   $M_j$ is divided by $1-g(4\pi T f_j)$ because the image may have
    //   lowered the measured peak by that much. A maximum below that bound
    //   is a side lobe, not a second mode.
    namespace
    {
      struct PeakSearchResult
      {
        std::vector<SpectralPeak> peaks;
        std::string               reason_if_none;
      };



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



      // The largest normalised magnitude of the truncated-decay spectrum
      // within one ripple period of the offset $w$, i.e. the envelope of its
      // side lobes there.
      double
      side_lobe_envelope(const double         frequency_offset,
                         const double         decay_exponent,
                         const SpectralWindow window)
      {
        const double peak_value =
          truncated_decay_spectrum(0., decay_exponent, window);
        const unsigned int n_points = 65;
        double             envelope = 0.;
        for (unsigned int i = 0; i < n_points; ++i)
          {
            const double w =
              std::abs(frequency_offset) + pi * (2. * i / (n_points - 1) - 1.);
            envelope = std::max(envelope,
                                truncated_decay_spectrum(std::max(w, 0.),
                                                         decay_exponent,
                                                         window));
          }
        return envelope / peak_value;
      }



      PeakSearchResult
      find_spectral_peaks(const std::vector<double> &magnitude,
                          const double               frequency_step,
                          const double               duration,
                          const SpectralOptions     &options)
      {
        // The search runs over the bins above the zero-frequency lobe. Each
        // local maximum is tested in turn against the criteria above; the
        // counters remember why maxima were rejected, to explain a "no
        // peak" result.
        const double dc_lobe_edge =
          (options.window == SpectralWindow::none ? 1. : 2.) / duration;
        const double narrowest_resonance =
          0.8 * truncated_decay_half_power_width(0., options.window) / duration;
        const std::size_t first_bin =
          std::max<std::size_t>(1,
                                static_cast<std::size_t>(
                                  std::ceil(dc_lobe_edge / frequency_step)));

        std::vector<double> above_dc_lobe(magnitude.begin() + first_bin,
                                          magnitude.end());
        std::nth_element(above_dc_lobe.begin(),
                         above_dc_lobe.begin() + above_dc_lobe.size() / 2,
                         above_dc_lobe.end());
        const double noise_floor = above_dc_lobe[above_dc_lobe.size() / 2];

        unsigned int n_local_maxima = 0, n_in_noise = 0, n_shoulders = 0,
                     n_side_lobes = 0;
        PeakSearchResult search;
        for (std::size_t k = first_bin; k + 1 < magnitude.size(); ++k)
          {
            if (!(magnitude[k] > magnitude[k - 1] &&
                  magnitude[k] >= magnitude[k + 1]))
              continue;
            ++n_local_maxima;
            if (magnitude[k] < 10. * noise_floor)
              {
                ++n_in_noise;
                continue;
              }

            // The vertex of the parabola; a flat top (zero curvature) keeps
            // the bin itself.
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
                ++n_shoulders;
                continue;
              }

            peak.bandwidth =
              peak.upper_half_power_frequency - peak.lower_half_power_frequency;
            if (peak.bandwidth < narrowest_resonance)
              {
                ++n_side_lobes;
                continue;
              }

            peak.quality_factor           = peak.frequency / peak.bandwidth;
            peak.damping_ratio_half_power = 0.5 / peak.quality_factor;
            search.peaks.push_back(peak);
          }

        // The accepted maxima by decreasing magnitude: the first is the
        // dominant peak. The others are kept, up to the requested number, if
        // they reach the threshold relative to the dominant peak and rise
        // above the leakage of all peaks kept before them; the decay
        // exponent of each kept peak is computed once, when it is first
        // needed.
        std::sort(search.peaks.begin(),
                  search.peaks.end(),
                  [](const SpectralPeak &a, const SpectralPeak &b) {
                    return a.magnitude > b.magnitude;
                  });
        if (!search.peaks.empty())
          {
            const double smallest_magnitude =
              options.secondary_peak_threshold * search.peaks[0].magnitude;
            std::vector<SpectralPeak> kept = {search.peaks[0]};
            std::vector<double>       decay_exponents;
            for (std::size_t i = 1; i < search.peaks.size() &&
                                    kept.size() <= options.max_secondary_peaks;
                 ++i)
              {
                const SpectralPeak &candidate = search.peaks[i];
                if (candidate.magnitude < smallest_magnitude)
                  break;

                double leakage = 0.;
                for (std::size_t j = 0; j < kept.size(); ++j)
                  {
                    if (decay_exponents.size() <= j)
                      {
                        const double s = decay_exponent_from_half_power_width(
                          kept[j].bandwidth * duration, options.window);
                        decay_exponents.push_back(std::isnan(s) ? 0. : s);
                      }
                    // The image at $-f_j$ may lower the measured peak
                    // itself by up to its envelope at $2f_j$.
                    const double image_at_peak =
                      side_lobe_envelope(4. * pi * duration * kept[j].frequency,
                                         decay_exponents[j],
                                         options.window);
                    leakage += kept[j].magnitude /
                               (1. - std::min(0.5, image_at_peak)) *
                               (side_lobe_envelope(2. * pi * duration *
                                                     (candidate.frequency -
                                                      kept[j].frequency),
                                                   decay_exponents[j],
                                                   options.window) +
                                side_lobe_envelope(2. * pi * duration *
                                                     (candidate.frequency +
                                                      kept[j].frequency),
                                                   decay_exponents[j],
                                                   options.window));
                  }
                if (candidate.magnitude > leakage)
                  kept.push_back(candidate);
              }
            search.peaks = kept;
          }
        else if (n_local_maxima == 0)
          search.reason_if_none =
            "the magnitude spectrum has no local maximum above " +
            format_number(dc_lobe_edge, 3) +
            " Hz, the edge of the zero-frequency lobe";
        else
          search.reason_if_none =
            "none of the " + std::to_string(n_local_maxima) +
            " local maxima of the spectrum above " +
            format_number(dc_lobe_edge, 3) +
            " Hz is a resonance: " + std::to_string(n_in_noise) +
            " are less than 20 dB above the noise floor (the median "
            "magnitude " +
            format_number(noise_floor, 3) + "), " +
            std::to_string(n_shoulders) +
            " do not fall by 3 dB on both sides, and " +
            std::to_string(n_side_lobes) + " are narrower than " +
            format_number(narrowest_resonance, 3) +
            " Hz, less than the main lobe of an undamped oscillation "
            "recorded for " +
            format_number(duration, 4) + " s (side lobes of the truncation)";
        return search;
      }
    } // namespace



    // @sect4{Turning points and the logarithmic decrement}
    //
    // The extrema of a single damped mode lie half a damped period apart,
    // and their distances from the equilibrium $c$ shrink by the factor
    // $e^{-\sigma T_d/2}$ from one to the next. The difference of two
    // successive extrema, the peak-to-peak amplitude of a half cycle,
    // @f[
    //   h_j = |u_{j+1} - u_j| \propto e^{-\sigma T_d\,j/2},
    // @f]
    // does not contain $c$ at all, so it is insensitive to the offset
    // estimate. A least-squares line through $\ln h_j$ against the cycle
    // index $j/2$ has the slope $-\delta$, the logarithmic decrement
    // $\delta = \sigma T_d = 2\pi\xi/\sqrt{1-\xi^2}$, and hence
    // $\xi = \delta/\sqrt{4\pi^2+\delta^2}$.
    //
    // Extrema are found with a hysteresis of 2 % of the signal range (a
    // maximum is confirmed only when the signal has fallen by that much
    // below it), which ignores small wiggles. Extrema at the first sample
    // are boundary values, not turning points, and are dropped. The value
    // of each extremum comes from the parabola through the largest sample
    // and its neighbours; its error, of order $(\omega\Delta t)^4$, is below
    // $10^{-3}$ of the amplitude at 16 samples per cycle.
    //
    // Which half cycles enter the line: the run starts at the largest
    // amplitude $h_j$ and continues while successive extrema are half a
    // period of the spectral peak apart (within 25 %) and $h_j$ is at least
    // 10 % of the largest one and 20 times the noise level $\sigma_n$. These
    // conditions end the run where noise begins to dominate: extrema of
    // noise are irregularly spaced, and each extremum carries an error of
    // order $\sigma_n$, i.e. 10 % of $\ln h_j$ at $h_j = 20\sigma_n$. For the
    // same reason the hysteresis is raised to $6\sigma_n$ if that is larger,
    // since a pair of noise samples reverses by that much with probability
    // $3\cdot10^{-5}$. The noise level is the rms residual of the modal fit
    // (zero without a valid fit); an estimate from the spectrum would
    // mistake the $1/f$ tail of the truncation for noise. Without these
    // limits, a record that decays into a noise of 1 % of its initial
    // amplitude has its decrement underestimated by several per cent.
    namespace
    {
      struct TurningPoint
      {
        double position;
        double value;
      };



      std::vector<TurningPoint>
      find_turning_points(const std::vector<double> &signal,
                          const double               noise_level = 0.)
      {
        const auto [smallest, largest] =
          std::minmax_element(signal.begin(), signal.end());
        const double hysteresis =
          std::max(turning_point_hysteresis * (*largest - *smallest),
                   6. * noise_level);
        if (!(hysteresis > 0.))
          return {};

        // The search is a small state machine. At first the direction is
        // unknown and the running minimum and maximum are tracked; as soon as
        // they are a hysteresis apart, the earlier of the two is the first
        // turning point, and the later one becomes the candidate for the
        // next. From then on the search alternates: while looking for a
        // maximum (direction +1), a larger value replaces the candidate, and
        // a value that lies a hysteresis below it confirms the candidate as
        // a maximum and starts the search for a minimum (direction -1), and
        // vice versa. A candidate that is not confirmed by the end of the
        // record is dropped, as are turning points at the first sample.
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

        std::vector<TurningPoint> turning_points;
        for (const std::size_t i : indices)
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



      LogarithmicDecrement
      logarithmic_decrement_of(const std::vector<TurningPoint> &turning_points,
                               const double half_period_in_samples,
                               const double noise_level)
      {
        LogarithmicDecrement decrement;
        decrement.decrement     = not_a_number;
        decrement.damping_ratio = not_a_number;

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

        // Least-squares line through $(j/2, \ln h_j)$.
        const std::size_t m          = log_amplitudes.size();
        const double      mean_index = 0.25 * (m - 1.);
        const double      mean_log   = mean_of(log_amplitudes);
        double            covariance = 0., variance = 0.;
        for (std::size_t j = 0; j < m; ++j)
          {
            covariance +=
              (0.5 * j - mean_index) * (log_amplitudes[j] - mean_log);
            variance += (0.5 * j - mean_index) * (0.5 * j - mean_index);
          }

        decrement.valid     = true;
        decrement.decrement = -covariance / variance;
        decrement.damping_ratio =
          decrement.decrement /
          std::sqrt(4. * pi * pi + decrement.decrement * decrement.decrement);
        return decrement;
      }
    } // namespace



    // @sect4{Fitting damped modes}
    //
    // The model for a record with $K$ spectral peaks is
    // @f[
    //   u(t) \approx c_0 + c_1\left(\frac tT-\frac12\right)
    //     + \sum_{k=1}^{K} e^{-\sigma_k t}
    //     \left(a_k\cos\omega_k t + b_k\sin\omega_k t\right),
    //   \qquad 0 \le t < T,
    // @f]
    // where the linear trend absorbs a residual offset and a slow drift of
    // the equilibrium (creep, marker drift), which would otherwise be
    // fitted by the modes. The model is linear in $c_0, c_1, a_k, b_k$ and
    // nonlinear in
    // $\mathbf p = (\sigma_k, \omega_k)_k$. Variable projection (Golub and
    // Pereyra) eliminates the linear coefficients: for given $\mathbf p$ they
    // are the least-squares solution, computed by a Householder QR
    // factorisation of the $N\times(2K+2)$ matrix of basis functions, and
    // the residual $\mathbf r(\mathbf p)$ that remains is minimised over the
    // $2K$ nonlinear parameters by Levenberg--Marquardt,
    // @f[
    //   \left(J^TJ + \lambda\,\operatorname{diag}J^TJ\right)\delta\mathbf p
    //   = -J^T\mathbf r,
    // @f]
    // with $J = \partial\mathbf r/\partial\mathbf p$ from central
    // differences. The frequencies start at the spectral peaks and the decay
    // rates at $\pi B$ (the Lorentzian value of the bandwidth $B$), at a third
    // and at a tenth of it, because truncation can make $\pi B$ ten times too
    // large; the best of the three minima is kept. A mode is accepted only if
    // its frequency stays within one bandwidth (or one resolution $1/T$, if
    // that is larger) of the peak it started from. As explained at the top of this
    // file, this is the fit of the truncated Lorentzian to the complex
    // spectrum, and for a record that is a sum of damped modes it recovers
    // $\sigma_k$ and $\omega_k$ exactly.
    namespace
    {
      struct ModalFit
      {
        bool                valid = false;
        std::string         reason;
        std::vector<double> decay_rates;
        std::vector<double> angular_frequencies;
        std::vector<double> amplitudes;
        double              relative_residual = not_a_number;
      };



      // Least squares for a tall matrix given by its columns; returns the
      // residual in the original coordinates (needed for the Jacobian) and
      // the coefficients. Columns that are linearly dependent on earlier
      // ones to round-off get a zero coefficient.
      //
      // Householder QR: for column $k$, the reflection
      // $H = I - 2\mathbf v\mathbf v^T/\mathbf v^T\mathbf v$ with
      // $\mathbf v = \mathbf a_k - \alpha\mathbf e_k$ (rows $k$ to $N-1$)
      // and $\alpha = -\operatorname{sign}(a_{kk})\|\mathbf a_k\|$ (the sign
      // that avoids cancellation) maps the column onto $\alpha\mathbf e_k$;
      // applied to the later columns and to the right-hand side, the
      // reflections build $R$ and $Q^T\mathbf b$, and back substitution
      // solves $R\mathbf c = (Q^T\mathbf b)_{0..p-1}$. This is slower than
      // the normal equations, but it loses no accuracy to the squared
      // condition number, which matters when two modes are close.
      std::vector<double>
      least_squares_residual(const std::vector<std::vector<double>> &columns,
                             const std::vector<double>              &rhs,
                             std::vector<double> &coefficients)
      {
        const std::size_t                n = rhs.size(), p = columns.size();
        std::vector<std::vector<double>> factor      = columns;
        std::vector<double>              rotated_rhs = rhs;
        std::vector<double>              diagonal(p, 0.);

        for (std::size_t k = 0; k < p; ++k)
          {
            double norm = 0.;
            for (std::size_t i = k; i < n; ++i)
              norm += factor[k][i] * factor[k][i];
            norm = std::sqrt(norm);
            if (norm == 0.)
              continue;

            std::vector<double> &v     = factor[k];
            const double         alpha = (v[k] > 0. ? -norm : norm);
            v[k] -= alpha;
            double v_norm_squared = 0.;
            for (std::size_t i = k; i < n; ++i)
              v_norm_squared += v[i] * v[i];

            const auto reflect = [&](std::vector<double> &x) {
              double projection = 0.;
              for (std::size_t i = k; i < n; ++i)
                projection += v[i] * x[i];
              const double scale = 2. * projection / v_norm_squared;
              for (std::size_t i = k; i < n; ++i)
                x[i] -= scale * v[i];
            };
            for (std::size_t j = k + 1; j < p; ++j)
              reflect(factor[j]);
            reflect(rotated_rhs);
            diagonal[k] = alpha;
          }

        double largest_diagonal = 0.;
        for (const double d : diagonal)
          largest_diagonal = std::max(largest_diagonal, std::abs(d));

        coefficients.assign(p, 0.);
        for (std::size_t k = p; k-- > 0;)
          {
            if (std::abs(diagonal[k]) <= 1e-12 * largest_diagonal)
              continue;
            double sum = rotated_rhs[k];
            for (std::size_t j = k + 1; j < p; ++j)
              sum -= factor[j][k] * coefficients[j];
            coefficients[k] = sum / diagonal[k];
          }

        std::vector<double> residual = rhs;
        for (std::size_t k = 0; k < p; ++k)
          for (std::size_t i = 0; i < n; ++i)
            residual[i] -= coefficients[k] * columns[k][i];
        return residual;
      }



      // The columns of the constant and the linear trend come first.
      constexpr std::size_t first_mode_column = 2;



      // The variable-projection residual for the nonlinear parameters
      // $(\sigma_1,\omega_1,\sigma_2,\omega_2,\dots)$.
      std::vector<double>
      modal_residual(const std::vector<double> &signal,
                     const double               time_step,
                     const std::vector<double> &parameters,
                     std::vector<double>       &coefficients)
      {
        const std::size_t                n       = signal.size();
        const std::size_t                n_modes = parameters.size() / 2;
        std::vector<std::vector<double>> columns(first_mode_column +
                                                   2 * n_modes,
                                                 std::vector<double>(n, 1.));
        for (std::size_t i = 0; i < n; ++i)
          columns[1][i] = (i + 0.5) / n - 0.5;
        for (std::size_t k = 0; k < n_modes; ++k)
          for (std::size_t i = 0; i < n; ++i)
            {
              const double time     = i * time_step;
              const double envelope = std::exp(-parameters[2 * k] * time);
              columns[first_mode_column + 2 * k][i] =
                envelope * std::cos(parameters[2 * k + 1] * time);
              columns[first_mode_column + 2 * k + 1][i] =
                envelope * std::sin(parameters[2 * k + 1] * time);
            }
        return least_squares_residual(columns, signal, coefficients);
      }



      double
      squared_norm(const std::vector<double> &vector)
      {
        return std::inner_product(vector.begin(),
                                  vector.end(),
                                  vector.begin(),
                                  0.);
      }



      // Solve the small dense system $A x = b$ by Gaussian elimination with
      // partial pivoting; returns false if $A$ is singular.
      bool
      solve_dense_system(std::vector<std::vector<double>> matrix,
                         std::vector<double>             &rhs)
      {
        const std::size_t m = rhs.size();
        for (std::size_t k = 0; k < m; ++k)
          {
            std::size_t pivot = k;
            for (std::size_t i = k + 1; i < m; ++i)
              if (std::abs(matrix[i][k]) > std::abs(matrix[pivot][k]))
                pivot = i;
            if (matrix[pivot][k] == 0.)
              return false;
            std::swap(matrix[k], matrix[pivot]);
            std::swap(rhs[k], rhs[pivot]);
            for (std::size_t i = k + 1; i < m; ++i)
              {
                const double factor = matrix[i][k] / matrix[k][k];
                for (std::size_t j = k; j < m; ++j)
                  matrix[i][j] -= factor * matrix[k][j];
                rhs[i] -= factor * rhs[k];
              }
          }
        for (std::size_t k = m; k-- > 0;)
          {
            for (std::size_t j = k + 1; j < m; ++j)
              rhs[k] -= matrix[k][j] * rhs[j];
            rhs[k] /= matrix[k][k];
          }
        return true;
      }



      // Levenberg--Marquardt from one starting point. The parameters are
      // measured in the natural units of the record, $1/T$ for decay rates
      // and $2\pi/T$ for angular frequencies, both for the finite-difference
      // steps and for the convergence test.
      //
      // Each iteration computes the Jacobian by central differences with a
      // step of $10^{-5}$ of those units (a balance between the truncation
      // error $O(h^2)$ and the cancellation error $O(\epsilon/h)$), and then
      // tries steps with increasing damping $\lambda$ until one lowers the
      // cost. An accepted step divides $\lambda$ by 3, a rejected one
      // multiplies it by 4; steps that would make a frequency non-positive
      // or a parameter non-finite are rejected. The iteration ends when no
      // step lowers the cost any more (the minimum has been reached to
      // round-off), when a step changes no parameter by more than
      // $10^{-10}$ of its unit, or after 200 iterations.
      std::vector<double>
      levenberg_marquardt(const std::vector<double> &signal,
                          const double               time_step,
                          std::vector<double>        parameters,
                          double                    &cost)
      {
        const std::size_t   m        = parameters.size();
        const double        duration = signal.size() * time_step;
        std::vector<double> scale(m);
        for (std::size_t i = 0; i < m; ++i)
          scale[i] = (i % 2 == 0 ? 1. : 2. * pi) / duration;

        std::vector<double> coefficients;
        std::vector<double> residual =
          modal_residual(signal, time_step, parameters, coefficients);
        cost = squared_norm(residual);

        double lambda = 1e-3;
        for (unsigned int iteration = 0; iteration < 200; ++iteration)
          {
            std::vector<std::vector<double>> jacobian(m);
            for (std::size_t i = 0; i < m; ++i)
              {
                const double        h     = 1e-5 * scale[i];
                std::vector<double> plus  = parameters;
                std::vector<double> minus = parameters;
                plus[i] += h;
                minus[i] -= h;
                const std::vector<double> r_plus =
                  modal_residual(signal, time_step, plus, coefficients);
                const std::vector<double> r_minus =
                  modal_residual(signal, time_step, minus, coefficients);
                jacobian[i].resize(signal.size());
                for (std::size_t n = 0; n < signal.size(); ++n)
                  jacobian[i][n] = (r_plus[n] - r_minus[n]) / (2. * h);
              }

            std::vector<std::vector<double>> normal_matrix(
              m, std::vector<double>(m));
            std::vector<double> gradient(m);
            for (std::size_t i = 0; i < m; ++i)
              {
                gradient[i] = std::inner_product(jacobian[i].begin(),
                                                 jacobian[i].end(),
                                                 residual.begin(),
                                                 0.);
                for (std::size_t j = 0; j < m; ++j)
                  normal_matrix[i][j] = std::inner_product(jacobian[i].begin(),
                                                           jacobian[i].end(),
                                                           jacobian[j].begin(),
                                                           0.);
              }

            bool   improved  = false;
            double step_size = 0.;
            while (lambda < 1e12)
              {
                std::vector<std::vector<double>> damped = normal_matrix;
                for (std::size_t i = 0; i < m; ++i)
                  damped[i][i] +=
                    lambda * std::max(normal_matrix[i][i], 1e-300);
                std::vector<double> step(m);
                for (std::size_t i = 0; i < m; ++i)
                  step[i] = -gradient[i];
                if (!solve_dense_system(damped, step))
                  {
                    lambda *= 4.;
                    continue;
                  }

                std::vector<double> trial      = parameters;
                bool                admissible = true;
                for (std::size_t i = 0; i < m; ++i)
                  {
                    trial[i] += step[i];
                    admissible = admissible && std::isfinite(trial[i]);
                  }
                for (std::size_t i = 1; i < m; i += 2)
                  admissible = admissible && trial[i] > 0.;
                if (admissible)
                  {
                    std::vector<double> trial_coefficients;
                    std::vector<double> trial_residual = modal_residual(
                      signal, time_step, trial, trial_coefficients);
                    const double trial_cost = squared_norm(trial_residual);
                    if (trial_cost < cost)
                      {
                        step_size = 0.;
                        for (std::size_t i = 0; i < m; ++i)
                          step_size =
                            std::max(step_size, std::abs(step[i]) / scale[i]);
                        const double decrease = cost - trial_cost;
                        parameters            = trial;
                        residual              = trial_residual;
                        cost                  = trial_cost;
                        lambda                = std::max(lambda / 3., 1e-12);
                        improved              = true;
                        if (decrease <= 1e-15 * cost)
                          step_size = 0.;
                        break;
                      }
                  }
                lambda *= 4.;
              }

            // No descent direction left (the minimum is reached to
            // round-off), or the last step was negligible.
            if (!improved || step_size < 1e-10)
              break;
          }
        return parameters;
      }



      // The fit proper: scale, start from the peaks with three initial
      // decay rates, keep the best result, and check it.
      ModalFit
      fit_damped_modes(const std::vector<double>       &signal,
                       const double                     sample_rate,
                       const std::vector<SpectralPeak> &peaks)
      {
        const double time_step = 1. / sample_rate;
        const double duration  = signal.size() * time_step;

        // Work with the signal scaled to unit root mean square, so that the
        // costs are of order one whatever the units of the displacement.
        const double mean        = mean_of(signal);
        double       mean_square = 0.;
        for (const double value : signal)
          mean_square += (value - mean) * (value - mean) / signal.size();
        const double        rms = std::sqrt(mean_square);
        std::vector<double> scaled(signal.size());
        for (std::size_t i = 0; i < signal.size(); ++i)
          scaled[i] = signal[i] / rms;

        ModalFit            fit;
        std::vector<double> best_parameters;
        double              best_cost = std::numeric_limits<double>::max();
        for (const double fraction : {1., 1. / 3., 1. / 10.})
          {
            std::vector<double> parameters;
            for (const SpectralPeak &peak : peaks)
              {
                parameters.push_back(fraction * pi * peak.bandwidth);
                parameters.push_back(2. * pi * peak.frequency);
              }
            double                    cost = 0.;
            const std::vector<double> fitted =
              levenberg_marquardt(scaled, time_step, parameters, cost);
            if (cost < best_cost)
              {
                best_cost       = cost;
                best_parameters = fitted;
              }
          }

        std::vector<double> coefficients;
        modal_residual(scaled, time_step, best_parameters, coefficients);
        // The scaled signal has unit mean square about its mean.
        fit.relative_residual = std::sqrt(best_cost / scaled.size());

        fit.valid = true;
        for (std::size_t k = 0; k < peaks.size(); ++k)
          {
            const double sigma = best_parameters[2 * k];
            const double omega = best_parameters[2 * k + 1];
            const double amplitude =
              rms * std::hypot(coefficients[first_mode_column + 2 * k],
                               coefficients[first_mode_column + 2 * k + 1]);
            fit.decay_rates.push_back(sigma);
            fit.angular_frequencies.push_back(omega);
            fit.amplitudes.push_back(amplitude);

            const double allowed_shift =
              std::max(peaks[k].bandwidth, 1. / duration);
            if (!std::isfinite(sigma) || !std::isfinite(omega) ||
                !(amplitude > 0.))
              {
                fit.valid  = false;
                fit.reason = "the fit did not produce finite parameters";
              }
            else if (std::abs(omega / (2. * pi) - peaks[k].frequency) >
                     allowed_shift)
              {
                fit.valid  = false;
                fit.reason = "the mode started at " +
                             format_number(peaks[k].frequency, 4) +
                             " Hz moved to " +
                             format_number(omega / (2. * pi), 4) +
                             " Hz, outside its half-power band";
              }
          }
        return fit;
      }
    } // namespace



    // @sect4{The analysis of one signal}
    //
    // The steps are those of the study, with the checks that a short record
    // needs: remove the offset, check that the signal oscillates at all,
    // window, transform, find the peaks and their bandwidths, and then add
    // the logarithmic decrement and the modal fit, the predicted truncation
    // bias and the warnings.
    //
    // The arguments are checked first, because a wrong sample rate or a
    // padding factor of zero would otherwise produce plausible-looking
    // nonsense rather than an error.
    SpectralResult
    analyse_signal(const std::vector<double> &samples,
                   const double               sample_rate,
                   const SpectralOptions     &options)
    {
      const std::size_t n = samples.size();
      if (n < minimal_number_of_samples)
        throw std::invalid_argument("The spectral analysis needs at least " +
                                    std::to_string(minimal_number_of_samples) +
                                    " samples, but got " + std::to_string(n) +
                                    ".");
      if (!std::isfinite(sample_rate) || !(sample_rate > 0.))
        throw std::invalid_argument(
          "The sample rate must be positive and finite, but is " +
          format_number(sample_rate) + " Hz.");
      for (std::size_t i = 0; i < n; ++i)
        if (!std::isfinite(samples[i]))
          throw std::invalid_argument("Sample " + std::to_string(i) +
                                      " of the signal is not finite.");
      if (options.zero_padding_factor < 1 || options.zero_padding_factor > 1024)
        throw std::invalid_argument(
          "The zero-padding factor must lie in [1, 1024], but is " +
          std::to_string(options.zero_padding_factor) + ".");
      if (!(options.secondary_peak_threshold > 0. &&
            options.secondary_peak_threshold <= 1.))
        throw std::invalid_argument(
          "The secondary-peak threshold must lie in (0, 1], but is " +
          format_number(options.secondary_peak_threshold) + ".");

      // The FFT length is the next power of two above the padded length; a
      // limit of $2^{27}$ points (1 GB of work arrays) keeps a typo in the
      // padding factor from exhausting the memory.
      std::size_t fft_length = 1;
      while (fft_length < options.zero_padding_factor * n)
        fft_length *= 2;
      if (fft_length > (std::size_t(1) << 27))
        throw std::invalid_argument(
          "A zero-padding factor of " +
          std::to_string(options.zero_padding_factor) + " for " +
          std::to_string(n) +
          " samples needs an FFT longer than 2^27 points; use a smaller "
          "factor.");

      SpectralResult result;
      result.damping_ratio        = not_a_number;
      result.n_samples            = n;
      result.fft_length           = fft_length;
      result.sample_rate          = sample_rate;
      result.duration             = n / sample_rate;
      result.frequency_resolution = 1. / result.duration;
      result.removed_offset =
        (options.offset_removal == OffsetRemoval::mean ? mean_of(samples)
                                                       : samples.back());

      std::vector<double> signal(n);
      for (std::size_t i = 0; i < n; ++i)
        signal[i] = samples[i] - result.removed_offset;

      // <i>Offset and window.</i> The record duration is $T = N/f_s$, the
      // period of the discrete Fourier transform, so that the resolution
      // $1/T$ is the spacing of the unpadded bins and the first zero of the
      // rectangular window's zero-frequency lobe. Subtracting the mean makes
      // the zero-frequency bin vanish exactly; subtracting the final value
      // leaves a residual constant whose leakage stays in that lobe as long
      // as it is small compared with the oscillation.
      //
      // The symmetric Hann window $w_n = \tfrac12(1-\cos(2\pi n/(N-1)))$
      // vanishes at both ends of the record.
      std::vector<double> weighted   = signal;
      double              window_sum = n;
      if (options.window == SpectralWindow::hann)
        {
          window_sum = 0.;
          for (std::size_t i = 0; i < n; ++i)
            {
              const double weight =
                0.5 * (1. - std::cos(2. * pi * i / (n - 1.)));
              weighted[i] *= weight;
              window_sum += weight;
            }
        }
      result.magnitudes =
        zero_padded_magnitude_spectrum(weighted, window_sum, fft_length);
      const double frequency_step = sample_rate / fft_length;
      result.frequencies.resize(result.magnitudes.size());
      for (std::size_t k = 0; k < result.frequencies.size(); ++k)
        result.frequencies[k] = k * frequency_step;

      // <i>Does the signal oscillate?</i> A constant (to round-off) has no
      // spectrum to speak of. A monotone or over-damped decay has at most
      // one turning point; one full cycle needs three. This test comes
      // before the spectral one because the spectrum of a decay $e^{-t/\tau}$
      // minus its mean does have a broad hump at $f \sim 1/T$ that can pass
      // for a peak; counting turning points decides the question in the
      // time domain, where it is unambiguous. The spectrum is filled in
      // before, so that it can be plotted in any case.
      const auto [smallest, largest] =
        std::minmax_element(samples.begin(), samples.end());
      const double size = std::max(std::abs(*smallest), std::abs(*largest));
      if (!(*largest - *smallest > 1e-12 * size))
        {
          result.no_peak_reason = "the signal is constant (its range " +
                                  format_number(*largest - *smallest) +
                                  " is at the round-off level of its size " +
                                  format_number(size) + ")";
          return result;
        }

      const std::vector<TurningPoint> turning_points =
        find_turning_points(signal);
      result.n_turning_points = turning_points.size();
      if (turning_points.size() < 3)
        {
          result.no_peak_reason =
            "the signal does not oscillate: it has " +
            std::to_string(turning_points.size()) +
            " turning points (extrema followed by a reversal of more than " +
            format_number(100. * turning_point_hysteresis) +
            " % of its range), and one cycle needs 3";
          return result;
        }

      PeakSearchResult search = find_spectral_peaks(result.magnitudes,
                                                    frequency_step,
                                                    result.duration,
                                                    options);
      if (search.peaks.empty())
        {
          result.no_peak_reason = search.reason_if_none;
          return result;
        }

      // <i>Peaks found.</i> The number of cycles $f_\text{peak}T$ in the
      // record is what decides, with the damping, how much of the decay the
      // record contains.
      result.has_peak = true;
      result.n_cycles = search.peaks[0].frequency * result.duration;

      // The modal fit sees the record without window: the window is a
      // property of the spectral estimate, not of the signal. If the joint
      // fit of all peaks fails, the dominant mode alone is tried.
      ModalFit fit;
      if (options.fit_damped_modes)
        {
          fit = fit_damped_modes(signal, sample_rate, search.peaks);
          if (!fit.valid && search.peaks.size() > 1)
            {
              const ModalFit single =
                fit_damped_modes(signal, sample_rate, {search.peaks[0]});
              if (single.valid)
                fit = single;
            }
          result.fit_relative_residual = fit.relative_residual;
        }

      // <i>The logarithmic decrement</i>, with the noise level of the fit
      // residual (the signal's rms times the relative residual) and half
      // the period of the dominant peak as the expected spacing of the
      // extrema.
      {
        double       mean_square = 0.;
        const double mean        = mean_of(signal);
        for (const double value : signal)
          mean_square += (value - mean) * (value - mean) / n;
        const double noise_level =
          fit.valid ? fit.relative_residual * std::sqrt(mean_square) : 0.;
        result.logarithmic_decrement =
          logarithmic_decrement_of(find_turning_points(signal, noise_level),
                                   0.5 * sample_rate /
                                     search.peaks[0].frequency,
                                   noise_level);
      }

      // <i>Per peak</i>: the fitted mode, and the truncation bias of its
      // half-power damping, from the fitted decay exponent $\sigma T$ (well
      // conditioned) or else from inverting the measured $BT$. The fitted
      // $\sigma$ and $\omega_d$ give the natural frequency
      // $\omega_n = \sqrt{\sigma^2+\omega_d^2}$ and the damping ratio
      // $\xi = \sigma/\omega_n$; both follow from $\sigma = \xi\omega_n$ and
      // $\omega_d = \omega_n\sqrt{1-\xi^2}$ without approximation.
      for (std::size_t k = 0; k < search.peaks.size(); ++k)
        {
          SpectralPeak &peak            = search.peaks[k];
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
            peak.fit_valid
              ? fit.decay_rates[k] * result.duration
              : decay_exponent_from_half_power_width(peak.bandwidth *
                                                       result.duration,
                                                     options.window);
          peak.half_power_truncation_bias =
            (decay_exponent > 0.
               ? half_power_truncation_bias(decay_exponent, options.window)
               : not_a_number);
        }

      result.dominant_peak = search.peaks[0];
      result.secondary_peaks.assign(search.peaks.begin() + 1,
                                    search.peaks.end());

      // <i>The recommended damping ratio</i>, in the order of reliability
      // for short records: the fit is unbiased for any record length and
      // separates modes; the decrement is unbiased for a single mode but
      // mixes modes and suffers from noise at small amplitudes; the
      // half-power value carries the truncation bias.
      const SpectralPeak &dominant = result.dominant_peak;
      if (dominant.fit_valid)
        {
          result.damping_ratio     = dominant.fitted_damping_ratio;
          result.damping_estimator = DampingEstimator::modal_fit;
        }
      else if (result.logarithmic_decrement.valid)
        {
          result.damping_ratio     = result.logarithmic_decrement.damping_ratio;
          result.damping_estimator = DampingEstimator::logarithmic_decrement;
        }
      else
        {
          result.damping_ratio     = dominant.damping_ratio_half_power;
          result.damping_estimator = DampingEstimator::half_power;
        }

      // <i>Warnings.</i> Each says what is wrong and which number is
      // affected. A record in which the mode decays by less than 10 %
      // ($\sigma T < 0.1$), or whose bandwidth does not exceed that of an
      // undamped record, does not resolve the damping by its bandwidth at
      // all; otherwise the predicted bias is compared with 5 %.
      for (const SpectralPeak &peak : search.peaks)
        {
          const std::string at   = format_number(peak.frequency, 4) + " Hz: ";
          const double      bias = peak.half_power_truncation_bias;
          const bool        hardly_decays =
            peak.fit_valid && peak.fitted_damping_ratio * 2. * pi *
                                  peak.fitted_natural_frequency *
                                  result.duration <
                                0.1;
          if (peak.fit_valid && peak.fitted_damping_ratio < 0.)
            result.warnings.push_back(
              at + "the fitted oscillation grows instead of decaying");
          else if (std::isnan(bias) || hardly_decays)
            result.warnings.push_back(
              at + "the oscillation hardly decays within the record of " +
              format_number(result.duration, 4) +
              " s, and the half-power bandwidth " +
              format_number(peak.bandwidth, 3) +
              " Hz is that of the record length, not of the damping: "
              "xi_half_power is an upper bound only");
          else if (std::abs(bias) > tolerated_relative_bias)
            result.warnings.push_back(
              at + "the record is too short for the half-power method (B*T = " +
              format_number(peak.bandwidth * result.duration, 3) +
              (options.window == SpectralWindow::none
                 ? "; the bias is below 5 % only for B*T >= 1.34"
                 : "; with the Hann window the bias exceeds 5 % for almost "
                   "any record length") +
              "): truncation makes xi_half_power " +
              (bias > 1. ? format_number(1. + bias, 3) + " times too large"
                         : format_number(std::abs(100. * bias), 2) +
                             (bias > 0. ? " % too large" : " % too small")));
        }

      if (!result.secondary_peaks.empty() && result.logarithmic_decrement.valid)
        {
          std::string frequencies;
          for (const SpectralPeak &peak : result.secondary_peaks)
            frequencies += (frequencies.empty() ? "" : ", ") +
                           format_number(peak.frequency, 4) + " Hz";
          result.warnings.push_back(
            "secondary peaks at " + frequencies +
            ": the logarithmic decrement mixes the modes and is not a modal "
            "damping ratio");
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

      // The two time-domain estimates are compared on the scale of the
      // decay within the record, $\sigma T \approx 2\pi\xi f_n T$, so that
      // nearly undamped records do not produce large relative differences.
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
          if (std::abs(difference) > 0.1 * std::max(std::abs(fitted_decay), 1.))
            result.warnings.push_back(
              "the logarithmic decrement (xi = " +
              format_number(result.logarithmic_decrement.damping_ratio, 3) +
              ") and the modal fit (xi = " +
              format_number(dominant.fitted_damping_ratio, 3) +
              ") disagree: the decay is not exponential (amplitude-dependent "
              "damping?), or noise biases the extrema");
        }
      return result;
    }



    // @sect4{The analysis of a whole trajectory}
    //
    // The pieces above in their natural order: skip the requested initial
    // interval (with the same checks whether or not anything is skipped),
    // make the sampling uniform, split the motion into directions, and
    // analyse each direction with the same options. A motion without a
    // preferred plane (depth and horizontal rms within 30 % of each other)
    // gets a warning, because then the two in-plane directions are an
    // arbitrary choice and their spectra should be read together.
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
          format_number(signals.out_of_plane_ratio, 3) +
          "), so the split into horizontal and depth is arbitrary");

      for (std::size_t d = 0; d < signals.names.size(); ++d)
        analysis.directions.push_back(
          {signals.names[d],
           analyse_signal(signals.samples[d], uniform.sample_rate, options)});
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
//   decimating the record to some 20 samples per period of the highest
//   peak before fitting would keep it cheap.
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
