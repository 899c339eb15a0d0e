// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{A pressure as a function of time}
//
// The pneumatic actuator is driven by the pressure its valve or pump sets:
// a step (a valve that opens), a ramp (a pressure regulator turned up), a
// sinusoid (a pulsating supply), or a record of measured pressures. The
// first three are expressions of the time $t$, as the tractions are
// (`Pneumatics/Pressure`, with the `Function constants` of the file); the
// last is a table (`Pneumatics/Pressure table`), a CSV file of pairs
// $(t_k, p_k)$ with increasing times, interpolated linearly,
// @f[
//   p(t) = p_k + \frac{t - t_k}{t_{k+1} - t_k}\,(p_{k+1} - p_k),
//   \qquad t_k \le t \le t_{k+1},
// @f]
// and held at $p_0$ before the first time and at the last value after the
// last one. The pressures are gauge pressures (above ambient) in kPa; a
// negative value is a vacuum.
//
// The same class evaluates the mass inflow rate of a gas cavity, an
// expression of $t$ as well (see GasCavity).
//
// Reading the table checks it: every line two finite numbers, the times
// strictly increasing. A mistake is an input error that names the
// parameter file, the entry, the table file and its line, found before
// anything is written.
//
// Implemented in source/physics/pressure_history.cc.

#ifndef soft_robot_physics_pressure_history_h
#define soft_robot_physics_pressure_history_h

#include <core/parameters.h>
#include <deal.II/base/function_parser.h>
#include <memory>
#include <string>
#include <vector>

namespace SoftRobot
{
  using namespace dealii;

  class PressureHistory
  {
  public:
    // A function of $t$ from the expression `expression` of the entry
    // `entry` (empty: zero), or, if `table_file` is not empty, the table in
    // that file; errors name the parameter file and the entry.
    PressureHistory(const Parameters::AllParameters &parameters,
                    const std::string               &entry,
                    const std::string               &expression,
                    const std::string               &table_file = "");

    // The prescribed pressure of the parameter file (Pneumatics/Pressure or
    // Pneumatics/Pressure table).
    static PressureHistory
    prescribed_pressure(const Parameters::AllParameters &parameters);

    double
    value(const double time) const;

    // Whether the function is a table, and its points.
    bool
    is_table() const
    {
      return !times.empty();
    }
    const std::vector<double> &
    table_times() const
    {
      return times;
    }

    // The expression evaluated at the times `check_times`: an input error
    // naming the entry if it cannot be parsed or gives a value that is not
    // finite. (A table is checked when it is read.)
    void
    check(const std::vector<double> &check_times) const;

  private:
    const Parameters::AllParameters   &parameters;
    std::string                        entry;
    std::string                        expression;
    std::shared_ptr<FunctionParser<1>> function;
    std::vector<double>                times;
    std::vector<double>                values;
  };



  // @sect4{Reading a table}
  //
  // The pairs (time, value) of a CSV file: lines whose first non-blank
  // character is '#' and blank lines are skipped, and so is a first line
  // that is not two numbers (a header of column names). Fields are
  // separated by a comma (or white space). Throws an input error whose
  // message begins with `where` and names the file and the line.
  void
  read_time_table(const std::string   &file,
                  const std::string   &where,
                  std::vector<double> &times,
                  std::vector<double> &values);
} // namespace SoftRobot

#endif
