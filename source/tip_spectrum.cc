// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{The tip-spectrum program}
//
// <code>tip-spectrum</code> reads a tip trajectory (from the simulator or
// from motion capture), and prints per direction of motion the peak
// frequency of the tip displacement's spectrum, its half-power bandwidth,
// the quality factor and three damping ratios: the half-power value
// $\xi = 1/(2Q)$ the reference study used, the logarithmic decrement, and
// the modal fit, which is the recommended one for short records (see
// truncation_theory.cc for why). With <code>--csv</code> it writes the same
// table as CSV, with <code>--spectrum</code> the magnitude spectra for
// plotting.
//
// Bad input stops the program with a message that names the file or the
// option and the allowed values, and with a non-zero exit code: 2 for a
// wrong command line, 1 for a file that cannot be read or analysed. Output
// files are written only after the analysis has succeeded, each first to a
// temporary file that is renamed at the end, so that no partial output is
// ever left behind.

#include <analysis/spectral_analysis.h>
#include <analysis/spectral_report.h>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace
{
  using namespace SoftRobot::Analysis;

  constexpr double pi = 3.14159265358979323846;

  const char usage_text[] =
    "Usage: tip-spectrum TRAJECTORY.csv [options]\n"
    "\n"
    "Peak frequency, half-power bandwidth and damping ratio of the tip\n"
    "displacement, per direction (vertical = x, horizontal and depth from\n"
    "the plane through the x axis that best fits the (y,z) motion).\n"
    "\n"
    "The CSV file has a header line with the columns t, u_x and optionally\n"
    "u_y, u_z (other columns are ignored); lines starting with # are\n"
    "comments.\n"
    "\n"
    "Options:\n"
    "  --window none|hann    window before the FFT (default none; a window\n"
    "                        biases the half-power damping ratio)\n"
    "  --padding N           zero padding: FFT length >= N times the number\n"
    "                        of samples, N an integer in [1, 1024]\n"
    "                        (default 16)\n"
    "  --offset mean|final   static offset removed before the FFT: the mean\n"
    "                        or the final value of the record (default mean)\n"
    "  --skip SECONDS        ignore the first SECONDS of the record, a number\n"
    "                        >= 0 that leaves at least 16 samples (default 0)\n"
    "  --csv FILE            also write the table to FILE as CSV\n"
    "  --spectrum FILE       write frequency and magnitude per direction to\n"
    "                        FILE as CSV\n"
    "  --help                print this text\n"
    "\n"
    "Damping ratios: xi_half-power = bandwidth / (2 f_peak) as in the\n"
    "reference study (biased for records in which the oscillation has not\n"
    "decayed to about 2 %; a warning gives the bias), xi_log-dec from the\n"
    "successive extrema, xi_fit from a least-squares fit of damped modes.\n"
    "The recommended value is marked with '*'.\n";

  // A wrong command line; reported with a hint to --help and exit code 2.
  class UsageError : public std::runtime_error
  {
  public:
    using std::runtime_error::runtime_error;
  };



  // @sect4{The command line}
  //
  // The command line holds the trajectory file, the analysis options and
  // the two optional output files. Every value is checked where it is
  // parsed, and a wrong one raises a UsageError that names the option, the
  // value given and the values allowed. The only check that needs the file,
  // whether --skip leaves enough of the record, is made after reading it,
  // by skip_initial_interval(), whose message gives the allowed range.
  struct CommandLine
  {
    std::string     trajectory_file;
    SpectralOptions options;
    double          skip_seconds = 0.;
    std::string     table_file;
    std::string     spectrum_file;
    bool            help = false;
  };



  // An unsigned integer must consist of digits only (no sign, no exponent,
  // no trailing characters, at most nine digits so that it cannot overflow)
  // and lie in the allowed range.
  unsigned int
  parse_unsigned_option(const std::string &option,
                        const std::string &text,
                        const unsigned int smallest,
                        const unsigned int largest)
  {
    const std::string allowed = "an integer in [" + std::to_string(smallest) +
                                ", " + std::to_string(largest) + "]";
    if (text.empty() ||
        text.find_first_not_of("0123456789") != std::string::npos ||
        text.size() > 9)
      throw UsageError("option " + option + " must be " + allowed +
                       ", but is '" + text + "'.");
    const unsigned long value = std::stoul(text);
    if (value < smallest || value > largest)
      throw UsageError("option " + option + " must be " + allowed +
                       ", but is " + text + ".");
    return value;
  }



  // A number of seconds is anything <code>strtod</code> reads completely
  // that is finite and not negative.
  double
  parse_seconds_option(const std::string &option, const std::string &text)
  {
    char        *end   = nullptr;
    const double value = std::strtod(text.c_str(), &end);
    if (text.empty() || end != text.c_str() + text.size() ||
        !std::isfinite(value) || value < 0.)
      throw UsageError("option " + option +
                       " must be a number of seconds >= 0 (leaving at least "
                       "16 samples of the record), but is '" +
                       text + "'.");
    return value;
  }



  // Options take their value either as the next argument or after an equals
  // sign, <code>--window hann</code> or <code>--window=hann</code>. Every
  // argument that does not start with <code>--</code> is a trajectory file,
  // and exactly one must be given. Output files must differ from the input
  // and from each other, since the staged writing below would otherwise
  // replace one by the other.
  CommandLine
  parse_command_line(const int argc, char **argv)
  {
    CommandLine command_line;
    for (int i = 1; i < argc; ++i)
      {
        const std::string argument = argv[i];
        if (argument == "--help" || argument == "-h")
          {
            command_line.help = true;
            continue;
          }
        if (argument.size() < 2 || argument.compare(0, 2, "--") != 0)
          {
            if (!command_line.trajectory_file.empty())
              throw UsageError("only one trajectory file can be analysed, "
                               "but both '" +
                               command_line.trajectory_file + "' and '" +
                               argument + "' are given.");
            command_line.trajectory_file = argument;
            continue;
          }

        std::string name      = argument, value;
        bool        has_value = false;
        if (const auto equals = argument.find('='); equals != std::string::npos)
          {
            name      = argument.substr(0, equals);
            value     = argument.substr(equals + 1);
            has_value = true;
          }
        const auto take_value = [&](const std::string &what) {
          if (has_value)
            return value;
          if (i + 1 >= argc)
            throw UsageError("option " + name + " needs a value (" + what +
                             ").");
          return std::string(argv[++i]);
        };

        if (name == "--window")
          {
            const std::string window = take_value("none or hann");
            if (window == "none")
              command_line.options.window = SpectralWindow::none;
            else if (window == "hann")
              command_line.options.window = SpectralWindow::hann;
            else
              throw UsageError("option --window must be 'none' or 'hann', "
                               "but is '" +
                               window + "'.");
          }
        else if (name == "--padding")
          command_line.options.zero_padding_factor = parse_unsigned_option(
            name, take_value("an integer in [1, 1024]"), 1, 1024);
        else if (name == "--offset")
          {
            const std::string offset = take_value("mean or final");
            if (offset == "mean")
              command_line.options.offset_removal = OffsetRemoval::mean;
            else if (offset == "final")
              command_line.options.offset_removal = OffsetRemoval::final_value;
            else
              throw UsageError("option --offset must be 'mean' or 'final', "
                               "but is '" +
                               offset + "'.");
          }
        else if (name == "--skip")
          command_line.skip_seconds =
            parse_seconds_option(name, take_value("a number of seconds >= 0"));
        else if (name == "--csv")
          command_line.table_file = take_value("an output file name");
        else if (name == "--spectrum")
          command_line.spectrum_file = take_value("an output file name");
        else
          throw UsageError("unknown option '" + name +
                           "'; the options are --window, --padding, "
                           "--offset, --skip, --csv, --spectrum and --help.");
      }

    if (command_line.help)
      return command_line;
    if (command_line.trajectory_file.empty())
      throw UsageError("no trajectory file given.");
    for (const std::string *output :
         {&command_line.table_file, &command_line.spectrum_file})
      if (!output->empty() && *output == command_line.trajectory_file)
        throw UsageError("the output file '" + *output +
                         "' would overwrite the trajectory file.");
    if (!command_line.table_file.empty() &&
        command_line.table_file == command_line.spectrum_file)
      throw UsageError("--csv and --spectrum name the same file '" +
                       command_line.table_file + "'.");
    return command_line;
  }



  // @sect4{Formatting}
  //
  // Quantities that could not be determined (NaN) are shown as '-' in the
  // table and as empty fields in the CSV files.
  std::string
  format_value(const double value, const int precision, const bool fixed = true)
  {
    if (!std::isfinite(value))
      return "-";
    std::ostringstream stream;
    if (fixed)
      stream << std::fixed;
    stream << std::setprecision(precision) << value;
    return stream.str();
  }



  // @sect4{The table on the screen}
  //
  // A header with what was analysed (file, samples, sample rate, whether
  // the record was resampled, duration and skipped interval), how (window,
  // offset, FFT length) and, for three-component records, the plane of the
  // swing. Then one line per direction:
  // - <code>f_peak</code>, <code>bandwidth</code>, <code>Q</code>: the
  //   spectral peak, its half-power bandwidth and $f_\text{peak}/B$;
  // - <code>xi_half-pow</code> $= 1/(2Q)$, <code>xi_log-dec</code>,
  //   <code>xi_fit</code>: the three damping ratios, the recommended one
  //   marked with '*';
  // - <code>f_n,fit</code>: the natural frequency of the fitted mode;
  // - <code>cycles</code> $= f_\text{peak}T$ and <code>resolution</code>
  //   $= 1/T$, which tell how much the record can resolve.
  //
  // Below each line come the secondary peaks, the reason if the
  // logarithmic decrement could not be formed, and the warnings.
  std::string
  format_table(const CommandLine        &command_line,
               const TrajectoryAnalysis &analysis,
               const unsigned int        n_components)
  {
    std::ostringstream    out;
    const SpectralResult &first = analysis.directions.front().result;
    out << "Tip trajectory '" << command_line.trajectory_file
        << "': " << analysis.n_samples << " samples at "
        << format_value(analysis.sample_rate, 6, false) << " Hz"
        << (analysis.resampled ? " (resampled from non-uniform time steps)"
                               : "")
        << ", " << format_value(first.duration, 4, false)
        << " s analysed after skipping "
        << format_value(command_line.skip_seconds, 4, false) << " s\n";
    out << "Window "
        << (command_line.options.window == SpectralWindow::none ? "none"
                                                                : "hann")
        << ", offset "
        << (command_line.options.offset_removal == OffsetRemoval::mean
              ? "mean"
              : "final value")
        << ", FFT length " << first.fft_length
        << " (zero padding >= " << command_line.options.zero_padding_factor
        << " x record)\n";
    if (n_components == 3)
      out << "Plane of the (y,z) motion: "
          << format_value(analysis.plane_angle * 180. / pi, 1)
          << " deg from +y towards +z (depth/horizontal rms "
          << format_value(analysis.out_of_plane_ratio, 3) << ")\n";
    for (const std::string &warning : analysis.warnings)
      out << "warning: " << warning << "\n";
    out << "\n";

    out << std::left << std::setw(11) << "direction" << std::right
        << std::setw(11) << "f_peak" << std::setw(11) << "bandwidth"
        << std::setw(8) << "Q" << std::setw(13) << "xi_half-pow"
        << std::setw(11) << "xi_log-dec" << std::setw(10) << "xi_fit"
        << std::setw(10) << "f_n,fit" << std::setw(8) << "cycles"
        << std::setw(11) << "resolution"
        << "\n"
        << std::left << std::setw(11) << "" << std::right << std::setw(11)
        << "[Hz]" << std::setw(11) << "[Hz]" << std::setw(8) << ""
        << std::setw(13) << "" << std::setw(11) << "" << std::setw(10) << ""
        << std::setw(10) << "[Hz]" << std::setw(8) << "" << std::setw(11)
        << "[Hz]"
        << "\n";

    for (const DirectionalAnalysis &direction : analysis.directions)
      {
        const SpectralResult &result = direction.result;
        out << std::left << std::setw(11) << direction.direction << std::right;
        if (!result.has_peak)
          {
            out << "  no peak: " << result.no_peak_reason << "\n";
            continue;
          }
        const SpectralPeak &peak = result.dominant_peak;
        const auto          mark = [&result](const DampingEstimator estimator) {
          return result.damping_estimator == estimator ? "*" : " ";
        };
        out << std::setw(11) << format_value(peak.frequency, 4) << std::setw(11)
            << format_value(peak.bandwidth, 4) << std::setw(8)
            << format_value(peak.quality_factor, 2) << std::setw(12)
            << format_value(peak.damping_ratio_half_power, 5)
            << mark(DampingEstimator::half_power) << std::setw(10)
            << format_value(result.logarithmic_decrement.damping_ratio, 5)
            << mark(DampingEstimator::logarithmic_decrement) << std::setw(9)
            << format_value(peak.fitted_damping_ratio, 5)
            << mark(DampingEstimator::modal_fit) << std::setw(10)
            << format_value(peak.fitted_natural_frequency, 4) << std::setw(8)
            << format_value(result.n_cycles, 2) << std::setw(11)
            << format_value(result.frequency_resolution, 4) << "\n";

        for (const SpectralPeak &secondary : result.secondary_peaks)
          out << "    secondary peak at "
              << format_value(secondary.frequency, 4) << " Hz ("
              << format_value(secondary.magnitude / peak.magnitude, 2)
              << " of the dominant magnitude): bandwidth "
              << format_value(secondary.bandwidth, 4) << " Hz, xi_half-power "
              << format_value(secondary.damping_ratio_half_power, 5)
              << ", xi_fit " << format_value(secondary.fitted_damping_ratio, 5)
              << ", f_n,fit "
              << format_value(secondary.fitted_natural_frequency, 4) << " Hz\n";
        if (!result.logarithmic_decrement.valid)
          out << "    no logarithmic decrement: "
              << result.logarithmic_decrement.reason << "\n";
        for (const std::string &warning : result.warnings)
          out << "    warning: " << warning << "\n";
      }
    out << "\n* recommended damping ratio (modal fit if it succeeded)\n";
    return out.str();
  }



  // @sect4{Writing without partial files}
  //
  // Each file is first written completely to a temporary file next to it;
  // only when all of them have been written are they renamed, and on any
  // failure the temporaries are removed.
  class StagedOutput
  {
  public:
    void
    stage(const std::string &file_name, const std::string &content)
    {
      const std::string temporary = file_name + ".incomplete";
      std::ofstream     out(temporary, std::ios::binary);
      out << content;
      out.close();
      if (!out)
        {
          std::remove(temporary.c_str());
          throw std::runtime_error("cannot write the output file '" +
                                   file_name + "'.");
        }
      staged.push_back({temporary, file_name});
    }

    void
    commit()
    {
      for (const auto &[temporary, file_name] : staged)
        if (std::rename(temporary.c_str(), file_name.c_str()) != 0)
          throw std::runtime_error("cannot create the output file '" +
                                   file_name + "'.");
      staged.clear();
    }

    ~StagedOutput()
    {
      for (const auto &file : staged)
        std::remove(file.first.c_str());
    }

  private:
    std::vector<std::pair<std::string, std::string>> staged;
  };
} // namespace



// @sect3{The main function}
//
// The order of the steps makes the promises of the introduction hold:
// the command line is parsed before any file is touched; the trajectory is
// read and analysed completely before any output is staged; all output
// files are staged before any is renamed into place; and the table is
// printed last, so that a failure never leaves a partial result on the
// screen or on disk. Usage errors end with exit code 2, all other errors
// with 1.
int
main(int argc, char **argv)
{
  CommandLine command_line;
  try
    {
      command_line = parse_command_line(argc, argv);
    }
  catch (const UsageError &error)
    {
      std::cerr << "tip-spectrum: " << error.what()
                << "\nRun 'tip-spectrum --help' for the options.\n";
      return 2;
    }
  if (command_line.help)
    {
      std::cout << usage_text;
      return 0;
    }

  try
    {
      const TipTrajectory trajectory =
        read_tip_trajectory(command_line.trajectory_file);

      if (trajectory.time.size() < 16)
        throw std::runtime_error("The tip trajectory file '" +
                                 command_line.trajectory_file + "' has " +
                                 std::to_string(trajectory.time.size()) +
                                 " data lines; the analysis needs at least "
                                 "16.");

      TipTrajectory analysed;
      try
        {
          analysed =
            skip_initial_interval(trajectory, command_line.skip_seconds);
        }
      catch (const std::invalid_argument &error)
        {
          throw UsageError("option --skip for '" +
                           command_line.trajectory_file + "': " + error.what());
        }

      const TrajectoryAnalysis analysis =
        analyse_trajectory(analysed, command_line.options);

      StagedOutput output;
      if (!command_line.table_file.empty())
        output.stage(command_line.table_file, spectral_table_csv(analysis));
      if (!command_line.spectrum_file.empty())
        output.stage(command_line.spectrum_file, spectrum_csv(analysis));
      output.commit();

      std::cout << format_table(command_line,
                                analysis,
                                trajectory.n_components);
    }
  catch (const UsageError &error)
    {
      std::cerr << "tip-spectrum: " << error.what() << "\n";
      return 2;
    }
  catch (const std::exception &error)
    {
      std::cerr << "tip-spectrum: " << error.what() << "\n";
      return 1;
    }
  return 0;
}
