// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{The kept tangent, rotated with the body}
//
// The modified Newton method of the time steps solves with a matrix
// assembled at an earlier state $\mathbf u_0$ (the kept matrix). For a body
// that turns, that matrix is the tangent of the body in its old
// orientation. In the total Lagrangian formulation a rigid rotation
// $\mathbf Q$ superposed on a state changes the first Piola-Kirchhoff
// stress to $\mathbf Q\mathbf P$ and its tangent to $\delta\mathbf F
// \mapsto \mathbf Q\,\mathbb A(\mathbf Q^T\delta\mathbf F)$, so the
// stiffness matrix becomes $\mathbf R\mathbf K\mathbf R^T$, where
// $\mathbf R$ applies $\mathbf Q$ to the displacement vector of every
// node. Our estimate, not checked by runs at other ratios of bulk to
// shear modulus: for a nearly incompressible body the mismatch of the
// unrotated matrix is of the order of the bulk modulus times the angle
// turned, which can exceed the shear stiffness after a few degrees; with
// the rotation the mismatch is what the rotation does not explain
// (stretch, and the change of the rotation along the body).
//
// This class turns the solve with the kept matrix into
// $\mathbf x = \mathbf R\,\mathbf K_0^{-1}\mathbf R^T\mathbf r$, with a
// rotation per node: the rotation of the polar decomposition of the
// incremental deformation gradient $\mathbf F(\mathbf u)\mathbf
// F(\mathbf u_0)^{-1}$ at the centre of every cell, averaged over the
// cells around the node and projected back onto the rotations. Only the
// linear solves change; the residual, and with it the converged answer,
// does not. Serial runs of the vector-valued displacement element only.
//
// Implemented in source/solvers/rotated_tangent.cc.

#ifndef soft_robot_solvers_rotated_tangent_h
#define soft_robot_solvers_rotated_tangent_h

#include <array>
#include <deal.II/base/tensor.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/lac/trilinos_vector.h>
#include <vector>

namespace SoftRobot
{
  using namespace dealii;

  template <int dim>
  class RotatedTangent
  {
  public:
    // The nodes (the dim dofs of one support point) of every cell.
    RotatedTangent(const Mapping<dim> &mapping, const DoFHandler<dim> &dofs);

    // The state at which the kept matrix was assembled.
    void
    set_matrix_state(const TrilinosWrappers::MPI::Vector &u);

    // The state at which the kept matrix was assembled (empty before the
    // first set_matrix_state()), for a checkpoint.
    const TrilinosWrappers::MPI::Vector &
    get_matrix_state() const
    {
      return matrix_state;
    }

    // The state the next solve is for (the last evaluated iterate).
    void
    set_iterate(const TrilinosWrappers::MPI::Vector &u);

    // x = R K^{-1} R^T rhs for the rotations from the matrix state to the
    // iterate, with `solve` computing K^{-1}; returns its iterations.
    template <typename Solve>
    unsigned int
    solve(const TrilinosWrappers::MPI::Vector &rhs,
          TrilinosWrappers::MPI::Vector       &x,
          const Solve                         &solve_with_matrix)
    {
      compute_rotations();
      rotated_rhs = rhs;
      rotate(rotated_rhs, true);
      const unsigned int iterations = solve_with_matrix(rotated_rhs, x);
      rotate(x, false);
      return iterations;
    }

    // The largest angle of the node rotations of the last solve, radians.
    double
    largest_angle() const
    {
      return max_angle;
    }

  private:
    void
    compute_rotations();

    // v_node = Q^T v_node (transpose) or Q v_node for every node.
    void
    rotate(TrilinosWrappers::MPI::Vector &v, const bool transpose) const;

    const Mapping<dim>    &mapping;
    const DoFHandler<dim> &dof_handler;

    std::vector<std::array<types::global_dof_index, dim>> nodes;
    // The nodes of every active cell, in the order of the cell iterators.
    std::vector<std::vector<unsigned int>> cell_nodes;
    std::vector<Tensor<2, dim>>            rotations;

    TrilinosWrappers::MPI::Vector matrix_state;
    TrilinosWrappers::MPI::Vector iterate;
    TrilinosWrappers::MPI::Vector rotated_rhs;
    bool                          rotations_current = false;
    double                        max_angle         = 0.;
  };
} // namespace SoftRobot

#endif
