// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Implementation of the RotatedTangent class}

#include <cmath>
#include <deal.II/base/exceptions.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>
#include <solvers/rotated_tangent.h>

namespace SoftRobot
{
  namespace
  {
    // The rotation of the polar decomposition A = Q U (det A > 0), by
    // Higham's iteration Q <- (Q + Q^{-T}) / 2.
    template <int dim>
    Tensor<2, dim>
    polar_rotation(const Tensor<2, dim> &A)
    {
      Tensor<2, dim> Q = A;
      for (unsigned int k = 0; k < 50; ++k)
        {
          const Tensor<2, dim> next   = 0.5 * (Q + transpose(invert(Q)));
          const double         change = (next - Q).norm();
          Q                           = next;
          if (change < 1e-13 * Q.norm())
            break;
        }
      return Q;
    }
  } // namespace



  // @sect4{RotatedTangent::RotatedTangent}
  //
  // A node is the set of dim dofs of one support point; it is found by the
  // global index of its first component.
  template <int dim>
  RotatedTangent<dim>::RotatedTangent(const Mapping<dim>    &mapping,
                                      const DoFHandler<dim> &dof_handler)
    : mapping(mapping)
    , dof_handler(dof_handler)
  {
    const auto &fe = dof_handler.get_fe();
    AssertThrow(fe.n_components() == dim && fe.n_base_elements() == 1,
                ExcMessage("The rotated tangent needs the vector-valued "
                           "displacement element FESystem(FE_Q, dim)."));
    const unsigned int nodes_per_cell = fe.base_element(0).n_dofs_per_cell();
    std::vector<unsigned int>            node_of_first_dof(dof_handler.n_dofs(),
                                                numbers::invalid_unsigned_int);
    std::vector<types::global_dof_index> dof_indices(fe.n_dofs_per_cell());
    for (const auto &cell : dof_handler.active_cell_iterators())
      {
        cell->get_dof_indices(dof_indices);
        std::vector<std::array<types::global_dof_index, dim>> cell_dofs(
          nodes_per_cell);
        for (unsigned int i = 0; i < fe.n_dofs_per_cell(); ++i)
          {
            const auto component_and_node = fe.system_to_component_index(i);
            cell_dofs[component_and_node.second][component_and_node.first] =
              dof_indices[i];
          }
        std::vector<unsigned int> ids(nodes_per_cell);
        for (unsigned int k = 0; k < nodes_per_cell; ++k)
          {
            unsigned int &id = node_of_first_dof[cell_dofs[k][0]];
            if (id == numbers::invalid_unsigned_int)
              {
                id = nodes.size();
                nodes.push_back(cell_dofs[k]);
              }
            ids[k] = id;
          }
        cell_nodes.push_back(std::move(ids));
      }
    rotations.resize(nodes.size(), unit_symmetric_tensor<dim>());
  }



  template <int dim>
  void
  RotatedTangent<dim>::set_matrix_state(const TrilinosWrappers::MPI::Vector &u)
  {
    matrix_state      = u;
    rotations_current = false;
  }



  template <int dim>
  void
  RotatedTangent<dim>::set_iterate(const TrilinosWrappers::MPI::Vector &u)
  {
    iterate           = u;
    rotations_current = false;
  }



  // @sect4{RotatedTangent::compute_rotations}
  //
  // Per cell the incremental deformation gradient at the centre, its
  // rotation added to the cell's nodes; per node the sum projected onto
  // the rotations (the polar factor of a sum of rotations is their mean
  // in the sense of the chordal distance).
  template <int dim>
  void
  RotatedTangent<dim>::compute_rotations()
  {
    if (rotations_current)
      return;
    rotations_current = true;
    max_angle         = 0.;
    if (matrix_state.size() == 0 || iterate.size() == 0)
      {
        std::fill(rotations.begin(),
                  rotations.end(),
                  Tensor<2, dim>(unit_symmetric_tensor<dim>()));
        return;
      }
    std::vector<Tensor<2, dim>>      sums(nodes.size());
    const QGauss<dim>                centre(1);
    FEValues<dim>                    fe_values(mapping,
                            dof_handler.get_fe(),
                            centre,
                            update_gradients);
    const FEValuesExtractors::Vector displacement(0);
    std::vector<Tensor<2, dim>>      old_gradient(1), new_gradient(1);
    const Tensor<2, dim>             identity(unit_symmetric_tensor<dim>());
    unsigned int                     c = 0;
    for (const auto &cell : dof_handler.active_cell_iterators())
      {
        fe_values.reinit(cell);
        fe_values[displacement].get_function_gradients(matrix_state,
                                                       old_gradient);
        fe_values[displacement].get_function_gradients(iterate, new_gradient);
        const Tensor<2, dim> increment =
          (identity + new_gradient[0]) * invert(identity + old_gradient[0]);
        const Tensor<2, dim> Q =
          determinant(increment) > 0. ? polar_rotation(increment) : identity;
        for (const unsigned int id : cell_nodes[c])
          sums[id] += Q;
        ++c;
      }
    for (unsigned int n = 0; n < nodes.size(); ++n)
      {
        rotations[n] =
          determinant(sums[n]) > 0. ? polar_rotation(sums[n]) : identity;
        const double cosine = dim == 3   ? 0.5 * (trace(rotations[n]) - 1.)
                              : dim == 2 ? 0.5 * trace(rotations[n])
                                         : 1.;
        max_angle =
          std::max(max_angle, std::acos(std::min(1., std::max(-1., cosine))));
      }
  }



  template <int dim>
  void
  RotatedTangent<dim>::rotate(TrilinosWrappers::MPI::Vector &v,
                              const bool                     transpose) const
  {
    for (unsigned int n = 0; n < nodes.size(); ++n)
      {
        Tensor<1, dim> value;
        for (unsigned int d = 0; d < dim; ++d)
          value[d] = v[nodes[n][d]];
        const Tensor<1, dim> result =
          transpose ? value * rotations[n] : rotations[n] * value;
        for (unsigned int d = 0; d < dim; ++d)
          v[nodes[n][d]] = result[d];
      }
  }



  template class RotatedTangent<1>;
  template class RotatedTangent<2>;
  template class RotatedTangent<3>;
} // namespace SoftRobot
