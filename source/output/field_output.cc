// @sect3{Field output for ParaView}
//
// See include/output/field_output.h.

#include <core/config.h>
#include <deal.II/base/timer.h>
#include <deal.II/base/utilities.h>
#include <output/field_output.h>

#include <cstdio>
#include <fstream>

namespace SoftRobot
{
  template <int dim>
  FieldOutput<dim>::FieldOutput(const std::string  &directory,
                                const Mapping<dim> &mapping,
                                const unsigned int  subdivisions,
                                const MPI_Comm      mpi_communicator)
    : directory(directory + "/")
    , mapping(mapping)
    , subdivisions(subdivisions)
    , n_processes(Utilities::MPI::n_mpi_processes(mpi_communicator))
    , rank(Utilities::MPI::this_mpi_process(mpi_communicator))
    , mpi_communicator(mpi_communicator)
  {}



  template <int dim>
  FieldOutput<dim>::~FieldOutput()
  {
    if (writer.joinable())
      writer.join();
  }



  // @sect4{FieldOutput::write}
  template <int dim>
  void
  FieldOutput<dim>::write(std::unique_ptr<DataOut<dim>> data_out,
                          const double                  time)
  {
    finish();
    const unsigned int index = pvd_records.size();
    pvd_records.emplace_back(time,
                             "solution_" + Utilities::int_to_string(index, 5) +
                               ".pvtu");
    job = std::move(data_out);
    writer = std::thread(
      [this, index, records = pvd_records, time]() {
        Timer timer;
        try
          {
            write_files(*job, index, records);
          }
        catch (std::exception &failure)
          {
            error = "writing the output at t = " + std::to_string(time) +
                    " s failed: " + failure.what();
          }
        writing_seconds += timer.wall_time();
      });
  }



  // @sect4{FieldOutput::write_files}
  //
  // The files deal.II's write_vtu_with_pvtu_record() writes, one piece per
  // process, without its MPI calls.
  template <int dim>
  void
  FieldOutput<dim>::write_files(
    DataOut<dim>                                      &data_out,
    const unsigned int                                 index,
    const std::vector<std::pair<double, std::string>> &records) const
  {
    data_out.build_patches(mapping, subdivisions);

    const std::string stem = "solution_" + Utilities::int_to_string(index, 5);
    const unsigned int rank_digits = Utilities::needed_digits(n_processes - 1);
    const auto piece = [&](const unsigned int r) {
      return stem + "." + Utilities::int_to_string(r, rank_digits) + ".vtu";
    };
    std::ofstream vtu(directory + piece(rank));
    data_out.write_vtu(vtu);
    AssertThrow(vtu, ExcIO());
    if (rank != 0)
      return;
    std::vector<std::string> pieces;
    for (unsigned int r = 0; r < n_processes; ++r)
      pieces.push_back(piece(r));
    std::ofstream pvtu(directory + stem + ".pvtu");
    data_out.write_pvtu_record(pvtu, pieces);
    AssertThrow(pvtu, ExcIO());
    const std::string pvd = directory + "solution.pvd";
    {
      std::ofstream record(pvd + ".tmp");
      DataOutBase::write_pvd_record(record, records);
      record.close();
      AssertThrow(record, ExcIO());
    }
    AssertThrow(std::rename((pvd + ".tmp").c_str(), pvd.c_str()) == 0,
                ExcIO());
  }



  // @sect4{FieldOutput::finish}
  template <int dim>
  void
  FieldOutput<dim>::finish()
  {
    if (writer.joinable())
      writer.join();
    job.reset();
    const int failed_somewhere =
      Utilities::MPI::max(error.empty() ? 0 : 1, mpi_communicator);
    if (failed_somewhere != 0)
      {
        const std::string message =
          error.empty() ? "writing the output failed on another MPI process" :
                          error;
        error.clear();
        AssertThrow(false, ExcMessage(message));
      }
  }



#define SOFT_ROBOT_INSTANTIATE(dim) template class FieldOutput<dim>;
  SOFT_ROBOT_FOR_EACH_DIMENSION(SOFT_ROBOT_INSTANTIATE)
#undef SOFT_ROBOT_INSTANTIATE
} // namespace SoftRobot
