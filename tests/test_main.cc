// SPDX-License-Identifier: LGPL-2.1-or-later

// The main() shared by all test executables: deal.II's Trilinos wrappers
// need MPI, so it is initialised here once for every GoogleTest case, with
// the settings of the program's runs on one process (core/mpi_session.h):
// ctest runs two tests at a time.

#include <core/mpi_session.h>
#include <deal.II/base/mpi.h>
#include <gtest/gtest.h>

int
main(int argc, char **argv)
{
  const SoftRobot::SerialMpiSession        mpi_session;
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
