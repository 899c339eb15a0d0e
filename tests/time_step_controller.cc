// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Tests of TimeStepController}
//
// The controller is driven by a time loop like the program's, in which a
// step fails when the test says so, and the sequence of steps it asks for
// is compared with the one its rules give, worked out by hand below: the
// end time reached exactly (or to its tolerance of $10^{-9}\Delta t$),
// halving on failure, regrowth only after `Regrowth steps` steps and only
// at multiples of the doubled step, and the two limits that abort the run,
// with their messages.

// Not typed on the dimension: the controller sees times and step sizes only.

#include <cmath>
#include <core/exceptions.h>
#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/parameter_handler.h>
#include <functional>
#include <gtest/gtest.h>
#include <solvers/time_step_controller.h>
#include <sstream>
#include <string>
#include <vector>

namespace
{
  using namespace dealii;
  using namespace SoftRobot;

  // The program's defaults, with the given end time and nominal step.
  Parameters::TimeIntegration
  time_parameters(const double end_time, const double time_step)
  {
    ParameterHandler prm;
    Parameters::TimeIntegration::declare_parameters(prm);
    Parameters::TimeIntegration parameters;
    parameters.parse_parameters(prm);
    parameters.end_time  = end_time;
    parameters.time_step = time_step;
    return parameters;
  }

  // One attempted step: where it started, its size, whether it failed.
  struct Attempt
  {
    double time;
    double dt;
    bool   failed;
  };

  // The time loop of the program, with a step that fails when `fails`
  // says so; returns the attempts and leaves the final time in `time`.
  std::vector<Attempt>
  run(TimeStepController                                &controller,
      const std::function<bool(double time, double dt)> &fails,
      double                                            &time)
  {
    std::vector<Attempt> attempts;
    time = 0.;
    while (!controller.finished(time))
      {
        const double dt = controller.next_step(time);
        if (fails(time, dt))
          {
            attempts.push_back({time, dt, true});
            controller.record_failure(time, dt, "test failure");
            continue;
          }
        attempts.push_back({time, dt, false});
        time += dt;
        controller.record_success(time);
      }
    return attempts;
  }

  const auto never = [](double, double) { return false; };



  // @sect4{The end time}
  //
  // Ten steps of 0.1 s add up to $1 - 2^{-53}$, within the tolerance
  // $10^{-10}$ of the end time 1: ten steps, and no eleventh of length
  // $10^{-16}$. With 0.3 s the last step is the rest, $1 - t_3$; $t_3 =
  // 0.8999999999999999$ lies within a factor of two of 1, so the
  // subtraction is exact (Sterbenz) and $t_3 + (1 - t_3) = 1$ exactly. An
  // end time $5\cdot 10^{-11}$ beyond the tenth step counts as reached; one
  // $2\cdot 10^{-10}$ beyond (twice the tolerance) gets a last step of that
  // length, to round-off.
  TEST(TimeStepControllerTest, EndTime)
  {
    std::ostringstream output;
    ConditionalOStream pcout(output, true);
    double             time = 0.;
    // Ten steps, each of exactly the nominal size (1 - t is never below
    // 0.1), and the sum within a few units of round-off of 1.
    {
      TimeStepController controller(time_parameters(1., 0.1), pcout);
      const auto         attempts = run(controller, never, time);
      EXPECT_EQ(attempts.size(), 10u);
      for (const Attempt &attempt : attempts)
        EXPECT_EQ(attempt.dt, 0.1);
      EXPECT_NEAR(time, 1., 1e-15);
      EXPECT_TRUE(controller.finished(time));
    }
    // Three nominal steps and the rest, which ends at 1 exactly.
    {
      TimeStepController controller(time_parameters(1., 0.3), pcout);
      const auto         attempts = run(controller, never, time);
      ASSERT_EQ(attempts.size(), 4u);
      EXPECT_NEAR(attempts[3].dt, 0.1, 1e-15);
      EXPECT_EQ(time, 1.);
    }
    // The tolerance, from either side.
    {
      TimeStepController controller(time_parameters(1. + 5e-11, 0.1), pcout);
      EXPECT_EQ(run(controller, never, time).size(), 10u);
    }
    {
      TimeStepController controller(time_parameters(1. + 2e-10, 0.1), pcout);
      const auto         attempts = run(controller, never, time);
      ASSERT_EQ(attempts.size(), 11u);
      EXPECT_NEAR(attempts.back().dt, 2e-10, 1e-15);
      EXPECT_EQ(time, 1. + 2e-10);
    }
    // Nothing failed, nothing was reported.
    EXPECT_EQ(output.str(), "");
  }



  // @sect4{Halving and regrowth}
  //
  // $\Delta t = 0.1$, `Regrowth steps` = 2, and the step from $t = 0.3$
  // fails twice (with 0.1 and 0.05). Then the steps are
  // - 0.025 to 0.325 and 0.35: two steps, and $0.35 = 7\cdot 0.05$: the
  //   step doubles to 0.05;
  // - 0.05 to 0.4 and 0.45: two steps, but $0.45/0.1 = 4.5$: no regrowth;
  // - 0.05 to 0.5 $= 5\cdot 0.1$: back to 0.1, and on the nominal grid to
  //   the end.
  TEST(TimeStepControllerTest, HalvingAndRegrowthOnTheGrid)
  {
    std::ostringstream          output;
    ConditionalOStream          pcout(output, true);
    Parameters::TimeIntegration parameters = time_parameters(1., 0.1);
    parameters.regrowth_steps              = 2;
    TimeStepController controller(parameters, pcout);
    double             time     = 0.;
    const auto         attempts = run(
      controller,
      [](const double t, const double dt) {
        return std::abs(t - 0.3) < 1e-12 && dt > 0.03;
      },
      time);

    // The attempts as listed above: three nominal steps, the two failures,
    // two quarter steps, three half steps, and the nominal steps from 0.5.
    // The sizes are compared to round-off: 0.3 is reached as
    // 0.30000000000000004, and the later times carry that error along.
    const std::vector<double> expected_dt = {0.1,
                                             0.1,
                                             0.1,
                                             0.1,
                                             0.05,
                                             0.025,
                                             0.025,
                                             0.05,
                                             0.05,
                                             0.05,
                                             0.1,
                                             0.1,
                                             0.1,
                                             0.1,
                                             0.1};
    ASSERT_EQ(attempts.size(), expected_dt.size());
    for (unsigned int i = 0; i < attempts.size(); ++i)
      {
        EXPECT_NEAR(attempts[i].dt, expected_dt[i], 1e-15) << "attempt " << i;
        EXPECT_EQ(attempts[i].failed, i == 3 || i == 4) << "attempt " << i;
      }
    EXPECT_NEAR(attempts[10].time, 0.5, 1e-15);
    EXPECT_NEAR(time, 1., 1e-14);
    // Two cut-backs, the nominal step again, and one line of report per
    // failure, with the end of the failed step and the new step size.
    EXPECT_EQ(controller.n_cutbacks(), 2u);
    EXPECT_EQ(controller.current_step(), 0.1);
    EXPECT_EQ(output.str(),
              "  step at t = 0.4 failed (test failure); time step cut back "
              "to 0.05 s\n"
              "  step at t = 0.35 failed (test failure); time step cut back "
              "to 0.025 s\n");
  }



  // A failed step that the end time had shortened: the step size is halved,
  // not the failed step. With $\Delta t = 0.1$ and the end time 0.23, the
  // last step is 0.03; after its failure the size is 0.05, and the step is
  // tried again with 0.03; after a second failure, with 0.025 and then
  // 0.005.
  TEST(TimeStepControllerTest, FailureOfTheShortenedLastStep)
  {
    std::ostringstream output;
    ConditionalOStream pcout(output, true);
    TimeStepController controller(time_parameters(0.23, 0.1), pcout);
    double             time     = 0.;
    unsigned int       failures = 0;
    const auto         attempts = run(
      controller,
      [&](const double t, const double) { return t > 0.15 && failures++ < 2; },
      time);
    const std::vector<double> expected_dt = {
      0.1, 0.1, 0.03, 0.03, 0.025, 0.005};
    ASSERT_EQ(attempts.size(), expected_dt.size());
    for (unsigned int i = 0; i < attempts.size(); ++i)
      EXPECT_NEAR(attempts[i].dt, expected_dt[i], 1e-15) << "attempt " << i;
    EXPECT_NEAR(time, 0.23, 1e-15);
    EXPECT_EQ(controller.current_step(), 0.025);
  }



  // @sect4{The limits}
  //
  // `Max cutbacks` = 2: the third failure aborts the run, after its report.
  // `Minimum time step` = 0.03: the second halving of 0.1 gives 0.025 <
  // 0.03 and aborts. When both limits are reached by the same failure, the
  // count of cut-backs is reported.
  TEST(TimeStepControllerTest, LimitsAbortTheRun)
  {
    const auto always = [](double, double) { return true; };
    {
      std::ostringstream          output;
      ConditionalOStream          pcout(output, true);
      Parameters::TimeIntegration parameters = time_parameters(1., 0.1);
      parameters.max_cutbacks                = 2;
      TimeStepController controller(parameters, pcout);
      double             time = 0.;
      try
        {
          run(controller, always, time);
          ADD_FAILURE() << "no RunAborted";
        }
      // The third failure, of the step of 0.025 from t = 0, is one too
      // many; its report precedes the exception.
      catch (const RunAborted &aborted)
        {
          EXPECT_EQ(std::string(aborted.what()),
                    "More than 2 time-step cut backs (Time integration/Max "
                    "cutbacks), the last at t = 0 s with dt = 0.025 s: test "
                    "failure. The motion cannot be followed with this mesh "
                    "and time step. The output up to this time has been "
                    "kept.");
        }
      EXPECT_EQ(controller.n_cutbacks(), 3u);
      EXPECT_EQ(output.str(),
                "  step at t = 0.1 failed (test failure); time step cut back "
                "to 0.05 s\n"
                "  step at t = 0.05 failed (test failure); time step cut back "
                "to 0.025 s\n"
                "  step at t = 0.025 failed (test failure); time step cut "
                "back to 0.0125 s\n");
    }
    {
      std::ostringstream          output;
      ConditionalOStream          pcout(output, false);
      Parameters::TimeIntegration parameters = time_parameters(1., 0.1);
      parameters.minimum_time_step           = 0.03;
      TimeStepController controller(parameters, pcout);
      double             time = 0.;
      try
        {
          run(
            controller, [](const double t, double) { return t > 0.25; }, time);
          ADD_FAILURE() << "no RunAborted";
        }
      // The steps from t = 0.3 fail: 0.1 and 0.05 are allowed, 0.025 is
      // not. (The report goes to a stream that is switched off.)
      catch (const RunAborted &aborted)
        {
          EXPECT_EQ(std::string(aborted.what()),
                    "The time step fell below the minimum of 0.03 s at t = "
                    "0.3 s: test failure. The output up to this time has "
                    "been kept.");
        }
      EXPECT_EQ(controller.n_cutbacks(), 2u);
      EXPECT_EQ(controller.current_step(), 0.025);
      EXPECT_EQ(output.str(), "");
    }
    {
      std::ostringstream          output;
      ConditionalOStream          pcout(output, false);
      Parameters::TimeIntegration parameters = time_parameters(1., 0.1);
      parameters.minimum_time_step           = 0.03;
      parameters.max_cutbacks                = 1;
      TimeStepController controller(parameters, pcout);
      double             time = 0.;
      try
        {
          run(controller, always, time);
          ADD_FAILURE() << "no RunAborted";
        }
      catch (const RunAborted &aborted)
        {
          EXPECT_EQ(std::string(aborted.what())
                      .rfind("More than 1 time-step "
                             "cut backs",
                             0),
                    0u);
        }
    }
  }
} // namespace
