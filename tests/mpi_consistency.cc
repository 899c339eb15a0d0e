// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{The same motion on one and on several MPI processes}
//
// Run under `mpiexec -n 2` and `-n 3` (see tests/CMakeLists.txt): the
// short 2D scene tests/cli/two_processes.prm is simulated once on all
// processes together and once on each process alone (MPI_COMM_SELF), and
// the tip motions are compared step by step. Partitioning changes only the
// order of the floating-point sums and the AMG hierarchy, so the two must
// agree to the tolerances of the solvers: Newton's relative tolerance 1e-11
// and CG's 1e-12 leave differences far below the 1e-7 relative allowed
// here. On one process there is nothing to compare, and the test is
// skipped (ctest also registers it serially). The AMG-solved scene is 2D;
// the comparisons below cover 1D, 2D and 3D with the direct solver.

#include "solver_test_tools.h"

#include <array>
#include <cmath>
#include <core/soft_robot_dynamics.h>
#include <cstdlib>
#include <deal.II/base/mpi.h>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <map>
#include <regex>
#include <sstream>
#include <string>

using namespace dealii;
using namespace SoftRobot;
using namespace SoftRobot::Testing;

TEST(MPI, PartitionedRunMatchesSerialRun)
{
  if (Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) == 1)
    GTEST_SKIP() << "nothing to compare on one MPI process; ctest runs this "
                    "file under mpiexec -n 2 and -n 3 (mpi.two_processes, "
                    "mpi.three_processes)";
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
  // Both runs end together: the scene's 10 steps, and as many more as
  // their (equal) cut-backs add (one at t = 0.08 s).
  EXPECT_FALSE(serial.advance_one_step());
  EXPECT_GE(steps, 10u);
  EXPECT_LE(worst, 1e-7 * amplitude);
}



// @sect3{Partitioned runs in every dimension and formulation}
//
// A bar of 6 x 2 (in 3D 6 x 1 x 1) cells clamped at x = 0, with damping, set in motion by an initial
// velocity that bends it (in 1D, stretches it) with strains of about 10 %,
// and loaded by gravity across its axis and a traction on its end that
// grows in time: four HHT steps with the direct solver, in 1D, 2D and 3D,
// with linear and quadratic elements, with the displacement and (in 3D)
// the mean-dilatation formulation. The run on all processes is compared
// with the run on each process alone (MPI_COMM_SELF) at every dof, after
// every step: the displacement and the velocity.
//
// The two runs solve the same equations, with different numberings and
// partitions of the dofs, so that only the order of the sums in the
// assembly and in the direct solver's elimination differ; those are
// round-off, $10^{-16}$ times the condition number. What differs more is
// where Newton's method stops: each run stops somewhere within its
// relative tolerance $\eta = 10^{-12}$ of the residual, and two such
// states differ by up to $2\eta\,\kappa(\mathbf K_\text{eff})$ relative,
// with $\kappa(\mathbf K_\text{eff}) \approx (1 + \beta\Omega_\text{max}^2)
// \kappa(\mathbf M) \lesssim 10^3$ for the step matrix of these meshes
// (highest $\Omega = \omega\Delta t \approx 10$, $\beta \approx 0.3$). The
// stepping does not amplify errors, so over four steps the runs must agree
// to $4\cdot 2\eta\cdot 10^3 \approx 10^{-8}$ of the largest displacement
// and velocity.
//
// On one process (ctest also registers every case of this file serially)
// there is nothing to compare, and the cases are skipped.
namespace
{
  Parameters::AllParameters
  swinging_bar(const unsigned int dim,
               const unsigned int degree,
               const std::string &formulation)
  {
    const double mu = 10., rho = 1e-6, L = 6., c = std::sqrt(3. * mu / rho);
    const double T                = L / c; // time for a wave to cross the bar
    const std::string velocity[3] = {dim == 1 ? "0.15*c*x/L" : "0.05*c*x/L",
                                     "0.1*c*(x/L)^2",
                                     "-0.05*c*(x/L)^2"};
    const std::string  traction[3] = {"2*t/T", "t/T", "-0.5*t/T"};
    std::ostringstream sections;
    sections
      << "subsection Geometry\n  set Generator = subdivided_hyper_rectangle\n"
      << "  set Generator arguments = "
      << box_arguments(dim, 6, dim == 3 ? 1 : 2, L, 1.)
      << "\n  set Random distortion = 0.1\nend\n"
      << "subsection Finite element\n  set Polynomial degree = " << degree
      << "\n  set Volumetric formulation = " << formulation << "\nend\n"
      << "subsection Material 1\n  set Name = silicone\n  set Shear modulus = "
      << mu << "\n  set Bulk modulus = " << 10. * mu
      << "\n  set Density = " << rho
      << "\n  set Damping coefficient = " << 0.02 * T << "\nend\n"
      << "subsection Loads and constraints\n  set Gravity = "
      << (dim == 1 ? "9810, 0, 0" : "0, -9810, 0")
      << "\n  set Fixed components = 0: " << std::string("xyz").substr(0, dim)
      << "\n  set Traction boundary ids = 1\n  set Traction = ";
    for (unsigned int d = 0; d < dim; ++d)
      sections << (d > 0 ? "; " : "") << traction[d];
    sections << "\n  set Function constants = c=" << c << ", L=" << L
             << ", T=" << T << "\nend\n"
             << "subsection Initial conditions\n  set Velocity = ";
    for (unsigned int d = 0; d < dim; ++d)
      sections << (d > 0 ? "; " : "") << velocity[d];
    sections << "\nend\n"
             << "subsection Time integration\n  set Alpha = -0.1\n"
             << "  set Time step = " << 0.2 * T
             << "\n  set End time = " << 0.8 * T << "\nend\n"
             << "subsection Nonlinear solver\n  set Absolute tolerance = 0\n"
                "  set Relative tolerance = 1e-12\nend\n"
             << "subsection Linear solver\n  set Solver = Direct\nend\n";
    Parameters::AllParameters parameters;
    parameters.read_string(parameter_text(dim, sections.str()));
    return parameters;
  }

  // The dofs this process owns in the partitioned run, each with the
  // number of the same dof in the serial run. Both triangulations are
  // copies of one mesh, with the cells in the same order.
  template <int dim>
  std::vector<std::pair<types::global_dof_index, types::global_dof_index>>
  matching_dofs(const DoFHandler<dim> &partitioned,
                const DoFHandler<dim> &serial)
  {
    std::map<types::global_dof_index, types::global_dof_index> pairs;
    const IndexSet &owned = partitioned.locally_owned_dofs();
    std::vector<types::global_dof_index> partitioned_dofs(
      partitioned.get_fe().n_dofs_per_cell()),
      serial_dofs(partitioned_dofs.size());
    auto serial_cell = serial.begin_active();
    for (const auto &cell : partitioned.active_cell_iterators())
      {
        AssertThrow(serial_cell != serial.end() &&
                      cell->center().distance(serial_cell->center()) == 0.,
                    ExcMessage("The two meshes differ."));
        if (cell->is_locally_owned())
          {
            cell->get_dof_indices(partitioned_dofs);
            serial_cell->get_dof_indices(serial_dofs);
            for (unsigned int i = 0; i < partitioned_dofs.size(); ++i)
              if (owned.is_element(partitioned_dofs[i]))
                pairs[partitioned_dofs[i]] = serial_dofs[i];
          }
        ++serial_cell;
      }
    AssertThrow(pairs.size() == owned.n_elements(),
                ExcMessage("A dof of this process is on no cell of it."));
    return {pairs.begin(), pairs.end()};
  }

  template <int dim>
  void
  compare_partitioned_run(const unsigned int degree,
                          const std::string &formulation)
  {
    const Parameters::AllParameters parameters =
      swinging_bar(dim, degree, formulation);
    Simulation<dim> partitioned(parameters, MPI_COMM_WORLD);
    Simulation<dim> serial(parameters, MPI_COMM_SELF);
    for (Simulation<dim> *run : {&partitioned, &serial})
      {
        run->make_grid();
        run->setup_system();
        run->initialize_state();
      }
    const auto pairs =
      matching_dofs(partitioned.get_dof_handler(), serial.get_dof_handler());
    EXPECT_GT(pairs.size(), 0u) << "a process without dofs";

    // The largest differences and values of the displacement and the
    // velocity, over the steps and the dofs.
    std::array<double, 4> largest = {{0., 0., 0., 0.}};
    unsigned int          steps   = 0;
    while (partitioned.advance_one_step())
      {
        ASSERT_TRUE(serial.advance_one_step());
        EXPECT_EQ(partitioned.time(), serial.time());
        for (const auto &[p, s] : pairs)
          {
            const double u = serial.displacement()(s), v = serial.velocity()(s);
            largest[0] =
              std::max(largest[0], std::abs(partitioned.displacement()(p) - u));
            largest[1] = std::max(largest[1], std::abs(u));
            largest[2] =
              std::max(largest[2], std::abs(partitioned.velocity()(p) - v));
            largest[3] = std::max(largest[3], std::abs(v));
          }
        ++steps;
      }
    for (double &value : largest)
      value = Utilities::MPI::max(value, MPI_COMM_WORLD);
    if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
      std::cout << dim << "D, p = " << degree << ", " << formulation << ", "
                << Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD)
                << " processes, " << steps
                << " steps: largest difference of the displacement "
                << largest[0] / largest[1] << " of the largest (" << largest[1]
                << " mm), of the velocity " << largest[2] / largest[3]
                << " of the largest (" << largest[3] << " mm/s)" << std::endl;
    EXPECT_EQ(steps, 4u);
    EXPECT_GT(largest[1], 0.);
    EXPECT_LE(largest[0], 1e-8 * largest[1]);
    EXPECT_LE(largest[2], 1e-8 * largest[3]);
  }
} // namespace

template <typename T>
class PartitionedRun : public ::testing::Test
{
};
TYPED_TEST_SUITE(PartitionedRun, Dimensions);

TYPED_TEST(PartitionedRun, MatchesSerialRunAtEveryDof)
{
  constexpr int dim = TypeParam::value;
  if (Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) == 1)
    GTEST_SKIP() << "nothing to compare on one MPI process; ctest runs this "
                    "file under mpiexec -n 2 and -n 3 (mpi.two_processes, "
                    "mpi.three_processes)";
  for (const unsigned int degree : {1u, 2u})
    {
      compare_partitioned_run<dim>(degree, "displacement");
      // The mean-dilatation formulation exists in 3D only.
      if constexpr (dim == 3)
        compare_partitioned_run<dim>(degree, "mean dilatation");
    }
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

// 2D only: the files and their exchange do not depend on the dimension.
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
// 2D only: the files and their exchange do not depend on the dimension.
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
    {
      EXPECT_NE(message.find("(on MPI process " +
                             std::to_string(n_processes - 1) + ")"),
                std::string::npos)
        << "process " << rank << ": '" << message << "'";
    }
}
