// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Cell data: one value per cell, written as cell data}
//
// See include/output/cell_data.h.

#include <core/config.h>
#include <cstdint>
#include <deal.II/base/exceptions.h>
#include <output/cell_data.h>
#include <zlib.h>

namespace SoftRobot
{
  namespace
  {
    // @sect4{Base64}
    //
    // VTK's "binary" format: the bytes in base64, three bytes to four
    // characters, padded with '='.
    std::string
    base64(const unsigned char *data, const std::size_t size)
    {
      static const char alphabet[] =
        "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
      std::string text;
      text.reserve(4 * ((size + 2) / 3));
      for (std::size_t i = 0; i < size; i += 3)
        {
          const unsigned int n = (data[i] << 16) |
                                 ((i + 1 < size ? data[i + 1] : 0) << 8) |
                                 (i + 2 < size ? data[i + 2] : 0);
          text += alphabet[(n >> 18) & 63];
          text += alphabet[(n >> 12) & 63];
          text += (i + 1 < size) ? alphabet[(n >> 6) & 63] : '=';
          text += (i + 2 < size) ? alphabet[n & 63] : '=';
        }
      return text;
    }

    // @sect4{One array}
    //
    // An uncompressed array is a 32-bit byte count followed by the data, in
    // one base64 text. A compressed one (vtkZLibDataCompressor, with the
    // 32-bit header type deal.II writes) is a header of four 32-bit
    // numbers -- one block, its size before compression twice (the block
    // size and the size of the last block), its size after -- and the
    // compressed block, each encoded on its own, as deal.II does.
    std::string
    encoded_array(const std::vector<float> &values, const bool compressed)
    {
      const auto *bytes =
        reinterpret_cast<const unsigned char *>(values.data());
      const std::uint32_t size =
        static_cast<std::uint32_t>(values.size() * sizeof(float));
      if (!compressed)
        {
          std::vector<unsigned char> block(sizeof(size) + size);
          std::copy_n(reinterpret_cast<const unsigned char *>(&size),
                      sizeof(size),
                      block.begin());
          std::copy_n(bytes, size, block.begin() + sizeof(size));
          return base64(block.data(), block.size());
        }
      uLongf                     compressed_size = compressBound(size);
      std::vector<unsigned char> block(compressed_size);
      const int                  status =
        compress2(block.data(), &compressed_size, bytes, size, Z_BEST_SPEED);
      AssertThrow(status == Z_OK, ExcMessage("zlib failed to compress."));
      const std::uint32_t header[4] = {
        1, size, size, static_cast<std::uint32_t>(compressed_size)};
      return base64(reinterpret_cast<const unsigned char *>(header),
                    sizeof(header)) +
             base64(block.data(), compressed_size);
    }
  } // namespace



  template <int dim>
  std::vector<float>
  CellData::in_output_order(const unsigned int        field,
                            const Triangulation<dim> &triangulation,
                            const unsigned int        cells_per_patch) const
  {
    std::vector<float> ordered;
    for (const auto &cell : triangulation.active_cell_iterators())
      if (cell->is_locally_owned())
        ordered.insert(ordered.end(),
                       cells_per_patch,
                       values[field][cell->active_cell_index()]);
    return ordered;
  }



  unsigned int
  vtu_cell_count(const std::string &vtu)
  {
    const std::string key   = "NumberOfCells=\"";
    const auto        start = vtu.find(key);
    AssertThrow(start != std::string::npos,
                ExcMessage("A VTU piece without NumberOfCells."));
    return std::stoul(vtu.substr(start + key.size()));
  }



  // @sect4{add_vtu_cell_data}
  //
  // The section goes at the end of the piece, after deal.II's
  // `<PointData>`: VTK reads the sections of a piece by name, in any order.
  template <int dim>
  void
  add_vtu_cell_data(std::string              &vtu,
                    const CellData           &cell_data,
                    const Triangulation<dim> &triangulation,
                    const unsigned int        cells_per_patch)
  {
    const bool compressed =
      vtu.find("compressor=\"vtkZLibDataCompressor\"") != std::string::npos;
    std::string section = "  <CellData>\n";
    for (unsigned int f = 0; f < cell_data.names.size(); ++f)
      {
        const std::vector<float> values =
          cell_data.in_output_order(f, triangulation, cells_per_patch);
        Assert(values.size() == vtu_cell_count(vtu), ExcInternalError());
        section += "    <DataArray type=\"Float32\" Name=\"" +
                   cell_data.names[f] + "\" format=\"binary\">\n" +
                   encoded_array(values, compressed) + "\n    </DataArray>\n";
      }
    section += "  </CellData>\n";
    const auto end_of_piece = vtu.rfind("</Piece>");
    AssertThrow(end_of_piece != std::string::npos,
                ExcMessage("A VTU text without a piece."));
    vtu.insert(end_of_piece, section);
  }



  void
  add_pvtu_cell_data(std::string &pvtu, const CellData &cell_data)
  {
    std::string section = "    <PCellData>\n";
    for (const std::string &name : cell_data.names)
      section += "      <PDataArray type=\"Float32\" Name=\"" + name +
                 "\" format=\"ascii\"/>\n";
    section += "    </PCellData>\n";
    const auto points = pvtu.find("<PPoints>");
    AssertThrow(points != std::string::npos,
                ExcMessage("A PVTU record without <PPoints>."));
    pvtu.insert(pvtu.rfind('\n', points) + 1, section);
  }



#define SOFT_ROBOT_INSTANTIATE(dim)                                            \
  template std::vector<float> CellData::in_output_order<dim>(                  \
    const unsigned int, const Triangulation<dim> &, const unsigned int) const; \
  template void add_vtu_cell_data<dim>(std::string &,                          \
                                       const CellData &,                       \
                                       const Triangulation<dim> &,             \
                                       const unsigned int);
  SOFT_ROBOT_FOR_EACH_DIMENSION(SOFT_ROBOT_INSTANTIATE)
#undef SOFT_ROBOT_INSTANTIATE
} // namespace SoftRobot
