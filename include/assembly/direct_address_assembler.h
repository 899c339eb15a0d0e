// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{The fast global addition: precomputed addresses}
//
// SystemAssembler adds a cell matrix through Epetra's SumIntoGlobalValues,
// which searches every row for every column, and reads the cells' values
// through a ghosted copy of each vector. With homogeneous constraints (the
// fixed components of the bellows and of every scene), where each
// constrained dof only drops out, both can be replaced by plain loops over
// addresses computed once: where each entry of a cell matrix goes in the
// value array of the Epetra matrix, and where each cell dof's value is in
// the vectors' value arrays.
//
// What this changes is only the order of the floating-point additions into
// a matrix entry, not their terms: tests/system_assembler.cc checks that
// both classes build the same matrices and vectors to round-off, serially
// and on several processes. The gain on the headline benchmark is stated
// in doc/performance_discussion.md (item 7).
//
// A constrained dof's row and column are left out, and its diagonal gets
// the absolute value of the cell matrix's diagonal entry (if that is zero,
// the mean absolute diagonal entry), as
// AffineConstraints::distribute_local_to_global() does: it keeps the matrix
// regular and of the scale of its other entries.
//
// In parallel runs the rows of this process have addresses; the few rows of
// a cell that another process owns (on the interface) still go through
// Epetra, which sends them to their owner when the matrix is compressed.
// The vectors' entries of those rows are collected in a small ghost vector
// and sent to their owners in one exchange whose pattern is set up once.
//
// This class and LinearSolver (with its SymmetricFactorization) are the
// only ones that reach into Epetra objects behind deal.II's wrappers (the
// value arrays of the matrices and vectors, and an Epetra_Import for the
// ghost exchange).
//
// Implemented in source/assembly/direct_address_assembler.cc.

#ifndef soft_robot_assembly_direct_address_assembler_h
#define soft_robot_assembly_direct_address_assembler_h

#include <array>
#include <assembly/system_assembler.h>
#include <memory>

class Epetra_Import;
class Epetra_Map;
class Epetra_Vector;

namespace SoftRobot
{
  template <int dim>
  class DirectAddressAssembler : public SystemAssembler<dim>
  {
  public:
    // The fast assembler if the constraints are homogeneous and the two
    // matrices (the second may be null) share their storage layout, on
    // every process (a collective call); otherwise the reference
    // SystemAssembler. `vector` is any vector of the system's layout.
    static std::unique_ptr<SystemAssembler<dim>>
    create(const CellGeometry<dim>              &geometry,
           const AffineConstraints<double>      &constraints,
           const IndexSet                       &locally_owned_dofs,
           const IndexSet                       &locally_relevant_dofs,
           const TrilinosWrappers::SparseMatrix &matrix,
           const TrilinosWrappers::SparseMatrix *second_matrix,
           const TrilinosWrappers::MPI::Vector  &vector,
           const MPI_Comm                        mpi_communicator);

    ~DirectAddressAssembler() override;

    bool
    uses_direct_addresses() const override
    {
      return true;
    }

  private:
    DirectAddressAssembler(const CellGeometry<dim>         &geometry,
                           const AffineConstraints<double> &constraints,
                           const IndexSet                  &locally_owned_dofs,
                           const IndexSet &locally_relevant_dofs,
                           const TrilinosWrappers::SparseMatrix &matrix,
                           const TrilinosWrappers::MPI::Vector  &vector,
                           const MPI_Comm mpi_communicator);

    // Whether the addresses can be used on this process.
    static bool
    usable(const AffineConstraints<double>      &constraints,
           const TrilinosWrappers::SparseMatrix &matrix,
           const TrilinosWrappers::SparseMatrix *second_matrix);

    void
    compute_matrix_addresses(const TrilinosWrappers::SparseMatrix &matrix,
                             const TrilinosWrappers::MPI::Vector  &vector);
    void
    setup_ghost_exchange(const TrilinosWrappers::MPI::Vector &vector);

    void
    gather(const TrilinosWrappers::MPI::Vector &global,
           std::vector<double>                 &cell_values) const override;
    void
    begin(const AssemblyRequest                        &request,
          const typename SystemAssembler<dim>::Targets &targets) override;
    void
    add(const CellContribution<dim>                  &local,
        const typename SystemAssembler<dim>::Targets &targets) override;
    void
    finish(const AssemblyRequest                        &request,
           const typename SystemAssembler<dim>::Targets &targets) override;
    void
    assemble_residual(
      const typename SystemAssembler<dim>::LocalIntegrator &integrate,
      CellContribution<dim>                                &prototype,
      const std::vector<std::vector<double>>               &cell_values,
      const typename SystemAssembler<dim>::Targets         &targets,
      AssemblyResult                                       &result) override;

    // A cell matrix at the addresses.
    void
    add_matrix(const CellContribution<dim>    &local,
               const FullMatrix<double>       &cell_matrix,
               double                         *values,
               TrilinosWrappers::SparseMatrix &matrix) const;
    // A cell vector at the addresses.
    void
    add_vector(const CellContribution<dim> &local,
               const Vector<double>        &cell_vector,
               double                      *values,
               Epetra_Vector               *ghost_values) const;

    const bool serial;
    // Where each entry of a cell matrix goes in the value array of the
    // matrices, [cell][i][j], -1 for a constrained row or column; where the
    // diagonal entry of each constrained dof of a cell is, [cell][i], -1 if
    // the dof is free. A row that another process owns has -2 in both.
    std::vector<int> matrix_positions;
    std::vector<int> diagonal_positions;
    // Per cell dof, [cell][i]: the index in this process's part of the
    // vectors for a dof it owns, -1 for a constrained dof, and -2 - g for
    // the free dof that another process owns and that is entry g of the
    // ghost vectors below.
    std::vector<int> vector_positions;

    // In parallel runs: the free dofs of the locally owned cells that other
    // processes own, the communication pattern between them and their
    // owners, and one vector for the values read from the owners and one
    // per force vector for the sums sent to them.
    std::unique_ptr<Epetra_Map>    ghost_map;
    std::unique_ptr<Epetra_Import> ghost_import;
    std::unique_ptr<Epetra_Vector> ghost_values, ghost_force,
      ghost_second_force;

    // In serial runs the force vectors of an assembly with matrices are
    // summed as assemble_residual() sums them: in the two halves of the
    // cells, each in the order of its cells, and the halves then added in
    // turn. A state's forces are then the same bits whether its matrices
    // were assembled with them or not (a restart assembles the state with
    // its matrix where the run did without).
    std::array<std::vector<double>, 2> half_force, half_second_force;
    bool                               forces_in_halves = false;

    // The value arrays of the targets during an assembly.
    double *matrix_values        = nullptr;
    double *second_matrix_values = nullptr;
    double *force_values         = nullptr;
    double *second_force_values  = nullptr;
  };
} // namespace SoftRobot

#endif
