// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{How a cavity is closed}
//
// See include/physics/cavity_closure.h.

#include <cmath>
#include <core/config.h>
#include <core/input_checks.h>
#include <deal.II/grid/grid_tools.h>
#include <iomanip>
#include <map>
#include <physics/cavity_closure.h>
#include <set>
#include <sstream>
#include <vector>

namespace SoftRobot
{
  namespace
  {
    // The fixed components of a boundary id, as bits (x = 1, y = 2, z = 4).
    unsigned int
    fixed_mask(const Parameters::AllParameters &parameters,
               const types::boundary_id         id)
    {
      const auto entry = parameters.fixed_components.find(id);
      if (entry == parameters.fixed_components.end())
        return 0;
      unsigned int mask = 0;
      for (const char letter : entry->second)
        mask |= 1u << (letter - 'x');
      return mask;
    }


    // An open edge of the cavity surface: its vertices, and the fixed
    // components of the boundaries that hold the whole edge.
    template <int dim>
    struct OpenEdge
    {
      std::vector<Point<dim>> vertices;
      unsigned int            fixed = 0;
    };

    // The open edges: in 3D the lines of one cavity face only, with the
    // fixed components of the faces that contain the line; in 2D the
    // vertices of one cavity face only, with those of the faces that
    // contain the vertex.
    template <int dim>
    std::vector<OpenEdge<dim>>
    open_edges(const Parameters::AllParameters &parameters,
               const Triangulation<dim>        &triangulation)
    {
      const std::set<types::boundary_id> cavity(
        parameters.pressure_boundary_ids.begin(),
        parameters.pressure_boundary_ids.end());
      // per edge (line in 3D, vertex in 2D): how many cavity faces have
      // it, its vertices, and the fixed components there
      std::map<unsigned int, OpenEdge<dim>> edges;
      std::map<unsigned int, unsigned int>  count, fixed;
      for (const auto &cell : triangulation.active_cell_iterators())
        for (const auto &face : cell->face_iterators())
          {
            if (!face->at_boundary())
              continue;
            const bool         is_cavity = cavity.count(face->boundary_id());
            const unsigned int mask =
              fixed_mask(parameters, face->boundary_id());
            if constexpr (dim == 3)
              for (unsigned int l = 0; l < face->n_lines(); ++l)
                {
                  const auto         line  = face->line(l);
                  const unsigned int index = line->index();
                  fixed[index] |= mask;
                  if (is_cavity)
                    {
                      ++count[index];
                      edges[index].vertices = {line->vertex(0),
                                               line->vertex(1)};
                    }
                }
            else if constexpr (dim == 2)
              for (const unsigned int v : face->vertex_indices())
                {
                  const unsigned int index = face->vertex_index(v);
                  fixed[index] |= mask;
                  if (is_cavity)
                    {
                      ++count[index];
                      edges[index].vertices = {face->vertex(v)};
                    }
                }
          }
      std::vector<OpenEdge<dim>> result;
      for (auto &[index, edge] : edges)
        if (count[index] == 1)
          {
            edge.fixed = fixed[index];
            result.push_back(edge);
          }
      return result;
    }
  } // namespace



  // @sect4{find_cavity_closure}
  //
  // For each open edge, the coordinate planes $x_j = \text{const}$ it can be
  // closed by: $u_j$ fixed on the whole edge, and all its vertices at the
  // same $x_j$ (to round-off of the mesh's size). Then the first axis $k$
  // for which the edges that can only be closed by planes normal to
  // $\mathbf e_k$ all lie in one such plane.
  template <int dim>
  CavityClosure
  find_cavity_closure(const Parameters::AllParameters &parameters,
                      const Triangulation<dim>        &triangulation)
  {
    CavityClosure closure;
    if (dim == 1 || parameters.equivalent_area > 0.)
      return closure;
    const double tolerance = 1e-9 * GridTools::diameter(triangulation);
    const std::vector<OpenEdge<dim>> edges =
      open_edges(parameters, triangulation);
    closure.n_open_edges = edges.size();
    // per edge: the planes (j, value) that close it
    std::vector<std::vector<std::pair<unsigned int, double>>> planes;
    for (const OpenEdge<dim> &edge : edges)
      {
        std::vector<std::pair<unsigned int, double>> candidates;
        for (unsigned int j = 0; j < dim; ++j)
          {
            if ((edge.fixed & (1u << j)) == 0)
              continue;
            bool in_plane = true;
            for (const Point<dim> &p : edge.vertices)
              in_plane =
                in_plane && std::abs(p[j] - edge.vertices[0][j]) <= tolerance;
            if (in_plane)
              candidates.emplace_back(j, edge.vertices[0][j]);
          }
        if (candidates.empty() && closure.closed)
          {
            closure.closed = false;
            Point<dim> centre;
            for (const Point<dim> &p : edge.vertices)
              centre += p / static_cast<double>(edge.vertices.size());
            closure.open_edge = InputChecks::point_text(centre);
          }
        planes.push_back(candidates);
      }
    if (!closure.closed)
      return closure;

    const char *axis_name = "xyz";
    for (unsigned int k = 0; k < dim; ++k)
      {
        // An edge that lies in a plane normal to the axis is closed by it
        // (a clamped edge lies in several coordinate planes: the base's,
        // normal to the axis, is the one that holds the opening); the
        // others by a plane parallel to the axis.
        std::set<double> origins;
        for (const auto &candidates : planes)
          for (const auto &[j, value] : candidates)
            if (j == k)
              origins.insert(value);
        // one plane normal to the axis, within the tolerance
        if (!origins.empty() &&
            *origins.rbegin() - *origins.begin() > tolerance)
          continue;
        closure.axis   = k;
        closure.origin = origins.empty() ? 0. : *origins.begin();
        std::set<std::pair<unsigned int, double>> used;
        for (const auto &candidates : planes)
          {
            std::pair<unsigned int, double> chosen = candidates[0];
            for (const auto &plane : candidates)
              if (plane.first == k)
                chosen = plane;
            used.insert({chosen.first,
                         std::round(chosen.second / tolerance) * tolerance});
          }
        std::ostringstream text;
        for (const auto &[j, value] : used)
          text << (text.str().empty() ? "" : ", ") << axis_name[j] << " = "
               << std::setprecision(6) << value;
        closure.closing_planes = text.str().empty() ? "none" : text.str();
        return closure;
      }
    // Open edges on two different planes normal to every axis.
    closure.closed    = false;
    closure.open_edge = "planes normal to every axis at two different "
                        "positions, which no volume integral along one "
                        "axis can leave out";
    return closure;
  }



#define SOFT_ROBOT_INSTANTIATE(dim)                \
  template CavityClosure find_cavity_closure<dim>( \
    const Parameters::AllParameters &, const Triangulation<dim> &);
  SOFT_ROBOT_FOR_EACH_DIMENSION(SOFT_ROBOT_INSTANTIATE)
#undef SOFT_ROBOT_INSTANTIATE
} // namespace SoftRobot
