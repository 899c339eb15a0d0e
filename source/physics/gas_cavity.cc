// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{A gas enclosed in the cavity}
//
// See include/physics/gas_cavity.h.

#include <cmath>
#include <core/exceptions.h>
#include <deal.II/base/exceptions.h>
#include <iomanip>
#include <physics/gas_cavity.h>
#include <sstream>

namespace SoftRobot
{
  namespace
  {
    // The grid on which the inflow rate is integrated, s.
    constexpr double inflow_grid = 1e-4;

    // The integral of f over [a, b] by three-point Gauss-Legendre.
    template <typename Function>
    double
    gauss3(const Function &f, const double a, const double b)
    {
      const double mid = 0.5 * (a + b), half = 0.5 * (b - a);
      const double x = half * std::sqrt(0.6);
      return half * (5. / 9. * (f(mid - x) + f(mid + x)) + 8. / 9. * f(mid));
    }

    std::string
    number_text(const double value)
    {
      std::ostringstream text;
      text << std::setprecision(6) << value;
      return text.str();
    }
  } // namespace



  GasCavity::GasCavity(const Parameters::AllParameters &parameters)
    : where(parameters.where())
    , ambient(parameters.ambient_pressure)
    , initial_absolute(parameters.ambient_pressure +
                       parameters.initial_gas_pressure)
    , exponent(parameters.gas_exponent)
    , temperature(parameters.gas_temperature)
    , has_inflow(!parameters.inflow_expression.empty())
    , inflow(parameters,
             "Pneumatics/Mass inflow rate",
             parameters.inflow_expression)
  {
    cumulative_inflow.assign(1, 0.);
  }



  // @sect4{GasCavity::seal}
  void
  GasCavity::seal(const double volume, const double cavity_volume)
  {
    // (The message is an input error: the volume follows from the input
    // before anything is written.)
    AssertThrow(volume > 0.,
                ExcMessage(where +
                           "Pneumatics/Dead volume and the cavity volume of "
                           "the initial state (" +
                           number_text(cavity_volume) +
                           " mm^3 for the whole body) give a gas volume of " +
                           number_text(volume) +
                           " mm^3 at t = 0: a gas needs a positive volume "
                           "(a larger Dead volume, or the cavity surface's "
                           "orientation: its volume is counted from the "
                           "closing planes)."));
    sealed_volume = volume;
    sealed_mass = initial_absolute / (air_gas_constant * temperature) * volume;
  }



  // @sect4{GasCavity::restore_seal}
  void
  GasCavity::restore_seal(const std::vector<double> &state)
  {
    AssertThrow(state.size() == 2 && state[0] > 0. && state[1] > 0.,
                ExcMessage("The checkpoint holds no sealed gas (" +
                           std::to_string(state.size()) +
                           " values), but this run has a gas cavity."));
    sealed_volume = state[0];
    sealed_mass   = state[1];
  }



  // @sect4{GasCavity::mass}
  //
  // $m_0$ plus the integral of the rate on the fixed grid, kept as it is
  // extended, and the last partial interval.
  double
  GasCavity::mass(const double time) const
  {
    if (!has_inflow || time <= 0.)
      return sealed_mass;
    const auto        rate = [this](const double t) { return inflow.value(t); };
    const std::size_t whole = static_cast<std::size_t>(time / inflow_grid);
    while (cumulative_inflow.size() <= whole)
      {
        const double a = (cumulative_inflow.size() - 1) * inflow_grid;
        cumulative_inflow.push_back(cumulative_inflow.back() +
                                    gauss3(rate, a, a + inflow_grid));
      }
    const double a = whole * inflow_grid;
    return sealed_mass + cumulative_inflow[whole] +
           (time > a ? gauss3(rate, a, time) : 0.);
  }



  // @sect4{GasCavity::gauge_pressure}
  double
  GasCavity::absolute_pressure(const double volume, const double time) const
  {
    Assert(is_sealed(), ExcMessage("The gas cavity has not been sealed."));
    if (!(volume > 0.))
      throw StepFailure("the gas volume of the cavity is not positive (" +
                        number_text(volume) + " mm^3)");
    const double m = mass(time);
    if (!(m > 0.))
      throw RunAborted("the Mass inflow rate has emptied the gas cavity by t "
                       "= " +
                       number_text(time) + " s (mass " + number_text(m) +
                       " kg)");
    return initial_absolute *
           std::pow(m / sealed_mass * sealed_volume / volume, exponent);
  }



  double
  GasCavity::gauge_pressure(const double volume, const double time) const
  {
    return absolute_pressure(volume, time) - ambient;
  }



  double
  GasCavity::pressure_derivative(const double volume, const double time) const
  {
    return -exponent * absolute_pressure(volume, time) / volume;
  }



  // @sect4{GasCavity::check}
  void
  GasCavity::check(const double end_time) const
  {
    std::vector<double> times;
    for (unsigned int k = 0; k <= 16; ++k)
      times.push_back(end_time * k / 16.);
    inflow.check(times);
  }
} // namespace SoftRobot
