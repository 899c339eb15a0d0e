// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{The size of the time steps}
//
// The time loop runs with the nominal step $\Delta t$ of `Time
// integration/Time step`. A step whose Newton iteration fails (StepFailure)
// is repeated from the same state with half the step, down to the
// `Minimum time step`; a run that needs more than `Max cutbacks` halvings
// in total is stopped (RunAborted), because a motion that the mesh and the
// step cannot follow otherwise ends in thousands of tiny steps that never
// grow back, which looks like a hang. After `Regrowth steps` successful
// steps the step is doubled again, but only at times that are multiples of
// the doubled step, so that the steps return to the nominal grid $t_n =
// n\,\Delta t$ (which the spectral analysis of the tip motion prefers); it
// never grows beyond the nominal step. The last step is shortened to end
// at the end time (to round-off, see TimeStepController::finished()).
//
// The controller holds the step size and the counts; the time itself, and
// what a step does, are the time loop's:
// @code
//   while (!controller.finished(time))
//     {
//       const double dt = controller.next_step(time);
//       try { ...solve the step from time to time + dt... }
//       catch (StepFailure &failure)
//         {
//           ...restore the old state...
//           controller.record_failure(time, dt, failure.what());
//           continue;
//         }
//       time += dt;
//       controller.record_success(time);
//     }
// @endcode
//
// Implemented in source/solvers/time_step_controller.cc.

#ifndef soft_robot_solvers_time_step_controller_h
#define soft_robot_solvers_time_step_controller_h

#include <core/parameters.h>
#include <deal.II/base/conditional_ostream.h>
#include <string>

namespace SoftRobot
{
  using namespace dealii;

  class TimeStepController
  {
  public:
    // The parameters are copied; `pcout`, on which every cut-back is
    // reported, must outlive the controller.
    TimeStepController(const Parameters::TimeIntegration &parameters,
                       const ConditionalOStream          &pcout);

    // Whether `time` is the end time (to $10^{-9}\Delta t$).
    bool
    finished(const double time) const;

    // The size of the step that starts at `time`: the current step size,
    // shortened so as not to pass the end time.
    double
    next_step(const double time) const;

    // The step of size `dt` from `time` failed for `reason`: halves the
    // step size and reports it on `pcout`. Throws RunAborted if this was
    // one cut-back too many, or if the step has become smaller than the
    // minimum.
    void
    record_failure(const double       time,
                   const double       dt,
                   const std::string &reason);

    // A step has ended successfully at `new_time`: doubles the step size
    // if it has been small for long enough and `new_time` lies on the grid
    // of the doubled step.
    void
    record_success(const double new_time);

    // The step size now (before next_step() shortens it at the end time).
    double
    current_step() const;

    // The cut-backs of the run so far.
    unsigned int
    n_cutbacks() const;

    // What the controller remembers between steps, for a checkpoint
    // (output/checkpoint.h): a restart that sets it goes on with the same
    // step sizes as the run that was interrupted.
    struct State
    {
      double       time_step;
      unsigned int steps_since_cutback;
      unsigned int total_cutbacks;
    };
    State
    state() const;
    void
    set_state(const State &state);

  private:
    const Parameters::TimeIntegration parameters;
    const ConditionalOStream         &pcout;

    double       time_step;
    unsigned int steps_since_cutback = 0;
    unsigned int total_cutbacks      = 0;
  };
} // namespace SoftRobot

#endif
