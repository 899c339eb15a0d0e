// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Writing files so that nothing is lost or half written}
//
// See include/output/safe_file.h.

#include <cerrno>
#include <core/exceptions.h>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <deal.II/base/utilities.h>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <output/safe_file.h>
#include <sstream>
#include <system_error>

namespace SoftRobot
{
  using namespace dealii;

  namespace
  {
    std::string
    reason_of_last_failure()
    {
      return errno != 0 ? std::generic_category().message(errno)
                        : std::string("the stream reports a failure");
    }
  } // namespace



  void
  check_written(const std::ostream &stream, const std::string &file_name)
  {
    if (!stream)
      throw WriteFailure("Cannot write '" + file_name +
                         "': " + reason_of_last_failure() + ".");
  }



  // @sect4{write_file_atomically}
  //
  // The file is flushed and closed before the rename, and the state of the
  // stream checked after both: a full disk is reported by the write that
  // empties the buffer, which may be the close.
  void
  write_file_atomically(const std::string                         &file_name,
                        const std::function<void(std::ostream &)> &write)
  {
    const std::string temporary = file_name + ".tmp";
    {
      errno = 0;
      std::ofstream file(temporary, std::ios::binary | std::ios::trunc);
      check_written(file, temporary);
      std::ostringstream text;
      write(text);
      const std::string content = text.str();
      file.write(content.data(), content.size() / 2);
      file.flush();
      check_written(file, temporary);
      test_hook_kill_during_write(file_name, file);
      file.write(content.data() + content.size() / 2,
                 content.size() - content.size() / 2);
      file.close();
      check_written(file, temporary);
    }
    std::error_code error;
    std::filesystem::rename(temporary, file_name, error);
    if (error)
      throw WriteFailure("Cannot rename '" + temporary + "' to '" + file_name +
                         "': " + error.message() + ".");
  }



  // @sect4{fail_everywhere}
  void
  fail_everywhere(const std::string &local_error,
                  const MPI_Comm     mpi_communicator)
  {
    const unsigned int n_processes =
      Utilities::MPI::n_mpi_processes(mpi_communicator);
    const unsigned int rank =
      Utilities::MPI::this_mpi_process(mpi_communicator);
    const unsigned int first_failed =
      Utilities::MPI::min(local_error.empty() ? n_processes : rank,
                          mpi_communicator);
    if (first_failed == n_processes)
      return;
    if (n_processes == 1)
      throw WriteFailure(local_error);
    const std::string message =
      Utilities::MPI::broadcast(mpi_communicator, local_error, first_failed);
    throw WriteFailure(
      message + (first_failed == 0
                   ? std::string()
                   : " (on MPI process " + std::to_string(first_failed) + ")"));
  }



  // @sect4{test_hook_kill_during_write}
  void
  test_hook_kill_during_write(const std::string &file_name,
                              std::ostream      &half_written)
  {
    const char *request = std::getenv("SOFT_ROBOT_TEST_KILL_DURING_WRITE");
    if (request == nullptr)
      return;
    const std::string text(request);
    const auto        colon = text.rfind(':');
    const std::string name  = text.substr(0, colon);
    if (name != std::filesystem::path(file_name).filename().string())
      return;
    static std::mutex                          mutex;
    static std::map<std::string, unsigned int> writings;
    std::lock_guard<std::mutex>                lock(mutex);
    const unsigned int                         count = ++writings[name];
    const unsigned int                         target =
      (colon == std::string::npos) ? 1 : std::stoul(text.substr(colon + 1));
    if (count == target)
      {
        half_written.flush();
        std::raise(SIGKILL);
      }
  }
} // namespace SoftRobot
