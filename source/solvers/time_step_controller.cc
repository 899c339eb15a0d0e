// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Implementation of TimeStepController}
//
// The rules of include/solvers/time_step_controller.h, one function each.

#include <algorithm>
#include <cmath>
#include <core/exceptions.h>
#include <deal.II/base/exceptions.h>
#include <solvers/time_step_controller.h>
#include <sstream>

namespace SoftRobot
{
  TimeStepController::TimeStepController(
    const Parameters::TimeIntegration &parameters,
    const ConditionalOStream          &pcout)
    : parameters(parameters)
    , pcout(pcout)
    , time_step(parameters.time_step)
  {
    AssertThrow(parameters.time_step > 0. &&
                  parameters.minimum_time_step <= parameters.time_step,
                ExcMessage("Time integration/Time step must be positive and "
                           "not smaller than Minimum time step."));
  }



  // @sect4{TimeStepController::finished and next_step}
  //
  // The times are sums of step sizes and carry their round-off: after ten
  // steps of 0.1 s the time is 0.9999999999999999 s. The end time is
  // therefore reached when the time is within $10^{-9}$ of the nominal step
  // of it; otherwise the accumulated round-off would cause a last step of
  // almost zero length, a step that the HHT method's coefficients
  // $1/(\beta\Delta t^2)$ turn into a badly scaled system. The last step
  // ends at the end time as closely as the subtraction of the two allows:
  // exactly, when the last step starts at more than half the end time (the
  // subtraction is then exact, by Sterbenz's lemma, and so is the sum).
  bool
  TimeStepController::finished(const double time) const
  {
    return time >= parameters.end_time - 1e-9 * parameters.time_step;
  }



  double
  TimeStepController::next_step(const double time) const
  {
    return std::min(time_step, parameters.end_time - time);
  }



  // @sect4{TimeStepController::record_failure}
  //
  // The step size is halved -- the size of the steps, not of the failed
  // step, which the end time may have shortened -- and the count of
  // halvings since the last regrowth starts again. The two limits are
  // checked after the report of the cut-back, the total number of cut-backs
  // first; their messages say where the run stopped and that its output is
  // kept, because RunAborted ends the program.
  void
  TimeStepController::record_failure(const double       time,
                                     const double       dt,
                                     const std::string &reason)
  {
    time_step *= 0.5;
    ++total_cutbacks;
    steps_since_cutback = 0;
    pcout << "  step at t = " << time + dt << " failed (" << reason
          << "); time step cut back to " << time_step << " s" << std::endl;
    if (total_cutbacks > parameters.max_cutbacks)
      {
        std::ostringstream message;
        message << "More than " << parameters.max_cutbacks
                << " time-step cut backs (Time integration/Max "
                   "cutbacks), the last at t = "
                << time << " s with dt = " << dt << " s: " << reason
                << ". The motion cannot be followed with this mesh "
                   "and time step. The output up to this time has "
                   "been kept.";
        throw RunAborted(message.str());
      }
    if (time_step < parameters.minimum_time_step)
      {
        std::ostringstream message;
        message << "The time step fell below the minimum of "
                << parameters.minimum_time_step << " s at t = " << time
                << " s: " << reason
                << ". The output up to this time has been kept.";
        throw RunAborted(message.str());
      }
  }



  // @sect4{TimeStepController::record_success}
  //
  // Regrowth: after `Regrowth steps` successful steps with a reduced step
  // size, the size is doubled if the time is a multiple of the doubled
  // size, $t/(2\Delta t) \in \mathbb{N}$ to $10^{-6}$ (which allows for the
  // round-off of the times); otherwise the next successful step asks again.
  // A step size that went from $\Delta t$ to $\Delta t/2^k$ therefore
  // grows back only on the grid of $\Delta t/2^{k-1}$, and so on up to the
  // nominal grid.
  void
  TimeStepController::record_success(const double new_time)
  {
    ++steps_since_cutback;
    if (time_step < parameters.time_step &&
        steps_since_cutback >= parameters.regrowth_steps)
      {
        const double doubled = 2. * time_step;
        const double n       = new_time / doubled;
        if (std::abs(n - std::round(n)) < 1e-6)
          {
            time_step           = std::min(doubled, parameters.time_step);
            steps_since_cutback = 0;
          }
      }
  }



  double
  TimeStepController::current_step() const
  {
    return time_step;
  }



  unsigned int
  TimeStepController::n_cutbacks() const
  {
    return total_cutbacks;
  }



  TimeStepController::State
  TimeStepController::state() const
  {
    return {time_step, steps_since_cutback, total_cutbacks};
  }



  void
  TimeStepController::set_state(const State &state)
  {
    time_step           = state.time_step;
    steps_since_cutback = state.steps_since_cutback;
    total_cutbacks      = state.total_cutbacks;
  }
} // namespace SoftRobot
