// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Reports of the spectral analysis as CSV}
//
// The results of analyse_trajectory() as text: the table of peaks and the
// magnitude spectra as CSV files, and one line per direction for a log.
// Only formatting happens here; every number comes from the analysis as it
// is.

#include <analysis/spectral_report.h>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <vector>

namespace SoftRobot
{
  namespace Analysis
  {
    namespace
    {
      // Numbers carry ten significant digits; quantities that could not be
      // determined (NaN) are empty fields.
      std::string
      csv_value(const double value)
      {
        if (!std::isfinite(value))
          return "";
        std::ostringstream stream;
        stream << std::setprecision(10) << value;
        return stream.str();
      }



      std::string
      csv_text(const std::string &text)
      {
        std::string quoted = "\"";
        for (const char c : text)
          quoted += (c == '"' ? std::string("\"\"") : std::string(1, c));
        return quoted + "\"";
      }



      std::string
      join_warnings(const std::vector<std::string> &warnings)
      {
        std::string joined;
        for (const std::string &warning : warnings)
          joined += (joined.empty() ? "" : "; ") + warning;
        return joined;
      }



    } // namespace



    // @sect4{The CSV files}
    //
    // One row per peak, the dominant one first; a direction without a peak
    // gets one row with the reason in the warnings column. The columns are
    // - <code>direction</code>, <code>peak</code> (dominant, secondary or
    //   none);
    // - <code>f_peak_Hz</code>, <code>magnitude</code> (of the amplitude
    //   spectrum, in the units of the displacement),
    //   <code>f_lower_Hz</code>, <code>f_upper_Hz</code> (the -3 dB
    //   crossings), <code>bandwidth_Hz</code>, <code>Q</code>;
    // - <code>xi_half_power</code> and
    //   <code>xi_half_power_truncation_bias</code>, the relative error of the
    //   former that truncation theory predicts;
    // - <code>xi_log_decrement</code> (dominant peak only), <code>xi_fit</code>,
    //   <code>f_damped_fit_Hz</code>, <code>f_natural_fit_Hz</code>;
    // - <code>xi_recommended</code> and <code>xi_recommended_from</code>
    //   (dominant peak only);
    // - <code>cycles</code>, <code>resolution_Hz</code>,
    //   <code>duration_s</code>, <code>sample_rate_Hz</code>;
    // - <code>warnings</code>, joined by "; " and quoted.
    //
    // Numbers carry ten significant digits, and quantities that could not be
    // determined are empty fields.
    std::string
    spectral_table_csv(const TrajectoryAnalysis &analysis)
    {
      std::ostringstream out;
      out << "direction,peak,f_peak_Hz,magnitude,f_lower_Hz,f_upper_Hz,"
             "bandwidth_Hz,Q,xi_half_power,xi_half_power_truncation_bias,"
             "xi_log_decrement,xi_fit,f_damped_fit_Hz,f_natural_fit_Hz,"
             "xi_recommended,xi_recommended_from,cycles,resolution_Hz,"
             "duration_s,sample_rate_Hz,warnings\n";
      for (const DirectionalAnalysis &direction : analysis.directions)
        {
          const SpectralResult &result = direction.result;
          const std::string     common_tail =
            csv_value(result.frequency_resolution) + "," +
            csv_value(result.duration) + "," + csv_value(result.sample_rate);
          if (!result.has_peak)
            {
              out << direction.direction << ",none,,,,,,,,,,,,,,,,"
                  << common_tail << ","
                  << csv_text("no peak: " + result.no_peak_reason) << "\n";
              continue;
            }

          std::vector<SpectralPeak> peaks = {result.dominant_peak};
          peaks.insert(peaks.end(),
                       result.secondary_peaks.begin(),
                       result.secondary_peaks.end());
          for (std::size_t k = 0; k < peaks.size(); ++k)
            {
              const SpectralPeak &peak     = peaks[k];
              const bool          dominant = (k == 0);
              out << direction.direction << ","
                  << (dominant ? "dominant" : "secondary") << ","
                  << csv_value(peak.frequency) << ","
                  << csv_value(peak.magnitude) << ","
                  << csv_value(peak.lower_half_power_frequency) << ","
                  << csv_value(peak.upper_half_power_frequency) << ","
                  << csv_value(peak.bandwidth) << ","
                  << csv_value(peak.quality_factor) << ","
                  << csv_value(peak.damping_ratio_half_power) << ","
                  << csv_value(peak.half_power_truncation_bias) << ","
                  << (dominant
                        ? csv_value(result.logarithmic_decrement.damping_ratio)
                        : "")
                  << "," << csv_value(peak.fitted_damping_ratio) << ","
                  << csv_value(peak.fitted_damped_frequency) << ","
                  << csv_value(peak.fitted_natural_frequency) << ","
                  << (dominant ? csv_value(result.damping_ratio) : "") << ","
                  << (dominant ? to_string(result.damping_estimator) : "")
                  << "," << csv_value(peak.frequency * result.duration) << ","
                  << common_tail << ","
                  << (dominant ? csv_text(join_warnings(result.warnings)) : "")
                  << "\n";
            }
        }
      return out.str();
    }



    // The spectrum file has the columns <code>frequency_Hz</code> and
    // <code>magnitude_</code><i>direction</i> for each direction, from zero to
    // the Nyquist frequency on the zero-padded grid. All directions share the
    // sample count and hence the frequency grid.
    std::string
    spectrum_csv(const TrajectoryAnalysis &analysis)
    {
      std::ostringstream out;
      out << "frequency_Hz";
      for (const DirectionalAnalysis &direction : analysis.directions)
        out << ",magnitude_" << direction.direction;
      out << "\n" << std::setprecision(10);
      const std::vector<double> &frequencies =
        analysis.directions.front().result.frequencies;
      for (std::size_t k = 0; k < frequencies.size(); ++k)
        {
          out << frequencies[k];
          for (const DirectionalAnalysis &direction : analysis.directions)
            out << "," << direction.result.magnitudes[k];
          out << "\n";
        }
      return out.str();
    }



    // @sect4{A summary for the log}
    std::string
    spectral_summary(const TrajectoryAnalysis &analysis)
    {
      std::ostringstream out;
      for (const DirectionalAnalysis &direction : analysis.directions)
        {
          const SpectralResult &result = direction.result;
          out << "  " << std::setw(10) << direction.direction << ": ";
          if (!result.has_peak)
            out << "no peak (" << result.no_peak_reason << ")";
          else
            out << "f_peak = " << std::setprecision(4)
                << result.dominant_peak.frequency
                << " Hz, xi = " << result.damping_ratio << " ("
                << to_string(result.damping_estimator) << "), xi half-power = "
                << result.dominant_peak.damping_ratio_half_power;
          out << "\n";
        }
      return out.str();
    }
  } // namespace Analysis
} // namespace SoftRobot
