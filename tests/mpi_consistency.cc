// @sect3{The same motion on one and on several MPI processes}
//
// Run under `mpiexec -n 2` (see tests/CMakeLists.txt): the short 2D scene
// tests/cli/two_processes.prm is simulated once on all processes together
// and once on each process alone (MPI_COMM_SELF), and the tip motions are
// compared step by step. Partitioning changes only the order of the
// floating-point sums and the AMG hierarchy, so the two must agree to the
// tolerances of the solvers: Newton's relative tolerance 1e-11 and CG's
// 1e-12 leave differences far below the 1e-7 relative allowed here. Run on
// one process, the test compares a run with itself.

#include "solver_test_tools.h"

#include <core/soft_robot_dynamics.h>
#include <cstdlib>
#include <deal.II/base/mpi.h>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <regex>
#include <sstream>
#include <string>

using namespace dealii;
using namespace SoftRobot;
using namespace SoftRobot::Testing;

TEST(MPI, PartitionedRunMatchesSerialRun)
{
  const char *root = std::getenv("SOFT_ROBOT_SOURCE_DIR");
  ASSERT_NE(root, nullptr);
  Parameters::AllParameters parameters;
  parameters.read_file(std::string(root) + "/tests/cli/two_processes.prm");

  Simulation<2> parallel(parameters, MPI_COMM_WORLD);
  Simulation<2> serial(parameters, MPI_COMM_SELF);
  for (Simulation<2> *run : {&parallel, &serial})
    {
      run->make_grid();
      run->setup_system();
      run->initialize_state();
    }

  unsigned int steps     = 0;
  double       worst     = 0.;
  double       amplitude = 0.;
  while (parallel.advance_one_step())
    {
      ASSERT_TRUE(serial.advance_one_step());
      const auto [u_parallel, v_parallel] = parallel.tip_motion();
      const auto [u_serial, v_serial]     = serial.tip_motion();
      worst     = std::max(worst, (u_parallel - u_serial).norm());
      amplitude = std::max(amplitude, u_serial.norm());
      ++steps;
    }
  std::cout << Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) << " processes, "
            << steps << " steps: largest difference of the "
            << "tip displacement " << worst << " mm of " << amplitude << " mm"
            << std::endl;
  EXPECT_EQ(steps, 10u);
  EXPECT_LE(worst, 1e-7 * amplitude);
}



// @sect3{The parallel run's VTU output}
//
// The whole run of the same scene on all processes, with its VTU output:
// each process's writing thread writes its own piece of the mesh, and
// process 0 the PVTU records and the PVD record. At every output time the
// PVD record must name a PVTU record, that record one piece per process,
// and the pieces together must hold every cell of the mesh once (the 12 x 3
// quadratic cells are written as 2 x 2 patches each).
namespace
{
  // This file's scene, with its output in a directory of the given name
  // where the test runs; process 0 removes what an earlier run left there.
  Parameters::AllParameters
  scene_writing_to(const std::string &directory_name)
  {
    const char *root = std::getenv("SOFT_ROBOT_SOURCE_DIR");
    AssertThrow(root != nullptr,
                ExcMessage("SOFT_ROBOT_SOURCE_DIR is not set"));
    Parameters::AllParameters parameters;
    parameters.read_file(std::string(root) + "/tests/cli/two_processes.prm");
    parameters.output_directory =
      std::filesystem::absolute(directory_name).string();
    if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
      std::filesystem::remove_all(parameters.output_directory);
    return parameters;
  }

  std::string
  file_contents(const std::filesystem::path &path)
  {
    std::ifstream     file(path);
    std::stringstream contents;
    contents << file.rdbuf();
    return contents.str();
  }

  std::vector<std::string>
  attribute_values(const std::string &text, const std::string &attribute)
  {
    const std::regex         pattern(attribute + "=\"([^\"]*)\"");
    std::vector<std::string> values;
    for (auto match = std::sregex_iterator(text.begin(), text.end(), pattern);
         match != std::sregex_iterator();
         ++match)
      values.push_back((*match)[1]);
    return values;
  }
} // namespace

TEST(MPI, OutputHasOnePiecePerProcess)
{
  const Parameters::AllParameters parameters =
    scene_writing_to("test_output/mpi_output");
  const std::filesystem::path directory = parameters.output_directory;
  const unsigned int          n_processes =
    Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD);
  MPI_Barrier(MPI_COMM_WORLD);
  {
    Simulation<2> run(parameters, MPI_COMM_WORLD);
    run.run();
  }
  MPI_Barrier(MPI_COMM_WORLD);
  if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) != 0)
    return;

  const std::vector<std::string> records =
    attribute_values(file_contents(directory / "solution.pvd"), "file");
  ASSERT_EQ(records.size(), 3u); // t = 0, 0.05 and 0.1 s
  for (unsigned int k = 0; k < records.size(); ++k)
    {
      const std::string stem = "solution_0000" + std::to_string(k);
      EXPECT_EQ(records[k], stem + ".pvtu");
      const std::vector<std::string> pieces =
        attribute_values(file_contents(directory / records[k]), "Source");
      ASSERT_EQ(pieces.size(), n_processes);
      unsigned int cells = 0;
      for (unsigned int rank = 0; rank < n_processes; ++rank)
        {
          EXPECT_EQ(pieces[rank], stem + "." + std::to_string(rank) + ".vtu");
          const std::vector<std::string> counts =
            attribute_values(file_contents(directory / pieces[rank]),
                             "NumberOfCells");
          ASSERT_EQ(counts.size(), 1u) << pieces[rank];
          cells += std::stoul(counts[0]);
        }
      EXPECT_EQ(cells, 12u * 3u * 4u) << records[k];
    }
}



// @sect3{A failed write stops every process}
//
// The same run, but the last process cannot write its piece of the second
// output (a directory stands where the file should go). Its writing thread
// records the failure; at the next output every process must stop with an
// exception -- the failing one with the reason, the others saying that
// another process failed -- instead of going on or waiting for the failed
// process in a collective operation.
TEST(MPI, OutputFailureStopsEveryProcess)
{
  const Parameters::AllParameters parameters =
    scene_writing_to("test_output/mpi_failed_output");
  const std::filesystem::path directory = parameters.output_directory;
  const unsigned int          n_processes =
    Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD);
  const unsigned int rank = Utilities::MPI::this_mpi_process(MPI_COMM_WORLD);
  const std::string  blocked =
    "solution_00001." + std::to_string(n_processes - 1) + ".vtu";
  if (rank == 0)
    std::filesystem::create_directories(directory / blocked);
  MPI_Barrier(MPI_COMM_WORLD);

  std::string message;
  try
    {
      Simulation<2> run(parameters, MPI_COMM_WORLD);
      run.run();
    }
  catch (const std::exception &error)
    {
      message = error.what();
    }
  // Every process reports the failing one's reason (a WriteFailure, see
  // output/safe_file.h), the others with its number.
  EXPECT_NE(message.find("Cannot write '"), std::string::npos)
    << "process " << rank << ": '" << message << "'";
  EXPECT_NE(message.find(blocked + "'"), std::string::npos)
    << "process " << rank << ": '" << message << "'";
  EXPECT_NE(message.find("the field output at t = 0.05"), std::string::npos)
    << "process " << rank << ": '" << message << "'";
  if (n_processes > 1)
    EXPECT_NE(message.find("(on MPI process " +
                           std::to_string(n_processes - 1) + ")"),
              std::string::npos)
      << "process " << rank << ": '" << message << "'";
}
