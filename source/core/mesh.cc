// @sect3{The mesh}
//
// See include/core/mesh.h.

#include <core/config.h>
#include <core/expression_function.h>
#include <core/mesh.h>
#include <deal.II/base/function_parser.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_in.h>
#include <deal.II/grid/grid_tools.h>

#include <fstream>
#include <set>
#include <sstream>

namespace SoftRobot
{
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
    if (parameters.mesh_source ==
        Parameters::Geometry::MeshSource::generator)
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
                                   std::to_string(dim) + "D: " + reason.str()));
          }
        if (parameters.convert_to_simplices && dim > 1)
          GridGenerator::convert_hypercube_to_simplex_mesh(generated, serial);
        else
          serial.copy_triangulation(generated);
      }
    else
      {
        GridIn<dim> grid_in;
        grid_in.attach_triangulation(serial);
        std::ifstream input(parameters.mesh_file);
        grid_in.read_msh(input);
      }

    if (parameters.distortion > 0)
      GridTools::distort_random(parameters.distortion, serial, true);

    if (parameters.mesh_source ==
        Parameters::Geometry::MeshSource::generator)
      for (const auto &cell : serial.active_cell_iterators())
        cell->set_material_id(1);
    if (!parameters.material_id_function.empty())
      {
        FunctionParser<dim> id_function(1);
        id_function.initialize(FunctionParser<dim>::default_variable_names(),
                               parameters.material_id_function,
                               parse_constants(parameters.constants));
        for (const auto &cell : serial.active_cell_iterators())
          cell->set_material_id(static_cast<types::material_id>(
            std::lround(id_function.value(cell->center()))));
      }

  }



  // @sect4{check_mesh_ids}
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
                  ExcMessage("In '" + parameters.source_name +
                             "': the mesh has cells with material id " +
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
    if (parameters.tip_region_type ==
        Parameters::Output::TipRegionType::boundary)
      named_boundaries.emplace_back(parameters.tip_region_id,
                                    "Output/Tip region");
    else
      AssertThrow(mesh_materials.count(parameters.tip_region_id) == 1,
                  ExcMessage("In '" + parameters.source_name +
                             "': Output/Tip region names material " +
                             std::to_string(parameters.tip_region_id) +
                             ", which no cell of the mesh has."));
    for (const auto &[id, entry] : named_boundaries)
      {
        std::string present;
        for (const auto b : mesh_boundaries)
          present += " " + std::to_string(b);
        AssertThrow(mesh_boundaries.count(id) == 1,
                    ExcMessage("In '" + parameters.source_name + "': " + entry +
                               " names boundary id " + std::to_string(id) +
                               ", which the mesh does not have (it has:" +
                               present + ")."));
      }

    return mesh_materials.size();
  }



#define SOFT_ROBOT_INSTANTIATE(dim)                                   \
  template void create_mesh<dim>(const Parameters::AllParameters &,   \
                                 Triangulation<dim> &);               \
  template unsigned int check_mesh_ids<dim>(                          \
    const Parameters::AllParameters &, const Triangulation<dim> &);
  SOFT_ROBOT_FOR_EACH_DIMENSION(SOFT_ROBOT_INSTANTIATE)
#undef SOFT_ROBOT_INSTANTIATE
} // namespace SoftRobot
