// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Field output in HDF5 with an XDMF record}
//
// The VTU output writes one file per MPI process per output time, and
// rewrites the mesh in every one of them. For large and parallel runs the
// HDF5 output (`Output/Write HDF5`) is the better form: one file per output
// time for all processes together (`solution_<n>.h5`, written collectively
// through MPI-IO by DataOutBase::write_hdf5_parallel()), the mesh in a file
// of its own (`solution_mesh.h5`) written once -- the fields are given on
// the reference configuration, which does not change -- and one XDMF
// record (`solution.xdmf`) that lists the outputs with their times and
// tells ParaView or VisIt where in the HDF5 files the mesh and each field
// are.
//
// The nodal fields go through deal.II's DataOutFilter, which merges the
// vertices the patches share on each process. The per-cell fields are
// written by this class, one value per cell in the filter's order of the
// cells, as datasets of the same file, and the XDMF record lists them with
// `Center="Cell"` (deal.II's XDMFEntry knows node attributes only, so the
// record is written here). Like the PVD record it is kept in memory, written
// to a temporary file and renamed at every output; a restart hands the
// records of the earlier part of the run to the constructor.
//
// The writes are collective MPI operations, which only the main thread may
// make: unlike the VTU output, this output is written while the time loop
// waits.
//
// Implemented in source/output/xdmf_output.cc.

#ifndef soft_robot_output_xdmf_output_h
#define soft_robot_output_xdmf_output_h

#include <cstdint>
#include <deal.II/fe/mapping.h>
#include <deal.II/numerics/data_out.h>
#include <output/cell_data.h>
#include <string>
#include <vector>

namespace SoftRobot
{
  using namespace dealii;

  template <int dim>
  class XdmfOutput
  {
  public:
    // Files go to `directory`; the patches have `subdivisions` per cell.
    // `records` are those of an earlier part of the run (see records()),
    // which a restart goes on from; the mesh file is then not written
    // again.
    XdmfOutput(const std::string        &directory,
               const Triangulation<dim> &triangulation,
               const Mapping<dim>       &mapping,
               const unsigned int        subdivisions,
               const MPI_Comm            mpi_communicator,
               const std::string        &records = "");

    // The outputs so far as text (one line each: time, file, fields), for
    // a checkpoint.
    std::string
    records() const;

    // Collective: writes the nodal fields of `data_out` and `cell_data` as
    // the output at `time`, and the XDMF record of all outputs so far.
    void
    write(DataOut<dim> &data_out, const CellData &cell_data, const double time);

  private:
    // One output: its time, its file, the fields in it, and the sizes of
    // the mesh (the same for all).
    struct Entry
    {
      double                                            time;
      std::string                                       solution_file;
      std::vector<std::pair<std::string, unsigned int>> node_fields;
      std::vector<std::string>                          cell_fields;
    };

    std::string
    xdmf_record() const;

    const std::string         directory;
    const Triangulation<dim> &triangulation;
    const Mapping<dim>       &mapping;
    const unsigned int        subdivisions;
    const MPI_Comm            mpi_communicator;
    const std::string         mesh_file = "solution_mesh.h5";

    std::vector<Entry> entries;
    std::uint64_t      n_nodes           = 0;
    std::uint64_t      n_cells           = 0;
    unsigned int       node_dimension    = 0;
    unsigned int       vertices_per_cell = 0;
  };
} // namespace SoftRobot

#endif
