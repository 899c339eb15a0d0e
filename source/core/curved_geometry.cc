// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Curved cells from a second-order mesh}
//
// See include/core/curved_geometry.h.

#include <core/config.h>
#include <core/curved_geometry.h>
#include <deal.II/fe/fe_simplex_p.h>
#include <deal.II/fe/mapping_fe_field.h>
#include <deal.II/lac/full_matrix.h>

namespace SoftRobot
{
  namespace
  {
    // The vertices of deal.II's reference simplex: the origin and the unit
    // vectors.
    template <int dim>
    Point<dim>
    reference_vertex(const unsigned int v)
    {
      Point<dim> point;
      if (v > 0)
        point[v - 1] = 1.;
      return point;
    }
  } // namespace



  // @sect4{CurvedGeometry::CurvedGeometry}
  //
  // The quadratic Lagrange element's support points on a simplex are its
  // vertices and the midpoints of its edges. On a cell of the coarsest
  // level, a vertex's position is the vertex and an edge midpoint's is the
  // mid-edge node of the file (the straight midpoint for an edge the file
  // did not curve). A refined cell takes its positions from its coarsest
  // ancestor's quadratic map.
  template <int dim>
  CurvedGeometry<dim>::CurvedGeometry(const Triangulation<dim> &triangulation,
                                      const MidEdgeNodes<dim>  &mid_edge_nodes)
    : fe(FE_SimplexP<dim>(2), dim)
    , dof_handler(triangulation)
  {
    AssertThrow(dim > 1 && triangulation.all_reference_cells_are_simplex(),
                ExcMessage("Second-order meshes are read for triangles and "
                           "tetrahedra in 2D and 3D only."));
    const std::vector<Point<dim>> &vertices = triangulation.get_vertices();
    for (const auto &[edge, node] : mid_edge_nodes)
      max_offset = std::max(max_offset,
                            node.distance(0.5 * (vertices[edge.first] +
                                                 vertices[edge.second])));

    dof_handler.distribute_dofs(fe);
    positions.reinit(dof_handler.n_dofs());

    const FiniteElement<dim>      &base = fe.base_element(0);
    const std::vector<Point<dim>> &support_point =
      base.get_unit_support_points();
    const unsigned int n_nodes = base.n_dofs_per_cell();

    // Which vertices each support point is the midpoint of (the same
    // vertex twice for a vertex).
    std::vector<std::pair<unsigned int, unsigned int>> node_vertices(n_nodes);
    for (unsigned int j = 0; j < n_nodes; ++j)
      {
        bool found = false;
        for (unsigned int a = 0; a <= dim && !found; ++a)
          for (unsigned int b = a; b <= dim && !found; ++b)
            if (support_point[j].distance(
                  0.5 * (reference_vertex<dim>(a) + reference_vertex<dim>(b))) <
                1e-12)
              {
                node_vertices[j] = {a, b};
                found            = true;
              }
        Assert(found, ExcInternalError());
      }

    std::vector<Point<dim>>              ancestor_nodes(n_nodes);
    std::vector<Point<dim>>              cell_nodes(n_nodes);
    std::vector<types::global_dof_index> dof_indices(fe.n_dofs_per_cell());
    for (const auto &cell : dof_handler.active_cell_iterators())
      {
        typename Triangulation<dim>::cell_iterator ancestor(cell);
        while (ancestor->level() > 0)
          ancestor = ancestor->parent();

        for (unsigned int j = 0; j < n_nodes; ++j)
          {
            const auto [a, b] = node_vertices[j];
            if (a == b)
              ancestor_nodes[j] = ancestor->vertex(a);
            else
              {
                const unsigned int va = ancestor->vertex_index(a);
                const unsigned int vb = ancestor->vertex_index(b);
                const auto         it =
                  mid_edge_nodes.find({std::min(va, vb), std::max(va, vb)});
                ancestor_nodes[j] =
                  (it != mid_edge_nodes.end())
                    ? it->second
                    : Point<dim>(0.5 * (vertices[va] + vertices[vb]));
              }
          }

        if (cell->level() == 0)
          cell_nodes = ancestor_nodes;
        else
          {
            // The refinement placed the cell's vertices affinely in the
            // ancestor's straight-sided simplex: x = v_0 + J xi, with the
            // edge vectors v_k - v_0 as the columns of J.
            FullMatrix<double> jacobian(dim, dim), inverse(dim, dim);
            for (unsigned int k = 0; k < dim; ++k)
              for (unsigned int d = 0; d < dim; ++d)
                jacobian(d, k) =
                  ancestor->vertex(k + 1)[d] - ancestor->vertex(0)[d];
            inverse.invert(jacobian);
            for (unsigned int j = 0; j < n_nodes; ++j)
              {
                const auto [a, b]  = node_vertices[j];
                const Point<dim> x = 0.5 * (cell->vertex(a) + cell->vertex(b));
                Point<dim>       xi;
                for (unsigned int k = 0; k < dim; ++k)
                  for (unsigned int d = 0; d < dim; ++d)
                    xi[k] += inverse(k, d) * (x[d] - ancestor->vertex(0)[d]);
                Point<dim> position;
                for (unsigned int i = 0; i < n_nodes; ++i)
                  position += base.shape_value(i, xi) * ancestor_nodes[i];
                cell_nodes[j] = position;
              }
          }

        cell->get_dof_indices(dof_indices);
        for (unsigned int i = 0; i < fe.n_dofs_per_cell(); ++i)
          {
            const auto [component, node] = fe.system_to_component_index(i);
            positions[dof_indices[i]]    = cell_nodes[node][component];
          }
      }
  }



  template <int dim>
  CurvedGeometry<dim>::~CurvedGeometry()
  {
    dof_handler.clear();
  }



  template <int dim>
  std::unique_ptr<Mapping<dim>>
  CurvedGeometry<dim>::create_mapping() const
  {
    return std::make_unique<MappingFEField<dim, dim, Vector<double>>>(
      dof_handler, positions);
  }



#define SOFT_ROBOT_INSTANTIATE(dim) template class CurvedGeometry<dim>;
  SOFT_ROBOT_FOR_EACH_DIMENSION(SOFT_ROBOT_INSTANTIATE)
#undef SOFT_ROBOT_INSTANTIATE
} // namespace SoftRobot
