// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{The LinearSolver class}
//
// Every Newton iteration of SoftRobotDynamics solves a linear system
// $\mathbf A\,\delta\mathbf u = -\mathbf r$ with the effective tangent
// @f[
//   \mathbf A = \frac{1}{\beta\Delta t^2}\mathbf M
//   + (1+\alpha)\left(\mathbf K + \frac{\gamma}{\beta\Delta t}\mathbf
//   C\right),
// @f]
// which is symmetric and, away from buckling, positive definite. This class
// solves these systems, in one of two ways chosen by the parameters:
// - a sparse direct solver of Trilinos Amesos (KLU, or MUMPS for larger
//   problems), for problems of up to some $10^5$ unknowns and as a check of
//   the iterative solvers;
// - CG (or GMRES) preconditioned by the algebraic multigrid of Trilinos ML,
//   whose coarse spaces are built from the rigid-body modes of the body (its
//   near null space, see set_near_null_space()).
//
// Preparing the solver -- the numerical factorization, or the multigrid
// hierarchy -- is separate from solving with it, because the modified
// Newton method keeps one matrix for all iterations of a time step and pays
// for the preparation once. Two things are kept from one preparation to the
// next while the matrix is the same object, because they depend on its
// sparsity pattern only, which never changes in a run: the symbolic
// analysis of the direct solver (the fill-reducing ordering) and the
// aggregates of the multigrid hierarchy (which unknowns each coarse unknown
// stands for).
//
// This class (with SymmetricFactorization, which it owns and which reads
// the Epetra matrix's arrays for MUMPS) is the only place of the program
// that uses Amesos, ML, MUMPS and the Epetra objects behind deal.II's
// Trilinos wrappers. Where it has to reach behind deal.II's interface,
// linear_solver.cc says why; tests/linear_solver.cc checks each of these
// places against the Trilinos version in use.
//
// The constraints of the problem are none of this class's business: the
// caller hands in a matrix with the constrained rows and columns already
// treated, and zeroes the constrained entries of the solution.
//
// Implemented in source/solvers/linear_solver.cc.

#ifndef soft_robot_solvers_linear_solver_h
#define soft_robot_solvers_linear_solver_h

#include <core/parameters.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>
#include <memory>
#include <solvers/symmetric_factorization.h>
#include <string>
#include <vector>

// The Trilinos classes the solver keeps, declared here so that their
// headers stay in linear_solver.cc.
class Amesos_BaseSolver;
class Epetra_LinearProblem;

namespace dealii::TrilinosWrappers
{
  class PreconditionAMG;
}

namespace SoftRobot
{
  using namespace dealii;

  class LinearSolver
  {
  public:
    // `Direct solver = automatic` takes MUMPS for matrices of at least this
    // many rows, KLU for smaller ones (see uses_mumps()).
    static constexpr types::global_dof_index automatic_mumps_threshold = 10000;

    // Whether the matrices given to this solver must be symmetric: for CG,
    // and for the symmetric factorization (`Symmetric factorization` with
    // MUMPS on one process; see SymmetricFactorization). The physics then
    // leaves out the non-symmetric parts of the tangent.
    static bool
    needs_symmetric_matrix(const Parameters::LinearSolver &parameters,
                           const types::global_dof_index   n_unknowns,
                           const MPI_Comm                  mpi_communicator);

    // The parameters are copied. The polynomial degree of the finite
    // element tells ML whether the matrix comes from higher-order elements.
    // The timer gets the sections "Factorization" (direct solvers),
    // "Preconditioner setup" (multigrid) and "Linear solve"; it must live
    // as long as this object.
    LinearSolver(const Parameters::LinearSolver &parameters,
                 const unsigned int              polynomial_degree,
                 const MPI_Comm                  mpi_communicator,
                 TimerOutput                    &timer);
    ~LinearSolver();

    // The solver holds pointers to the matrix, to Trilinos objects that
    // refer to each other, and to its own null-space array, so it is
    // neither copied nor moved.
    LinearSolver(const LinearSolver &) = delete;
    LinearSolver &
    operator=(const LinearSolver &) = delete;

    // The near null space for ML, usually the rigid-body modes: one vector
    // per mode, each with the locally owned entries of the matrix's rows
    // in their order. Without it ML uses its default, the constant vector.
    // It is used by the next hierarchy built from scratch, which is the
    // next prepare() (not a recomputation on the old aggregates).
    void
    set_near_null_space(const std::vector<std::vector<double>> &modes);

    // Whether the symmetric factorization may keep its factor in single
    // precision, as `Factorization precision = single` asks (it may by
    // default). A single-precision back substitution solves to about
    // single precision's round-off times the matrix's condition number.
    // The static solve of the actuator without gravity stalled with a
    // single-precision factor while the time steps converged
    // (doc/performance_discussion.md, item 47); presumably because the
    // static tangent lacks the time steps' mass term $c\,\mathbf M$, $c =
    // 1/(\beta\Delta t^2)$, and with it a bounded condition number (not
    // measured). The static equilibrium therefore asks for double
    // precision (DoublePrecisionFactor). A change takes effect with the
    // next prepare(), which then analyses the pattern again.
    void
    allow_single_precision_factor(const bool allow);

    // Factorize this matrix, or build (or recompute) the multigrid hierarchy
    // for it. The matrix object must stay alive and unchanged until the
    // next call of prepare(): solve() multiplies with it, and KLU may read
    // its values in place. While it is the same object as in the last
    // call, with the same size, the symbolic analysis or the aggregates are
    // reused. Throws StepFailure if the factorization fails (a singular
    // matrix).
    void
    prepare(const TrilinosWrappers::SparseMatrix &matrix);

    // Solve with what prepare() made, starting from zero; returns the
    // number of iterations (1 for the direct solvers). Throws StepFailure
    // if the iterative solver does not converge within the maximum number
    // of iterations.
    unsigned int
    solve(const TrilinosWrappers::MPI::Vector &rhs,
          TrilinosWrappers::MPI::Vector       &solution);

    // The number of calls of prepare() so far, the failed ones included:
    // the factorizations or multigrid set-ups.
    unsigned int
    n_preparations() const;
    // The count of an earlier part of the run, at a restart.
    void
    set_n_preparations(const unsigned int n);

    // The solver prepared last: the Amesos class that was created
    // ("Amesos_Klu", "Amesos_Mumps"), "MUMPS symmetric" for
    // SymmetricFactorization, or "CG with ML" / "GMRES with ML"; empty
    // before the first prepare().
    std::string
    solver_in_use() const;

    // ML's operator complexity: the nonzeros of the matrices of all levels
    // of the hierarchy over those of the finest. It is computed when a
    // hierarchy is built from scratch (the recomputation keeps the
    // aggregates, and with them the sizes of the levels); zero until then
    // and with the direct solvers.
    double
    multigrid_operator_complexity() const;

  private:
    // @sect4{The two ways of preparing}
    bool
    uses_direct_solver() const;
    // Whether the direct solver for a matrix of this size is MUMPS (else
    // KLU).
    bool
    uses_mumps(const types::global_dof_index n_unknowns) const;
    // The same for given parameters: `Direct solver = MUMPS`, or
    // `automatic` from the threshold on.
    static bool
    mumps_for(const Parameters::LinearSolver &parameters,
              const types::global_dof_index   n_unknowns);
    // Whether the direct solver for a matrix of this size is
    // SymmetricFactorization.
    bool
    uses_symmetric_factorization(
      const types::global_dof_index n_unknowns) const;
    // Whether `matrix` is the matrix object analysed last (and has kept its
    // size), so that the symbolic analysis or the aggregates can be reused.
    bool
    is_analysed_matrix(const TrilinosWrappers::SparseMatrix &matrix) const;
    void
    remember_analysed_matrix(const TrilinosWrappers::SparseMatrix &matrix);

    void
    prepare_factorization(const TrilinosWrappers::SparseMatrix &matrix);
    void
    create_factorization(const TrilinosWrappers::SparseMatrix &matrix);
    void
    prepare_multigrid(const TrilinosWrappers::SparseMatrix &matrix);
    void
    build_multigrid(const TrilinosWrappers::SparseMatrix &matrix);

    void
    solve_direct(const TrilinosWrappers::MPI::Vector &rhs,
                 TrilinosWrappers::MPI::Vector       &solution);
    unsigned int
    solve_iterative(const TrilinosWrappers::MPI::Vector &rhs,
                    TrilinosWrappers::MPI::Vector       &solution);

    const Parameters::LinearSolver parameters;
    const unsigned int             polynomial_degree;
    const MPI_Comm                 mpi_communicator;
    TimerOutput                   &timer;

    // The modes given to set_near_null_space().
    std::vector<std::vector<double>> near_null_space;

    // The matrix of the last prepare(), and whether that preparation
    // succeeded (solve() needs one that did).
    const TrilinosWrappers::SparseMatrix *prepared_matrix = nullptr;
    bool                                  is_prepared     = false;

    // The Epetra matrix inside the deal.II matrix object whose pattern was
    // analysed last, with its size. Only compared, never dereferenced.
    const void             *analysed_matrix   = nullptr;
    types::global_dof_index analysed_rows     = 0;
    types::global_dof_index analysed_nonzeros = 0;

    // The direct solver: the linear problem that Amesos works on (it holds
    // the pointers to the matrix and the vectors), the solver that Amesos'
    // factory created for it, and that solver's name. The problem is
    // declared first so that it outlives the solver.
    std::unique_ptr<Epetra_LinearProblem> direct_problem;
    std::unique_ptr<Amesos_BaseSolver>    direct_factorization;
    std::string                           direct_solver_name;
    // Or MUMPS's symmetric factorization, called directly.
    std::unique_ptr<SymmetricFactorization> symmetric_factorization;
    bool                                    single_precision_allowed = true;

    // The multigrid hierarchy and the near null space it was given, one
    // mode after the other in the layout of an Epetra_MultiVector. ML keeps
    // a pointer to the array, so it is declared first and outlives the
    // hierarchy.
    std::vector<double>                                ml_null_space;
    std::unique_ptr<TrilinosWrappers::PreconditionAMG> amg_preconditioner;
    double                                             operator_complexity = 0.;

    unsigned int preparations = 0;
  };



  // While an object of this class lives, the solver's symmetric factor is
  // in double precision (see LinearSolver::allow_single_precision_factor()).
  class DoublePrecisionFactor
  {
  public:
    explicit DoublePrecisionFactor(LinearSolver &solver)
      : solver(solver)
    {
      solver.allow_single_precision_factor(false);
    }

    ~DoublePrecisionFactor()
    {
      solver.allow_single_precision_factor(true);
    }

    DoublePrecisionFactor(const DoublePrecisionFactor &) = delete;
    DoublePrecisionFactor &
    operator=(const DoublePrecisionFactor &) = delete;

  private:
    LinearSolver &solver;
  };



  // @sect3{The operations on ML's hierarchy}
  //
  // In two places LinearSolver works on ML's hierarchy behind deal.II's
  // PreconditionAMG (see linear_solver.cc for why). They are declared here,
  // apart from the class, so that tests/linear_solver.cc can check them on
  // hierarchies it builds itself with deal.II; the program uses them
  // through LinearSolver only.
  namespace LinearSolverInternals
  {
    // Recompute the hierarchy of `amg` for the new values of the matrix it
    // was built for, on the old aggregates, with nothing of the old values
    // kept.
    void
    recompute_on_old_aggregates(TrilinosWrappers::PreconditionAMG &amg);

    // ML's operator complexity of the hierarchy of `amg`, built for
    // `matrix`: the nonzeros of all levels over those of the matrix.
    double
    operator_complexity(const TrilinosWrappers::PreconditionAMG &amg,
                        const TrilinosWrappers::SparseMatrix    &matrix,
                        const MPI_Comm mpi_communicator);
  } // namespace LinearSolverInternals
} // namespace SoftRobot

#endif
