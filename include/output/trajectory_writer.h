// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{The tip trajectory file}
//
// One row per time step in a CSV file: the time series that the spectral
// analysis reads (tip-spectrum, or Output/Spectral analysis at the end of a
// run) and that doc/plot_tip_trajectory.py plots. Lines starting with '#'
// are comments; the first other line names the columns. Only MPI process 0
// writes; every row is flushed at once, so that a run that is interrupted
// leaves whole rows, and the stream is checked after every flush: a full
// disk stops the run with a WriteFailure on every process (exit code 3)
// at the row that could not be written. A restart opens the file of the
// earlier part of the run (reopen()), cuts it back to the length it had at
// the checkpoint, and appends to it.
//
// Implemented in source/output/trajectory_writer.cc.

#ifndef soft_robot_output_trajectory_writer_h
#define soft_robot_output_trajectory_writer_h

#include <cstdint>
#include <deal.II/base/mpi.h>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

namespace SoftRobot
{
  class TrajectoryWriter
  {
  public:
    explicit TrajectoryWriter(const MPI_Comm mpi_communicator);

    // Creates `file_name` with the comment lines (each without its '#')
    // and the header of the columns.
    void
    open(const std::string              &file_name,
         const std::vector<std::string> &comments,
         const std::vector<std::string> &columns);

    // Opens `file_name`, written by an earlier part of the run, cuts it to
    // its first `length` bytes (the rows up to the checkpoint the run
    // continues from) and appends to it. Throws an input error if the file
    // is missing or shorter than that.
    void
    reopen(const std::string &file_name, const std::uint64_t length);

    // The length of the file so far, in bytes, on process 0 (zero on the
    // others): where a restart from this point cuts the file.
    std::uint64_t
    length() const;

    // One row, in the order of the columns, with ten significant digits;
    // every value must be finite. Collective, as are open() and close().
    void
    write_row(const std::vector<double> &values);

    void
    close();

  private:
    void
    on_root(const std::function<void()> &write);

    const MPI_Comm mpi_communicator;
    const bool     root;
    std::string    name;
    std::ofstream  file;
    std::uint64_t  bytes = 0;
  };
} // namespace SoftRobot

#endif
