// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Guards against runs without physical meaning}
//
// See include/core/plausibility_guard.h.

#include <cmath>
#include <core/config.h>
#include <core/exceptions.h>
#include <core/plausibility_guard.h>
#include <deal.II/base/utilities.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/grid_tools.h>
#include <limits>
#include <set>
#include <sstream>

namespace SoftRobot
{
  namespace
  {
    std::string
    number_text(const double value)
    {
      std::ostringstream text;
      text << std::setprecision(4) << value;
      return text.str();
    }

    // The outward unit normal of a boundary face (from its vertices, away
    // from the centre of its cell).
    template <typename CellIterator, typename FaceIterator, int dim>
    Tensor<1, dim>
    outward_normal(const CellIterator &cell, const FaceIterator &face)
    {
      Tensor<1, dim> normal;
      if constexpr (dim == 1)
        normal[0] = 1.;
      else if constexpr (dim == 2)
        {
          const Tensor<1, dim> edge = face->vertex(1) - face->vertex(0);
          normal[0]                 = edge[1];
          normal[1]                 = -edge[0];
        }
      else
        normal = cross_product_3d(face->vertex(1) - face->vertex(0),
                                  face->vertex(2) - face->vertex(0));
      if (normal * (face->center() - cell->center()) < 0)
        normal *= -1.;
      return normal / normal.norm();
    }
  } // namespace



  // @sect4{PlausibilityGuard::reinit}
  template <int dim>
  void
  PlausibilityGuard<dim>::reinit(
    const Parameters::AllParameters                       &parameters,
    const Mapping<dim>                                    &mapping,
    const DoFHandler<dim>                                 &dof_handler,
    const std::function<double(const types::material_id)> &density,
    const MPI_Comm                                         communicator)
  {
    mpi_communicator                        = communicator;
    const Triangulation<dim> &triangulation = dof_handler.get_triangulation();
    const auto   box  = GridTools::compute_bounding_box(triangulation);
    const double size = box.get_boundary_points().first.distance(
      box.get_boundary_points().second);
    crossing_tolerance = 0.02 * size;

    if (parameters.runaway_displacement > 0)
      {
        max_displacement    = parameters.runaway_displacement;
        displacement_origin = "Problem/Run-away displacement";
      }
    else
      {
        max_displacement    = 10. * size;
        displacement_origin = "ten times the size of the body, " +
                              number_text(size) +
                              " mm; Problem/Run-away displacement sets it";
      }

    std::set<types::material_id> used;
    for (const auto &cell : triangulation.active_cell_iterators())
      used.insert(cell->material_id());
    double slowest = std::numeric_limits<double>::max();
    for (const types::material_id id : used)
      slowest = std::min(slowest,
                         std::sqrt(parameters.by_id.at(id).shear_modulus /
                                   density(id)));
    if (parameters.runaway_speed > 0)
      {
        max_speed    = parameters.runaway_speed;
        speed_origin = "Problem/Run-away speed";
      }
    else
      {
        max_speed    = 10. * slowest;
        speed_origin = "ten times the shear wave speed of the softest "
                       "material, " +
                       number_text(slowest) +
                       " mm/s; Problem/Run-away speed sets it";
      }

    // The plane fixed boundaries whose normal displacement is fixed.
    planes.clear();
    for (const auto &[boundary_id, letters] : parameters.fixed_components)
      {
        bool       found = false, planar = true;
        FixedPlane plane{boundary_id, Point<dim>(), Tensor<1, dim>()};
        for (const auto &cell : triangulation.active_cell_iterators())
          for (const auto &face : cell->face_iterators())
            if (face->at_boundary() && face->boundary_id() == boundary_id)
              {
                if (!found)
                  {
                    plane.point = face->vertex(0);
                    plane.outward_normal =
                      outward_normal<decltype(cell), decltype(face), dim>(cell,
                                                                          face);
                    found = true;
                  }
                for (const unsigned int v : face->vertex_indices())
                  if (std::abs((face->vertex(v) - plane.point) *
                               plane.outward_normal) > 1e-8 * size)
                    planar = false;
              }
        bool normal_fixed = true;
        for (unsigned int d = 0; d < dim; ++d)
          if (std::abs(plane.outward_normal[d]) > 1e-8 &&
              letters.find(static_cast<char>('x' + d)) == std::string::npos)
            normal_fixed = false;
        if (found && planar && normal_fixed)
          planes.push_back(plane);
      }

    // The nodes of the locally owned cells whose dofs this process owns.
    node_positions.clear();
    node_dofs.clear();
    if (planes.empty())
      return;
    const FiniteElement<dim> &fe = dof_handler.get_fe();
    const Quadrature<dim> support(fe.base_element(0).get_unit_support_points());
    FEValues<dim>   fe_values(mapping, fe, support, update_quadrature_points);
    const IndexSet &owned = dof_handler.locally_owned_dofs();
    std::vector<types::global_dof_index> dof_indices(fe.n_dofs_per_cell());
    std::set<types::global_dof_index>    seen;
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          cell->get_dof_indices(dof_indices);
          for (unsigned int n = 0; n < support.size(); ++n)
            {
              std::array<types::global_dof_index, dim> dofs;
              for (unsigned int c = 0; c < dim; ++c)
                dofs[c] = dof_indices[fe.component_to_system_index(c, n)];
              if (owned.is_element(dofs[0]) && seen.insert(dofs[0]).second)
                {
                  node_positions.push_back(fe_values.quadrature_point(n));
                  node_dofs.push_back(dofs);
                }
            }
        }
  }



  // @sect4{PlausibilityGuard::check_finite}
  template <int dim>
  void
  PlausibilityGuard<dim>::check_finite(
    const double                                       time,
    const std::vector<std::pair<std::string, double>> &values) const
  {
    for (const auto &[name, value] : values)
      if (!std::isfinite(value) || std::abs(value) > 3.4e38)
        throw RunAborted(
          "At t = " + number_text(time) + " s the state is " +
          (std::isfinite(value) ? "beyond the range the output can store"
                                : "no longer finite") +
          " (" + name + " = " + number_text(value) +
          "); it is not written. The output up to the step before has been "
          "kept.");
  }



  // @sect4{PlausibilityGuard::check_motion}
  template <int dim>
  void
  PlausibilityGuard<dim>::check_motion(
    const double                         time,
    const Tensor<1, dim>                &tip_displacement,
    const Tensor<1, dim>                &tip_velocity,
    const TrilinosWrappers::MPI::Vector &u) const
  {
    const std::string at = "At t = " + number_text(time) + " s ";
    const std::string kept =
      " The motion has no physical reading beyond this point (a load far "
      "beyond what the body can carry?); the output up to this time has "
      "been kept.";
    if (tip_displacement.norm() > max_displacement)
      throw RunAborted(at + "the tip has moved by " +
                       number_text(tip_displacement.norm()) +
                       " mm, more than the run-away displacement of " +
                       number_text(max_displacement) + " mm (" +
                       displacement_origin + ")." + kept);
    if (tip_velocity.norm() > max_speed)
      throw RunAborted(
        at + "the tip moves at " + number_text(tip_velocity.norm()) +
        " mm/s, faster than the run-away speed of " + number_text(max_speed) +
        " mm/s (" + speed_origin + ")." + kept);
    for (const FixedPlane &plane : planes)
      {
        double depth = 0.;
        for (unsigned int n = 0; n < node_positions.size(); ++n)
          {
            Point<dim> x = node_positions[n];
            for (unsigned int c = 0; c < dim; ++c)
              x[c] += u(node_dofs[n][c]);
            depth = std::max(depth, (x - plane.point) * plane.outward_normal);
          }
        depth = Utilities::MPI::max(depth, mpi_communicator);
        if (depth > crossing_tolerance)
          throw RunAborted(
            at + "the body has passed through its fixed boundary " +
            std::to_string(plane.boundary_id) +
            " (Loads and constraints/Fixed components): a point lies " +
            number_text(depth) + " mm beyond the plane of that boundary." +
            kept);
      }
  }



#define SOFT_ROBOT_INSTANTIATE(dim) template class PlausibilityGuard<dim>;
  SOFT_ROBOT_FOR_EACH_DIMENSION(SOFT_ROBOT_INSTANTIATE)
#undef SOFT_ROBOT_INSTANTIATE
} // namespace SoftRobot
