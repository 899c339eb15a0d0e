// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Helpers shared by the files of the spectral analysis}
//
// The two functions declared in include/analysis/utilities.h. Both are
// written so that the numbers they produce are exactly those the analysis
// has always produced: the messages quote numbers with the stream's default
// notation, and the mean is accumulated in the order of the samples.

#include <analysis/utilities.h>
#include <numeric>
#include <sstream>

namespace SoftRobot
{
  namespace Analysis
  {
    namespace internal
    {
      // @sect4{Numbers in messages}
      //
      // Error messages and warnings quote the values they complain about.
      // Six significant digits are enough to recognise a value from an
      // input file; a caller that needs more (a time that must be told
      // apart from its neighbour) asks for them.
      std::string
      format_number(const double value, const int precision)
      {
        std::ostringstream stream;
        stream.precision(precision);
        stream << value;
        return stream.str();
      }



      // @sect4{The mean of a record}
      //
      // The plain sum divided by the count. The records hold at most a few
      // $10^5$ samples of similar size, for which the rounding error of the
      // sum, at most $n\epsilon$ relative, is far below anything the
      // analysis resolves, so no compensated summation is needed.
      double
      mean_of(const std::vector<double> &values)
      {
        return std::accumulate(values.begin(), values.end(), 0.) /
               values.size();
      }
    } // namespace internal
  }   // namespace Analysis
} // namespace SoftRobot
