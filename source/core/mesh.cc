// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{The mesh}
//
// See include/core/mesh.h.

#include <core/config.h>
#include <core/expression_function.h>
#include <core/input_checks.h>
#include <core/mesh.h>
#include <core/parameter_file.h>
#include <deal.II/base/function_parser.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_in.h>
#include <deal.II/grid/grid_tools.h>
#include <fstream>
#include <set>
#include <sstream>

namespace SoftRobot
{
  // @sect4{read_mesh_file}
  //
  // deal.II's GridIn reports a file it cannot read in its own words ("The
  // string <> is not recognized at the present position of a Gmsh Mesh
  // file" for an empty one, a page on input streams for a truncated one),
  // without the file's name. The file is therefore looked at first (does it
  // exist, is it empty, does it start as a gmsh file does), and a failure
  // of GridIn is reported with the file's name and GridIn's reason.
  namespace
  {
    template <int dim>
    void
    read_mesh_file(const Parameters::AllParameters &parameters,
                   Triangulation<dim>              &serial)
    {
      const std::string where = parameters.where() + "Geometry/Mesh file '" +
                                parameters.mesh_file + "' ";
      std::ifstream input(parameters.mesh_file);
      AssertThrow(input, ExcMessage(where + "cannot be opened."));
      std::string first_word;
      input >> first_word;
      AssertThrow(!first_word.empty(), ExcMessage(where + "is empty."));
      AssertThrow(first_word == "$MeshFormat",
                  ExcMessage(where + "is not a gmsh mesh: it starts with '" +
                             first_word.substr(0, 40) +
                             "' instead of '$MeshFormat' (formats 2.2 and 4.1 "
                             "are read, written as ASCII)."));
      input.seekg(0);
      GridIn<dim> grid_in;
      grid_in.attach_triangulation(serial);
      try
        {
          grid_in.read_msh(input);
        }
      catch (ExceptionBase &error)
        {
          std::ostringstream reason;
          error.print_info(reason);
          std::string text = Parameters::one_line(reason.str());
          while (!text.empty() && text.back() == '.')
            text.pop_back();
          if (text.find("input stream") != std::string::npos ||
              text.find("ExcIO") != std::string::npos || text.empty())
            text = "it ends before the mesh is complete (a truncated file?)";
          AssertThrow(false,
                      ExcMessage(where + "cannot be read as a " +
                                 std::to_string(dim) + "D gmsh mesh: " + text +
                                 "."));
        }
      AssertThrow(serial.n_active_cells() > 0,
                  ExcMessage(where + "has no cells of dimension " +
                             std::to_string(dim) + "."));
    }
  } // namespace



  // @sect4{create_mesh}
  //
  // Generators number materials in their own ways (colorized boxes by
  // octant); a generated mesh is of material 1 unless the parameter file's
  // function says otherwise.
  template <int dim>
  void
  create_mesh(const Parameters::AllParameters &parameters,
              Triangulation<dim>              &serial)
  {
    if (parameters.mesh_source == Parameters::Geometry::MeshSource::generator)
      {
        Triangulation<dim> generated;
        try
          {
            GridGenerator::generate_from_name_and_arguments(
              generated,
              parameters.generator_name,
              parameters.generator_arguments);
          }
        catch (ExceptionBase &error)
          {
            std::ostringstream reason;
            error.print_info(reason);
            AssertThrow(false,
                        ExcMessage("In '" + parameters.source_name +
                                   "': Geometry/Generator '" +
                                   parameters.generator_name +
                                   "' does not accept the arguments '" +
                                   parameters.generator_arguments + "' in " +
                                   std::to_string(dim) +
                                   "D: " + Parameters::one_line(reason.str())));
          }
        if (parameters.convert_to_simplices && dim > 1)
          GridGenerator::convert_hypercube_to_simplex_mesh(generated, serial);
        else
          serial.copy_triangulation(generated);
      }
    else
      read_mesh_file(parameters, serial);

    if (parameters.distortion > 0)
      GridTools::distort_random(parameters.distortion, serial, true);

    if (parameters.mesh_source == Parameters::Geometry::MeshSource::generator)
      for (const auto &cell : serial.active_cell_iterators())
        cell->set_material_id(1);
    if (!parameters.material_id_function.empty())
      {
        // The function is evaluated at every cell centre first, so that a
        // syntax error or a value that is not finite is an input error that
        // names the entry (see InputChecks::check_expression()).
        const std::string   entry = "Geometry/Material id function";
        FunctionParser<dim> id_function(1);
        try
          {
            id_function.initialize(
              FunctionParser<dim>::default_variable_names(),
              parameters.material_id_function,
              parse_constants(parameters.constants));
          }
        catch (ExceptionBase &error)
          {
            std::ostringstream reason;
            error.print_info(reason);
            AssertThrow(false,
                        ExcMessage(parameters.where() + entry + ": " +
                                   Parameters::one_line(reason.str())));
          }
        std::vector<Point<dim>> centres;
        for (const auto &cell : serial.active_cell_iterators())
          centres.push_back(cell->center());
        InputChecks::check_expression(id_function,
                                      parameters,
                                      entry,
                                      parameters.material_id_function,
                                      centres,
                                      {0.});
        for (const auto &cell : serial.active_cell_iterators())
          {
            const long id = std::lround(id_function.value(cell->center()));
            AssertThrow(
              id >= 0 && id <= Parameters::Materials::max_material_id,
              ExcMessage(
                parameters.where() + entry + " = '" +
                parameters.material_id_function + "' gives the material id " +
                std::to_string(id) +
                " at the centre of a "
                "cell; ids are 0 to " +
                std::to_string(Parameters::Materials::max_material_id) + "."));
            cell->set_material_id(static_cast<types::material_id>(id));
          }
      }
  }



  // @sect4{check_mesh_ids}
  //
  // The messages name the mesh: its file, or the generator.
  namespace
  {
    std::string
    mesh_name(const Parameters::AllParameters &parameters)
    {
      return (parameters.mesh_source == Parameters::Geometry::MeshSource::file)
               ? "the mesh file '" + parameters.mesh_file + "'"
               : "the mesh of Geometry/Generator '" +
                   parameters.generator_name + "'";
    }
  } // namespace

  template <int dim>
  unsigned int
  check_mesh_ids(const Parameters::AllParameters &parameters,
                 const Triangulation<dim>        &triangulation)
  {
    std::set<types::material_id> mesh_materials;
    std::set<types::boundary_id> mesh_boundaries;
    for (const auto &cell : triangulation.active_cell_iterators())
      {
        mesh_materials.insert(cell->material_id());
        for (const auto &face : cell->face_iterators())
          if (face->at_boundary())
            mesh_boundaries.insert(face->boundary_id());
      }
    for (const types::material_id id : mesh_materials)
      AssertThrow(parameters.by_id.count(id) == 1,
                  ExcMessage(parameters.where() + mesh_name(parameters) +
                             " has cells with material id " +
                             std::to_string(id) +
                             ", but the file has no subsection 'Material " +
                             std::to_string(id) + "' with a Name."));
    std::vector<std::pair<unsigned int, std::string>> named_boundaries;
    for (const auto &entry : parameters.fixed_components)
      named_boundaries.emplace_back(entry.first,
                                    "Loads and constraints/Fixed components");
    for (const unsigned int id : parameters.traction_boundary_ids)
      named_boundaries.emplace_back(
        id, "Loads and constraints/Traction boundary ids");
    for (const unsigned int id : parameters.drag_boundary_ids)
      named_boundaries.emplace_back(id, "Damping/Drag boundary ids");
    for (const unsigned int id : parameters.pressure_boundary_ids)
      named_boundaries.emplace_back(id, "Pneumatics/Pressure boundary ids");
    if (parameters.tip_region_type ==
        Parameters::Output::TipRegionType::boundary)
      named_boundaries.emplace_back(parameters.tip_region_id,
                                    "Output/Tip region");
    else
      AssertThrow(mesh_materials.count(parameters.tip_region_id) == 1,
                  ExcMessage("In '" + parameters.source_name +
                             "': Output/Tip region names material " +
                             std::to_string(parameters.tip_region_id) +
                             ", which no cell of " + mesh_name(parameters) +
                             " has."));
    for (const auto &[id, entry] : named_boundaries)
      {
        std::string present;
        for (const auto b : mesh_boundaries)
          present += " " + std::to_string(b);
        AssertThrow(mesh_boundaries.count(id) == 1,
                    ExcMessage("In '" + parameters.source_name + "': " + entry +
                               " names boundary id " + std::to_string(id) +
                               ", which " + mesh_name(parameters) +
                               " does not have (it has:" + present + ")."));
      }

    return mesh_materials.size();
  }



#define SOFT_ROBOT_INSTANTIATE(dim)                                            \
  template void         create_mesh<dim>(const Parameters::AllParameters &,    \
                                 Triangulation<dim> &);                \
  template unsigned int check_mesh_ids<dim>(const Parameters::AllParameters &, \
                                            const Triangulation<dim> &);
  SOFT_ROBOT_FOR_EACH_DIMENSION(SOFT_ROBOT_INSTANTIATE)
#undef SOFT_ROBOT_INSTANTIATE
} // namespace SoftRobot
