// @sect3{The main program}
//
// Reads the parameter file (whose entries do not depend on the dimension),
// then runs SoftRobotDynamics<dim> for the dimension it names. Errors in the input end the
// program with a message naming the file and the entry, and exit code 1;
// a simulation that cannot continue (the time step fell below its
// minimum) ends with exit code 2 and keeps the output written so far.

#include <core/parameters.h>
#include <core/soft_robot_dynamics.h>
#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

namespace
{
  template <int dim>
  void
  run(const SoftRobot::Parameters::AllParameters &parameters)
  {
    SoftRobot::SoftRobotDynamics<dim> simulation(parameters, MPI_COMM_WORLD);
    simulation.run();
  }

  void
  print_usage()
  {
    std::cerr
      << "Usage: soft-robot <file.prm> [--set 'Subsection/Entry=value']...\n"
         "       soft-robot --print-parameters   (all entries with "
         "defaults and documentation)\n"
         "Each --set replaces one entry of the file, e.g.\n"
         "  --set 'Time integration/End time=0.5'\n"
         "  --set 'Silicone library/Parameter set=calibrated'\n";
  }
} // namespace

int
main(int argc, char *argv[])
{
  using namespace SoftRobot;
  // A run started without mpirun is an MPI singleton, for which Open MPI
  // starts a helper daemon (orted) that probes the machine; that costs a
  // quarter of a second at every start and is of no use to a program that
  // never spawns processes. Open MPI's own switch turns it off. A singleton
  // also has no one to talk to, yet Open MPI's default message layer (UCX)
  // probes the machine's network devices, another fifth of a second; the
  // basic layer (ob1, with its process-to-itself transport) serves a single
  // process just as well. Neither variable replaces a value the user set;
  // other MPI implementations ignore them.
  if (std::getenv("OMPI_COMM_WORLD_SIZE") == nullptr)
    {
      setenv("OMPI_MCA_ess_singleton_isolated", "1", /*overwrite=*/0);
      setenv("OMPI_MCA_pml", "ob1", /*overwrite=*/0);
    }
  // Threads for the assembly: deal.II's default, the cores of the machine
  // divided among its MPI processes (DEAL_II_NUM_THREADS limits them).
  dealii::Utilities::MPI::MPI_InitFinalize mpi(
    argc, argv, dealii::numbers::invalid_unsigned_int);
  const bool                               root =
    dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;

  if (argc < 2)
    {
      if (root)
        print_usage();
      return 1;
    }
  const std::string        argument = argv[1];
  std::vector<std::string> overrides;
  for (int i = 2; i < argc; ++i)
    {
      if (std::string(argv[i]) != "--set" || i + 1 == argc)
        {
          if (root)
            print_usage();
          return 1;
        }
      overrides.emplace_back(argv[++i]);
    }
  try
    {
      if (argument == "--print-parameters")
        {
          dealii::ParameterHandler prm;
          Parameters::AllParameters::declare_parameters(prm);
          if (root)
            prm.print_parameters(std::cout, dealii::ParameterHandler::PRM);
          return 0;
        }

      Parameters::AllParameters parameters;
      parameters.read_file(argument, overrides);
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
      if (root)
        std::cerr << "\nThe simulation stopped: " << aborted.what()
                  << std::endl;
      return 2;
    }
  catch (dealii::ExceptionBase &error)
    {
      // deal.II's exceptions (among them ParameterHandler's messages about
      // entries out of range): only their message, without the location in
      // the source code, which is of no use to a user.
      if (root)
        {
          std::cerr << "\nError in the input:\n";
          error.print_info(std::cerr);
          std::cerr << std::endl;
        }
      return 1;
    }
  catch (std::exception &error)
    {
      if (root)
        std::cerr << "\nError: " << error.what() << std::endl;
      return 1;
    }
  return 0;
}
