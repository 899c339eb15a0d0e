// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Cell data: one value per cell, written as cell data}
//
// The per-cell fields of the output -- the cell averages of the volume
// ratio and of the Cauchy stress, the von Mises stress, the material id and
// the MPI rank -- have one value per cell. deal.II 9.4's DataOut accepts
// such vectors (`type_cell_data`), but its writers store every field as
// point data: each cell is a patch with points of its own, and the cell's
// value is repeated at all of them. ParaView then shows them as point
// arrays, interpolates them across the cell, and its cell-based filters
// (Threshold on the material id, "Cell Data to Point Data") do not see
// them. DataOutBase's VtkFlags (9.4) have no option for cell data, and
// neither do the HDF5 writer and XDMFEntry, whose attributes are always
// `Center="Node"`.
//
// So the program writes these fields itself: DataOut gets the nodal fields
// only, and the cell fields are added to what it writes, as a `<CellData>`
// section of each VTU piece (its arrays compressed and encoded the way
// deal.II encodes its own arrays, with the file's zlib compressor and
// base64) and a `<PCellData>` list in the PVTU record; in the HDF5 output
// as datasets of one value per cell beside deal.II's, listed with
// `Center="Cell"` in the XDMF record (see output/xdmf_output.h). Both keep
// DataOut's order of the cells: the locally owned active cells in the
// order of the triangulation, each written as `cells_per_patch` cells (the
// subdivisions of a patch, `subdivisions^dim` for hypercubes, one for
// simplices).
//
// Implemented in source/output/cell_data.cc.

#ifndef soft_robot_output_cell_data_h
#define soft_robot_output_cell_data_h

#include <deal.II/grid/tria.h>
#include <deal.II/lac/vector.h>
#include <string>
#include <vector>

namespace SoftRobot
{
  using namespace dealii;

  // The per-cell fields of one output, indexed by active cell index.
  struct CellData
  {
    std::vector<std::string>   names;
    std::vector<Vector<float>> values;

    void
    add(const std::string &name, const Vector<float> &value)
    {
      names.push_back(name);
      values.push_back(value);
    }

    // The values of field `field` on the locally owned cells of
    // `triangulation`, in DataOut's order, each repeated `cells_per_patch`
    // times.
    template <int dim>
    std::vector<float>
    in_output_order(const unsigned int        field,
                    const Triangulation<dim> &triangulation,
                    const unsigned int        cells_per_patch) const;
  };

  // Adds a `<CellData>` section with `cell_data` to the VTU text `vtu` that
  // DataOut::write_vtu() wrote (one piece), compressed if the file is.
  template <int dim>
  void
  add_vtu_cell_data(std::string              &vtu,
                    const CellData           &cell_data,
                    const Triangulation<dim> &triangulation,
                    const unsigned int        cells_per_patch);

  // Adds the `<PCellData>` list of `cell_data` to the PVTU record `pvtu`.
  void
  add_pvtu_cell_data(std::string &pvtu, const CellData &cell_data);

  // The number of cells in a VTU piece (its `NumberOfCells`).
  unsigned int
  vtu_cell_count(const std::string &vtu);
} // namespace SoftRobot

#endif
