// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Writing files so that nothing is lost or half written}
//
// A run of an hour must not end with a result that looks complete and is
// not. Three rules follow, and every writer of the program keeps them:
// - Every stream is checked after it is written and closed: a full disk
//   (ENOSPC), a quota or a lost network file system shows up as a failed
//   write, often only when the buffer is flushed. A failure is a
//   WriteFailure that names the file and the operating system's reason, and
//   the program ends with exit code 3.
// - A file that is rewritten as a whole (the PVD and XDMF records, the run
//   statistics, the spectra) is written to `<name>.tmp` and renamed to its
//   name when it is complete: rename() replaces the old file atomically, so
//   that a reader, or a run killed at any moment, finds the old version or
//   the new one, never a part of either.
// - A write failure on one MPI process is made known to all of them at the
//   same point of the run (fail_everywhere()), so that all of them stop and
//   none waits for the others in a collective operation.
//
// Implemented in source/output/safe_file.cc.

#ifndef soft_robot_output_safe_file_h
#define soft_robot_output_safe_file_h

#include <deal.II/base/mpi.h>
#include <functional>
#include <ostream>
#include <string>

namespace SoftRobot
{
  // Throws WriteFailure("Cannot write '<file_name>': <reason>") if `stream`
  // has failed; the reason is the operating system's for the last failed
  // call.
  void
  check_written(const std::ostream &stream, const std::string &file_name);

  // Writes `file_name` through `<file_name>.tmp`: calls `write` on the
  // temporary file, checks and closes it, and renames it. Throws
  // WriteFailure, leaving the old file as it was.
  void
  write_file_atomically(const std::string                         &file_name,
                        const std::function<void(std::ostream &)> &write);

  // Collective: if `local_error` is not empty on some process, every
  // process throws WriteFailure with the message of the lowest such
  // process.
  void
  fail_everywhere(const std::string &local_error,
                  const MPI_Comm     mpi_communicator);

  // The test hook of the interrupted PVD write: if the environment variable
  // SOFT_ROBOT_TEST_KILL_DURING_WRITE names `file_name`'s last component
  // (e.g. "solution.pvd") and the count after the colon (e.g.
  // "solution.pvd:3" for its third writing), the process kills itself
  // (SIGKILL) in the middle of that writing, after half of the temporary
  // file is on disk. Called by write_file_atomically().
  void
  test_hook_kill_during_write(const std::string &file_name,
                              std::ostream      &half_written);
} // namespace SoftRobot

#endif
