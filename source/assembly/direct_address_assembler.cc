// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{The fast global addition: precomputed addresses}
//
// See include/assembly/direct_address_assembler.h.

#include <Epetra_CrsMatrix.h>
#include <Epetra_Import.h>
#include <Epetra_Map.h>
#include <Epetra_Vector.h>
#include <algorithm>
#include <array>
#include <assembly/direct_address_assembler.h>
#include <core/config.h>
#include <deal.II/base/multithread_info.h>
#include <deal.II/base/thread_management.h>

namespace SoftRobot
{
  // @sect4{DirectAddressAssembler::create}
  //
  // All processes take the same decision, since setting up the ghost
  // exchange is a collective operation.
  template <int dim>
  std::unique_ptr<SystemAssembler<dim>>
  DirectAddressAssembler<dim>::create(
    const CellGeometry<dim>              &geometry,
    const AffineConstraints<double>      &constraints,
    const IndexSet                       &locally_owned_dofs,
    const IndexSet                       &locally_relevant_dofs,
    const TrilinosWrappers::SparseMatrix &matrix,
    const TrilinosWrappers::SparseMatrix *second_matrix,
    const TrilinosWrappers::MPI::Vector  &vector,
    const MPI_Comm                        mpi_communicator)
  {
    const bool everywhere =
      Utilities::MPI::min(usable(constraints, matrix, second_matrix) ? 1 : 0,
                          mpi_communicator) == 1;
    if (!everywhere)
      return std::make_unique<SystemAssembler<dim>>(geometry,
                                                    constraints,
                                                    locally_owned_dofs,
                                                    locally_relevant_dofs,
                                                    mpi_communicator);
    return std::unique_ptr<SystemAssembler<dim>>(
      new DirectAddressAssembler<dim>(geometry,
                                      constraints,
                                      locally_owned_dofs,
                                      locally_relevant_dofs,
                                      matrix,
                                      vector,
                                      mpi_communicator));
  }



  // @sect4{DirectAddressAssembler::usable}
  //
  // Homogeneous constraints only, matrices whose value arrays Epetra hands
  // out, and a second matrix with the same rows, columns and offsets, so
  // that one set of addresses serves both.
  template <int dim>
  bool
  DirectAddressAssembler<dim>::usable(
    const AffineConstraints<double>      &constraints,
    const TrilinosWrappers::SparseMatrix &matrix,
    const TrilinosWrappers::SparseMatrix *second_matrix)
  {
    for (const auto &line : constraints.get_lines())
      if (!line.entries.empty() || line.inhomogeneity != 0.)
        return false;
    int                    *offsets = nullptr, *columns = nullptr;
    double                 *values = nullptr;
    const Epetra_CrsMatrix &A      = matrix.trilinos_matrix();
    if (A.ExtractCrsDataPointers(offsets, columns, values) != 0)
      return false;
    if (second_matrix == nullptr)
      return true;
    int                    *second_offsets = nullptr, *second_columns = nullptr;
    double                 *second_values = nullptr;
    const Epetra_CrsMatrix &B             = second_matrix->trilinos_matrix();
    return B.ExtractCrsDataPointers(second_offsets,
                                    second_columns,
                                    second_values) == 0 &&
           B.RowMap().SameAs(A.RowMap()) && B.ColMap().SameAs(A.ColMap()) &&
           B.NumMyNonzeros() == A.NumMyNonzeros() &&
           std::equal(columns, columns + A.NumMyNonzeros(), second_columns) &&
           std::equal(offsets, offsets + A.NumMyRows() + 1, second_offsets);
  }



  template <int dim>
  DirectAddressAssembler<dim>::DirectAddressAssembler(
    const CellGeometry<dim>              &geometry,
    const AffineConstraints<double>      &constraints,
    const IndexSet                       &locally_owned_dofs,
    const IndexSet                       &locally_relevant_dofs,
    const TrilinosWrappers::SparseMatrix &matrix,
    const TrilinosWrappers::MPI::Vector  &vector,
    const MPI_Comm                        mpi_communicator)
    : SystemAssembler<dim>(geometry,
                           constraints,
                           locally_owned_dofs,
                           locally_relevant_dofs,
                           mpi_communicator)
    , serial(Utilities::MPI::n_mpi_processes(mpi_communicator) == 1)
  {
    if (!serial)
      setup_ghost_exchange(vector);
    compute_matrix_addresses(matrix, vector);
  }



  template <int dim>
  DirectAddressAssembler<dim>::~DirectAddressAssembler() = default;



  // @sect4{DirectAddressAssembler::setup_ghost_exchange}
  //
  // The ghost vectors: the free dofs of this process's cells that another
  // process owns, in increasing order.
  template <int dim>
  void
  DirectAddressAssembler<dim>::setup_ghost_exchange(
    const TrilinosWrappers::MPI::Vector &vector)
  {
    std::vector<TrilinosWrappers::types::int_type> ghosts;
    for (const types::global_dof_index dof : this->geometry.dof_indices)
      if (!this->locally_owned_dofs.is_element(dof) &&
          !this->constraints.is_constrained(dof))
        ghosts.push_back(static_cast<TrilinosWrappers::types::int_type>(dof));
    std::sort(ghosts.begin(), ghosts.end());
    ghosts.erase(std::unique(ghosts.begin(), ghosts.end()), ghosts.end());
    const Epetra_BlockMap &vector_map = vector.trilinos_vector().Map();
    ghost_map                         = std::make_unique<Epetra_Map>(
      -1, static_cast<int>(ghosts.size()), ghosts.data(), 0, vector_map.Comm());
    ghost_import = std::make_unique<Epetra_Import>(*ghost_map, vector_map);
    ghost_values = std::make_unique<Epetra_Vector>(*ghost_map);
    ghost_force  = std::make_unique<Epetra_Vector>(*ghost_map);
    ghost_second_force = std::make_unique<Epetra_Vector>(*ghost_map);
  }



  // @sect4{DirectAddressAssembler::compute_matrix_addresses}
  template <int dim>
  void
  DirectAddressAssembler<dim>::compute_matrix_addresses(
    const TrilinosWrappers::SparseMatrix &global_matrix,
    const TrilinosWrappers::MPI::Vector  &vector)
  {
    const CellGeometry<dim>         &geometry    = this->geometry;
    const AffineConstraints<double> &constraints = this->constraints;
    int                             *row_offsets = nullptr, *columns = nullptr;
    double                          *values = nullptr;
    const Epetra_CrsMatrix          &matrix = global_matrix.trilinos_matrix();
    matrix.ExtractCrsDataPointers(row_offsets, columns, values);
    const Epetra_BlockMap &vector_map = vector.trilinos_vector().Map();

    // The position of entry (row, column) in the value array.
    const auto position = [&](const types::global_dof_index row,
                              const types::global_dof_index column) {
      const int local_row    = matrix.LRID(static_cast<int>(row));
      const int local_column = matrix.LCID(static_cast<int>(column));
      AssertThrow(local_row >= 0 && local_column >= 0, ExcInternalError());
      for (int k = row_offsets[local_row]; k < row_offsets[local_row + 1]; ++k)
        if (columns[k] == local_column)
          return k;
      AssertThrow(false, ExcMessage("A cell's entry is not in the matrix."));
      return -1;
    };

    const unsigned int n = geometry.dofs_per_cell;
    matrix_positions.resize(geometry.dof_indices.size() * n);
    diagonal_positions.resize(geometry.dof_indices.size());
    vector_positions.resize(geometry.dof_indices.size());
    for (unsigned int cell = 0; cell < geometry.n_cells; ++cell)
      {
        const types::global_dof_index *dofs = &geometry.dof_indices[cell * n];
        for (unsigned int i = 0; i < n; ++i)
          {
            const unsigned int            k   = cell * n + i;
            const types::global_dof_index dof = dofs[i];
            const bool fixed                  = constraints.is_constrained(dof);
            const bool owned = this->locally_owned_dofs.is_element(dof);
            if (fixed)
              vector_positions[k] = -1;
            else if (owned)
              vector_positions[k] = vector_map.LID(
                static_cast<TrilinosWrappers::types::int_type>(dof));
            else
              vector_positions[k] =
                -2 - ghost_map->LID(
                       static_cast<TrilinosWrappers::types::int_type>(dof));
            if (!owned)
              {
                diagonal_positions[k] = -2;
                for (unsigned int j = 0; j < n; ++j)
                  matrix_positions[k * n + j] = -2;
                continue;
              }
            diagonal_positions[k] = fixed ? position(dof, dof) : -1;
            for (unsigned int j = 0; j < n; ++j)
              matrix_positions[k * n + j] =
                (fixed || constraints.is_constrained(dofs[j]))
                  ? -1
                  : position(dof, dofs[j]);
          }
      }
  }



  // @sect4{DirectAddressAssembler::gather}
  //
  // Straight from the vector's value array, with the entries of other
  // processes fetched first.
  template <int dim>
  void
  DirectAddressAssembler<dim>::gather(
    const TrilinosWrappers::MPI::Vector &global,
    std::vector<double>                 &cell_values) const
  {
    const double *values = global.trilinos_vector()[0];
    const double *ghosts = nullptr;
    if (!serial)
      {
        ghost_values->Import(global.trilinos_vector(), *ghost_import, Insert);
        ghosts = ghost_values->Values();
      }
    cell_values.resize(vector_positions.size());
    for (std::size_t k = 0; k < cell_values.size(); ++k)
      {
        const int position = vector_positions[k];
        cell_values[k]     = (position >= 0)    ? values[position]
                             : (position == -1) ? 0.
                                                : ghosts[-2 - position];
      }
  }



  template <int dim>
  void
  DirectAddressAssembler<dim>::begin(
    const AssemblyRequest                        &request,
    const typename SystemAssembler<dim>::Targets &targets)
  {
    int *offsets = nullptr, *columns = nullptr;
    if (request.matrix)
      targets.matrix->trilinos_matrix().ExtractCrsDataPointers(offsets,
                                                               columns,
                                                               matrix_values);
    if (request.second_matrix)
      targets.second_matrix->trilinos_matrix().ExtractCrsDataPointers(
        offsets, columns, second_matrix_values);
    force_values = targets.force->trilinos_vector()[0];
    if (request.second_force)
      second_force_values = targets.second_force->trilinos_vector()[0];
    forces_in_halves = serial && request.matrix;
    if (forces_in_halves)
      for (unsigned int half = 0; half < 2; ++half)
        {
          half_force[half].assign(targets.force->locally_owned_size(), 0.);
          if (request.second_force)
            half_second_force[half].assign(targets.force->locally_owned_size(),
                                           0.);
        }
    if (!serial)
      {
        ghost_force->PutScalar(0.);
        ghost_second_force->PutScalar(0.);
      }
  }



  // @sect4{DirectAddressAssembler::add_matrix}
  //
  // A row of another process (address -2) goes through Epetra, which sends
  // it to its owner when the matrix is compressed.
  template <int dim>
  void
  DirectAddressAssembler<dim>::add_matrix(
    const CellContribution<dim>    &local,
    const FullMatrix<double>       &cell_matrix,
    double                         *values,
    TrilinosWrappers::SparseMatrix &matrix) const
  {
    const unsigned int n = this->geometry.dofs_per_cell;
    AssertDimension(cell_matrix.m(), n);
    AssertDimension(cell_matrix.n(), n);
    AssertIndexRange(local.cell * n * n + n * n - 1, matrix_positions.size());
    AssertIndexRange(local.cell * n + n - 1, diagonal_positions.size());
    const int    *matrix_position   = &matrix_positions[local.cell * n * n];
    const int    *diagonal_position = &diagonal_positions[local.cell * n];
    const double *entries           = &cell_matrix(0, 0);
    for (unsigned int k = 0; k < n * n; ++k)
      if (matrix_position[k] >= 0)
        values[matrix_position[k]] += entries[k];
    double mean_diagonal = 0.;
    for (unsigned int i = 0; i < n; ++i)
      mean_diagonal += std::abs(cell_matrix(i, i));
    mean_diagonal /= n;
    if (mean_diagonal == 0.)
      mean_diagonal = cell_matrix.l1_norm() / n;
    if (mean_diagonal == 0.)
      mean_diagonal = 1.;
    for (unsigned int i = 0; i < n; ++i)
      {
        const double diagonal = (cell_matrix(i, i) != 0.)
                                  ? std::abs(cell_matrix(i, i))
                                  : mean_diagonal;
        if (diagonal_position[i] >= 0)
          values[diagonal_position[i]] += diagonal;
        else if (diagonal_position[i] == -2)
          {
            const types::global_dof_index row = local.dof_indices[i];
            if (this->constraints.is_constrained(row))
              matrix.add(row, row, diagonal);
            else
              for (unsigned int j = 0; j < n; ++j)
                if (!this->constraints.is_constrained(local.dof_indices[j]))
                  matrix.add(row, local.dof_indices[j], cell_matrix(i, j));
          }
      }
  }



  template <int dim>
  void
  DirectAddressAssembler<dim>::add_vector(const CellContribution<dim> &local,
                                          const Vector<double> &cell_vector,
                                          double               *values,
                                          Epetra_Vector *ghost_values) const
  {
    const unsigned int n = this->geometry.dofs_per_cell;
    AssertDimension(cell_vector.size(), n);
    AssertIndexRange(local.cell * n + n - 1, vector_positions.size());
    Assert(ghost_values != nullptr ||
             std::none_of(&vector_positions[local.cell * n],
                          &vector_positions[local.cell * n] + n,
                          [](const int p) { return p <= -2; }),
           ExcMessage("A row of another process without a ghost vector."));
    const int *position = &vector_positions[local.cell * n];
    for (unsigned int i = 0; i < n; ++i)
      if (position[i] >= 0)
        values[position[i]] += cell_vector(i);
      else if (position[i] <= -2)
        (*ghost_values)[-2 - position[i]] += cell_vector(i);
  }



  template <int dim>
  void
  DirectAddressAssembler<dim>::add(
    const CellContribution<dim>                  &local,
    const typename SystemAssembler<dim>::Targets &targets)
  {
    if (forces_in_halves)
      {
        // The halves of assemble_residual().
        const unsigned int half =
          (local.cell < this->geometry.n_cells / 2) ? 0 : 1;
        add_vector(local, local.force, half_force[half].data(), nullptr);
        if (local.request.second_force)
          add_vector(local,
                     local.second_force,
                     half_second_force[half].data(),
                     nullptr);
      }
    else
      {
        add_vector(local, local.force, force_values, ghost_force.get());
        if (local.request.second_force)
          add_vector(local,
                     local.second_force,
                     second_force_values,
                     ghost_second_force.get());
      }
    if (local.request.matrix)
      add_matrix(local, local.matrix, matrix_values, *targets.matrix);
    if (local.request.second_matrix)
      add_matrix(local,
                 local.second_matrix,
                 second_matrix_values,
                 *targets.second_matrix);
  }



  // @sect4{DirectAddressAssembler::finish}
  //
  // The matrices' rows of other processes go to their owners when the
  // matrices are compressed; the force vectors' entries of other processes
  // in the exchange set up by the constructor. In serial runs the vectors
  // were not touched through deal.II, and there is nothing to exchange.
  template <int dim>
  void
  DirectAddressAssembler<dim>::finish(
    const AssemblyRequest                        &request,
    const typename SystemAssembler<dim>::Targets &targets)
  {
    if (request.matrix)
      targets.matrix->compress(VectorOperation::add);
    if (request.second_matrix)
      targets.second_matrix->compress(VectorOperation::add);
    if (forces_in_halves)
      {
        const unsigned int n_values = targets.force->locally_owned_size();
        for (unsigned int half = 0; half < 2; ++half)
          {
            for (unsigned int k = 0; k < n_values; ++k)
              force_values[k] += half_force[half][k];
            if (request.second_force)
              for (unsigned int k = 0; k < n_values; ++k)
                second_force_values[k] += half_second_force[half][k];
          }
      }
    if (serial)
      return;
    const int error =
      targets.force->trilinos_vector().Export(*ghost_force, *ghost_import, Add);
    AssertThrow(error == 0, ExcMessage("Sending the interface forces failed."));
    if (request.second_force)
      {
        const int second_error =
          targets.second_force->trilinos_vector().Export(*ghost_second_force,
                                                         *ghost_import,
                                                         Add);
        AssertThrow(second_error == 0,
                    ExcMessage("Sending the interface forces failed."));
      }
  }



  // @sect4{DirectAddressAssembler::assemble_residual}
  //
  // In serial runs the cells are split into two halves, each summed into its
  // own copy of the force vectors, and the two copies are added in a fixed
  // order: with two or more threads the halves run at the same time, and the
  // result does not depend on the number of threads. Parallel runs
  // integrate their cells in one thread, as the reference class does.
  template <int dim>
  void
  DirectAddressAssembler<dim>::assemble_residual(
    const typename SystemAssembler<dim>::LocalIntegrator &integrate,
    CellContribution<dim>                                &prototype,
    const std::vector<std::vector<double>>               &cell_values,
    const typename SystemAssembler<dim>::Targets         &targets,
    AssemblyResult                                       &result)
  {
    if (!serial)
      {
        SystemAssembler<dim>::assemble_residual(
          integrate, prototype, cell_values, targets, result);
        return;
      }
    constexpr unsigned int n_parts  = 2;
    const unsigned int     n_cells  = this->geometry.n_cells;
    const unsigned int     n        = this->geometry.dofs_per_cell;
    const unsigned int     n_values = targets.force->locally_owned_size();
    const bool             second   = prototype.request.second_force;
    std::array<std::vector<double>, n_parts> part_force, part_second_force;
    std::array<AssemblyResult, n_parts>      part_result;
    const auto assemble_part = [&](const unsigned int part) {
      part_force[part].assign(n_values, 0.);
      if (second)
        part_second_force[part].assign(n_values, 0.);
      CellContribution<dim> local = prototype;
      for (unsigned int cell = part * n_cells / n_parts;
           cell < (part + 1) * n_cells / n_parts;
           ++cell)
        {
          this->integrate_cell(integrate, cell, cell_values, local);
          const int *position = &vector_positions[cell * n];
          for (unsigned int i = 0; i < n; ++i)
            if (position[i] >= 0)
              {
                part_force[part][position[i]] += local.force(i);
                if (second)
                  part_second_force[part][position[i]] += local.second_force(i);
              }
          this->accumulate(local, part_result[part]);
        }
    };
    if (MultithreadInfo::n_threads() > 1)
      {
        Threads::Task<void> first_half =
          Threads::new_task([&assemble_part]() { assemble_part(0); });
        assemble_part(1);
        first_half.join();
      }
    else
      for (unsigned int part = 0; part < n_parts; ++part)
        assemble_part(part);
    for (unsigned int part = 0; part < n_parts; ++part)
      {
        for (unsigned int k = 0; k < n_values; ++k)
          force_values[k] += part_force[part][k];
        if (second)
          for (unsigned int k = 0; k < n_values; ++k)
            second_force_values[k] += part_second_force[part][k];
        result.strain_energy += part_result[part].strain_energy;
        result.min_jacobian =
          std::min(result.min_jacobian, part_result[part].min_jacobian);
        result.inverted_point_found =
          result.inverted_point_found || part_result[part].inverted_point_found;
      }
  }



#define SOFT_ROBOT_INSTANTIATE(dim) template class DirectAddressAssembler<dim>;
  SOFT_ROBOT_FOR_EACH_DIMENSION(SOFT_ROBOT_INSTANTIATE)
#undef SOFT_ROBOT_INSTANTIATE
} // namespace SoftRobot
