// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{The main program}
//
// Reads the parameter file (whose entries do not depend on the dimension),
// then runs SoftRobotDynamics<dim> for the dimension it names. Each way a
// run can end has its exit code and a message of one line (see
// core/exceptions.h):
// - 0: the run reached its end time and everything was written;
// - 1: an error in the input, found before anything was written: the
//   message names the file, the entry, the value and what is allowed;
// - 2: the run cannot continue, or its motion has lost its physical
//   meaning; the output written so far is kept;
// - 3: a file could not be written; the message names it and the reason;
// - 4: the run was interrupted (SIGINT, SIGTERM) and wrote a checkpoint
//   after its current step; `--restart DIR` continues it (see
//   output/checkpoint.h).
//
// Only process 0 prints. The simulator is destroyed before its exception is
// reported: its timer communicates in its destructor, and destroyed while
// an exception is in flight it would print deal.II's warning about that
// instead of the message.

#include <core/exceptions.h>
#include <core/input_checks.h>
#include <core/mpi_session.h>
#include <core/parameter_file.h>
#include <core/parameters.h>
#include <core/soft_robot_dynamics.h>
#include <cstdlib>
#include <deal.II/base/config.h>
#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>
#include <exception>
#include <iostream>
#include <new>
#include <solvers/blas_kernels.h>
#include <sstream>
#include <string>
#include <vector>

#ifndef SOFT_ROBOT_VERSION
#  define SOFT_ROBOT_VERSION "unknown"
#endif

namespace
{
  template <int dim>
  void
  run(const SoftRobot::Parameters::AllParameters &parameters)
  {
    SoftRobot::InputChecks::check_expression_syntax<dim>(parameters);
    std::exception_ptr failure;
    {
      SoftRobot::SoftRobotDynamics<dim> simulation(parameters, MPI_COMM_WORLD);
      try
        {
          simulation.run();
        }
      catch (...)
        {
          failure = std::current_exception();
        }
    }
    if (failure)
      std::rethrow_exception(failure);
  }

  const char *usage =
    "Usage: soft-robot <file.prm> [--set 'Subsection/Entry=value']... "
    "[--restart DIR]\n"
    "       soft-robot --print-parameters   (all entries with defaults and "
    "documentation)\n"
    "       soft-robot --help | --version\n"
    "Each --set replaces one entry of the file, e.g.\n"
    "  --set 'Time integration/End time=0.5'\n"
    "  --set 'Silicone library/Parameter set=calibrated'\n"
    "--restart DIR continues the run from the latest checkpoint in DIR (the "
    "output directory's 'checkpoint', written every Output/Checkpoint "
    "interval steps and at SIGINT or SIGTERM), with the same parameter "
    "file and --set options; only End time, Checkpoint interval and "
    "Progress interval may change.\n"
    "Exit codes: 0 success, 1 error in the input (nothing written), 2 the "
    "run stopped (the output so far kept), 3 a file could not be written, 4 "
    "interrupted by a signal (a checkpoint written).\n";

  // What the command line asks for.
  struct Command
  {
    enum class Action
    {
      run,
      print_parameters,
      help,
      version
    } action = Action::run;
    std::string              parameter_file;
    std::vector<std::string> overrides;
    std::string              restart_directory;
    // Not empty: what is wrong with the command line.
    std::string error;
  };

  Command
  parse_command_line(const int argc, char *argv[])
  {
    Command command;
    for (int i = 1; i < argc; ++i)
      {
        const std::string argument = argv[i];
        if (argument == "--help" || argument == "-h")
          command.action = Command::Action::help;
        else if (argument == "--version")
          command.action = Command::Action::version;
        else if (argument == "--print-parameters")
          command.action = Command::Action::print_parameters;
        else if (argument == "--set")
          {
            if (i + 1 == argc)
              command.error =
                "--set needs an argument 'Subsection/Entry=value'.";
            else
              command.overrides.emplace_back(argv[++i]);
          }
        else if (argument == "--restart")
          {
            if (i + 1 == argc)
              command.error = "--restart needs an argument, the checkpoint "
                              "directory.";
            else
              command.restart_directory = argv[++i];
          }
        else if (argument.rfind("-", 0) == 0)
          command.error = "unknown option '" + argument + "'.";
        else if (!command.parameter_file.empty())
          command.error = "a second parameter file '" + argument +
                          "' (after '" + command.parameter_file +
                          "'); give one, and change its entries with --set.";
        else
          command.parameter_file = argument;
        if (!command.error.empty())
          return command;
      }
    if (command.action == Command::Action::run &&
        command.parameter_file.empty())
      command.error = "no parameter file given.";
    return command;
  }



  // The message of a deal.II exception (among them ParameterHandler's and
  // the program's input errors), without the location in the source code,
  // which is of no use to a user, on one line.
  std::string
  message_of(const dealii::ExceptionBase &error)
  {
    std::ostringstream info;
    error.print_info(info);
    return SoftRobot::Parameters::one_line(info.str());
  }
} // namespace



int
main(int argc, char *argv[])
{
  using namespace SoftRobot;
  // OpenBLAS's kernels for this processor, before anything calls them
  // (solvers/blas_kernels.h).
  const BlasKernels::Selection blas = BlasKernels::select();
  // Open MPI's settings for a run without mpirun (core/mpi_session.h);
  // created before MPI_Init, destroyed after MPI_Finalize.
  const SerialMpiSession mpi_session;
  // Threads for the assembly: deal.II's default, the cores of the machine
  // divided among its MPI processes (DEAL_II_NUM_THREADS limits them).
  dealii::Utilities::MPI::MPI_InitFinalize mpi(
    argc, argv, dealii::numbers::invalid_unsigned_int);
  const bool root =
    dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;

  const Command command = parse_command_line(argc, argv);
  if (!command.error.empty())
    {
      if (root)
        std::cerr << "soft-robot: " << command.error << "\n\n" << usage;
      return ExitCode::input_error;
    }
  if (command.action == Command::Action::help)
    {
      if (root)
        std::cout << usage;
      return ExitCode::success;
    }
  if (command.action == Command::Action::version)
    {
      if (root)
        std::cout << "soft-robot " << SOFT_ROBOT_VERSION << " (deal.II "
                  << DEAL_II_PACKAGE_VERSION << ")\n";
      return ExitCode::success;
    }

  const auto report = [root](const std::string &kind,
                             const std::string &message) {
    if (root)
      std::cerr << kind << message << std::endl;
  };
  try
    {
      if (command.action == Command::Action::print_parameters)
        {
          dealii::ParameterHandler prm;
          Parameters::AllParameters::declare_parameters(prm);
          if (root)
            prm.print_parameters(std::cout, dealii::ParameterHandler::PRM);
          return ExitCode::success;
        }

      Parameters::AllParameters parameters;
      parameters.read_file(command.parameter_file, command.overrides);
      parameters.restart_directory = command.restart_directory;
      if (root && blas.changed())
        std::cout << "BLAS: OpenBLAS's " << blas.in_use
                  << " kernels instead of its generic ones ("
                  << blas.library_choice
                  << "), which it chose on this processor it does not "
                     "know; OPENBLAS_CORETYPE overrides the choice.\n";
      switch (parameters.dimension)
        {
          case 1:
            run<1>(parameters);
            break;
          case 2:
            run<2>(parameters);
            break;
          default:
            run<3>(parameters);
        }
    }
  catch (RunAborted &aborted)
    {
      report("The simulation stopped: ", aborted.what());
      return ExitCode::run_aborted;
    }
  catch (WriteFailure &failure)
    {
      report("Error writing the output: ", failure.what());
      return ExitCode::write_failure;
    }
  catch (RunInterrupted &interruption)
    {
      report("The run was interrupted: ", interruption.what());
      return ExitCode::interrupted;
    }
  catch (dealii::ExceptionBase &error)
    {
      report("Error in the input: ", message_of(error));
      return ExitCode::input_error;
    }
  catch (std::bad_alloc &)
    {
      report("Error: ",
             "out of memory: the mesh or the run is too large for this "
             "machine (fewer Global refinements, a coarser mesh, or more "
             "MPI processes on more machines).");
      return ExitCode::run_aborted;
    }
  catch (std::exception &error)
    {
      report("Error: ", error.what());
      return ExitCode::input_error;
    }
  return ExitCode::success;
}
