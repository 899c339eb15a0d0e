// @sect3{How a run fails}
//
// Three things can stop a time step or a run, and each has its own type, so
// that the place that can act on it catches it:
// - StepFailure: the current time step cannot be completed with its size
//   (Newton's method did not converge, the linear solver failed, a
//   quadrature point was inverted). The time loop catches it and cuts the
//   step back.
// - RunAborted: the run cannot go on (the step would fall below its
//   minimum, too many cut-backs, no static equilibrium). main() ends the
//   program with exit code 2; the output written so far is kept.
// Errors in the input are deal.II's ExcMessage, thrown by AssertThrow with a
// message that names the file, the entry and the allowed values.

#ifndef soft_robot_core_exceptions_h
#define soft_robot_core_exceptions_h

#include <stdexcept>

namespace SoftRobot
{
  struct StepFailure : public std::runtime_error
  {
    using std::runtime_error::runtime_error;
  };

  struct RunAborted : public std::runtime_error
  {
    using std::runtime_error::runtime_error;
  };
} // namespace SoftRobot

#endif
