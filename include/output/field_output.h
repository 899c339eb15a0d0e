// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Field output for ParaView}
//
// VTU files of the whole body at the output interval, listed in a PVD
// record that carries the physical times, so that ParaView plays them as a
// time series. Each output time has one `.vtu` piece per MPI process
// (`solution_<n>.<rank>.vtu`) and a `.pvtu` record that lists them.
//
// The work is split in two. The time loop's thread fills a DataOut object
// with all fields: deal.II copies the nodal values into vectors of its own
// there, with the ghost values of the cells at the processes' interfaces,
// and that copy is a collective MPI operation (even on one process), which
// only the main thread may do. The rest -- building the patches,
// compressing and writing the files, most of the work -- is done by a
// thread of its own while the time loop goes on: the loop's serial parts
// (factorizations, back substitutions, vector operations, and in parallel
// runs the waits for the other process) leave a core free. That thread
// makes no MPI call and touches no Trilinos object; it only reads the
// DataOut object, the mesh and the finite element, which nothing changes
// during the run. Each process writes its own piece of the mesh, and
// process 0 also the PVTU and PVD records that list the pieces. The next
// output, the end of the run and the destructor wait for the thread
// (finish()), so that no file is left half written. The PVD record is
// written to a temporary file and renamed, so that an interrupted run
// leaves the previous record intact (output/safe_file.h); every file's
// stream is checked, and a failure stops the run with a WriteFailure on
// all processes at the next finish().
//
// The per-cell fields are written as true cell data (output/cell_data.h).
// The record of the outputs so far is kept in memory and rewritten whole
// at every output; a restart that continues a run hands the records of
// the earlier part to the constructor and goes on numbering from there.
//
// Implemented in source/output/field_output.cc.

#ifndef soft_robot_output_field_output_h
#define soft_robot_output_field_output_h

#include <deal.II/fe/mapping.h>
#include <deal.II/numerics/data_out.h>
#include <memory>
#include <output/cell_data.h>
#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace SoftRobot
{
  using namespace dealii;

  template <int dim>
  class FieldOutput
  {
  public:
    // Files go to `directory`; the patches have `subdivisions` per cell.
    // `records` are the outputs of an earlier part of the run (time and
    // PVTU file), which the PVD record goes on from.
    FieldOutput(
      const std::string                                 &directory,
      const Triangulation<dim>                          &triangulation,
      const Mapping<dim>                                &mapping,
      const unsigned int                                 subdivisions,
      const MPI_Comm                                     mpi_communicator,
      const std::vector<std::pair<double, std::string>> &records = {});
    ~FieldOutput();

    // Waits for the previous output, then starts writing `data_out` (with
    // its nodal fields and flags) and `cell_data` as the output at `time`
    // in the writing thread.
    void
    write(std::unique_ptr<DataOut<dim>> data_out,
          CellData                      cell_data,
          const double                  time);

    // Waits for the writing thread and reports its failure. Every process
    // calls it at the same point of the run, and a failure on one of them
    // stops all of them.
    void
    finish();

    // The outputs so far (time and PVTU file), for a checkpoint.
    const std::vector<std::pair<double, std::string>> &
    records() const
    {
      return pvd_records;
    }

    // The wall time the writing thread has spent so far.
    double
    background_seconds() const
    {
      return writing_seconds;
    }

  private:
    // The writing thread's work for output number `index` (building the
    // patches changes the DataOut object, which only this thread touches
    // until finish()).
    void
    write_files(
      DataOut<dim>                                      &data_out,
      const CellData                                    &cell_data,
      const unsigned int                                 index,
      const std::vector<std::pair<double, std::string>> &records) const;

    const std::string         directory;
    const Triangulation<dim> &triangulation;
    const Mapping<dim>       &mapping;
    const unsigned int        subdivisions;
    const unsigned int        n_processes;
    const unsigned int        rank;
    const MPI_Comm            mpi_communicator;

    std::vector<std::pair<double, std::string>> pvd_records;
    std::unique_ptr<DataOut<dim>>               job;
    CellData                                    job_cell_data;
    std::thread                                 writer;
    std::string                                 error;
    double                                      writing_seconds = 0.;
  };
} // namespace SoftRobot

#endif
