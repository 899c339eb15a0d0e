// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Implementation of the LinearSolver class}
//
// The linear solver of Newton's method, declared in
// include/solvers/linear_solver.h: Amesos' sparse direct solvers and CG or
// GMRES with ML's algebraic multigrid. deal.II's wrappers of these Trilinos
// packages do most of what is needed; in four places this file goes behind
// them, each explained where it happens:
// - Amesos is given the Epetra matrix inside deal.II's matrix, which
//   deal.II hands out as const only (prepare_factorization());
// - the rigid-body modes reach ML through its own parameter list
//   (build_multigrid());
// - before ML recomputes a hierarchy, two values it caches with the finest
//   level are cleared in ML's own data structure
//   (LinearSolverInternals::recompute_on_old_aggregates());
// - the operator complexity is counted from the levels of that structure
//   (LinearSolverInternals::operator_complexity()).

#include <Amesos.h>
#include <Amesos_BaseSolver.h>
#include <Amesos_Mumps.h>
#include <Epetra_CrsMatrix.h>
#include <Epetra_LinearProblem.h>
#include <Epetra_MultiVector.h>
#include <Teuchos_ParameterList.hpp>
#include <core/exceptions.h>
#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/solver_gmres.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <ml_MultiLevelPreconditioner.h>
#include <solvers/linear_solver.h>
#include <sstream>

namespace SoftRobot
{
  // @sect4{LinearSolver::LinearSolver}
  LinearSolver::LinearSolver(const Parameters::LinearSolver &parameters,
                             const unsigned int              polynomial_degree,
                             const MPI_Comm                  mpi_communicator,
                             TimerOutput                    &timer)
    : parameters(parameters)
    , polynomial_degree(polynomial_degree)
    , mpi_communicator(mpi_communicator)
    , timer(timer)
  {
    AssertThrow(polynomial_degree >= 1,
                ExcMessage("The polynomial degree of the finite element must "
                           "be at least 1, but is " +
                           std::to_string(polynomial_degree) + "."));
    AssertThrow(uses_direct_solver() ||
                  (parameters.linear_relative_tolerance > 0. &&
                   parameters.linear_max_iterations > 0),
                ExcMessage("An iterative linear solver needs a positive "
                           "relative tolerance and a positive maximum number "
                           "of iterations (Linear solver/Relative tolerance, "
                           "Max iterations)."));
  }



  // The members are destroyed in the reverse order of their declaration:
  // the Amesos solver before its linear problem, the hierarchy before its
  // null-space array. The destructor is defined here, where the Trilinos
  // classes are complete.
  LinearSolver::~LinearSolver() = default;



  // @sect4{LinearSolver::set_near_null_space}
  //
  // The modes are only stored here; build_multigrid() lays them out for ML.
  // Changing them must not touch the array that a living hierarchy points
  // to. To make the next prepare() use them, the analysed matrix is
  // forgotten, so that the next hierarchy is built from scratch.
  void
  LinearSolver::set_near_null_space(
    const std::vector<std::vector<double>> &modes)
  {
    for (const auto &mode : modes)
      AssertThrow(mode.size() == modes[0].size(),
                  ExcMessage("All near-null-space modes must have the same "
                             "number of entries (the locally owned rows)."));
    near_null_space = modes;
    if (!uses_direct_solver())
      analysed_matrix = nullptr;
  }



  // @sect4{LinearSolver::allow_single_precision_factor}
  //
  // A new symmetric factorization in the other precision at the next
  // prepare(); until then solve() has no factor to use.
  void
  LinearSolver::allow_single_precision_factor(const bool allow)
  {
    if (allow == single_precision_allowed)
      return;
    single_precision_allowed = allow;
    if (parameters.single_precision_factor && symmetric_factorization)
      {
        symmetric_factorization.reset();
        analysed_matrix = nullptr;
        is_prepared     = false;
      }
  }



  // @sect4{LinearSolver::prepare}
  //
  // Every call counts as a preparation, also one that fails: the statistics
  // count the factorizations attempted, the failed ones included.
  void
  LinearSolver::prepare(const TrilinosWrappers::SparseMatrix &matrix)
  {
    AssertThrow(matrix.m() == matrix.n(),
                ExcMessage("The linear solver needs a square matrix."));
    ++preparations;
    is_prepared     = false;
    prepared_matrix = &matrix;
    if (uses_direct_solver())
      prepare_factorization(matrix);
    else
      prepare_multigrid(matrix);
    is_prepared = true;
  }



  // @sect4{LinearSolver::uses_mumps}
  //
  // `Direct solver = automatic` takes MUMPS from this many unknowns on, and
  // KLU below. On the bellows meshes, with OpenBLAS, the two break even at
  // about 8,000 unknowns of linear tetrahedra; MUMPS's factorizations are
  // 10 % faster at 11,931 unknowns of quadratic ones and 35 % faster at
  // 19,209 of linear ones (doc/performance_discussion.md, item 29).
  bool
  LinearSolver::uses_mumps(const types::global_dof_index n_unknowns) const
  {
    return mumps_for(parameters, n_unknowns);
  }



  bool
  LinearSolver::mumps_for(const Parameters::LinearSolver &parameters,
                          const types::global_dof_index   n_unknowns)
  {
    using Type = Parameters::LinearSolver::DirectSolverType;
    return parameters.direct_solver == Type::mumps ||
           (parameters.direct_solver == Type::automatic &&
            n_unknowns >= automatic_mumps_threshold);
  }


  bool
  LinearSolver::uses_symmetric_factorization(
    const types::global_dof_index n_unknowns) const
  {
    return uses_direct_solver() &&
           needs_symmetric_matrix(parameters, n_unknowns, mpi_communicator);
  }



  // @sect4{LinearSolver::needs_symmetric_matrix}
  bool
  LinearSolver::needs_symmetric_matrix(
    const Parameters::LinearSolver &parameters,
    const types::global_dof_index   n_unknowns,
    const MPI_Comm                  mpi_communicator)
  {
    using Solver = Parameters::LinearSolver::LinearSolverType;
    if (parameters.linear_solver == Solver::cg)
      return true;
    return parameters.linear_solver == Solver::direct &&
           mumps_for(parameters, n_unknowns) &&
           parameters.symmetric_factorization &&
           dealii::Utilities::MPI::n_mpi_processes(mpi_communicator) == 1;
  }



  bool
  LinearSolver::uses_direct_solver() const
  {
    return parameters.linear_solver ==
           Parameters::LinearSolver::LinearSolverType::direct;
  }



  // The analysed matrix is recognised by the address of the Epetra matrix
  // inside the deal.II object: deal.II replaces that Epetra object when the
  // matrix is reinitialised with a new pattern, and keeps it when only the
  // values change. The number of rows and of nonzeros are compared as
  // well, so that a new Epetra matrix that happens to be created at the
  // address of a destroyed one with another pattern is not mistaken for
  // it.
  bool
  LinearSolver::is_analysed_matrix(
    const TrilinosWrappers::SparseMatrix &matrix) const
  {
    return analysed_matrix == &matrix.trilinos_matrix() &&
           analysed_rows == matrix.m() &&
           analysed_nonzeros == matrix.n_nonzero_elements();
  }



  void
  LinearSolver::remember_analysed_matrix(
    const TrilinosWrappers::SparseMatrix &matrix)
  {
    analysed_matrix   = &matrix.trilinos_matrix();
    analysed_rows     = matrix.m();
    analysed_nonzeros = matrix.n_nonzero_elements();
  }



  // @sect4{LinearSolver::prepare_factorization}
  //
  // The fill-reducing ordering depends only on the sparsity pattern, which
  // never changes: the symbolic analysis is done once per matrix object,
  // the numerical factorization for every new matrix. (deal.II's
  // SolverDirect repeats both every time.)
  //
  // KLU also keeps the pivot sequence of its first factorization and
  // refactorizes the following matrices with it (Amesos' parameter
  // "Refactorize"), which skips the search for pivots: half the
  // factorization's time on the coarse bellows meshes, no gain at some
  // 20,000 unknowns, where the arithmetic dominates. When the old pivots
  // give a poorly conditioned factor -- the smallest diagonal entry of
  // $\mathbf U$ over the largest at most $10^{-12}$, Amesos' test -- or a
  // zero pivot, Amesos factorizes with pivoting afresh. A matrix that is
  // singular even then makes the factorization fail, and the step with it.
  void
  LinearSolver::prepare_factorization(
    const TrilinosWrappers::SparseMatrix &matrix)
  {
    TimerOutput::Scope timer_section(timer, "Factorization");
    if (!is_analysed_matrix(matrix))
      create_factorization(matrix);
    if (symmetric_factorization)
      {
        if (!symmetric_factorization->factorize(matrix))
          throw StepFailure("the symmetric factorization found the matrix "
                            "singular");
        return;
      }
    if (direct_factorization->NumericFactorization() != 0)
      throw StepFailure("the sparse factorization failed (singular "
                        "matrix?)");
  }



  // A new Amesos solver for a new matrix object, with its symbolic
  // analysis. Amesos works on an Epetra_LinearProblem, whose SetOperator()
  // takes a non-const pointer, but deal.II hands out its Epetra matrix as
  // const only. The solvers read the matrix and do not write to it (KLU
  // reads the values in place when the matrix is on one process), which
  // tests/linear_solver.cc checks; hence the const_cast.
  //
  // The name of the solver is the one given to Amesos' factory, which is
  // also the name of the class it creates (the test checks that too).
  void
  LinearSolver::create_factorization(
    const TrilinosWrappers::SparseMatrix &matrix)
  {
    direct_factorization.reset();
    symmetric_factorization.reset();
    if (uses_symmetric_factorization(matrix.m()))
      {
        direct_problem.reset();
        symmetric_factorization = std::make_unique<SymmetricFactorization>(
          (parameters.single_precision_factor && single_precision_allowed)
            ? SymmetricFactorization::Precision::single_precision
            : SymmetricFactorization::Precision::double_precision);
        symmetric_factorization->analyse(matrix);
        direct_solver_name = "MUMPS symmetric";
        remember_analysed_matrix(matrix);
        return;
      }
    direct_problem = std::make_unique<Epetra_LinearProblem>();
    direct_problem->SetOperator(
      const_cast<Epetra_CrsMatrix *>(&matrix.trilinos_matrix()));
    const std::string package =
      uses_mumps(matrix.m()) ? "Amesos_Mumps" : "Amesos_Klu";
    Amesos factory;
    direct_factorization.reset(
      factory.Create(package.c_str(), *direct_problem));
    AssertThrow(direct_factorization != nullptr,
                ExcMessage("Trilinos has no " + package +
                           " solver (Linear solver/Direct solver)."));
    direct_solver_name = package;
    if (!uses_mumps(matrix.m()))
      {
        Teuchos::ParameterList amesos_parameters;
        amesos_parameters.set("Refactorize", true);
        direct_factorization->SetParameters(amesos_parameters);
      }
    else
      {
        // MUMPS without its scaling of rows and columns (ICNTL(8) = 0
        // instead of its automatic choice; its threshold pivoting stays):
        // on the hexahedral bellows the factorizations took a quarter less
        // time and gave the same iterates to round-off
        // (doc/performance_discussion.md, item 31).
        auto *mumps = dynamic_cast<Amesos_Mumps *>(direct_factorization.get());
        AssertThrow(mumps != nullptr, ExcInternalError());
        mumps->SetICNTL(8, 0);
      }
    AssertThrow(direct_factorization->SymbolicFactorization() == 0,
                ExcMessage(package + ": the symbolic factorization failed."));
    remember_analysed_matrix(matrix);
  }



  // @sect4{LinearSolver::prepare_multigrid}
  //
  // ML's aggregates -- which unknowns each coarse unknown stands for --
  // follow from the sparsity pattern, which never changes, and from the
  // strength of the couplings, which at the default threshold counts nearly
  // every coupling. After the first matrix of a matrix object, the
  // hierarchy is therefore recomputed on the aggregates it has: the
  // prolongators, coarse matrices, smoothers and the coarse factorization
  // come from the new matrix, and only the aggregation is skipped, which on
  // the bellows takes a sixth to a quarter off a set-up's time (measured in
  // doc/performance_discussion.md).
  void
  LinearSolver::prepare_multigrid(const TrilinosWrappers::SparseMatrix &matrix)
  {
    TimerOutput::Scope timer_section(timer, "Preconditioner setup");
    if (amg_preconditioner != nullptr && is_analysed_matrix(matrix))
      LinearSolverInternals::recompute_on_old_aggregates(*amg_preconditioner);
    else
      build_multigrid(matrix);
  }



  // @sect4{LinearSolver::build_multigrid}
  //
  // A hierarchy from scratch. ML is told that the problem is elliptic and,
  // for quadratic elements, that the matrix comes from higher-order
  // elements; deal.II turns these choices into ML's parameter list
  // (smoothed aggregation, Chebyshev smoothing, KLU on the coarsest level
  // of at most 2,000 unknowns).
  //
  // ML builds its coarse spaces from the near null space. deal.II's
  // interface takes only modes of zeros and ones (the constant modes of
  // each component); for elasticity the rotations belong to it too, and
  // without them CG needs many more iterations. They reach ML through its
  // parameter list, in the layout deal.II uses for the constant modes:
  // mode $k$ of the $n$ locally owned rows at positions $kn,\dots,kn+n-1$
  // of one array. ML keeps a pointer to that array, which therefore lives
  // as long as the hierarchy; the old hierarchy goes before the array is
  // refilled.
  void
  LinearSolver::build_multigrid(const TrilinosWrappers::SparseMatrix &matrix)
  {
    amg_preconditioner.reset();
    operator_complexity = 0.;

    TrilinosWrappers::PreconditionAMG::AdditionalData data;
    data.elliptic              = true;
    data.higher_order_elements = (polynomial_degree > 1);
    data.smoother_sweeps       = parameters.smoother_sweeps;
    data.aggregation_threshold = parameters.aggregation_threshold;

    Teuchos::ParameterList              ml_parameters;
    std::unique_ptr<Epetra_MultiVector> constant_modes;
    data.set_parameters(ml_parameters,
                        constant_modes,
                        matrix.trilinos_matrix());

    if (!near_null_space.empty())
      {
        const std::size_t n_local =
          matrix.trilinos_matrix().DomainMap().NumMyElements();
        AssertThrow(near_null_space[0].size() == n_local,
                    ExcMessage("The near-null-space modes have " +
                               std::to_string(near_null_space[0].size()) +
                               " entries, but the matrix has " +
                               std::to_string(n_local) +
                               " locally owned rows."));
        ml_null_space.assign(near_null_space.size() * n_local, 0.);
        for (unsigned int k = 0; k < near_null_space.size(); ++k)
          std::copy(near_null_space[k].begin(),
                    near_null_space[k].end(),
                    ml_null_space.begin() + k * n_local);
        ml_parameters.set("null space: type", "pre-computed");
        ml_parameters.set("null space: dimension",
                          static_cast<int>(near_null_space.size()));
        ml_parameters.set("null space: vectors", ml_null_space.data());
      }
    amg_preconditioner = std::make_unique<TrilinosWrappers::PreconditionAMG>();
    amg_preconditioner->initialize(matrix, ml_parameters);
    remember_analysed_matrix(matrix);

    operator_complexity =
      LinearSolverInternals::operator_complexity(*amg_preconditioner,
                                                 matrix,
                                                 mpi_communicator);
  }



  // @sect4{LinearSolver::solve}
  //
  // The iterative solvers stop when the residual has dropped by the
  // relative tolerance, $\|\mathbf b - \mathbf A\mathbf x_k\| \le
  // \varepsilon_\text{rel}\|\mathbf b\|$: in the inexact Newton method that
  // is the forcing term, and the Newton iteration decides the accuracy of
  // the result. Not converging within the maximum number of iterations is a
  // failure of the step, which the time loop answers with a smaller step.
  unsigned int
  LinearSolver::solve(const TrilinosWrappers::MPI::Vector &rhs,
                      TrilinosWrappers::MPI::Vector       &solution)
  {
    TimerOutput::Scope timer_section(timer, "Linear solve");
    Assert(prepared_matrix != nullptr && is_prepared,
           ExcMessage("LinearSolver::solve() needs a successful prepare()."));
    Assert(rhs.size() == prepared_matrix->m(),
           ExcDimensionMismatch(rhs.size(), prepared_matrix->m()));
    Assert(solution.size() == prepared_matrix->n(),
           ExcDimensionMismatch(solution.size(), prepared_matrix->n()));
    solution = 0.;
    if (uses_direct_solver())
      {
        solve_direct(rhs, solution);
        return 1;
      }
    return solve_iterative(rhs, solution);
  }



  // The triangular solves. Like the matrix, the right-hand side goes to
  // Amesos through Epetra_LinearProblem's non-const pointer; Amesos copies
  // it and does not write to it (checked by the test). A failure here,
  // after a successful factorization, is not a property of the step but an
  // error.
  void
  LinearSolver::solve_direct(const TrilinosWrappers::MPI::Vector &rhs,
                             TrilinosWrappers::MPI::Vector       &solution)
  {
    if (symmetric_factorization)
      {
        symmetric_factorization->solve(rhs, solution);
        return;
      }
    direct_problem->SetLHS(&solution.trilinos_vector());
    direct_problem->SetRHS(
      const_cast<Epetra_MultiVector *>(&rhs.trilinos_vector()));
    AssertThrow(direct_factorization->Solve() == 0,
                ExcMessage("The direct solver's triangular solves failed."));
  }



  unsigned int
  LinearSolver::solve_iterative(const TrilinosWrappers::MPI::Vector &rhs,
                                TrilinosWrappers::MPI::Vector       &solution)
  {
    SolverControl control(parameters.linear_max_iterations,
                          parameters.linear_relative_tolerance * rhs.l2_norm());
    try
      {
        if (parameters.linear_solver ==
            Parameters::LinearSolver::LinearSolverType::cg)
          {
            SolverCG<TrilinosWrappers::MPI::Vector> cg(control);
            cg.solve(*prepared_matrix, solution, rhs, *amg_preconditioner);
          }
        else
          {
            // Right preconditioning: GMRES then minimizes, and the control
            // tests, the residual of the system itself. With deal.II's
            // default, left preconditioning, the control would test the
            // preconditioned residual, which AMG scales by the inverse of
            // the stiffness: a step of the bellows "converged" in three
            // iterations with a wrong update.
            SolverGMRES<TrilinosWrappers::MPI::Vector> gmres(
              control,
              SolverGMRES<TrilinosWrappers::MPI::Vector>::AdditionalData(30,
                                                                         true));
            gmres.solve(*prepared_matrix, solution, rhs, *amg_preconditioner);
          }
      }
    catch (SolverControl::NoConvergence &failure)
      {
        std::ostringstream message;
        message << "the linear solver did not converge in " << failure.last_step
                << " iterations (residual " << failure.last_residual << ")";
        throw StepFailure(message.str());
      }
    return control.last_step();
  }



  // @sect4{The statistics}
  unsigned int
  LinearSolver::n_preparations() const
  {
    return preparations;
  }



  void
  LinearSolver::set_n_preparations(const unsigned int n)
  {
    preparations = n;
  }



  std::string
  LinearSolver::solver_in_use() const
  {
    if (uses_direct_solver())
      return (direct_factorization || symmetric_factorization)
               ? direct_solver_name
               : "";
    return amg_preconditioner
             ? Parameters::name_of(parameters.linear_solver) + " with ML"
             : "";
  }



  double
  LinearSolver::multigrid_operator_complexity() const
  {
    return operator_complexity;
  }



  namespace LinearSolverInternals
  {
    namespace
    {
      // @sect4{ML's data behind deal.II's preconditioner}
      //
      // deal.II's PreconditionAMG gives access to the Trilinos operator it
      // built, an ML_Epetra::MultiLevelPreconditioner, only as an
      // Epetra_Operator, and that class in turn hands out its hierarchy,
      // the C structure `ML`, only as a const pointer. The recomputation
      // below has to change two values in that structure, and the operator
      // complexity reads the sizes of its levels; neither deal.II nor ML's
      // C++ class provides these. (The dynamic_cast throws std::bad_cast if
      // deal.II ever builds a different operator.)
      ML_Epetra::MultiLevelPreconditioner &
      multilevel_preconditioner(const TrilinosWrappers::PreconditionAMG &amg)
      {
        return dynamic_cast<ML_Epetra::MultiLevelPreconditioner &>(
          amg.trilinos_operator());
      }



      ML &
      multigrid_hierarchy(const TrilinosWrappers::PreconditionAMG &amg)
      {
        ML *ml = const_cast<ML *>(multilevel_preconditioner(amg).GetML());
        Assert(ml != nullptr, ExcInternalError());
        return *ml;
      }
    } // namespace



    // @sect4{LinearSolverInternals::recompute_on_old_aggregates}
    //
    // ML's ReComputePreconditioner() -- which deal.II's
    // PreconditionAMG::reinit() calls, and nothing more -- rebuilds all
    // levels below the finest on the old aggregates, but on the finest
    // level it keeps two values it computed from the old matrix: the
    // diagonal $\mathbf D$ and the estimate $\lambda_\text{max}$ of the
    // largest eigenvalue of $\mathbf D^{-1}\mathbf A$. With them it smooths
    // the tentative prolongator, $\mathbf P = (\mathbf I -
    // \tfrac{4}{3\lambda_\text{max}}\mathbf D^{-1}\mathbf A)\mathbf P_0$,
    // and sets up the Chebyshev smoother on the interval
    // $[\lambda_\text{max}/\alpha, \lambda_\text{max}]$ (up to a safety
    // factor), $\alpha = 10$. When the new matrix differs from the old one
    // by more than a little, both are wrong: after four time-step cut-backs
    // in a row the mass's share of the matrix has grown by $2^8 = 256$, and
    // CG with the recomputed hierarchy diverged (in the 1D run of
    // tests/modified_newton.cc). The two values are therefore cleared first
    // -- the diagonal freed, the eigenvalue estimates set to $-666.666$,
    // ML's mark for "not computed" -- so that the recomputed hierarchy
    // comes from the new matrix alone, on the old aggregates.
    //
    // tests/linear_solver.cc checks that these two are all that ML keeps
    // of the old matrix: given the new hierarchy's eigenvalue estimate, the
    // recomputed hierarchy is the new one to the last bit. (Without it, ML
    // estimates the eigenvalue again from another random start vector,
    // which changes the estimate by up to a few per cent.)
    void
    recompute_on_old_aggregates(TrilinosWrappers::PreconditionAMG &amg)
    {
      ML          &ml     = multigrid_hierarchy(amg);
      ML_Operator &finest = ml.Amat[ml.ML_finest_level];
      if (finest.diagonal != nullptr)
        ML_DVector_Destroy(&finest.diagonal);
      finest.diagonal   = nullptr;
      finest.lambda_max = -666.666;
      finest.lambda_min = -666.666;
      AssertThrow(multilevel_preconditioner(amg).ReComputePreconditioner() == 0,
                  ExcMessage("ML could not recompute the multigrid "
                             "hierarchy."));
    }



    // @sect4{LinearSolverInternals::operator_complexity}
    //
    // The hierarchy's size, for the run statistics: a CG iteration applies
    // every level's matrix, so its cost follows the nonzeros of all levels,
    // $\sum_\ell \mathrm{nnz}(\mathbf A_\ell)/\mathrm{nnz}(\mathbf A_0)$,
    // counted as the entries that the rows of each level's matrix hold. ML
    // numbers its levels up or down from the finest; each process counts
    // its rows. The recomputation keeps the aggregates, and with them the
    // sizes of the levels, so the number holds as long as the matrix
    // object does.
    double
    operator_complexity(const TrilinosWrappers::PreconditionAMG &amg,
                        const TrilinosWrappers::SparseMatrix    &matrix,
                        const MPI_Comm mpi_communicator)
    {
      ML       &ml   = multigrid_hierarchy(amg);
      const int step = (ml.ML_coarsest_level >= ml.ML_finest_level ? 1 : -1);
      double    all_levels = 0.;
      for (int level = ml.ML_finest_level;; level += step)
        {
          all_levels += ML_Operator_ComputeNumNzs(&ml.Amat[level]);
          if (level == ml.ML_coarsest_level)
            break;
        }
      // (Qualified: Amesos_Mumps.h opens namespace Teuchos, which has a
      // Utilities of its own.)
      return dealii::Utilities::MPI::sum(all_levels, mpi_communicator) /
             static_cast<double>(matrix.n_nonzero_elements());
    }
  } // namespace LinearSolverInternals
} // namespace SoftRobot
