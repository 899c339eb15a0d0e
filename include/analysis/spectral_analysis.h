// @sect3{Spectral analysis of a tip trajectory}
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
// length rather than by the damping (see the discussion of truncation in
// spectral_analysis.cc). The functions declared here therefore report three
// damping estimates side by side:
// - the half-power value exactly as the study computed it, together with the
//   bias that truncation theory predicts for it,
// - the logarithmic decrement of the successive extrema (a time-domain cross
//   check that needs no spectrum), and
// - a least-squares fit of damped modes to the record (the recommended
//   result: it is the Fourier-domain fit of the truncated Lorentzian, done
//   in the time domain, and it is unbiased for short records).
//
// Everything here is plain C++17 with FFTW3; nothing depends on deal.II, so
// that the analysis can be used on motion-capture data without the solver.

#ifndef soft_robot_analysis_spectral_analysis_h
#define soft_robot_analysis_spectral_analysis_h

#include <array>
#include <limits>
#include <string>
#include <vector>

namespace SoftRobot
{
  namespace Analysis
  {
    // @sect4{The tip trajectory as recorded}
    //
    // A trajectory is a sequence of times and tip displacements. The $x$
    // axis is the actuator axis (vertical, gravity points along $+x$); a
    // planar or one-dimensional record has only the first one or two
    // displacement components, and <code>n_components</code> says how many
    // are meaningful (the others are zero).
    struct TipTrajectory
    {
      std::vector<double>                time;
      std::vector<std::array<double, 3>> displacement;
      unsigned int                       n_components = 1;
    };

    // Read a trajectory from a CSV file. Lines whose first non-blank
    // character is <code>#</code> are comments, blank lines are skipped.
    // The first other line is a header of comma-separated column names;
    // the columns <code>t</code> and <code>u_x</code> are required,
    // <code>u_y</code> and then <code>u_z</code> are optional, and all other
    // columns (velocities, energies, ...) are ignored. Times must increase
    // strictly. Malformed input throws std::runtime_error with a message
    // that names the file, the line and the column.
    TipTrajectory
    read_tip_trajectory(const std::string &csv_file);

    // Drop the samples in the first <code>seconds</code> of the record, e.g.
    // an actuation phase before the free decay. Throws
    // std::invalid_argument unless $0 \le$ <code>seconds</code> and enough
    // of the record (at least 16 samples) remains.
    TipTrajectory
    skip_initial_interval(const TipTrajectory &trajectory,
                          const double         seconds);



    // @sect4{Uniform sampling}
    //
    // The FFT needs equidistant samples. Records whose steps agree to within
    // <code>relative_step_tolerance</code> (default 1 %, which absorbs the
    // jitter of times printed with few digits) are used as they are, with
    // the sample rate $(n-1)/(t_{n-1}-t_0)$. Otherwise (time-step cutbacks
    // of the simulator, dropped motion-capture frames) the record is
    // interpolated linearly onto a grid with the median step.
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



    // @sect4{Directions of motion}
    //
    // The vertical direction is $x$. The horizontal and depth directions are
    // defined by the plane that contains the $x$ axis and best fits the
    // $(y,z)$ motion: the horizontal direction is the principal direction of
    // the covariance of $(u_y, u_z)$, at the angle <code>plane_angle</code>
    // from $+y$ towards $+z$ (in $(-\pi/2,\pi/2]$), and the depth direction
    // is the plane's normal, such that (vertical, horizontal, depth) is
    // right-handed. A one-component record has only the vertical direction,
    // a two-component record the vertical and horizontal ($=u_y$) ones.
    struct DirectionalSignals
    {
      std::vector<std::string>         names;
      std::vector<std::vector<double>> samples;
      double                           plane_angle = 0.;
      // Root mean square of the depth motion over that of the horizontal
      // motion: zero for a motion in a plane through the axis, one for a
      // motion without a preferred plane (then the angle is arbitrary).
      double out_of_plane_ratio = 0.;
    };

    DirectionalSignals
    split_into_directions(const UniformTrajectory &trajectory);



    // @sect4{Options of the analysis}
    //
    // <code>OffsetRemoval</code>: the static offset that is subtracted before
    // the transform, either the mean of the record (default; it makes the
    // zero-frequency bin vanish exactly) or its final value (the equilibrium
    // position, if the oscillation has died out by the end of the record).
    //
    // <code>SpectralWindow</code>: none (default) or Hann. A window lowers
    // the side lobes but widens the main lobe of every peak (for an
    // undamped record from $0.886/T$ to $1.44/T$), so it inflates the
    // half-power bandwidth of a lightly damped short record; for a record
    // in which the oscillation decays it even does the opposite, because it
    // suppresses the large early part of the free decay. Damping estimates
    // must therefore be made without a window; Hann is only useful to see
    // weak secondary peaks next to a strong one.
    //
    // <code>zero_padding_factor</code>: the FFT length is the smallest power
    // of two that is at least this factor times the number of samples, so
    // that the peak and the -3 dB crossings are interpolated on a fine grid.
    //
    // <code>secondary_peak_threshold</code>: a spectral peak other than the
    // dominant one is reported (and fitted) if its magnitude is at least
    // this fraction of the dominant one; at most
    // <code>max_secondary_peaks</code> such peaks are kept.
    //
    // <code>fit_damped_modes</code>: fit a damped mode to every reported
    // peak (the recommended damping estimate; switch it off only to save
    // time on long records).
    enum class OffsetRemoval
    {
      mean,
      final_value
    };

    enum class SpectralWindow
    {
      none,
      hann
    };

    struct SpectralOptions
    {
      OffsetRemoval  offset_removal           = OffsetRemoval::mean;
      SpectralWindow window                   = SpectralWindow::none;
      unsigned int   zero_padding_factor      = 16;
      double         secondary_peak_threshold = 0.1;
      unsigned int   max_secondary_peaks      = 3;
      bool           fit_damped_modes         = true;
    };



    // @sect4{Results}
    //
    // One peak of the magnitude spectrum with its half-power bandwidth, and,
    // if the modal fit succeeded, the damped mode fitted to it. All
    // frequencies are in Hz; quantities that could not be determined are
    // NaN. The magnitude is that of the amplitude spectrum (a steady
    // sinusoid of amplitude $A$ has a peak of height $A$).
    //
    // <code>frequency</code> is the peak of the spectrum, as the study used
    // it. It estimates the damped frequency $f_d = f_n\sqrt{1-\xi^2}$, and in
    // records of few cycles the leakage of the negative-frequency image
    // shifts it by up to about $0.3/(fT)^2$ relative (0.5 % for 5 cycles);
    // <code>fitted_natural_frequency</code> has neither error and is the
    // recommended frequency.
    struct SpectralPeak
    {
      double frequency                  = 0.;
      double magnitude                  = 0.;
      double lower_half_power_frequency = 0.;
      double upper_half_power_frequency = 0.;
      double bandwidth                  = 0.;
      double quality_factor             = 0.;
      double damping_ratio_half_power   = 0.;

      // Relative error of <code>damping_ratio_half_power</code> that the
      // truncation of the record causes for a single damped mode, i.e.
      // $\xi_\text{half power}/\xi - 1$ predicted by the theory in
      // spectral_analysis.cc (from the fitted decay if available, otherwise
      // from the measured bandwidth).
      double half_power_truncation_bias = 0.;

      bool   fit_valid                = false;
      double fitted_damped_frequency  = 0.;
      double fitted_natural_frequency = 0.;
      double fitted_damping_ratio     = 0.;
      double fitted_amplitude         = 0.;
    };

    // The logarithmic decrement $\delta$ of the extrema of the signal, from
    // a least-squares line through $\ln$ (peak-to-peak amplitude of each
    // half cycle) against the cycle index, and the damping ratio
    // $\xi = \delta/\sqrt{4\pi^2+\delta^2}$.
    struct LogarithmicDecrement
    {
      bool         valid = false;
      std::string  reason;
      unsigned int n_extrema     = 0;
      double       decrement     = 0.;
      double       damping_ratio = 0.;
    };

    // Which estimate <code>SpectralResult::damping_ratio</code> holds.
    enum class DampingEstimator
    {
      none,
      modal_fit,
      logarithmic_decrement,
      half_power
    };

    std::string
    to_string(const DampingEstimator estimator);

    // The result of the analysis of one signal. If the signal does not
    // oscillate, <code>has_peak</code> is false and
    // <code>no_peak_reason</code> says why; the spectrum is still filled in.
    // Otherwise the dominant peak and any secondary peaks (by decreasing
    // magnitude) are given, and <code>damping_ratio</code> is the
    // recommended estimate: the modal fit if it is valid, else the
    // logarithmic decrement, else the half-power value.
    struct SpectralResult
    {
      bool        has_peak = false;
      std::string no_peak_reason;

      SpectralPeak              dominant_peak;
      std::vector<SpectralPeak> secondary_peaks;
      LogarithmicDecrement      logarithmic_decrement;

      double           damping_ratio = std::numeric_limits<double>::quiet_NaN();
      DampingEstimator damping_estimator = DampingEstimator::none;

      // Root mean square of the fit residual over that of the signal.
      double fit_relative_residual = 0.;

      unsigned int n_samples            = 0;
      unsigned int fft_length           = 0;
      unsigned int n_turning_points     = 0;
      double       sample_rate          = 0.;
      double       duration             = 0.; // T = n_samples / sample_rate
      double       frequency_resolution = 0.; // 1/T
      double       n_cycles             = 0.; // f_peak T
      double       removed_offset       = 0.;

      std::vector<std::string> warnings;

      // The zero-padded magnitude (amplitude) spectrum for plotting.
      std::vector<double> frequencies;
      std::vector<double> magnitudes;
    };

    // Analyse one uniformly sampled signal. Throws std::invalid_argument for
    // fewer than 16 samples, a non-positive sample rate, non-finite samples
    // or options out of range.
    SpectralResult
    analyse_signal(const std::vector<double> &samples,
                   const double               sample_rate,
                   const SpectralOptions     &options = SpectralOptions());



    // @sect4{Analysis of a whole trajectory}
    //
    // Skip the initial interval, make the sampling uniform, split into
    // directions and analyse each.
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



    // @sect4{Truncation theory}
    //
    // For a single mode $e^{-\sigma t}\cos(\omega_d t)$ recorded for $T$
    // seconds the half-power bandwidth $B$ depends only on the decay
    // exponent $s = \sigma T$ and on the window; these functions return the
    // dimensionless bandwidth $B\,T$ and the relative bias
    // $\pi B T / s - 1$ of the half-power damping ratio (the exact value
    // would be $B T = s/\pi$). For $s \to 0$, $BT \to 0.886$ (no window)
    // and $1.441$ (Hann): the width of the main lobe of an undamped record.
    double
    truncated_decay_half_power_width(const double         decay_exponent,
                                     const SpectralWindow window);

    double
    half_power_truncation_bias(const double         decay_exponent,
                               const SpectralWindow window);
  } // namespace Analysis
} // namespace SoftRobot

#endif
