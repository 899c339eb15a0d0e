// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Inertia and gravity}
//
// See include/physics/inertia.h.

#include <Epetra_CrsMatrix.h>
#include <Epetra_Map.h>
#include <core/config.h>
#include <deal.II/base/mpi.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>
#include <physics/inertia.h>

namespace SoftRobot
{
  // @sect4{Inertia::compute_densities}
  //
  // Densities: given, or from the mass of the region. The meshed volume of
  // a region times its section is the volume of the modelled part of the
  // body; dividing by the model fraction gives the whole body's.
  template <int dim>
  void
  Inertia<dim>::compute_densities(const Parameters::AllParameters &parameters,
                                  const Mapping<dim>              &mapping,
                                  const DoFHandler<dim>           &dof_handler,
                                  const Quadrature<dim>           &quadrature,
                                  const MPI_Comm mpi_communicator)
  {
    std::map<types::material_id, double> region_volume;
    FEValues<dim>                        fe_values(mapping,
                            dof_handler.get_fe(),
                            quadrature,
                            update_JxW_values);
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          for (const unsigned int q : fe_values.quadrature_point_indices())
            region_volume[cell->material_id()] += fe_values.JxW(q);
        }
    densities.clear();
    for (const auto &[id, material] : parameters.by_id)
      {
        const double volume =
          Utilities::MPI::sum(region_volume[id], mpi_communicator);
        if (material.mass > 0)
          {
            AssertThrow(volume > 0,
                        ExcMessage("In '" + parameters.source_name +
                                   "': Material " + std::to_string(id) +
                                   "/Mass is given, but no "
                                   "cell of the mesh has this material id."));
            densities[id] = material.mass * parameters.model_fraction /
                            (volume * material.section);
          }
        else
          densities[id] = material.density;
        if (volume > 0 &&
            Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
          std::cout << "Material " << id << " (" << material.name
                    << "): mu = " << material.shear_modulus
                    << " kPa, density = " << densities[id]
                    << " kg/mm^3, mass in the model = "
                    << densities[id] * volume * material.section << " kg"
                    << std::endl;
      }
  }



  // @sect4{Inertia::reinit}
  //
  // The nodes of a cell are the support points of the scalar base element;
  // node n carries the dofs component_to_system_index(c, n).
  template <int dim>
  void
  Inertia<dim>::reinit(const Parameters::AllParameters &parameters,
                       const Mapping<dim>              &mapping,
                       const DoFHandler<dim>           &dof_handler,
                       const Quadrature<dim>           &volume_quadrature,
                       const Quadrature<dim>           &quadrature,
                       const AffineConstraints<double> &constraints,
                       const MPI_Comm                   mpi_communicator)
  {
    compute_densities(
      parameters, mapping, dof_handler, volume_quadrature, mpi_communicator);

    const FiniteElement<dim> &fe = dof_handler.get_fe();
    FEValues<dim>             fe_values(mapping,
                            fe,
                            quadrature,
                            update_values | update_JxW_values);
    const unsigned int        dofs_per_cell = fe.n_dofs_per_cell();
    FullMatrix<double>        cell_matrix(dofs_per_cell, dofs_per_cell);
    Vector<double>            cell_gravity(dofs_per_cell);
    std::vector<types::global_dof_index> dof_indices(dofs_per_cell);
    const FEValuesExtractors::Vector     displacements(0);
    Tensor<1, dim>                       gravity;
    for (unsigned int d = 0; d < dim; ++d)
      gravity[d] = parameters.gravity[d];

    gravity_force.reinit(dof_handler.locally_owned_dofs(), mpi_communicator);
    mass                   = 0.;
    const bool mass_damped = has_mass_damping(parameters);
    if (mass_damped)
      mass_damping = 0.;
    const unsigned int nodes_per_cell = fe.base_element(0).n_dofs_per_cell();
    const std::vector<Point<dim>> &unit_nodes =
      fe.base_element(0).get_unit_support_points();
    cell_nodal_mass.clear();
    cell_node_positions.clear();
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          cell_matrix        = 0.;
          cell_gravity       = 0.;
          const double rho_A = densities.at(cell->material_id()) *
                               parameters.by_id.at(cell->material_id()).section;
          for (const unsigned int q : fe_values.quadrature_point_indices())
            for (const unsigned int i : fe_values.dof_indices())
              {
                const Tensor<1, dim> N_i = fe_values[displacements].value(i, q);
                cell_gravity(i) += rho_A * N_i * gravity * fe_values.JxW(q);
                for (const unsigned int j : fe_values.dof_indices())
                  cell_matrix(i, j) += rho_A * N_i *
                                       fe_values[displacements].value(j, q) *
                                       fe_values.JxW(q);
              }
          for (unsigned int n = 0; n < nodes_per_cell; ++n)
            {
              cell_node_positions.push_back(
                mapping.transform_unit_to_real_cell(cell, unit_nodes[n]));
              for (unsigned int k = 0; k < nodes_per_cell; ++k)
                cell_nodal_mass.push_back(
                  cell_matrix(fe.component_to_system_index(0, n),
                              fe.component_to_system_index(0, k)));
            }
          cell->get_dof_indices(dof_indices);
          constraints.distribute_local_to_global(
            cell_matrix, cell_gravity, dof_indices, mass, gravity_force);
          const double alpha =
            parameters.by_id.at(cell->material_id()).mass_damping;
          if (mass_damped && alpha > 0.)
            {
              cell_matrix *= alpha;
              constraints.distribute_local_to_global(cell_matrix,
                                                     dof_indices,
                                                     mass_damping);
            }
        }
    mass.compress(VectorOperation::add);
    copy_nonzero_entries(mass, compact_mass);
    if (mass_damped)
      {
        mass_damping.compress(VectorOperation::add);
        copy_nonzero_entries(mass_damping, compact_mass_damping);
      }
    gravity_force.compress(VectorOperation::add);
  }



  // @sect4{Inertia::copy_nonzero_entries}
  //
  // Row by row from the Epetra matrix's own arrays (a row's columns are
  // local indices of its column map): first the pattern of the locally
  // owned rows' nonzero entries, then their values. The rows keep the
  // partition of `full`; the columns are those of the entries, owned or
  // not.
  template <int dim>
  void
  Inertia<dim>::copy_nonzero_entries(const TrilinosWrappers::SparseMatrix &full,
                                     TrilinosWrappers::SparseMatrix &compact)
  {
    const Epetra_CrsMatrix &matrix       = full.trilinos_matrix();
    const MPI_Comm          communicator = full.get_mpi_communicator();
    std::vector<std::vector<types::global_dof_index>> columns(
      matrix.NumMyRows());
    std::vector<std::vector<double>> values(matrix.NumMyRows());
    std::size_t                      zeros = 0;
    for (int row = 0; row < matrix.NumMyRows(); ++row)
      {
        int     n_entries;
        double *row_values;
        int    *row_columns;
        matrix.ExtractMyRowView(row, n_entries, row_values, row_columns);
        for (int k = 0; k < n_entries; ++k)
          if (row_values[k] != 0.)
            {
              columns[row].push_back(matrix.ColMap().GID64(row_columns[k]));
              values[row].push_back(row_values[k]);
            }
          else
            ++zeros;
      }
    if (Utilities::MPI::sum(zeros, communicator) == 0)
      {
        compact.clear();
        return;
      }

    TrilinosWrappers::SparsityPattern pattern(
      full.locally_owned_range_indices(), communicator);
    for (int row = 0; row < matrix.NumMyRows(); ++row)
      pattern.add_entries(matrix.RowMap().GID64(row),
                          columns[row].begin(),
                          columns[row].end());
    pattern.compress();
    compact.reinit(pattern);
    for (int row = 0; row < matrix.NumMyRows(); ++row)
      compact.set(matrix.RowMap().GID64(row),
                  columns[row].size(),
                  columns[row].data(),
                  values[row].data());
    compact.compress(VectorOperation::insert);
  }



  template <int dim>
  bool
  Inertia<dim>::has_mass_damping(const Parameters::AllParameters &parameters)
  {
    for (const auto &[id, material] : parameters.by_id)
      if (material.mass_damping > 0.)
        return true;
    return false;
  }



  // @sect4{Inertia::angular_momentum}
  //
  // $\mathbf L = \sum_{\text{cells}}\sum_{n,k} m_{nk}\,\mathbf x_n\times
  // \mathbf v_k$ with the scalar cell mass matrices $m_{nk} = \int\rho_0
  // \varphi_n\varphi_k\,dV$ and the nodal positions and velocities.
  template <int dim>
  Tensor<1, 3>
  Inertia<dim>::angular_momentum(const DoFHandler<dim> &dof_handler,
                                 const TrilinosWrappers::MPI::Vector &u,
                                 const TrilinosWrappers::MPI::Vector &v,
                                 const MPI_Comm mpi_communicator) const
  {
    Tensor<1, 3> L;
    if constexpr (dim > 1)
      {
        const FiniteElement<dim> &fe = dof_handler.get_fe();
        const unsigned int        nodes_per_cell =
          fe.base_element(0).n_dofs_per_cell();
        std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
        std::vector<Tensor<1, dim>> x(nodes_per_cell), velocity(nodes_per_cell);
        unsigned int                cell_number = 0;
        for (const auto &cell : dof_handler.active_cell_iterators())
          if (cell->is_locally_owned())
            {
              cell->get_dof_indices(dofs);
              for (unsigned int n = 0; n < nodes_per_cell; ++n)
                for (unsigned int c = 0; c < dim; ++c)
                  {
                    const unsigned int i = fe.component_to_system_index(c, n);
                    x[n][c] =
                      cell_node_positions[cell_number * nodes_per_cell + n][c] +
                      u(dofs[i]);
                    velocity[n][c] = v(dofs[i]);
                  }
              const double *m =
                &cell_nodal_mass[cell_number * nodes_per_cell * nodes_per_cell];
              for (unsigned int n = 0; n < nodes_per_cell; ++n)
                {
                  Tensor<1, dim> p;
                  for (unsigned int k = 0; k < nodes_per_cell; ++k)
                    p += m[n * nodes_per_cell + k] * velocity[k];
                  if constexpr (dim == 3)
                    L += cross_product_3d(x[n], p);
                  else
                    L[2] += x[n][0] * p[1] - x[n][1] * p[0];
                }
              ++cell_number;
            }
        for (unsigned int d = 0; d < 3; ++d)
          L[d] = Utilities::MPI::sum(L[d], mpi_communicator);
      }
    return L;
  }



#define SOFT_ROBOT_INSTANTIATE(dim) template class Inertia<dim>;
  SOFT_ROBOT_FOR_EACH_DIMENSION(SOFT_ROBOT_INSTANTIATE)
#undef SOFT_ROBOT_INSTANTIATE
} // namespace SoftRobot
