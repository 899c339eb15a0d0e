// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{The mesh}
//
// See include/core/mesh.h.

#include <array>
#include <core/bellows_mesh.h>
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
#include <map>
#include <set>
#include <sstream>

namespace SoftRobot
{
  // @sect4{Second-order gmsh files}
  //
  // deal.II 9.4's GridIn reads linear cells only. A second-order MSH 2.2
  // file is therefore rewritten as the linear mesh of the same cells --
  // each element's corner nodes, in gmsh's order, which begins with the
  // corners, and only the nodes that are corners -- and the mid-edge nodes
  // are kept with the two corner nodes of their edge. gmsh numbers the
  // edges of the 3-node line (0,1), of the 6-node triangle (0,1), (1,2),
  // (2,0), and of the 10-node tetrahedron (0,1), (1,2), (2,0), (3,0), (3,2),
  // (3,1). The corner nodes' lines are copied as they are, so that GridIn
  // parses the same numbers; the vertices are then found again by their
  // coordinates.
  namespace
  {
    struct GmshMidNode
    {
      long                  element;
      long                  a, b;
      std::array<double, 3> x;
    };

    struct LinearizedMesh
    {
      std::string                           text;
      std::map<long, std::array<double, 3>> corners;
      std::vector<GmshMidNode>              mid_nodes;
    };

    // The number of nodes of the MSH 2.2 element types (0 for a type this
    // reader does not know).
    unsigned int
    gmsh_nodes_per_element(const int type)
    {
      switch (type)
        {
          case 1:
            return 2;
          case 2:
            return 3;
          case 3:
            return 4;
          case 4:
            return 4;
          case 5:
            return 8;
          case 6:
            return 6;
          case 7:
            return 5;
          case 8:
            return 3;
          case 9:
            return 6;
          case 11:
            return 10;
          case 15:
            return 1;
          default:
            return 0;
        }
    }

    // Fills `linear` and returns true if the file has second-order
    // elements; returns false, and leaves `linear` alone, if it has none.
    bool
    linearize_second_order(const std::string &text,
                           const std::string &where,
                           LinearizedMesh    &linear)
    {
      static const std::map<int,
                            std::pair<int, std::vector<std::pair<int, int>>>>
        second_order = {
          {8, {1, {{0, 1}}}},
          {9, {2, {{0, 1}, {1, 2}, {2, 0}}}},
          {11, {4, {{0, 1}, {1, 2}, {2, 0}, {3, 0}, {3, 2}, {3, 1}}}}};
      std::istringstream                        in(text);
      std::string                               line;
      std::string                               version;
      std::vector<std::pair<long, std::string>> node_lines;
      std::vector<std::vector<long>>            elements; // id type tags nodes
      std::ostringstream                        head, tail;
      std::ostringstream                       *out = &head;
      bool                                      any = false;
      while (std::getline(in, line))
        {
          if (line.rfind("$MeshFormat", 0) == 0)
            {
              *out << line << '\n';
              std::getline(in, version);
              *out << version << '\n';
            }
          else if (line.rfind("$Nodes", 0) == 0)
            {
              std::getline(in, line);
              long n = 0;
              std::istringstream(line) >> n;
              for (long i = 0; i < n && std::getline(in, line); ++i)
                {
                  std::istringstream node(line);
                  long               id = 0;
                  node >> id;
                  node_lines.emplace_back(id, line);
                }
              std::getline(in, line); // $EndNodes
              out = &tail;
            }
          else if (line.rfind("$Elements", 0) == 0)
            {
              if (version.rfind("2", 0) != 0)
                return false;
              std::getline(in, line);
              long n = 0;
              std::istringstream(line) >> n;
              long i = 0;
              for (; i < n && std::getline(in, line); ++i)
                {
                  std::istringstream element(line);
                  std::vector<long>  numbers;
                  long               value;
                  while (element >> value)
                    numbers.push_back(value);
                  const int type =
                    (numbers.size() >= 3) ? static_cast<int>(numbers[1]) : 0;
                  const bool known = gmsh_nodes_per_element(type) > 0;
                  // A line this reader does not understand: GridIn reports
                  // it for a linear mesh; in a second-order one it is
                  // reported here.
                  if (!known || static_cast<long>(numbers.size()) !=
                                  3 + numbers[2] + gmsh_nodes_per_element(type))
                    {
                      AssertThrow(!any,
                                  ExcMessage(where +
                                             "has an element line that is "
                                             "not a 3-node line, 6-node "
                                             "triangle or 10-node tetrahedron "
                                             "(the second-order elements read) "
                                             "or a linear element: '" +
                                             line + "'."));
                      return false;
                    }
                  any = any || second_order.count(type) > 0;
                  elements.push_back(std::move(numbers));
                }
              if (i < n)
                {
                  AssertThrow(!any,
                              ExcMessage(where +
                                         "ends before its last element (a "
                                         "truncated file?)."));
                  return false;
                }
              std::getline(in, line); // $EndElements
            }
          else
            *out << line << '\n';
        }
      if (!any)
        return false;

      std::map<long, std::array<double, 3>> coordinates;
      for (const auto &[id, text_line] : node_lines)
        {
          std::istringstream    node(text_line);
          long                  number;
          std::array<double, 3> x;
          node >> number >> x[0] >> x[1] >> x[2];
          coordinates[id] = x;
        }
      const auto position = [&](const long id) {
        const auto it = coordinates.find(id);
        AssertThrow(it != coordinates.end(),
                    ExcMessage(where + "refers to node " + std::to_string(id) +
                               ", which its $Nodes section does not have."));
        return it->second;
      };

      std::ostringstream element_text;
      std::set<long>     corner_ids;
      for (const auto &numbers : elements)
        {
          const int          type   = static_cast<int>(numbers[1]);
          const unsigned int n_tags = static_cast<unsigned int>(numbers[2]);
          const unsigned int first  = 3 + n_tags;
          int                linear_type = type;
          unsigned int       n_corners   = gmsh_nodes_per_element(type);
          const auto         second      = second_order.find(type);
          if (second != second_order.end())
            {
              linear_type       = second->second.first;
              n_corners         = gmsh_nodes_per_element(linear_type);
              const auto &edges = second->second.second;
              for (unsigned int e = 0; e < edges.size(); ++e)
                linear.mid_nodes.push_back(
                  {numbers[0],
                   numbers[first + edges[e].first],
                   numbers[first + edges[e].second],
                   position(numbers[first + n_corners + e])});
            }
          element_text << numbers[0] << ' ' << linear_type;
          for (unsigned int i = 2; i < first; ++i)
            element_text << ' ' << numbers[i];
          for (unsigned int i = 0; i < n_corners; ++i)
            {
              element_text << ' ' << numbers[first + i];
              corner_ids.insert(numbers[first + i]);
            }
          element_text << '\n';
        }

      std::ostringstream result;
      result << head.str() << "$Nodes\n" << corner_ids.size() << '\n';
      for (const auto &[id, text_line] : node_lines)
        if (corner_ids.count(id) == 1)
          {
            result << text_line << '\n';
            linear.corners[id] = coordinates[id];
          }
      result << "$EndNodes\n$Elements\n"
             << elements.size() << '\n'
             << element_text.str() << "$EndElements\n"
             << tail.str();
      linear.text = result.str();
      return true;
    }



    // @sect4{read_mesh_file}
    //
    // deal.II's GridIn reports a file it cannot read in its own words ("The
    // string <> is not recognized at the present position of a Gmsh Mesh
    // file" for an empty one, a page on input streams for a truncated one),
    // without the file's name. The file is therefore looked at first (does
    // it exist, is it empty, does it start as a gmsh file does), and a
    // failure of GridIn is reported with the file's name and GridIn's
    // reason.
    template <int dim>
    void
    read_mesh_file(const Parameters::AllParameters &parameters,
                   Triangulation<dim>              &serial,
                   MidEdgeNodes<dim>               *mid_edge_nodes)
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
      std::stringstream whole;
      whole << input.rdbuf();
      LinearizedMesh linear;
      const bool curved = linearize_second_order(whole.str(), where, linear);
      std::istringstream linear_input(curved ? linear.text : std::string());
      std::istream      &mesh_input =
        curved ? static_cast<std::istream &>(linear_input) : whole;
      whole.seekg(0);

      GridIn<dim> grid_in;
      grid_in.attach_triangulation(serial);
      try
        {
          grid_in.read_msh(mesh_input);
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
      if (!curved || mid_edge_nodes == nullptr)
        return;

      // The vertices by their coordinates, then the mid-edge nodes by the
      // vertex indices of their edge. A mid-edge node must lie nearer to
      // its edge's midpoint than half the edge's length, or the file's
      // node order is not gmsh's.
      AssertThrow(dim > 1,
                  ExcMessage(where + "has second-order cells; they are read "
                                     "in 2D and 3D only."));
      const auto key = [](const auto &x) {
        std::array<double, dim> k;
        for (unsigned int d = 0; d < dim; ++d)
          k[d] = x[d];
        return k;
      };
      std::map<std::array<double, dim>, unsigned int> vertex_at;
      const std::vector<Point<dim>> &vertices = serial.get_vertices();
      for (unsigned int v = 0; v < vertices.size(); ++v)
        vertex_at[key(vertices[v])] = v;
      const auto vertex_of = [&](const long node) {
        const auto it = vertex_at.find(key(linear.corners.at(node)));
        AssertThrow(it != vertex_at.end(),
                    ExcMessage(where + "has a corner node " +
                               std::to_string(node) +
                               " that is not a vertex of the mesh read."));
        return it->second;
      };
      for (const GmshMidNode &node : linear.mid_nodes)
        {
          const unsigned int a = vertex_of(node.a);
          const unsigned int b = vertex_of(node.b);
          Point<dim>         x;
          for (unsigned int d = 0; d < dim; ++d)
            x[d] = node.x[d];
          const Point<dim> middle = 0.5 * (vertices[a] + vertices[b]);
          AssertThrow(x.distance(middle) <
                        0.5 * vertices[a].distance(vertices[b]),
                      ExcMessage(where + "element " +
                                 std::to_string(node.element) +
                                 ": the mid-edge node of the edge between "
                                 "nodes " +
                                 std::to_string(node.a) + " and " +
                                 std::to_string(node.b) +
                                 " is farther from the edge's midpoint than "
                                 "half the edge's length (is the node order "
                                 "gmsh's?)."));
          (*mid_edge_nodes)[{std::min(a, b), std::max(a, b)}] = x;
        }
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
              Triangulation<dim>              &serial,
              MidEdgeNodes<dim>               *mid_edge_nodes)
  {
    if (mid_edge_nodes != nullptr)
      mid_edge_nodes->clear();
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
    else if (parameters.mesh_source ==
             Parameters::Geometry::MeshSource::bellows)
      {
        // The checks of the parameters allow this source in 3D only.
        if constexpr (dim == 3)
          {
            BellowsDesign design;
            try
              {
                design = BellowsDesign::read(parameters.mesh_file);
              }
            catch (ExceptionBase &error)
              {
                std::ostringstream reason;
                error.print_info(reason);
                AssertThrow(false,
                            ExcMessage(parameters.where() +
                                       "Geometry/Mesh file: " +
                                       Parameters::one_line(reason.str())));
              }
            BellowsResolution resolution;
            resolution.cells_through_wall =
              parameters.bellows_cells_through_wall;
            resolution.cells_along_flank = parameters.bellows_cells_along_flank;
            resolution.cells_per_chord   = parameters.bellows_cells_per_chord;
            resolution.cells_per_quarter_turn =
              parameters.bellows_cells_per_quarter_turn;
            make_bellows_mesh(design,
                              resolution,
                              static_cast<unsigned int>(
                                std::lround(4. * parameters.model_fraction)),
                              serial);
          }
        else
          AssertThrow(false, ExcInternalError());
      }
    else
      read_mesh_file(parameters, serial, mid_edge_nodes);

    AssertThrow(parameters.distortion == 0 || mid_edge_nodes == nullptr ||
                  mid_edge_nodes->empty(),
                ExcMessage(parameters.where() + "Geometry/Distortion = " +
                           std::to_string(parameters.distortion) +
                           " moves the vertices of a linear mesh; the mesh "
                           "file '" +
                           parameters.mesh_file +
                           "' is second order (its mid-edge nodes would stay "
                           "behind). Use 0 with it."));
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
      switch (parameters.mesh_source)
        {
          case Parameters::Geometry::MeshSource::file:
            return "the mesh file '" + parameters.mesh_file + "'";
          case Parameters::Geometry::MeshSource::bellows:
            return "the bellows mesh of '" + parameters.mesh_file + "'";
          default:
            return "the mesh of Geometry/Generator '" +
                   parameters.generator_name + "'";
        }
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
                                 Triangulation<dim> &,                 \
                                 MidEdgeNodes<dim> *);                 \
  template unsigned int check_mesh_ids<dim>(const Parameters::AllParameters &, \
                                            const Triangulation<dim> &);
  SOFT_ROBOT_FOR_EACH_DIMENSION(SOFT_ROBOT_INSTANTIATE)
#undef SOFT_ROBOT_INSTANTIATE
} // namespace SoftRobot
