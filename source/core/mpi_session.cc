// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Open MPI's settings for a run on one process}
//
// See include/core/mpi_session.h.

#include <core/mpi_session.h>
#include <cstdlib>
#include <filesystem>
#include <system_error>
#include <vector>

namespace SoftRobot
{
  SerialMpiSession::SerialMpiSession()
  {
    if (std::getenv("OMPI_COMM_WORLD_SIZE") != nullptr)
      return;
    setenv("OMPI_MCA_ess_singleton_isolated", "1", /*overwrite=*/0);
    setenv("OMPI_MCA_pml", "ob1", /*overwrite=*/0);
    if (std::getenv("OMPI_MCA_orte_tmpdir_base") != nullptr)
      return;

    const char       *tmpdir = std::getenv("TMPDIR");
    const std::string base =
      (tmpdir != nullptr && *tmpdir != '\0') ? tmpdir : "/tmp";
    std::string       pattern = base + "/soft-robot-mpi-XXXXXX";
    std::vector<char> name(pattern.begin(), pattern.end());
    name.push_back('\0');
    if (mkdtemp(name.data()) == nullptr)
      return;
    directory = name.data();
    setenv("OMPI_MCA_orte_tmpdir_base", directory.c_str(), /*overwrite=*/1);
  }



  // Open MPI removes its own session files at MPI_Finalize; what is left
  // (after an abort, its files too) goes with the directory. Errors are
  // ignored: a destructor has no one to report them to, and a left-over
  // directory in the temporary directory harms no later run.
  SerialMpiSession::~SerialMpiSession()
  {
    if (directory.empty())
      return;
    std::error_code error;
    std::filesystem::remove_all(directory, error);
  }
} // namespace SoftRobot
