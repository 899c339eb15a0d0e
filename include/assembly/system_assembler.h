// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{The global addition: from cell contributions to the global system}
//
// A SystemAssembler runs the physics (a function that integrates over one
// cell, such as HyperelasticSolid::cell_contribution()) on every locally
// owned cell and adds the results into the global force vectors and
// matrices. It knows nothing of the physics; the physics knows nothing of
// it.
//
// With a matrix, the cells are processed by deal.II's WorkStream: the cell
// integrals, which hold nearly all of the arithmetic, run on all threads;
// the additions into the global objects one after the other, in the order
// of the cells, so that the result does not depend on the number of
// threads. The number of threads is deal.II's default -- the cores divided
// among the MPI processes of the machine -- and can be limited with the
// environment variable DEAL_II_NUM_THREADS. A residual alone costs about a
// microsecond per linear tetrahedron, too little for WorkStream's
// synchronisation to pay; its cells are integrated in one thread.
//
// This class is the readable reference: it reads the cells' values from a
// ghosted copy of each input vector and adds through
// AffineConstraints::distribute_local_to_global(), which also gives each
// constrained dof's row a diagonal entry of the size of the others. The
// program uses the faster DirectAddressAssembler wherever the constraints
// allow it; a test checks that the two give the same matrices and vectors
// to round-off.
//
// Implemented in source/assembly/system_assembler.cc.

#ifndef soft_robot_assembly_system_assembler_h
#define soft_robot_assembly_system_assembler_h

#include <assembly/assembly_result.h>
#include <assembly/cell_contribution.h>
#include <deal.II/base/index_set.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>
#include <functional>
#include <physics/cell_geometry.h>
#include <vector>

namespace SoftRobot
{
  template <int dim>
  class SystemAssembler
  {
  public:
    // The integral over one cell: reads `local.cell`, `local.request` and
    // `local.input_values`, writes the outputs of `local`.
    using LocalIntegrator = std::function<void(CellContribution<dim> &)>;

    // The global objects an assembly writes: always a force vector, and as
    // requested a second force vector, the matrix and the second matrix.
    struct Targets
    {
      TrilinosWrappers::MPI::Vector  *force         = nullptr;
      TrilinosWrappers::MPI::Vector  *second_force  = nullptr;
      TrilinosWrappers::SparseMatrix *matrix        = nullptr;
      TrilinosWrappers::SparseMatrix *second_matrix = nullptr;
    };

    SystemAssembler(const CellGeometry<dim>         &geometry,
                    const AffineConstraints<double> &constraints,
                    const IndexSet                  &locally_owned_dofs,
                    const IndexSet                  &locally_relevant_dofs,
                    const MPI_Comm                   mpi_communicator);

    virtual ~SystemAssembler() = default;

    // Sets the targets of the request to zero, runs `integrate` on every
    // cell with the cells' values of `inputs`, adds the results, and
    // returns the sums and extremes of the cells' scalar results over all
    // processes.
    AssemblyResult
    assemble(const LocalIntegrator &integrate,
             const std::vector<const TrilinosWrappers::MPI::Vector *> &inputs,
             const AssemblyRequest                                    &request,
             const Targets                                            &targets);

    // Whether the assembly adds at precomputed addresses.
    virtual bool
    uses_direct_addresses() const
    {
      return false;
    }

  protected:
    // The values of a global vector at every cell's dofs, [cell][i], with
    // zero for a constrained dof.
    virtual void
    gather(const TrilinosWrappers::MPI::Vector &global,
           std::vector<double>                 &cell_values) const;

    // Prepares the targets (they are zero already).
    virtual void
    begin(const AssemblyRequest &request, const Targets &targets);

    // Adds one cell's contribution into the targets.
    virtual void
    add(const CellContribution<dim> &local, const Targets &targets);

    // Completes the additions (the exchange between processes).
    virtual void
    finish(const AssemblyRequest &request, const Targets &targets);

    // The assembly of the force vectors alone: every cell in turn.
    virtual void
    assemble_residual(const LocalIntegrator                  &integrate,
                      CellContribution<dim>                  &prototype,
                      const std::vector<std::vector<double>> &cell_values,
                      const Targets                          &targets,
                      AssemblyResult                         &result);

    // Sets up `local` for `cell` and runs the integral on it.
    void
    integrate_cell(const LocalIntegrator                  &integrate,
                   const unsigned int                      cell,
                   const std::vector<std::vector<double>> &cell_values,
                   CellContribution<dim>                  &local) const;

    // The cell's scalar results, into the assembly's.
    static void
    accumulate(const CellContribution<dim> &local, AssemblyResult &result);

    const CellGeometry<dim>         &geometry;
    const AffineConstraints<double> &constraints;
    const IndexSet                  &locally_owned_dofs;
    const IndexSet                  &locally_relevant_dofs;
    const MPI_Comm                   mpi_communicator;
  };
} // namespace SoftRobot

#endif
