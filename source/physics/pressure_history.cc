// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{A pressure as a function of time}
//
// See include/physics/pressure_history.h.

#include <algorithm>
#include <cmath>
#include <core/expression_function.h>
#include <core/input_checks.h>
#include <core/parameter_file.h>
#include <deal.II/base/exceptions.h>
#include <deal.II/base/point.h>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <physics/pressure_history.h>
#include <sstream>

namespace SoftRobot
{
  namespace
  {
    std::string
    number_text(const double value)
    {
      std::ostringstream text;
      text << std::setprecision(6) << value;
      return text.str();
    }

    // The fields of one line of a table, split at commas and white space.
    std::vector<std::string>
    fields_of(const std::string &line)
    {
      std::string text = line;
      std::replace(text.begin(), text.end(), ',', ' ');
      std::istringstream       stream(text);
      std::vector<std::string> fields;
      std::string              field;
      while (stream >> field)
        fields.push_back(field);
      return fields;
    }


    // A field as a number, or false if it is not one (all of it).
    bool
    to_number(const std::string &field, double &value)
    {
      char *end = nullptr;
      value     = std::strtod(field.c_str(), &end);
      return end != field.c_str() && *end == '\0';
    }
  } // namespace



  // @sect4{read_time_table}
  void
  read_time_table(const std::string   &file,
                  const std::string   &where,
                  std::vector<double> &times,
                  std::vector<double> &values)
  {
    times.clear();
    values.clear();
    std::ifstream input(file);
    AssertThrow(input, ExcMessage(where + "cannot open '" + file + "'."));
    std::string  line;
    unsigned int line_number = 0, previous_line = 0;
    bool         first_content_line = true;
    while (std::getline(input, line))
      {
        ++line_number;
        const std::vector<std::string> fields = fields_of(line);
        if (fields.empty() || fields[0][0] == '#')
          continue;
        const std::string at =
          where + "'" + file + "', line " + std::to_string(line_number) + ": ";
        double     t = 0., p = 0.;
        const bool numbers = fields.size() == 2 && to_number(fields[0], t) &&
                             to_number(fields[1], p);
        if (!numbers && first_content_line)
          {
            // a header of column names
            first_content_line = false;
            continue;
          }
        first_content_line = false;
        AssertThrow(numbers,
                    ExcMessage(at +
                               "expected two numbers 'time, pressure', "
                               "got '" +
                               line + "'."));
        AssertThrow(std::isfinite(t) && std::isfinite(p),
                    ExcMessage(at + "the values must be finite, got '" + line +
                               "'."));
        AssertThrow(times.empty() || t > times.back(),
                    ExcMessage(at + "the time " + number_text(t) +
                               " is not later than the time " +
                               number_text(times.back()) + " of line " +
                               std::to_string(previous_line) +
                               ": the times of a table must increase."));
        times.push_back(t);
        values.push_back(p);
        previous_line = line_number;
      }
    AssertThrow(times.size() >= 1,
                ExcMessage(where + "'" + file +
                           "' holds no pair 'time, pressure'."));
  }



  // @sect4{PressureHistory::PressureHistory}
  //
  // The expression is a function of the one variable $t$: deal.II's
  // FunctionParser<1> with its spatial variable named `t`, evaluated at the
  // point $t$.
  PressureHistory::PressureHistory(const Parameters::AllParameters &parameters,
                                   const std::string               &entry,
                                   const std::string               &expression,
                                   const std::string               &table_file)
    : parameters(parameters)
    , entry(entry)
    , expression(expression)
  {
    if (!table_file.empty())
      {
        read_time_table(table_file,
                        parameters.where() + entry + " ",
                        times,
                        values);
        return;
      }
    function = std::make_shared<FunctionParser<1>>(1);
    try
      {
        function->initialize("t",
                             expression.empty() ? "0" : expression,
                             parse_constants(parameters.constants),
                             /*time_dependent=*/false);
      }
    catch (ExceptionBase &error)
      {
        std::ostringstream reason;
        error.print_info(reason);
        AssertThrow(false,
                    ExcMessage(parameters.where() + entry + " = '" +
                               expression + "' cannot be parsed: " +
                               Parameters::one_line(reason.str())));
      }
  }



  PressureHistory
  PressureHistory::prescribed_pressure(
    const Parameters::AllParameters &parameters)
  {
    return parameters.pressure_table.empty()
             ? PressureHistory(parameters,
                               "Pneumatics/Pressure",
                               parameters.pressure_expression)
             : PressureHistory(parameters,
                               "Pneumatics/Pressure table",
                               "",
                               parameters.pressure_table);
  }



  // @sect4{PressureHistory::value}
  double
  PressureHistory::value(const double time) const
  {
    if (!is_table())
      return function->value(Point<1>(time));
    if (time <= times.front())
      return values.front();
    if (time >= times.back())
      return values.back();
    const std::size_t k =
      std::upper_bound(times.begin(), times.end(), time) - times.begin() - 1;
    const double s = (time - times[k]) / (times[k + 1] - times[k]);
    return values[k] + s * (values[k + 1] - values[k]);
  }



  // @sect4{PressureHistory::check}
  //
  // muparser parses at the first evaluation; its errors and values that
  // are not finite become input errors that name the entry.
  void
  PressureHistory::check(const std::vector<double> &check_times) const
  {
    if (is_table())
      return;
    InputChecks::SilencedErrorStream silence;
    for (const double t : check_times)
      {
        double value = 0.;
        try
          {
            value = function->value(Point<1>(t));
          }
        catch (ExceptionBase &error)
          {
            std::ostringstream reason;
            error.print_info(reason);
            std::string text = Parameters::one_line(reason.str());
            const auto  said = text.find("The parser said: ");
            if (said != std::string::npos)
              text = text.substr(said + 17);
            while (!text.empty() && text.back() == '.')
              text.pop_back();
            AssertThrow(false,
                        ExcMessage(parameters.where() + entry + " = '" +
                                   expression + "' cannot be parsed: " + text +
                                   "."));
          }
        AssertThrow(std::isfinite(value),
                    ExcMessage(parameters.where() + entry + " = '" +
                               expression + "' gives " + number_text(value) +
                               " at t = " + number_text(t) +
                               ", which is not a finite number."));
      }
  }
} // namespace SoftRobot
