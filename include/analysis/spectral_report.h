// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Reports of the spectral analysis as CSV}
//
// Implemented in source/analysis/spectral_report.cc.
//
// The results of analyse_trajectory() as the two CSV files that both the
// program `tip-spectrum` and the simulator (at the end of a scene whose
// parameter file asks for it) write: one row per spectral peak and
// direction, and the magnitude spectra for plotting.

#ifndef soft_robot_analysis_spectral_report_h
#define soft_robot_analysis_spectral_report_h

#include <analysis/spectral_analysis.h>
#include <string>

namespace SoftRobot
{
  namespace Analysis
  {
    // One row per peak, the dominant one first (see the .cc file for the
    // columns).
    std::string
    spectral_table_csv(const TrajectoryAnalysis &analysis);

    // The columns frequency_Hz and magnitude_<direction>.
    std::string
    spectrum_csv(const TrajectoryAnalysis &analysis);

    // One line per direction for a log: frequency and damping ratio.
    std::string
    spectral_summary(const TrajectoryAnalysis &analysis);
  } // namespace Analysis
} // namespace SoftRobot

#endif
