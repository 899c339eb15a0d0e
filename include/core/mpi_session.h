// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Open MPI's settings for a run on one process}
//
// A program started without `mpirun` is an MPI singleton. Three of Open
// MPI's defaults do not suit it:
// - it starts a helper daemon (orted) that probes the machine, a quarter of
//   a second at every start, of no use to a program that never spawns
//   processes (`OMPI_MCA_ess_singleton_isolated` turns it off);
// - its default message layer (UCX) probes the machine's network devices,
//   another fifth of a second, where the basic layer (`ob1`, with its
//   process-to-itself transport) serves a single process just as well;
// - every isolated singleton of a user puts its session directory at the
//   same path, `<tmpdir>/ompi.<host>.<uid>/jf.0/...`, and removes it when
//   it ends. Two runs at once (the validation script runs two scenes at a
//   time, ctest two tests) then share it, and one run's
//   clean-up can remove the directory while the other creates its own
//   files in it: that run fails at its start ("mkdir ... No such file or
//   directory" from `orte_session_dir`). Each singleton therefore gets a
//   private directory for Open MPI's session files
//   (`OMPI_MCA_orte_tmpdir_base`), made under `TMPDIR` (or /tmp) and
//   removed when the object is destroyed, after MPI_Finalize.
//
// The object must be created before MPI_Init and destroyed after
// MPI_Finalize: declare it before deal.II's MPI_InitFinalize in main().
// None of the variables replaces a value the user set, and nothing is
// changed under mpirun (which sets OMPI_COMM_WORLD_SIZE); other MPI
// implementations ignore them. If the private directory cannot be made,
// Open MPI's default applies. A process killed by a signal (SIGKILL, or an
// abort that skips the destructors) leaves its directory behind, with the
// few empty directories Open MPI made in it, as Open MPI's own session
// directory would be left without this object.
//
// Implemented in source/core/mpi_session.cc.

#ifndef soft_robot_core_mpi_session_h
#define soft_robot_core_mpi_session_h

#include <string>

namespace SoftRobot
{
  class SerialMpiSession
  {
  public:
    SerialMpiSession();
    ~SerialMpiSession();

    SerialMpiSession(const SerialMpiSession &) = delete;
    SerialMpiSession &
    operator=(const SerialMpiSession &) = delete;

    // The private directory for Open MPI's session files, empty if none
    // was made (under mpirun, a directory set by the user, or a failure).
    const std::string &
    session_directory() const
    {
      return directory;
    }

  private:
    std::string directory;
  };
} // namespace SoftRobot

#endif
