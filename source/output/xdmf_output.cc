// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Field output in HDF5 with an XDMF record}
//
// See include/output/xdmf_output.h.

#include <core/config.h>
#include <core/exceptions.h>
#include <core/parameter_file.h>
#include <deal.II/base/hdf5.h>
#include <deal.II/base/utilities.h>
#include <output/safe_file.h>
#include <output/xdmf_output.h>
#include <sstream>

namespace SoftRobot
{
  template <int dim>
  XdmfOutput<dim>::XdmfOutput(const std::string        &directory,
                              const Triangulation<dim> &triangulation,
                              const Mapping<dim>       &mapping,
                              const unsigned int        subdivisions,
                              const MPI_Comm            mpi_communicator,
                              const std::string        &records)
    : directory(directory + "/")
    , triangulation(triangulation)
    , mapping(mapping)
    , subdivisions(subdivisions)
    , mpi_communicator(mpi_communicator)
  {
    std::istringstream lines(records);
    std::string        line;
    while (std::getline(lines, line))
      {
        std::istringstream words(line);
        Entry              entry;
        std::string        time;
        unsigned int       n_node_fields = 0, n_cell_fields = 0;
        words >> time >> entry.solution_file >> n_node_fields;
        entry.time = std::stod(time);
        for (unsigned int i = 0; i < n_node_fields; ++i)
          {
            std::pair<std::string, unsigned int> field;
            words >> field.first >> field.second;
            entry.node_fields.push_back(field);
          }
        words >> n_cell_fields;
        entry.cell_fields.resize(n_cell_fields);
        for (std::string &name : entry.cell_fields)
          words >> name;
        AssertThrow(!words.fail(),
                    ExcMessage("The checkpoint's XDMF record '" + line +
                               "' is damaged."));
        entries.push_back(entry);
      }
  }



  // @sect4{XdmfOutput::records}
  //
  // The times in hexadecimal floating point, which keeps every bit.
  template <int dim>
  std::string
  XdmfOutput<dim>::records() const
  {
    std::ostringstream out;
    for (const Entry &entry : entries)
      {
        out << std::hexfloat << entry.time << std::defaultfloat << ' '
            << entry.solution_file << ' ' << entry.node_fields.size();
        for (const auto &[name, components] : entry.node_fields)
          out << ' ' << name << ' ' << components;
        out << ' ' << entry.cell_fields.size();
        for (const std::string &name : entry.cell_fields)
          out << ' ' << name;
        out << '\n';
      }
    return out.str();
  }



  // @sect4{XdmfOutput::write}
  //
  // deal.II's writer reports a failed HDF5 call with ExcIO or an internal
  // error; both are write failures of the file it was writing.
  template <int dim>
  void
  XdmfOutput<dim>::write(DataOut<dim>   &data_out,
                         const CellData &cell_data,
                         const double    time)
  {
    Entry entry;
    entry.time = time;
    entry.solution_file =
      "solution_" + Utilities::int_to_string(entries.size(), 5) + ".h5";
    const std::string file = directory + entry.solution_file;

    // Every cell through the mapping, as in FieldOutput::write_files().
    data_out.build_patches(mapping,
                           subdivisions,
                           DataOut<dim>::CurvedCellRegion::curved_inner_cells);
    DataOutBase::DataOutFilter filter(
      DataOutBase::DataOutFilterFlags(/*filter_duplicate_vertices=*/true,
                                      /*xdmf_hdf5_output=*/true));
    data_out.write_filtered_data(filter);
    for (unsigned int i = 0; i < filter.n_data_sets(); ++i)
      entry.node_fields.emplace_back(filter.get_data_set_name(i),
                                     filter.get_data_set_dim(i));
    entry.cell_fields = cell_data.names;

    const std::uint64_t local_cells = filter.n_cells();
    // The cells of the processes before this one, the order in which
    // write_hdf5_parallel() writes them.
    std::uint64_t cell_offset = 0;
    const int     status      = MPI_Exscan(
      &local_cells, &cell_offset, 1, MPI_UINT64_T, MPI_SUM, mpi_communicator);
    AssertThrowMPI(status);
    if (Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
      cell_offset = 0;
    n_nodes =
      Utilities::MPI::sum<std::uint64_t>(filter.n_nodes(), mpi_communicator);
    n_cells = Utilities::MPI::sum(local_cells, mpi_communicator);
    vertices_per_cell =
      triangulation.all_reference_cells_are_simplex() ? dim + 1 : (1 << dim);

    unsigned int n_patches = 0;
    for (const auto &cell : triangulation.active_cell_iterators())
      if (cell->is_locally_owned())
        ++n_patches;
    const unsigned int cells_per_patch =
      (n_patches > 0) ? local_cells / n_patches : 1;

    try
      {
        data_out.write_hdf5_parallel(filter,
                                     /*write_mesh_file=*/entries.empty(),
                                     directory + mesh_file,
                                     file,
                                     mpi_communicator);
        HDF5::File h5(file, HDF5::File::FileAccessMode::open, mpi_communicator);
        for (unsigned int f = 0; f < cell_data.names.size(); ++f)
          {
            auto dataset =
              h5.create_dataset<float>(cell_data.names[f], {n_cells});
            const std::vector<float> values =
              cell_data.in_output_order(f, triangulation, cells_per_patch);
            if (local_cells > 0)
              dataset.write_hyperslab(values, {cell_offset}, {local_cells});
            else
              dataset.write_none<float>();
          }
      }
    catch (ExceptionBase &failure)
      {
        std::ostringstream reason;
        failure.print_info(reason);
        throw WriteFailure("Cannot write the HDF5 output '" + file +
                           "': " + Parameters::one_line(reason.str()));
      }
    // The HDF5 mesh's nodes have two coordinates in 1D and 2D, three in 3D
    // (XDMF has no geometry with one).
    node_dimension = (dim == 3) ? 3 : 2;
    entries.push_back(entry);

    std::string error;
    if (Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
      try
        {
          write_file_atomically(directory + "solution.xdmf",
                                [&](std::ostream &out) {
                                  out << xdmf_record();
                                });
        }
      catch (WriteFailure &failure)
        {
          error = failure.what();
        }
    fail_everywhere(error, mpi_communicator);
  }



  // @sect4{XdmfOutput::xdmf_record}
  //
  // A temporal collection of uniform grids that share the mesh's topology
  // and geometry; each grid has the attributes of its file.
  template <int dim>
  std::string
  XdmfOutput<dim>::xdmf_record() const
  {
    const bool         simplex  = (vertices_per_cell == dim + 1);
    const std::string  topology = (dim == 1) ? "Polyline"
                                  : (dim == 2)
                                    ? (simplex ? "Triangle" : "Quadrilateral")
                                    : (simplex ? "Tetrahedron" : "Hexahedron");
    std::ostringstream out;
    out.precision(12);
    out << "<?xml version=\"1.0\" ?>\n"
        << "<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n"
        << "<Xdmf Version=\"2.0\">\n"
        << "  <Domain>\n"
        << "    <Grid Name=\"CellTime\" GridType=\"Collection\" "
           "CollectionType=\"Temporal\">\n";
    for (const Entry &entry : entries)
      {
        out << "      <Grid Name=\"mesh\" GridType=\"Uniform\">\n"
            << "        <Time Value=\"" << entry.time << "\"/>\n"
            << "        <Geometry GeometryType=\""
            << (node_dimension == 3 ? "XYZ" : "XY") << "\">\n"
            << "          <DataItem Dimensions=\"" << n_nodes << ' '
            << node_dimension
            << "\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">\n"
            << "            " << mesh_file << ":/nodes\n"
            << "          </DataItem>\n"
            << "        </Geometry>\n"
            << "        <Topology TopologyType=\"" << topology
            << "\" NumberOfElements=\"" << n_cells << "\""
            << (dim == 1 ? " NodesPerElement=\"2\"" : "") << ">\n"
            << "          <DataItem Dimensions=\"" << n_cells << ' '
            << vertices_per_cell << "\" NumberType=\"UInt\" Format=\"HDF\">\n"
            << "            " << mesh_file << ":/cells\n"
            << "          </DataItem>\n"
            << "        </Topology>\n";
        for (const auto &[name, components] : entry.node_fields)
          out << "        <Attribute Name=\"" << name << "\" AttributeType=\""
              << (components > 1 ? "Vector" : "Scalar")
              << "\" Center=\"Node\">\n"
              << "          <DataItem Dimensions=\"" << n_nodes << ' '
              << components
              << "\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">\n"
              << "            " << entry.solution_file << ":/" << name << '\n'
              << "          </DataItem>\n"
              << "        </Attribute>\n";
        for (const std::string &name : entry.cell_fields)
          out << "        <Attribute Name=\"" << name
              << "\" AttributeType=\"Scalar\" Center=\"Cell\">\n"
              << "          <DataItem Dimensions=\"" << n_cells
              << "\" NumberType=\"Float\" Precision=\"4\" Format=\"HDF\">\n"
              << "            " << entry.solution_file << ":/" << name << '\n'
              << "          </DataItem>\n"
              << "        </Attribute>\n";
        out << "      </Grid>\n";
      }
    out << "    </Grid>\n"
        << "  </Domain>\n"
        << "</Xdmf>\n";
    return out.str();
  }



#define SOFT_ROBOT_INSTANTIATE(dim) template class XdmfOutput<dim>;
  SOFT_ROBOT_FOR_EACH_DIMENSION(SOFT_ROBOT_INSTANTIATE)
#undef SOFT_ROBOT_INSTANTIATE
} // namespace SoftRobot
