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

#include <core/soft_robot_dynamics.h>
#include <cstdlib>
#include <deal.II/base/mpi.h>
#include <gtest/gtest.h>
#include <string>

using namespace dealii;
using namespace SoftRobot;

TEST(MPI, PartitionedRunMatchesSerialRun)
{
  const char *root = std::getenv("SOFT_ROBOT_SOURCE_DIR");
  ASSERT_NE(root, nullptr);
  Parameters::AllParameters parameters;
  parameters.read_file(std::string(root) + "/tests/cli/two_processes.prm");

  SoftRobotDynamics<2> parallel(parameters, MPI_COMM_WORLD);
  SoftRobotDynamics<2> serial(parameters, MPI_COMM_SELF);
  for (SoftRobotDynamics<2> *run : {&parallel, &serial})
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
