// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{The global addition: from cell contributions to the global system}
//
// See include/assembly/system_assembler.h.

#include <algorithm>
#include <assembly/system_assembler.h>
#include <core/config.h>
#include <deal.II/base/multithread_info.h>
#include <deal.II/base/work_stream.h>
#include <numeric>

namespace SoftRobot
{
  namespace
  {
    // WorkStream's per-thread scratch object; the cell integrals keep their
    // work space in the CellContribution instead.
    struct NoScratch
    {
    };
  } // namespace



  template <int dim>
  SystemAssembler<dim>::SystemAssembler(
    const CellGeometry<dim>         &geometry,
    const AffineConstraints<double> &constraints,
    const IndexSet                  &locally_owned_dofs,
    const IndexSet                  &locally_relevant_dofs,
    const MPI_Comm                   mpi_communicator)
    : geometry(geometry)
    , constraints(constraints)
    , locally_owned_dofs(locally_owned_dofs)
    , locally_relevant_dofs(locally_relevant_dofs)
    , mpi_communicator(mpi_communicator)
  {
  }



  // @sect4{SystemAssembler::assemble}
  //
  // The cells' values of the inputs are read once, before the loop, so that
  // the threads only read plain arrays.
  template <int dim>
  AssemblyResult
  SystemAssembler<dim>::assemble(
    const LocalIntegrator                                    &integrate,
    const std::vector<const TrilinosWrappers::MPI::Vector *> &inputs,
    const AssemblyRequest                                    &request,
    const Targets                                            &targets)
  {
    Assert(targets.force != nullptr, ExcInternalError());
    Assert(!request.matrix || targets.matrix != nullptr, ExcInternalError());
    Assert(!request.second_matrix || targets.second_matrix != nullptr,
           ExcInternalError());
    Assert(!request.second_force || targets.second_force != nullptr,
           ExcInternalError());
    if (request.matrix)
      *targets.matrix = 0.;
    if (request.second_matrix)
      *targets.second_matrix = 0.;
    *targets.force = 0.;
    if (request.second_force)
      *targets.second_force = 0.;
    begin(request, targets);

    std::vector<std::vector<double>> cell_values(inputs.size());
    for (unsigned int k = 0; k < inputs.size(); ++k)
      gather(*inputs[k], cell_values[k]);

    CellContribution<dim> prototype;
    prototype.request = request;
    AssemblyResult result;
    if (request.matrix)
      {
        std::vector<unsigned int> cells(geometry.n_cells);
        std::iota(cells.begin(), cells.end(), 0U);
        // The threads take the cells in chunks; while the last chunk runs,
        // the other threads have nothing left to do. Sixteen chunks per
        // thread keep that wait short on the few hundred expensive cells of
        // the quadratic meshes; on the thousands of cheap cells of the
        // linear ones, chunks of at most 64 cells keep the overhead per
        // chunk small (doc/performance_discussion.md, item 39).
        const unsigned int chunk_size = std::clamp<unsigned int>(
          geometry.n_cells / (16 * MultithreadInfo::n_threads()), 1, 64);
        WorkStream::run(
          cells.data(),
          cells.data() + cells.size(),
          [&](const unsigned int *cell,
              NoScratch &,
              CellContribution<dim> &local) {
            integrate_cell(integrate, *cell, cell_values, local);
          },
          [&](const CellContribution<dim> &local) {
            accumulate(local, result);
            add(local, targets);
          },
          NoScratch(),
          prototype,
          2 * MultithreadInfo::n_threads(),
          chunk_size);
      }
    else
      assemble_residual(integrate, prototype, cell_values, targets, result);
    finish(request, targets);

    result.strain_energy =
      Utilities::MPI::sum(result.strain_energy, mpi_communicator);
    result.min_jacobian =
      Utilities::MPI::min(result.min_jacobian, mpi_communicator);
    result.inverted_point_found =
      Utilities::MPI::max(result.inverted_point_found ? 1 : 0,
                          mpi_communicator) == 1;
    return result;
  }



  template <int dim>
  void
  SystemAssembler<dim>::integrate_cell(
    const LocalIntegrator                  &integrate,
    const unsigned int                      cell,
    const std::vector<std::vector<double>> &cell_values,
    CellContribution<dim>                  &local) const
  {
    const unsigned int n = geometry.dofs_per_cell;
    local.cell           = cell;
    local.reset(n);
    local.input_values.resize(cell_values.size());
    for (unsigned int k = 0; k < cell_values.size(); ++k)
      local.input_values[k] = &cell_values[k][cell * n];
    std::copy_n(geometry.dof_indices.begin() + cell * n,
                n,
                local.dof_indices.begin());
    integrate(local);
  }



  template <int dim>
  void
  SystemAssembler<dim>::accumulate(const CellContribution<dim> &local,
                                   AssemblyResult              &result)
  {
    result.strain_energy += local.strain_energy;
    result.min_jacobian = std::min(result.min_jacobian, local.min_jacobian);
    result.inverted_point_found = result.inverted_point_found || local.inverted;
  }



  // @sect4{The reference implementation of the additions}
  //
  // The values at the cells' dofs from a copy of the vector with the
  // entries of the dofs this process does not own.
  template <int dim>
  void
  SystemAssembler<dim>::gather(const TrilinosWrappers::MPI::Vector &global,
                               std::vector<double> &cell_values) const
  {
    TrilinosWrappers::MPI::Vector ghosted(locally_owned_dofs,
                                          locally_relevant_dofs,
                                          mpi_communicator);
    ghosted = global;
    cell_values.resize(geometry.dof_indices.size());
    for (std::size_t k = 0; k < cell_values.size(); ++k)
      cell_values[k] = ghosted(geometry.dof_indices[k]);
  }



  template <int dim>
  void
  SystemAssembler<dim>::begin(const AssemblyRequest &, const Targets &)
  {
  }



  template <int dim>
  void
  SystemAssembler<dim>::add(const CellContribution<dim> &local,
                            const Targets               &targets)
  {
    if (local.request.matrix)
      constraints.distribute_local_to_global(local.matrix,
                                             local.force,
                                             local.dof_indices,
                                             *targets.matrix,
                                             *targets.force);
    else
      constraints.distribute_local_to_global(local.force,
                                             local.dof_indices,
                                             *targets.force);
    if (local.request.second_matrix)
      constraints.distribute_local_to_global(local.second_matrix,
                                             local.dof_indices,
                                             *targets.second_matrix);
    if (local.request.second_force)
      constraints.distribute_local_to_global(local.second_force,
                                             local.dof_indices,
                                             *targets.second_force);
  }



  template <int dim>
  void
  SystemAssembler<dim>::finish(const AssemblyRequest &request,
                               const Targets         &targets)
  {
    if (request.matrix)
      targets.matrix->compress(VectorOperation::add);
    if (request.second_matrix)
      targets.second_matrix->compress(VectorOperation::add);
    targets.force->compress(VectorOperation::add);
    if (request.second_force)
      targets.second_force->compress(VectorOperation::add);
  }



  template <int dim>
  void
  SystemAssembler<dim>::assemble_residual(
    const LocalIntegrator                  &integrate,
    CellContribution<dim>                  &prototype,
    const std::vector<std::vector<double>> &cell_values,
    const Targets                          &targets,
    AssemblyResult                         &result)
  {
    for (unsigned int cell = 0; cell < geometry.n_cells; ++cell)
      {
        integrate_cell(integrate, cell, cell_values, prototype);
        accumulate(prototype, result);
        add(prototype, targets);
      }
  }



#define SOFT_ROBOT_INSTANTIATE(dim) template class SystemAssembler<dim>;
  SOFT_ROBOT_FOR_EACH_DIMENSION(SOFT_ROBOT_INSTANTIATE)
#undef SOFT_ROBOT_INSTANTIATE
} // namespace SoftRobot
