// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Field output for ParaView}
//
// See include/output/field_output.h.

#include <cerrno>
#include <core/config.h>
#include <core/exceptions.h>
#include <core/parameter_file.h>
#include <cstdio>
#include <deal.II/base/timer.h>
#include <deal.II/base/utilities.h>
#include <fstream>
#include <output/field_output.h>
#include <output/safe_file.h>
#include <sstream>

namespace SoftRobot
{
  template <int dim>
  FieldOutput<dim>::FieldOutput(
    const std::string                                 &directory,
    const Triangulation<dim>                          &triangulation,
    const Mapping<dim>                                &mapping,
    const unsigned int                                 subdivisions,
    const MPI_Comm                                     mpi_communicator,
    const std::vector<std::pair<double, std::string>> &records)
    : directory(directory + "/")
    , triangulation(triangulation)
    , mapping(mapping)
    , subdivisions(subdivisions)
    , n_processes(Utilities::MPI::n_mpi_processes(mpi_communicator))
    , rank(Utilities::MPI::this_mpi_process(mpi_communicator))
    , mpi_communicator(mpi_communicator)
    , pvd_records(records)
  {
  }



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
                          CellData                      cell_data,
                          const double                  time)
  {
    finish();
    const unsigned int index = pvd_records.size();
    pvd_records.emplace_back(time,
                             "solution_" + Utilities::int_to_string(index, 5) +
                               ".pvtu");
    job           = std::move(data_out);
    job_cell_data = std::move(cell_data);
    writer        = std::thread([this, index, records = pvd_records, time]() {
      Timer timer;
      try
        {
          write_files(*job, job_cell_data, index, records);
        }
      catch (ExceptionBase &failure)
        {
          std::ostringstream reason;
          failure.print_info(reason);
          std::ostringstream text;
          text << "Cannot write the field output at t = " << time
               << " s: " << Parameters::one_line(reason.str());
          error = text.str();
        }
      catch (std::exception &failure)
        {
          std::ostringstream text;
          text << failure.what() << " (the field output at t = " << time
               << " s)";
          error = text.str();
        }
      writing_seconds += timer.wall_time();
    });
  }



  // @sect4{FieldOutput::write_files}
  //
  // The files deal.II's write_vtu_with_pvtu_record() writes, one piece per
  // process, without its MPI calls, with the cell data added to the texts
  // deal.II writes. Each patch is written as the same number of cells
  // (the subdivisions), which the piece's cell count divided by the
  // number of patches gives.
  template <int dim>
  void
  FieldOutput<dim>::write_files(
    DataOut<dim>                                      &data_out,
    const CellData                                    &cell_data,
    const unsigned int                                 index,
    const std::vector<std::pair<double, std::string>> &records) const
  {
    // Every cell through the mapping, not only those at the boundary
    // (deal.II's default): on a curved mesh an interior cell's points
    // would otherwise lie on straight lines, away from the points its
    // curved neighbours give the same edges.
    data_out.build_patches(mapping,
                           subdivisions,
                           DataOut<dim>::CurvedCellRegion::curved_inner_cells);

    const std::string  stem = "solution_" + Utilities::int_to_string(index, 5);
    const unsigned int rank_digits = Utilities::needed_digits(n_processes - 1);
    const auto         piece       = [&](const unsigned int r) {
      return stem + "." + Utilities::int_to_string(r, rank_digits) + ".vtu";
    };
    std::ostringstream vtu_text;
    data_out.write_vtu(vtu_text);
    std::string  vtu       = vtu_text.str();
    unsigned int n_patches = 0;
    for (const auto &cell : triangulation.active_cell_iterators())
      if (cell->is_locally_owned())
        ++n_patches;
    if (n_patches > 0)
      add_vtu_cell_data(vtu,
                        cell_data,
                        triangulation,
                        vtu_cell_count(vtu) / n_patches);
    {
      const std::string name = directory + piece(rank);
      errno                  = 0;
      std::ofstream file(name, std::ios::binary);
      file << vtu;
      file.close();
      check_written(file, name);
    }
    if (rank != 0)
      return;
    std::vector<std::string> pieces;
    for (unsigned int r = 0; r < n_processes; ++r)
      pieces.push_back(piece(r));
    std::ostringstream pvtu_text;
    data_out.write_pvtu_record(pvtu_text, pieces);
    std::string pvtu = pvtu_text.str();
    add_pvtu_cell_data(pvtu, cell_data);
    {
      const std::string name = directory + stem + ".pvtu";
      errno                  = 0;
      std::ofstream file(name, std::ios::binary);
      file << pvtu;
      file.close();
      check_written(file, name);
    }
    write_file_atomically(directory + "solution.pvd", [&](std::ostream &out) {
      DataOutBase::write_pvd_record(out, records);
    });
  }



  // @sect4{FieldOutput::finish}
  template <int dim>
  void
  FieldOutput<dim>::finish()
  {
    if (writer.joinable())
      writer.join();
    job.reset();
    const std::string message = error;
    error.clear();
    fail_everywhere(message, mpi_communicator);
  }



#define SOFT_ROBOT_INSTANTIATE(dim) template class FieldOutput<dim>;
  SOFT_ROBOT_FOR_EACH_DIMENSION(SOFT_ROBOT_INSTANTIATE)
#undef SOFT_ROBOT_INSTANTIATE
} // namespace SoftRobot
