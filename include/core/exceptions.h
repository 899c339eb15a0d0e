// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{How a run fails}
//
// Five things can stop a time step or a run, and each has its own type, so
// that the place that can act on it catches it and main() gives each its
// own exit code:
// - StepFailure: the current time step cannot be completed with its size
//   (Newton's method did not converge, the linear solver failed, a
//   quadrature point was inverted). The time loop catches it and cuts the
//   step back.
// - RunAborted: the run cannot go on, or what it would compute has no
//   physical meaning (the step would fall below its minimum, too many
//   cut-backs, no static equilibrium, a tip that runs away, a body that
//   passes through its fixed boundary). main() ends the program with exit
//   code 2; the output written so far is kept.
// - WriteFailure: a file of the output could not be written (the disk is
//   full, the directory is not writable). main() ends the program with exit
//   code 3 and a message that names the file and the reason; it is never
//   reported as an error in the input.
// - RunInterrupted: the run received SIGINT or SIGTERM; it has written a
//   checkpoint after the step it was in (output/checkpoint.h), and main()
//   ends the program with exit code 4 and the command that continues it.
// - Errors in the input are deal.II's ExcMessage, thrown by AssertThrow with
//   a message that names the file, the entry, the value and the allowed
//   values; main() ends the program with exit code 1. They are all raised
//   before the first byte of output is written (see core/input_checks.h).
//
// Every process of an MPI run raises these at the same point (the input
// and the mesh are the same everywhere, and a write failure on one process
// is made known to all, see output/safe_file.h), so that the simulator can
// be destroyed normally on all of them.

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

  struct WriteFailure : public std::runtime_error
  {
    using std::runtime_error::runtime_error;
  };

  struct RunInterrupted : public std::runtime_error
  {
    using std::runtime_error::runtime_error;
  };

  // The exit codes of main().
  namespace ExitCode
  {
    constexpr int success       = 0;
    constexpr int input_error   = 1;
    constexpr int run_aborted   = 2;
    constexpr int write_failure = 3;
    constexpr int interrupted   = 4;
  } // namespace ExitCode
} // namespace SoftRobot

#endif
