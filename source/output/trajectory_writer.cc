// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{The tip trajectory file}
//
// See include/output/trajectory_writer.h.

#include <cerrno>
#include <cmath>
#include <core/exceptions.h>
#include <deal.II/base/exceptions.h>
#include <deal.II/base/utilities.h>
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
