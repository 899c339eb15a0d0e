// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Helpers shared by the files of the spectral analysis}
//
// Implemented in source/analysis/utilities.cc.
//
// A few constants and two small functions that several files of the
// analysis need. They live in the namespace <code>internal</code>, because
// they are not part of what the library offers: programs that use the
// analysis (tip-spectrum, the simulator, calibrate) define their own
// <code>pi</code> and their own number formatting, and a using-directive for
// <code>SoftRobot::Analysis</code> must not make those ambiguous.

#ifndef soft_robot_analysis_utilities_h
#define soft_robot_analysis_utilities_h

#include <limits>
#include <string>
#include <vector>

namespace SoftRobot
{
  namespace Analysis
  {
    namespace internal
    {
      constexpr double pi           = 3.14159265358979323846;
      constexpr double not_a_number = std::numeric_limits<double>::quiet_NaN();

      // The smallest record the analysis accepts; below this neither a
      // spectrum nor a decrement means anything. Skipping an initial
      // interval must leave at least this many samples, and a signal to
      // analyse must have at least this many.
      constexpr unsigned int minimal_number_of_samples = 16;

      // A number as it appears in the messages of the analysis: with
      // <code>precision</code> significant digits in the default (neither
      // fixed nor scientific) notation of a C++ stream.
      std::string
      format_number(const double value, const int precision = 6);

      // The arithmetic mean, summed from the first value to the last.
      double
      mean_of(const std::vector<double> &values);
    } // namespace internal
  }   // namespace Analysis
} // namespace SoftRobot

#endif
