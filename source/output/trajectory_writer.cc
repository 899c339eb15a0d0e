// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{The tip trajectory file}
//
// See include/output/trajectory_writer.h.

#include <cerrno>
#include <cmath>
#include <core/exceptions.h>
#include <deal.II/base/exceptions.h>
#include <deal.II/base/utilities.h>
#include <filesystem>
#include <iomanip>
#include <output/safe_file.h>
#include <output/trajectory_writer.h>

namespace SoftRobot
{
  using namespace dealii;

  TrajectoryWriter::TrajectoryWriter(const MPI_Comm mpi_communicator)
    : mpi_communicator(mpi_communicator)
    , root(Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
  {
  }



  // @sect4{TrajectoryWriter::on_root}
  //
  // Process 0 writes; a failure there is made known to every process.
  void
  TrajectoryWriter::on_root(const std::function<void()> &write)
  {
    std::string error;
    if (root)
      try
        {
          errno = 0;
          write();
          file.flush();
          check_written(file, name);
          bytes = static_cast<std::uint64_t>(file.tellp());
        }
      catch (WriteFailure &failure)
        {
          error = failure.what();
        }
    fail_everywhere(error, mpi_communicator);
  }



  void
  TrajectoryWriter::open(const std::string              &file_name,
                         const std::vector<std::string> &comments,
                         const std::vector<std::string> &columns)
  {
    name = file_name;
    on_root([&]() {
      file.open(name);
      check_written(file, name);
      for (const std::string &comment : comments)
        file << "# " << comment << '\n';
      for (unsigned int c = 0; c < columns.size(); ++c)
        file << (c == 0 ? "" : ",") << columns[c];
      file << '\n';
    });
  }



  // @sect4{TrajectoryWriter::reopen}
  //
  // The rows after the checkpoint, written before the run was interrupted,
  // are cut off, so that the continued run writes them again, and the
  // file ends up as the uninterrupted run's.
  void
  TrajectoryWriter::reopen(const std::string  &file_name,
                           const std::uint64_t length)
  {
    name = file_name;
    std::string problem;
    if (root)
      {
        std::error_code      error;
        const std::uintmax_t size = std::filesystem::file_size(name, error);
        if (error)
          problem = "cannot open the trajectory '" + name +
                    "' of the run to be continued: " + error.message() + ".";
        else if (size < length)
          problem = "the trajectory '" + name + "' has " +
                    std::to_string(size) + " bytes, fewer than the " +
                    std::to_string(length) +
                    " it had at the checkpoint; it is not the file of the "
                    "run to be continued.";
      }
    problem = Utilities::MPI::broadcast(mpi_communicator, problem, 0);
    AssertThrow(problem.empty(), ExcMessage("Cannot restart: " + problem));
    on_root([&]() {
      std::error_code error;
      std::filesystem::resize_file(name, length, error);
      if (error)
        throw WriteFailure("Cannot cut '" + name +
                           "' back to the checkpoint: " + error.message());
      file.open(name, std::ios::app | std::ios::ate);
      check_written(file, name);
    });
    bytes = root ? length : 0;
  }



  std::uint64_t
  TrajectoryWriter::length() const
  {
    return bytes;
  }



  void
  TrajectoryWriter::write_row(const std::vector<double> &values)
  {
    for (const double value : values)
      {
        (void)value;
        Assert(std::isfinite(value),
               ExcMessage("A trajectory row must be finite; the "
                          "simulator's guards check the state first."));
      }
    on_root([&]() {
      file << std::setprecision(10);
      for (unsigned int c = 0; c < values.size(); ++c)
        file << (c == 0 ? "" : ",") << values[c];
      file << '\n';
    });
  }



  void
  TrajectoryWriter::close()
  {
    std::string error;
    if (root && file.is_open())
      try
        {
          errno = 0;
          file.close();
          check_written(file, name);
        }
      catch (WriteFailure &failure)
        {
          error = failure.what();
        }
    fail_everywhere(error, mpi_communicator);
  }
} // namespace SoftRobot
