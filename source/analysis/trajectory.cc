// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{The tip trajectory as recorded: reading and trimming}
//
// The reader finds its columns by name, so that the simulator and the
// motion-capture scripts may write further columns in any order. Every
// error names the file, the line and, where there is one, the column,
// because a trajectory is usually produced by a different program than the
// one that complains about it.
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
//   <code>u_y</code>, which is more likely a mistake than a planar record in
//   the $x$-$z$ plane;
// - every data line has as many fields as the header. Only the columns that
//   are used are parsed, so the others may hold anything;
// - a number is read with <code>strtod</code> (the C locale's decimal
//   point), must fill its whole field and must be finite: a diverged
//   simulation that wrote <code>nan</code> should stop the analysis, not
//   feed it;
// - times increase strictly. A repeated time, e.g. from a restart that
//   appended to the file, would make the sampling ambiguous.

#include <analysis/trajectory.h>
#include <analysis/utilities.h>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <stdexcept>

namespace SoftRobot
{
  namespace Analysis
  {
    namespace
    {
      // @sect4{Lines and fields}
      //
      // Fields are separated by commas and trimmed of blanks, tabs and the
      // carriage return of Windows line ends. No quoting of commas is
      // supported: none of the writers puts commas into a value.
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



      // The beginning of every message about a particular line.
      std::string
      location_in(const std::string &csv_file, const unsigned int line_number)
      {
        return "In the tip trajectory file '" + csv_file + "', line " +
               std::to_string(line_number) + ": ";
      }



      // @sect4{The header}
      //
      // The header decides which field of a data line holds what. Column
      // names may be quoted, as spreadsheet programs write them. The
      // checks follow the order of the rules above: a duplicated name is
      // reported as soon as it is seen, then a missing required column
      // (with the list of the names that were found, which usually shows
      // the mistake at once), then <code>u_z</code> without
      // <code>u_y</code>.
      struct CsvColumns
      {
        std::vector<std::string> names;
        unsigned int             header_line_number   = 0;
        int                      time_column          = -1;
        std::array<int, 3>       displacement_columns = {{-1, -1, -1}};
        unsigned int             n_components         = 1;
      };



      CsvColumns
      parse_header(const std::vector<std::string> &fields,
                   const std::string              &csv_file,
                   const unsigned int              line_number)
      {
        const std::array<std::string, 3> displacement_names = {
          {"u_x", "u_y", "u_z"}};

        CsvColumns columns;
        columns.header_line_number = line_number;
        for (std::string name : fields)
          {
            if (name.size() >= 2 && name.front() == '"' && name.back() == '"')
              name = trim(name.substr(1, name.size() - 2));
            columns.names.push_back(name);
          }

        const std::vector<std::string> &names = columns.names;
        std::string                     listed_names;
        for (unsigned int c = 0; c < names.size(); ++c)
          {
            listed_names += (c > 0 ? ", '" : "'") + names[c] + "'";
            for (unsigned int d = 0; d < c; ++d)
              if (names[d] == names[c])
                throw std::runtime_error(location_in(csv_file, line_number) +
                                         "the column '" + names[c] +
                                         "' appears twice in the header.");
            if (names[c] == "t")
              columns.time_column = c;
            for (unsigned int i = 0; i < 3; ++i)
              if (names[c] == displacement_names[i])
                columns.displacement_columns[i] = c;
          }

        const std::array<int, 3> &displacement = columns.displacement_columns;
        if (columns.time_column < 0 || displacement[0] < 0)
          throw std::runtime_error(
            location_in(csv_file, line_number) +
            "the header must name the columns 't' and 'u_x' "
            "(optionally also 'u_y' and 'u_z'), but it names " +
            listed_names + ".");
        if (displacement[2] >= 0 && displacement[1] < 0)
          throw std::runtime_error(
            location_in(csv_file, line_number) +
            "the header names a column 'u_z' but no column 'u_y'; "
            "a record has the components u_x, (u_x, u_y) or "
            "(u_x, u_y, u_z).");
        columns.n_components = (displacement[2] >= 0   ? 3
                                : displacement[1] >= 0 ? 2
                                                       : 1);
        return columns;
      }



      // @sect4{A data line}
      //
      // The field count is checked first, since a short line would
      // otherwise be reported as a missing number in some column. The time
      // is compared with the previous one as printed (the message quotes
      // both texts, which is what the user sees in the file).
      double
      parse_field(const std::vector<std::string> &fields,
                  const CsvColumns               &columns,
                  const int                       column,
                  const std::string              &csv_file,
                  const unsigned int              line_number)
      {
        const std::string &text  = fields[column];
        char              *end   = nullptr;
        const double       value = std::strtod(text.c_str(), &end);
        if (text.empty() || end != text.c_str() + text.size() ||
            !std::isfinite(value))
          throw std::runtime_error(
            location_in(csv_file, line_number) + "column '" +
            columns.names[column] + "' (field " + std::to_string(column + 1) +
            ") holds '" + text + "', which is not a finite number.");
        return value;
      }



      void
      append_data_line(const std::vector<std::string> &fields,
                       const CsvColumns               &columns,
                       const std::string              &csv_file,
                       const unsigned int              line_number,
                       std::string                    &previous_time_text,
                       TipTrajectory                  &trajectory)
      {
        if (fields.size() != columns.names.size())
          throw std::runtime_error(
            location_in(csv_file, line_number) + "found " +
            std::to_string(fields.size()) +
            " comma-separated fields, but the header on line " +
            std::to_string(columns.header_line_number) + " names " +
            std::to_string(columns.names.size()) + " columns.");

        const double time = parse_field(
          fields, columns, columns.time_column, csv_file, line_number);
        if (!trajectory.time.empty() && !(time > trajectory.time.back()))
          throw std::runtime_error(
            location_in(csv_file, line_number) + "column 't' holds the time " +
            fields[columns.time_column] +
            ", which is not larger than the time " + previous_time_text +
            " on the previous data line; times must increase strictly.");
        previous_time_text = fields[columns.time_column];

        std::array<double, 3> displacement = {{0., 0., 0.}};
        for (unsigned int i = 0; i < trajectory.n_components; ++i)
          displacement[i] = parse_field(fields,
                                        columns,
                                        columns.displacement_columns[i],
                                        csv_file,
                                        line_number);

        trajectory.time.push_back(time);
        trajectory.displacement.push_back(displacement);
      }
    } // namespace



    // @sect4{Reading the trajectory}
    //
    // One pass through the file: skip comments and blank lines, take the
    // first other line as the header, and append every further line. The
    // checks that need the whole file come at the end: a read error, a
    // file without header, and fewer than two data lines (the least from
    // which a sample rate follows).
    TipTrajectory
    read_tip_trajectory(const std::string &csv_file)
    {
      std::ifstream input(csv_file);
      if (!input)
        throw std::runtime_error("Cannot open the tip trajectory file '" +
                                 csv_file + "' for reading.");

      CsvColumns    columns;
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

          if (columns.names.empty())
            {
              columns = parse_header(fields, csv_file, line_number);
              trajectory.n_components = columns.n_components;
              continue;
            }
          append_data_line(fields,
                           columns,
                           csv_file,
                           line_number,
                           previous_time_text,
                           trajectory);
        }

      if (input.bad())
        throw std::runtime_error("Reading the tip trajectory file '" +
                                 csv_file + "' failed after line " +
                                 std::to_string(line_number) + ".");
      if (columns.names.empty())
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
    // The longest interval that may be skipped ends at the sample that
    // leaves exactly the minimal number of samples,
    // $t_{N-16} - t_0$. Samples up to a millionth of a time step before the
    // requested start are kept, so that a start time that is printed with
    // fewer digits than the times in the file does not lose the first
    // sample.
    TipTrajectory
    skip_initial_interval(const TipTrajectory &trajectory, const double seconds)
    {
      using internal::format_number;
      using internal::minimal_number_of_samples;

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
  } // namespace Analysis
} // namespace SoftRobot
