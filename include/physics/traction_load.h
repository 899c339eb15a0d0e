// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Nominal tractions on the boundary}
//
// The dead load $\bar{\mathbf t}(\mathbf X, t)$ per unit reference area on
// the boundaries the parameter file names (`Loads and constraints/Traction
// boundary ids`), a function of the reference position and time given as
// an expression (`Loads and constraints/Traction`); its nodal forces are
// $\int_{\Gamma_\text{N}} \mathbf N_i\cdot\bar{\mathbf t}\,dA$ (times the
// section factor of the reduced models). The faces and what their forces
// need in the reference configuration, which never changes, are computed
// once: the quadrature points, and per point the values of the scalar shape
// functions times the weight and the section factor. The traction is
// evaluated at the points every step; faces where it vanishes -- every face
// after a release -- add nothing.
//
// Implemented in source/physics/traction_load.cc.

#ifndef soft_robot_physics_traction_load_h
#define soft_robot_physics_traction_load_h

#include <core/parameters.h>
#include <deal.II/base/function_parser.h>
#include <deal.II/base/quadrature.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/trilinos_vector.h>
#include <vector>

namespace SoftRobot
{
  using namespace dealii;

  template <int dim>
  class TractionLoad
  {
  public:
    // Parses the traction expression (errors name the entry).
    explicit TractionLoad(const Parameters::AllParameters &parameters);

    // The faces of the locally owned cells on the loaded boundaries.
    void
    reinit(const Mapping<dim>        &mapping,
           const DoFHandler<dim>     &dof_handler,
           const Quadrature<dim - 1> &quadrature);

    // Whether any boundary is loaded.
    bool
    empty() const
    {
      return boundary_ids.empty();
    }

    // Adds the nodal forces of the tractions at `time` to `force` (which
    // must be compressed by the caller).
    void
    add_forces(const double                     time,
               const AffineConstraints<double> &constraints,
               TrilinosWrappers::MPI::Vector   &force) const;

  private:
    const Parameters::AllParameters &parameters;
    std::vector<unsigned int>        boundary_ids;
    mutable FunctionParser<dim>      traction;

    unsigned int                         n_faces       = 0;
    unsigned int                         n_q_points    = 0;
    unsigned int                         dofs_per_cell = 0;
    std::vector<unsigned int>            components;
    std::vector<types::global_dof_index> dof_indices;
    std::vector<Point<dim>>              points;
    std::vector<double>                  weighted_shape_values;
  };
} // namespace SoftRobot

#endif
