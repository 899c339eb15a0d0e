// @sect3{The tip trajectory file}
//
// See include/output/trajectory_writer.h.

#include <deal.II/base/exceptions.h>
#include <deal.II/base/utilities.h>
#include <output/trajectory_writer.h>

#include <iomanip>

namespace SoftRobot
{
  using namespace dealii;

  TrajectoryWriter::TrajectoryWriter(const MPI_Comm mpi_communicator)
    : root(Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
  {}



  void
  TrajectoryWriter::open(const std::string              &file_name,
                         const std::vector<std::string> &comments,
                         const std::vector<std::string> &columns)
  {
    if (!root)
      return;
    name = file_name;
    file.open(name);
    AssertThrow(file,
                ExcMessage("Cannot write the trajectory file '" + name + "'."));
    for (const std::string &comment : comments)
      file << "# " << comment << '\n';
    for (unsigned int c = 0; c < columns.size(); ++c)
      file << (c == 0 ? "" : ",") << columns[c];
    file << '\n';
  }



  void
  TrajectoryWriter::write_row(const std::vector<double> &values)
  {
    if (!root)
      return;
    file << std::setprecision(10);
    for (unsigned int c = 0; c < values.size(); ++c)
      file << (c == 0 ? "" : ",") << values[c];
    file << '\n';
    file.flush();
  }



  void
  TrajectoryWriter::close()
  {
    if (root && file.is_open())
      file.close();
  }
} // namespace SoftRobot
