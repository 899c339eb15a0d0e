// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Tests of the linear solver}
//
// LinearSolver (source/solvers/linear_solver.cc) relies on Trilinos in
// ways that deal.II's wrappers do not promise, and each of them is checked
// here against the Trilinos version in use:
// - Amesos reads, and does not write, the matrix and the right-hand side
//   it gets through non-const pointers;
// - KLU refactorizes a new matrix with the old pivots and falls back to a
//   factorization with pivoting when these pivots are bad;
// - the rigid-body modes passed through ML's parameter list are ML's near
//   null space, in deal.II's layout;
// - the finest level's diagonal and eigenvalue estimate are all that ML's
//   recomputation on the old aggregates keeps of the old matrix: after
//   clearing them it gives the hierarchy built from scratch (up to ML's
//   new eigenvalue estimate), and without the clearing it does not;
// - the operator complexity counted from ML's levels is ML's own (to the
//   few entries by which ML's records of the coarse matrices differ);
// - the names of the direct solvers are the classes Amesos creates;
// - MUMPS's back substitution calls the program's dgemm_ and dtrsm_ (and
//   sgemm_ and strsm_ for the single-precision factor), whose
//   single-column calls give what OpenBLAS's routines give.
// Besides, the tests check the solver's contract: exact solutions of the
// direct solvers, the tolerance of the iterative ones, StepFailure when a
// factorization or an iteration fails, and the statistics.
//
// The matrices are those of linear elasticity (Lamé parameters
// $\lambda=\mu=1$) on the unit square or cube of linear elements, clamped
// at $x=0$, in the form of the effective tangent of a time step,
// $\mathbf A = \mathbf K + c\,\mathbf M$, with $c = n^2$ for $n$ cells per
// direction, which makes the mass's share of the diagonal about that of the
// stiffness (in 1D the matrix is that of $-3u'' + c\,u$). Multigrid needs
// more unknowns than ML's coarsest level (2,000) to have more than one
// level: 2,400 cells in 1D, 36 x 36 in 2D, 10 x 10 x 10 in 3D (2,401,
// 2,738 and 3,993 unknowns).

#include <Amesos.h>
#include <Amesos_BaseSolver.h>
#include <Amesos_Klu.h>
#include <Amesos_Mumps.h>
#include <Epetra_CrsMatrix.h>
#include <Epetra_LinearProblem.h>
#include <Teuchos_ParameterList.hpp>
#include <algorithm>
#include <cmath>
#include <core/exceptions.h>
#include <cstddef>
#include <cstdint>
#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/function.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/timer.h>
#include <deal.II/distributed/shared_tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/lapack_templates.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/numerics/vector_tools.h>
#include <gtest/gtest.h>
#include <iostream>
#include <limits>
#include <memory>
#include <ml_MultiLevelPreconditioner.h>
#include <solvers/linear_solver.h>
#include <solvers/single_column_blas.h>
#include <string>
#include <type_traits>
#include <vector>

using namespace dealii;
using namespace SoftRobot;

namespace
{
  using Dimensions = ::testing::Types<std::integral_constant<int, 1>,
                                      std::integral_constant<int, 2>,
                                      std::integral_constant<int, 3>>;

  // Cells per direction of the meshes that give ML a hierarchy of several
  // levels, and of meshes below ML's coarsest size (201, 242 and 375
  // unknowns), where the hierarchy is the finest level alone.
  constexpr unsigned int multilevel_cells[3]   = {2400, 36, 10};
  constexpr unsigned int single_level_cells[3] = {200, 10, 4};

  using SolverType = Parameters::LinearSolver::LinearSolverType;
  using DirectType = Parameters::LinearSolver::DirectSolverType;

  Parameters::LinearSolver
  solver_parameters(const SolverType   type,
                    const DirectType   direct         = DirectType::klu,
                    const double       tolerance      = 1e-10,
                    const unsigned int max_iterations = 1000)
  {
    Parameters::LinearSolver parameters;
    parameters.linear_solver             = type;
    parameters.direct_solver             = direct;
    parameters.linear_relative_tolerance = tolerance;
    parameters.linear_max_iterations     = max_iterations;
    parameters.smoother_sweeps           = 2;
    parameters.aggregation_threshold     = 1e-4;
    return parameters;
  }



  // @sect4{The elastic body}
  //
  // Stiffness and mass matrix of the clamped unit cube, distributed over
  // the processes, with the constrained rows and columns treated by
  // AffineConstraints as in the program; the near null space at the
  // vertices; and a right-hand side.
  template <int dim>
  class ElasticBody
  {
  public:
    explicit ElasticBody(const unsigned int n_cells);

    // $\mathbf K + c\,\mathbf M$ in the matrix object `matrix`, whose
    // Epetra matrix is kept if it has the pattern already.
    void
    set_matrix(const double c, TrilinosWrappers::SparseMatrix &matrix) const;

    // $c = n^2$: the mass's share of the diagonal about the stiffness's.
    double
    mass_factor() const
    {
      return static_cast<double>(n_cells) * n_cells;
    }

    // An irregular right-hand side, zero where the displacement is
    // prescribed.
    TrilinosWrappers::MPI::Vector
    right_hand_side() const;

    // The translations, and with `with_rotations` the rotations, at the
    // vertices: one vector of the locally owned entries per mode.
    std::vector<std::vector<double>>
    rigid_body_modes(const bool with_rotations) const;

    // The translations as deal.II's AMG takes them.
    std::vector<std::vector<bool>>
    constant_modes() const;

    // The locally owned dof of component `component` at the vertex nearest
    // to the centre of the body, on the process that owns it; an invalid
    // index on the others.
    types::global_dof_index
    centre_dof(const unsigned int component) const;

    const unsigned int                   n_cells;
    parallel::shared::Triangulation<dim> triangulation;
    FESystem<dim>                        fe;
    DoFHandler<dim>                      dof_handler;
    IndexSet                             owned_dofs;
    IndexSet                             relevant_dofs;
    AffineConstraints<double>            constraints;
    TrilinosWrappers::SparsityPattern    sparsity;
    TrilinosWrappers::SparseMatrix       stiffness;
    TrilinosWrappers::SparseMatrix       mass;

  private:
    void
    assemble();
    // The vertices of the owned dofs and their components.
    std::vector<Point<dim>>   owned_points;
    std::vector<unsigned int> owned_components;
  };



  template <int dim>
  ElasticBody<dim>::ElasticBody(const unsigned int n_cells)
    : n_cells(n_cells)
    , triangulation(MPI_COMM_WORLD)
    , fe(FE_Q<dim>(1), dim)
    , dof_handler(triangulation)
  {
    const std::vector<unsigned int> repetitions(dim, n_cells);
    Point<dim>                      corner;
    for (unsigned int d = 0; d < dim; ++d)
      corner[d] = 1.;
    GridGenerator::subdivided_hyper_rectangle(
      triangulation, repetitions, Point<dim>(), corner, true);
    dof_handler.distribute_dofs(fe);
    owned_dofs = dof_handler.locally_owned_dofs();
    DoFTools::extract_locally_relevant_dofs(dof_handler, relevant_dofs);

    constraints.reinit(relevant_dofs);
    VectorTools::interpolate_boundary_values(dof_handler,
                                             0,
                                             Functions::ZeroFunction<dim>(dim),
                                             constraints);
    constraints.close();

    sparsity.reinit(owned_dofs, owned_dofs, relevant_dofs, MPI_COMM_WORLD);
    DoFTools::make_sparsity_pattern(dof_handler,
                                    sparsity,
                                    constraints,
                                    false,
                                    dealii::Utilities::MPI::this_mpi_process(
                                      MPI_COMM_WORLD));
    sparsity.compress();
    stiffness.reinit(sparsity);
    mass.reinit(sparsity);
    assemble();
  }



  // The bilinear forms $\int\lambda\,\nabla\cdot\mathbf v\,\nabla\cdot\mathbf
  // u + 2\mu\,\varepsilon(\mathbf v):\varepsilon(\mathbf u)$ and $\int\mathbf
  // v\cdot\mathbf u$, and the vertex of every owned dof.
  template <int dim>
  void
  ElasticBody<dim>::assemble()
  {
    const double      lambda = 1., mu = 1.;
    const QGauss<dim> quadrature(2);
    FEValues<dim>     fe_values(
      fe, quadrature, update_values | update_gradients | update_JxW_values);
    const Quadrature<dim> vertices(fe.get_unit_support_points());
    FEValues<dim>         vertex_values(fe, vertices, update_quadrature_points);
    const unsigned int    n = fe.n_dofs_per_cell();
    FullMatrix<double>    cell_stiffness(n, n), cell_mass(n, n);
    std::vector<types::global_dof_index> dofs(n);
    owned_points.resize(owned_dofs.n_elements());
    owned_components.resize(owned_dofs.n_elements());

    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          cell_stiffness = 0.;
          cell_mass      = 0.;
          for (unsigned int q = 0; q < quadrature.size(); ++q)
            for (unsigned int i = 0; i < n; ++i)
              {
                const unsigned int   ci = fe.system_to_component_index(i).first;
                const Tensor<1, dim> grad_i = fe_values.shape_grad(i, q);
                for (unsigned int j = 0; j < n; ++j)
                  {
                    const unsigned int cj =
                      fe.system_to_component_index(j).first;
                    const Tensor<1, dim> grad_j = fe_values.shape_grad(j, q);
                    double               k = lambda * grad_i[ci] * grad_j[cj] +
                               mu * grad_i[cj] * grad_j[ci];
                    if (ci == cj)
                      {
                        k += mu * (grad_i * grad_j);
                        cell_mass(i, j) += fe_values.shape_value(i, q) *
                                           fe_values.shape_value(j, q) *
                                           fe_values.JxW(q);
                      }
                    cell_stiffness(i, j) += k * fe_values.JxW(q);
                  }
              }
          cell->get_dof_indices(dofs);
          constraints.distribute_local_to_global(cell_stiffness,
                                                 dofs,
                                                 stiffness);
          constraints.distribute_local_to_global(cell_mass, dofs, mass);

          vertex_values.reinit(cell);
          for (unsigned int i = 0; i < n; ++i)
            if (owned_dofs.is_element(dofs[i]))
              {
                const auto local        = owned_dofs.index_within_set(dofs[i]);
                owned_points[local]     = vertex_values.quadrature_point(i);
                owned_components[local] = fe.system_to_component_index(i).first;
              }
        }
    stiffness.compress(VectorOperation::add);
    mass.compress(VectorOperation::add);
  }



  template <int dim>
  void
  ElasticBody<dim>::set_matrix(const double                    c,
                               TrilinosWrappers::SparseMatrix &matrix) const
  {
    if (matrix.m() == 0)
      matrix.reinit(sparsity);
    matrix = 0.;
    matrix.add(1., stiffness);
    matrix.add(c, mass);
  }



  template <int dim>
  TrilinosWrappers::MPI::Vector
  ElasticBody<dim>::right_hand_side() const
  {
    TrilinosWrappers::MPI::Vector rhs(owned_dofs, MPI_COMM_WORLD);
    for (const auto i : owned_dofs)
      rhs[i] = 0.5 + std::cos(1.3 * static_cast<double>(i));
    rhs.compress(VectorOperation::insert);
    constraints.set_zero(rhs);
    return rhs;
  }



  template <int dim>
  std::vector<std::vector<double>>
  ElasticBody<dim>::rigid_body_modes(const bool with_rotations) const
  {
    const unsigned int n_rotations = with_rotations ? dim * (dim - 1) / 2 : 0;
    std::vector<std::vector<double>> modes(
      dim + n_rotations, std::vector<double>(owned_dofs.n_elements(), 0.));
    for (unsigned int local = 0; local < owned_points.size(); ++local)
      {
        const unsigned int c = owned_components[local];
        const Point<dim>  &x = owned_points[local];
        modes[c][local]      = 1.;
        if constexpr (dim == 2)
          if (with_rotations)
            modes[2][local] = (c == 0) ? -x[1] : x[0];
        if constexpr (dim == 3)
          if (with_rotations)
            {
              // Rotations about x, y and z: (0,-z,y), (z,0,-x), (-y,x,0).
              const double rx[3] = {0., -x[2], x[1]};
              const double ry[3] = {x[2], 0., -x[0]};
              const double rz[3] = {-x[1], x[0], 0.};
              modes[3][local]    = rx[c];
              modes[4][local]    = ry[c];
              modes[5][local]    = rz[c];
            }
      }
    return modes;
  }



  template <int dim>
  std::vector<std::vector<bool>>
  ElasticBody<dim>::constant_modes() const
  {
    std::vector<std::vector<bool>> modes;
    DoFTools::extract_constant_modes(dof_handler,
                                     ComponentMask(dim, true),
                                     modes);
    return modes;
  }



  template <int dim>
  types::global_dof_index
  ElasticBody<dim>::centre_dof(const unsigned int component) const
  {
    Point<dim> centre;
    for (unsigned int d = 0; d < dim; ++d)
      centre[d] = 0.5;
    for (unsigned int local = 0; local < owned_points.size(); ++local)
      if (owned_components[local] == component &&
          owned_points[local].distance(centre) < 1e-10)
        return owned_dofs.nth_index_in_set(local);
    return numbers::invalid_dof_index;
  }



  // @sect4{Helpers}

  // $\|\mathbf b - \mathbf A\mathbf x\| / \|\mathbf b\|$.
  double
  relative_residual(const TrilinosWrappers::SparseMatrix &matrix,
                    const TrilinosWrappers::MPI::Vector  &solution,
                    const TrilinosWrappers::MPI::Vector  &rhs)
  {
    TrilinosWrappers::MPI::Vector residual(rhs);
    matrix.vmult(residual, solution);
    residual.sadd(-1., 1., rhs);
    return residual.l2_norm() / rhs.l2_norm();
  }

  // $\|\mathbf x - \mathbf y\| / \|\mathbf y\|$.
  double
  relative_difference(const TrilinosWrappers::MPI::Vector &x,
                      const TrilinosWrappers::MPI::Vector &y)
  {
    TrilinosWrappers::MPI::Vector difference(x);
    difference -= y;
    return difference.l2_norm() / y.l2_norm();
  }

  // The largest difference of two matrices with the same pattern.
  double
  max_difference(const TrilinosWrappers::SparseMatrix &a,
                 const TrilinosWrappers::SparseMatrix &b)
  {
    TrilinosWrappers::SparseMatrix difference;
    difference.copy_from(a);
    difference.add(-1., b);
    return difference.linfty_norm();
  }

  // Sets the entries of row `row` to the values `row_values(column)`, on
  // the process that owns it (collective).
  template <typename Function>
  void
  set_row(TrilinosWrappers::SparseMatrix &matrix,
          const types::global_dof_index   row,
          const Function                 &row_values)
  {
    if (row != numbers::invalid_dof_index &&
        matrix.locally_owned_range_indices().is_element(row))
      {
        std::vector<std::pair<types::global_dof_index, double>> entries;
        for (auto entry = matrix.begin(row); entry != matrix.end(row); ++entry)
          entries.emplace_back(entry->column(), row_values(entry->column()));
        for (const auto &[column, value] : entries)
          matrix.set(row, column, value);
      }
    matrix.compress(VectorOperation::insert);
  }

  // The index that one process knows, on all of them.
  types::global_dof_index
  on_all_processes(const types::global_dof_index index)
  {
    const types::global_dof_index known =
      (index == numbers::invalid_dof_index) ? 0 : index + 1;
    return dealii::Utilities::MPI::max(known, MPI_COMM_WORLD) - 1;
  }

  // CG with deal.II's own AMG, for comparison with the LinearSolver's:
  // the number of iterations to the relative tolerance, or the maximum
  // number plus one if CG does not converge in it.
  unsigned int
  cg_iterations(const TrilinosWrappers::SparseMatrix    &matrix,
                const TrilinosWrappers::PreconditionAMG &amg,
                const TrilinosWrappers::MPI::Vector     &rhs,
                TrilinosWrappers::MPI::Vector           &solution,
                const double                             tolerance,
                const unsigned int                       max_iterations = 1000)
  {
    SolverControl control(max_iterations, tolerance * rhs.l2_norm());
    SolverCG<TrilinosWrappers::MPI::Vector> cg(control);
    solution = 0.;
    try
      {
        cg.solve(matrix, solution, rhs, amg);
      }
    catch (const SolverControl::NoConvergence &)
      {
        return max_iterations + 1;
      }
    return control.last_step();
  }

  // deal.II's AMG with the parameters the LinearSolver uses, and the
  // translations as deal.II passes constant modes to ML.
  TrilinosWrappers::PreconditionAMG::AdditionalData
  amg_data(const std::vector<std::vector<bool>> &constant_modes)
  {
    TrilinosWrappers::PreconditionAMG::AdditionalData data;
    data.elliptic              = true;
    data.higher_order_elements = false;
    data.smoother_sweeps       = 2;
    data.aggregation_threshold = 1e-4;
    data.constant_modes        = constant_modes;
    return data;
  }

  std::string
  processes_prefix()
  {
    return "[" +
           std::to_string(
             dealii::Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD)) +
           " process(es)] ";
  }
} // namespace



template <typename T>
class LinearSolverTest : public ::testing::Test
{
protected:
  LinearSolverTest()
    : quiet(std::cout, false)
    , timer(MPI_COMM_WORLD, quiet, TimerOutput::never, TimerOutput::wall_times)
    , log(std::cout,
          dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
  {
  }

  ConditionalOStream quiet;
  TimerOutput        timer;
  ConditionalOStream log;
};
TYPED_TEST_SUITE(LinearSolverTest, Dimensions);



// @sect4{The direct solvers}
//
// Both direct solvers solve the system to round-off. A backward-stable
// solver leaves a residual $\|\mathbf b - \mathbf A\mathbf x\| \le
// c_n\epsilon\|\mathbf A\|\,\|\mathbf x\|$, and $\|\mathbf
// A\|\,\|\mathbf x\|/\|\mathbf b\|$ is at most the condition number,
// below $10^3$ for these matrices; with a modest growth factor $c_n$ the
// relative residual must be below $10^{-12}$ (measured: $4\cdot10^{-16}$
// to $3\cdot10^{-15}$). Amesos gets the matrix and the right-hand side
// through non-const pointers (deal.II hands them out as const): neither
// may change, not in the last bit.
TYPED_TEST(LinearSolverTest, DirectSolversSolveExactlyAndLeaveTheirInputAlone)
{
  constexpr int                  dim = TypeParam::value;
  const ElasticBody<dim>         body(multilevel_cells[dim - 1]);
  TrilinosWrappers::SparseMatrix matrix, matrix_before;
  body.set_matrix(body.mass_factor(), matrix);
  matrix_before.copy_from(matrix);
  const TrilinosWrappers::MPI::Vector rhs = body.right_hand_side();
  const TrilinosWrappers::MPI::Vector rhs_before(rhs);

  // One solver of each kind on the same matrix and right-hand side, which
  // must come out of both unchanged.
  for (const DirectType type : {DirectType::klu, DirectType::mumps})
    {
      LinearSolver solver(solver_parameters(SolverType::direct, type),
                          1,
                          MPI_COMM_WORLD,
                          this->timer);
      TrilinosWrappers::MPI::Vector solution(body.owned_dofs, MPI_COMM_WORLD);
      solver.prepare(matrix);
      EXPECT_EQ(solver.solve(rhs, solution), 1u);
      const double residual = relative_residual(matrix, solution, rhs);
      this->log << processes_prefix() << dim << "D " << solver.solver_in_use()
                << ": relative residual " << residual << std::endl;
      EXPECT_LT(residual, 1e-12);
      EXPECT_EQ(max_difference(matrix, matrix_before), 0.);
      EXPECT_EQ(relative_difference(rhs, rhs_before), 0.);
      EXPECT_EQ(solver.n_preparations(), 1u);
      EXPECT_EQ(solver.multigrid_operator_complexity(), 0.);
    }
  // The direct solvers' time is booked in their two sections only.
  const auto times = this->timer.get_summary_data(TimerOutput::total_wall_time);
  EXPECT_EQ(times.count("Factorization"), 1u);
  EXPECT_EQ(times.count("Linear solve"), 1u);
  EXPECT_EQ(times.count("Preconditioner setup"), 0u);
}



// @sect4{KLU's refactorization}
//
// The solver keeps KLU's pivot sequence from one matrix to the next of the
// same matrix object (Amesos' "Refactorize"). Three matrices in one object:
// $\mathbf K + c\mathbf M$; $\mathbf K + 256c\mathbf M$, as after four
// time-step cut-backs, for which the old (diagonal) pivots serve well; and
// a matrix for which they are useless: two coupled unknowns $i$, $j$ at the
// centre are cut off from all others and coupled by the block
// @f[ \begin{pmatrix} \delta & s\\ s & \delta\end{pmatrix},\qquad
//   \delta = 10^{-14}s, @f]
// whose first diagonal pivot is $\delta$ in any elimination order. The
// matrix is as well conditioned as the first (the block's eigenvalues are
// $\pm s + \delta$), but elimination with the old pivots loses about
// $\epsilon s/\delta = 10^{-2}$ of the solution in these two unknowns. Amesos
// sees the smallest diagonal entry of $\mathbf U$ over the largest below
// $10^{-12}$ and factorizes with pivoting afresh. Each solution must be
// exact to $10^{-12}$ (see above); and to show that the fall-back is what
// makes the third one exact, KLU made to accept any refactorization
// (an rcond threshold of -1) must miss it by far.
TYPED_TEST(LinearSolverTest, KluRefactorizationSolvesEachNewMatrix)
{
  constexpr int                       dim = TypeParam::value;
  const ElasticBody<dim>              body(multilevel_cells[dim - 1]);
  const TrilinosWrappers::MPI::Vector rhs = body.right_hand_side();
  TrilinosWrappers::MPI::Vector       solution(body.owned_dofs, MPI_COMM_WORLD);
  TrilinosWrappers::SparseMatrix      matrix;
  body.set_matrix(body.mass_factor(), matrix);
  const Epetra_CrsMatrix *const epetra_matrix = &matrix.trilinos_matrix();

  LinearSolver solver(solver_parameters(SolverType::direct, DirectType::klu),
                      1,
                      MPI_COMM_WORLD,
                      this->timer);
  // The first matrix: the symbolic analysis and a factorization with
  // pivoting.
  solver.prepare(matrix);
  solver.solve(rhs, solution);
  EXPECT_LT(relative_residual(matrix, solution, rhs), 1e-12);

  // The second, in the same object: refactorized with the old pivots.
  body.set_matrix(256. * body.mass_factor(), matrix);
  solver.prepare(matrix);
  solver.solve(rhs, solution);
  const double residual_256 = relative_residual(matrix, solution, rhs);
  EXPECT_LT(residual_256, 1e-12);

  // The third: i at the centre, j a free unknown coupled to it, s the
  // diagonal entry of i; each known to all processes.
  body.set_matrix(body.mass_factor(), matrix);
  const types::global_dof_index i = on_all_processes(body.centre_dof(0));
  types::global_dof_index       j = numbers::invalid_dof_index;
  double                        s = 0.;
  if (matrix.locally_owned_range_indices().is_element(i))
    {
      s = matrix.diag_element(i);
      for (auto entry = matrix.begin(i); entry != matrix.end(i); ++entry)
        if (entry->column() != i &&
            !body.constraints.is_constrained(entry->column()))
          j = entry->column();
    }
  j                  = on_all_processes(j);
  s                  = dealii::Utilities::MPI::max(s, MPI_COMM_WORLD);
  const double delta = 1e-14 * s;
  for (const auto row : body.owned_dofs)
    if (row != i && row != j)
      {
        // Columns i and j vanish in the other rows (the pattern stays).
        std::vector<types::global_dof_index> columns;
        for (auto entry = matrix.begin(row); entry != matrix.end(row); ++entry)
          if (entry->column() == i || entry->column() == j)
            columns.push_back(entry->column());
        for (const auto column : columns)
          matrix.set(row, column, 0.);
      }
  matrix.compress(VectorOperation::insert);
  for (const auto &[row, other] : {std::make_pair(i, j), std::make_pair(j, i)})
    set_row(matrix, row, [&, row = row, other = other](const auto column) {
      return column == row ? delta : (column == other ? s : 0.);
    });
  // Still the same Epetra matrix, or the solver would analyse it afresh
  // and the refactorization would not be tested.
  ASSERT_EQ(&matrix.trilinos_matrix(), epetra_matrix);

  solver.prepare(matrix);
  solver.solve(rhs, solution);
  const double residual_block = relative_residual(matrix, solution, rhs);
  EXPECT_LT(residual_block, 1e-12);
  EXPECT_EQ(solver.n_preparations(), 3u);

  // The first and the third matrix with KLU accepting any refactorization:
  // a KLU solver of the test's own, on an object of its own, which
  // receives the third matrix's values in place.
  double residual_forced = 0.;
  {
    TrilinosWrappers::SparseMatrix first;
    body.set_matrix(body.mass_factor(), first);
    Epetra_LinearProblem problem;
    problem.SetOperator(
      const_cast<Epetra_CrsMatrix *>(&first.trilinos_matrix()));
    Amesos_Klu             klu(problem);
    Teuchos::ParameterList klu_parameters;
    klu_parameters.set("Refactorize", true);
    klu_parameters.set("RcondThreshold", -1.);
    klu.SetParameters(klu_parameters);
    ASSERT_EQ(klu.SymbolicFactorization(), 0);
    ASSERT_EQ(klu.NumericFactorization(), 0);
    first.copy_from(matrix);
    ASSERT_EQ(&first.trilinos_matrix(), problem.GetMatrix());
    ASSERT_EQ(klu.NumericFactorization(), 0);
    solution = 0.;
    problem.SetLHS(&solution.trilinos_vector());
    problem.SetRHS(const_cast<Epetra_MultiVector *>(&rhs.trilinos_vector()));
    ASSERT_EQ(klu.Solve(), 0);
    residual_forced = relative_residual(matrix, solution, rhs);
  }
  this->log << processes_prefix() << dim
            << "D KLU refactorization, relative residuals: K + 256cM "
            << residual_256 << ", new pivots needed " << residual_block
            << ", the same with the old pivots forced " << residual_forced
            << std::endl;
  EXPECT_GT(residual_forced, 1e-6);
}



// @sect4{The analysis follows the matrix object}
//
// The symbolic analysis and the aggregates belong to one matrix object.
// Two objects of different sizes, prepared in turn by the same solver,
// must each be solved correctly: the direct solvers to round-off, CG to
// its tolerance (the true residual may exceed the recursively updated one
// that CG tests by a little; 2 times the tolerance is ample). The
// multigrid hierarchy must be built anew for each: its complexity is that
// of the object's mesh (exactly 1 for the small one, more for the large
// one). No near null space is set here (ML then takes the constant
// vector), since setting one would force a new hierarchy by itself.
TYPED_TEST(LinearSolverTest, AnalysisFollowsTheMatrixObject)
{
  constexpr int                  dim = TypeParam::value;
  const ElasticBody<dim>         large(multilevel_cells[dim - 1]);
  const ElasticBody<dim>         small(single_level_cells[dim - 1]);
  TrilinosWrappers::SparseMatrix large_matrix, small_matrix;
  large.set_matrix(large.mass_factor(), large_matrix);
  small.set_matrix(small.mass_factor(), small_matrix);
  const TrilinosWrappers::MPI::Vector large_rhs = large.right_hand_side();
  const TrilinosWrappers::MPI::Vector small_rhs = small.right_hand_side();

  for (const auto &parameters :
       {solver_parameters(SolverType::direct, DirectType::klu),
        solver_parameters(SolverType::direct, DirectType::mumps),
        solver_parameters(SolverType::cg)})
    {
      const double bound = (parameters.linear_solver == SolverType::direct)
                             ? 1e-12
                             : 2. * parameters.linear_relative_tolerance;
      LinearSolver solver(parameters, 1, MPI_COMM_WORLD, this->timer);
      // large, small, large, small: every preparation meets another object.
      for (unsigned int round = 0; round < 2; ++round)
        {
          TrilinosWrappers::MPI::Vector solution(large.owned_dofs,
                                                 MPI_COMM_WORLD);
          solver.prepare(large_matrix);
          solver.solve(large_rhs, solution);
          EXPECT_LT(relative_residual(large_matrix, solution, large_rhs),
                    bound);
          if (parameters.linear_solver == SolverType::cg)
            {
              EXPECT_GT(solver.multigrid_operator_complexity(), 1.);
            }

          TrilinosWrappers::MPI::Vector small_solution(small.owned_dofs,
                                                       MPI_COMM_WORLD);
          solver.prepare(small_matrix);
          solver.solve(small_rhs, small_solution);
          EXPECT_LT(relative_residual(small_matrix, small_solution, small_rhs),
                    bound);
          if (parameters.linear_solver == SolverType::cg)
            {
              EXPECT_EQ(solver.multigrid_operator_complexity(), 1.);
            }
        }
      EXPECT_EQ(solver.n_preparations(), 4u);
    }
}



// @sect4{A singular matrix fails the step}
//
// A matrix with a zero row (its entries kept in the pattern, as when a
// degree of freedom has lost all stiffness) is singular, and elimination
// meets an exactly zero pivot whatever the order. The factorization must
// throw StepFailure -- for the first matrix of an object, and for a later
// one, which KLU first tries with the old pivots -- and the solver must
// recover when the matrix is regular again, as it is after the time loop
// has cut the step back.
TYPED_TEST(LinearSolverTest, SingularMatrixFailsTheStep)
{
  constexpr int                       dim = TypeParam::value;
  const ElasticBody<dim>              body(single_level_cells[dim - 1]);
  const TrilinosWrappers::MPI::Vector rhs = body.right_hand_side();
  const types::global_dof_index       i = on_all_processes(body.centre_dof(0));
  // The row of the unknown at the centre set to zero. (Amesos_Mumps
  // reports MUMPS' error -10, "numerically singular", on the terminal.)
  const auto make_singular = [&](TrilinosWrappers::SparseMatrix &m) {
    set_row(m, i, [](const auto) { return 0.; });
  };

  for (const DirectType type : {DirectType::klu, DirectType::mumps})
    {
      TrilinosWrappers::SparseMatrix matrix;
      body.set_matrix(body.mass_factor(), matrix);
      make_singular(matrix);
      // The first matrix of a solver singular.
      {
        LinearSolver solver(solver_parameters(SolverType::direct, type),
                            1,
                            MPI_COMM_WORLD,
                            this->timer);
        EXPECT_THROW(solver.prepare(matrix), StepFailure);
        EXPECT_EQ(solver.n_preparations(), 1u);
      }

      LinearSolver solver(solver_parameters(SolverType::direct, type),
                          1,
                          MPI_COMM_WORLD,
                          this->timer);
      TrilinosWrappers::MPI::Vector solution(body.owned_dofs, MPI_COMM_WORLD);
      // A regular, a singular and a regular matrix in the same object.
      body.set_matrix(body.mass_factor(), matrix);
      solver.prepare(matrix);
      solver.solve(rhs, solution);
      make_singular(matrix);
      EXPECT_THROW(solver.prepare(matrix), StepFailure);
      body.set_matrix(body.mass_factor(), matrix);
      solver.prepare(matrix);
      solver.solve(rhs, solution);
      EXPECT_LT(relative_residual(matrix, solution, rhs), 1e-12);
      EXPECT_EQ(solver.n_preparations(), 3u);
    }
}



// @sect4{The symmetric factorization}
//
// With `Symmetric factorization` MUMPS factorizes $(\mathbf A + \mathbf
// A^T)/2$ from its lower triangle (SymmetricFactorization, one process;
// on several the solver is Amesos' MUMPS). On the body's symmetric
// matrix it solves to round-off, leaves the matrix and the right-hand side
// alone, and reuses its analysis for a second matrix in the same object,
// $\mathbf K + 256c\,\mathbf M$. Given $\mathbf A + \mathbf N$ with an
// antisymmetric $\mathbf N$ (one pair of entries $\pm0.3 a_{ii}$ at the
// centre), it solves with $\mathbf A$, the symmetric part. A singular
// matrix (the centre's row and column zero) throws StepFailure, and the
// solver recovers with the regular matrix.
TYPED_TEST(LinearSolverTest, SymmetricFactorizationSolvesTheSymmetricPart)
{
  constexpr int          dim = TypeParam::value;
  const ElasticBody<dim> body(multilevel_cells[dim - 1]);
  const bool             serial =
    dealii::Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) == 1;
  Parameters::LinearSolver parameters =
    solver_parameters(SolverType::direct, DirectType::mumps);
  parameters.symmetric_factorization = true;
  EXPECT_EQ(LinearSolver::needs_symmetric_matrix(parameters,
                                                 body.owned_dofs.size(),
                                                 MPI_COMM_WORLD),
            serial);
  LinearSolver solver(parameters, 1, MPI_COMM_WORLD, this->timer);

  TrilinosWrappers::SparseMatrix matrix, matrix_before;
  body.set_matrix(body.mass_factor(), matrix);
  matrix_before.copy_from(matrix);
  const TrilinosWrappers::MPI::Vector rhs = body.right_hand_side();
  const TrilinosWrappers::MPI::Vector rhs_before(rhs);
  TrilinosWrappers::MPI::Vector       solution(body.owned_dofs, MPI_COMM_WORLD);
  solver.prepare(matrix);
  EXPECT_EQ(solver.solver_in_use(),
            serial ? "MUMPS symmetric" : "Amesos_Mumps");
  const std::uint64_t forwarded_before = SingleColumnBlas::n_forwarded_calls();
  solver.solve(rhs, solution);
  // MUMPS's back substitution calls the program's dgemm_ and dtrsm_, which
  // hand its single-column calls to dgemv and dtrsv (SingleColumnBlas).
  if (serial)
    {
      EXPECT_GT(SingleColumnBlas::n_forwarded_calls(), forwarded_before);
    }
  const double residual = relative_residual(matrix, solution, rhs);
  EXPECT_LT(residual, 1e-12);
  EXPECT_EQ(max_difference(matrix, matrix_before), 0.);
  EXPECT_EQ(relative_difference(rhs, rhs_before), 0.);

  body.set_matrix(256. * body.mass_factor(), matrix);
  solver.prepare(matrix);
  solver.solve(rhs, solution);
  const double second_residual = relative_residual(matrix, solution, rhs);
  EXPECT_LT(second_residual, 1e-12);

  double antisymmetric_residual = 0.;
  if (serial)
    {
      // The centre's unknown and a neighbour it is coupled to.
      body.set_matrix(body.mass_factor(), matrix);
      const types::global_dof_index i = body.centre_dof(0);
      const double                  a = matrix.el(i, i);
      types::global_dof_index       j = i;
      for (auto entry = matrix.begin(i); entry != matrix.end(i); ++entry)
        if (entry->column() != i)
          j = entry->column();
      ASSERT_NE(i, j);
      TrilinosWrappers::SparseMatrix perturbed;
      perturbed.copy_from(matrix);
      perturbed.set(i, j, matrix.el(i, j) + 0.3 * a);
      perturbed.set(j, i, matrix.el(j, i) - 0.3 * a);
      perturbed.compress(VectorOperation::insert);
      solver.prepare(perturbed);
      solver.solve(rhs, solution);
      antisymmetric_residual = relative_residual(matrix, solution, rhs);
      EXPECT_LT(antisymmetric_residual, 1e-12);
      EXPECT_GT(relative_residual(perturbed, solution, rhs), 1e-6);

      // The centre's row and column zero: singular.
      TrilinosWrappers::SparseMatrix singular;
      singular.copy_from(matrix);
      set_row(singular, i, [](const auto) { return 0.; });
      for (auto entry = matrix.begin(i); entry != matrix.end(i); ++entry)
        singular.set(entry->column(), i, 0.);
      singular.compress(VectorOperation::insert);
      solver.prepare(matrix);
      EXPECT_THROW(solver.prepare(singular), StepFailure);
      solver.prepare(matrix);
      solver.solve(rhs, solution);
      EXPECT_LT(relative_residual(matrix, solution, rhs), 1e-12);
    }
  this->log << processes_prefix() << dim << "D " << solver.solver_in_use()
            << ": relative residuals " << residual << ", " << second_residual
            << "; of the symmetric part of a non-symmetric matrix "
            << antisymmetric_residual << std::endl;
}



// @sect4{The single-precision factor}
//
// With `Factorization precision = single` the symmetric factorization
// keeps its factor in single precision. A back substitution then solves to
// single precision only: its relative residual is above double precision's
// round-off (so the factor is not the double one) and below $10^{-4}$. The
// iteration the modified Newton method does, $\mathbf x \leftarrow
// \mathbf x + \tilde{\mathbf A}^{-1}(\mathbf b - \mathbf A\mathbf x)$
// with the residual in double precision, reduces the residual by at least
// a factor of 100 per step and reaches the double-precision factor's
// solution to $10^{-12}$ within three steps. The back substitution calls
// the program's sgemm_ and strsm_. Inside a DoublePrecisionFactor scope
// the same solver solves to double precision's round-off, and after it
// as before. On several processes the solver is
// Amesos' MUMPS in double precision, and the test is skipped.
TYPED_TEST(LinearSolverTest, SingleFactorIsRefinedByTheResidual)
{
  constexpr int dim = TypeParam::value;
  if (dealii::Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) > 1)
    GTEST_SKIP() << "the single-precision factor is for one process";
  const ElasticBody<dim>   body(multilevel_cells[dim - 1]);
  Parameters::LinearSolver parameters =
    solver_parameters(SolverType::direct, DirectType::mumps);
  parameters.symmetric_factorization = true;
  LinearSolver double_solver(parameters, 1, MPI_COMM_WORLD, this->timer);
  parameters.single_precision_factor = true;
  LinearSolver single_solver(parameters, 1, MPI_COMM_WORLD, this->timer);

  TrilinosWrappers::SparseMatrix matrix;
  body.set_matrix(body.mass_factor(), matrix);
  const TrilinosWrappers::MPI::Vector rhs = body.right_hand_side();
  TrilinosWrappers::MPI::Vector       exact(body.owned_dofs, MPI_COMM_WORLD);
  double_solver.prepare(matrix);
  double_solver.solve(rhs, exact);

  single_solver.prepare(matrix);
  EXPECT_EQ(single_solver.solver_in_use(), "MUMPS symmetric");
  TrilinosWrappers::MPI::Vector solution(body.owned_dofs, MPI_COMM_WORLD);
  const std::uint64_t forwarded_before = SingleColumnBlas::n_forwarded_calls();
  single_solver.solve(rhs, solution);
  EXPECT_GT(SingleColumnBlas::n_forwarded_calls(), forwarded_before);
  const double first_residual = relative_residual(matrix, solution, rhs);
  EXPECT_GT(first_residual, 1e-12);
  EXPECT_LT(first_residual, 1e-4);

  std::vector<double>           residuals = {first_residual};
  TrilinosWrappers::MPI::Vector residual(rhs), correction(solution);
  for (unsigned int step = 0; step < 3; ++step)
    {
      matrix.vmult(residual, solution);
      residual.sadd(-1., 1., rhs);
      single_solver.solve(residual, correction);
      solution += correction;
      residuals.push_back(relative_residual(matrix, solution, rhs));
      if (residuals[step] > 1e-13)
        {
          EXPECT_LT(residuals[step + 1], 1e-2 * residuals[step]) << step;
        }
    }
  const double difference = relative_difference(solution, exact);
  EXPECT_LT(difference, 1e-12);

  // Inside a DoublePrecisionFactor scope (the static equilibrium's) the
  // same solver factorizes in double precision, and after it in single
  // precision again.
  double scoped_residual = 0.;
  {
    const DoublePrecisionFactor double_precision(single_solver);
    single_solver.prepare(matrix);
    single_solver.solve(rhs, solution);
    scoped_residual = relative_residual(matrix, solution, rhs);
    EXPECT_LT(scoped_residual, 1e-12);
  }
  single_solver.prepare(matrix);
  single_solver.solve(rhs, solution);
  EXPECT_GT(relative_residual(matrix, solution, rhs), 1e-12);

  this->log << dim << "D single-precision factor: relative residuals";
  for (const double r : residuals)
    this->log << ' ' << r;
  this->log << "; against the double factor's solution " << difference
            << "; in a double-precision scope " << scoped_residual << std::endl;
}



// @sect4{Single-column BLAS calls}
//
// Inside a SingleColumnBlas scope, gemm with one column of B and trsm
// from the left with one column give what the BLAS library's routines give
// outside it (to round-off, 100 times the precision's epsilon: gemv sums in
// another order), for every combination of transposes, triangles and
// diagonals, and are counted as forwarded; a call with two columns is not
// forwarded. Both precisions: double (dgemm, dtrsm) and single (sgemm,
// strsm, for the single-precision factor). The matrices are 37 x 23
// (gemm's A) and of order 29 (trsm's triangle, diagonally dominant), with
// leading dimensions larger than their rows. gemm is called through
// deal.II's wrapper (without gfortran's hidden string lengths, as deal.II
// calls it), trsm, which deal.II does not wrap, with them (as
// analysis/lapack.h declares its routines).
extern "C" {
void
dtrsm_(const char   *side,
       const char   *uplo,
       const char   *transa,
       const char   *diag,
       const int    *m,
       const int    *n,
       const double *alpha,
       const double *a,
       const int    *lda,
       double       *b,
       const int    *ldb,
       std::size_t   side_length,
       std::size_t   uplo_length,
       std::size_t   transa_length,
       std::size_t   diag_length);

void
strsm_(const char  *side,
       const char  *uplo,
       const char  *transa,
       const char  *diag,
       const int   *m,
       const int   *n,
       const float *alpha,
       const float *a,
       const int   *lda,
       float       *b,
       const int   *ldb,
       std::size_t  side_length,
       std::size_t  uplo_length,
       std::size_t  transa_length,
       std::size_t  diag_length);
}

namespace
{
  // trsm from the left with one column, $\alpha = 1$, in either precision.
  template <typename Number>
  void
  trsm_one_column(const char           uplo,
                  const char           trans,
                  const char           diag,
                  const int            m,
                  const Number        *a,
                  const int            lda,
                  std::vector<Number> &b)
  {
    const int    n = 1, ldb = b.size();
    const Number one  = 1.;
    const auto   trsm = []() {
      if constexpr (std::is_same_v<Number, double>)
        return &dtrsm_;
      else
        return &strsm_;
    }();
    trsm("L",
         &uplo,
         &trans,
         &diag,
         &m,
         &n,
         &one,
         a,
         &lda,
         b.data(),
         &ldb,
         1,
         1,
         1,
         1);
  }

  template <typename Number>
  std::vector<Number>
  pseudo_random_entries(const unsigned int n, const double seed)
  {
    std::vector<Number> entries(n);
    for (unsigned int i = 0; i < n; ++i)
      entries[i] = std::sin(seed * (i + 1.)) + 0.1;
    return entries;
  }

  // A BLAS call applied to copies of the same array outside and inside a
  // SingleColumnBlas scope: the largest difference of the results relative
  // to the library's, with a failure if the call inside was not forwarded.
  template <typename Number, typename Call>
  double
  forwarded_against_library(const std::vector<Number> &start, const Call &call)
  {
    std::vector<Number> library = start, forwarded = start;
    call(library);
    const std::uint64_t before = SingleColumnBlas::n_forwarded_calls();
    {
      const SingleColumnBlas scope;
      call(forwarded);
    }
    EXPECT_EQ(SingleColumnBlas::n_forwarded_calls(), before + 1);
    double difference = 0., size = 0.;
    for (unsigned int i = 0; i < start.size(); ++i)
      {
        difference =
          std::max<double>(difference, std::abs(forwarded[i] - library[i]));
        size = std::max<double>(size, std::abs(library[i]));
      }
    return difference / size;
  }

  template <typename Number>
  class SingleColumnBlasTest : public ::testing::Test
  {
  };

  using Precisions = ::testing::Types<double, float>;
} // namespace

TYPED_TEST_SUITE(SingleColumnBlasTest, Precisions);

TYPED_TEST(SingleColumnBlasTest, AgreesWithTheLibraryRoutines)
{
  using Number           = TypeParam;
  const double tolerance = 100. * std::numeric_limits<Number>::epsilon();
  const Number alpha = -0.7, beta = 0.4;
  double       worst = 0.;
  for (const char transa : {'N', 'T'})
    for (const char transb : {'N', 'T'})
      {
        const int                 m = 37, k = 23, n = 1;
        const int                 lda = (transa == 'N' ? m : k) + 3;
        const int                 ldb = (transb == 'N' ? k : n) + 2;
        const int                 ldc = m + 1;
        const std::vector<Number> a =
          pseudo_random_entries<Number>(lda * (transa == 'N' ? k : m), 0.37);
        const std::vector<Number> b =
          pseudo_random_entries<Number>(ldb * (transb == 'N' ? n : k), 0.91);
        const double difference =
          forwarded_against_library(pseudo_random_entries<Number>(ldc * n, 1.3),
                                    [&](std::vector<Number> &c) {
                                      dealii::gemm(&transa,
                                                   &transb,
                                                   &m,
                                                   &n,
                                                   &k,
                                                   &alpha,
                                                   a.data(),
                                                   &lda,
                                                   b.data(),
                                                   &ldb,
                                                   &beta,
                                                   c.data(),
                                                   &ldc);
                                    });
        EXPECT_LT(difference, tolerance) << transa << transb;
        worst = std::max(worst, difference);
      }

  const int           m = 29, lda = 31;
  std::vector<Number> a = pseudo_random_entries<Number>(lda * m, 0.53);
  for (int i = 0; i < m; ++i)
    a[i + i * lda] += 4.;
  for (const char uplo : {'U', 'L'})
    for (const char trans : {'N', 'T'})
      for (const char diag : {'N', 'U'})
        {
          const double difference = forwarded_against_library(
            pseudo_random_entries<Number>(m + 2, 0.77),
            [&](std::vector<Number> &b) {
              trsm_one_column(uplo, trans, diag, m, a.data(), lda, b);
            });
          EXPECT_LT(difference, tolerance) << uplo << trans << diag;
          worst = std::max(worst, difference);
        }

  // Two columns are the library's.
  {
    const int                 m = 5, n = 2, k = 4;
    const std::vector<Number> a = pseudo_random_entries<Number>(m * k, 0.2);
    const std::vector<Number> b = pseudo_random_entries<Number>(k * n, 0.3);
    std::vector<Number>       c(m * n, 0.);
    const Number              zero = 0., one = 1.;
    const std::uint64_t       before = SingleColumnBlas::n_forwarded_calls();
    const SingleColumnBlas    scope;
    dealii::gemm("N",
                 "N",
                 &m,
                 &n,
                 &k,
                 &one,
                 a.data(),
                 &m,
                 b.data(),
                 &k,
                 &zero,
                 c.data(),
                 &m);
    EXPECT_EQ(SingleColumnBlas::n_forwarded_calls(), before);
  }
  std::cout << "single-column BLAS calls against the library's ("
            << (sizeof(Number) == sizeof(double) ? "double" : "single")
            << " precision): worst relative difference " << worst << std::endl;
}



// @sect4{The iterative solvers}
//
// CG and GMRES with multigrid stop at the relative tolerance
// $\varepsilon = 10^{-8}$. CG tests the recursively updated residual, which
// drifts from the true one by round-off only (about $10^{-16}$ times the
// condition number), so the true residual must be below
// $1.1\varepsilon\|\mathbf b\|$. GMRES is preconditioned from the right,
// so that its least-squares residual is that of the system itself, and the
// same bound holds. (With deal.II's default, left preconditioning, GMRES
// tests $\|\mathbf P^{-1}\mathbf r\|$, which the multigrid cycle scales
// by about $\|\mathbf A\|^{-1}$: in 1D, $\|\mathbf A\|_\infty \approx 3\cdot
// 10^4$, its true residual was $6\cdot 10^{-5}$, and on the bellows a
// Newton step ended after three GMRES iterations with a wrong update.)
// Both need far fewer iterations than unknowns.
TYPED_TEST(LinearSolverTest, IterativeSolversConvergeToTheTolerance)
{
  constexpr int                  dim = TypeParam::value;
  const ElasticBody<dim>         body(multilevel_cells[dim - 1]);
  TrilinosWrappers::SparseMatrix matrix;
  body.set_matrix(body.mass_factor(), matrix);
  const TrilinosWrappers::MPI::Vector rhs = body.right_hand_side();

  // Each with the rigid-body modes, as in the program.
  for (const SolverType type : {SolverType::cg, SolverType::gmres})
    {
      LinearSolver solver(solver_parameters(type, DirectType::klu, 1e-8),
                          1,
                          MPI_COMM_WORLD,
                          this->timer);
      solver.set_near_null_space(body.rigid_body_modes(true));
      TrilinosWrappers::MPI::Vector solution(body.owned_dofs, MPI_COMM_WORLD);
      solver.prepare(matrix);
      const unsigned int iterations = solver.solve(rhs, solution);
      const double       residual   = relative_residual(matrix, solution, rhs);
      this->log << processes_prefix() << dim << "D " << solver.solver_in_use()
                << ": " << iterations << " iterations, relative residual "
                << residual << ", operator complexity "
                << solver.multigrid_operator_complexity() << std::endl;
      EXPECT_LT(residual, 1.1e-8);
      EXPECT_GT(iterations, 1u);
      EXPECT_LT(iterations, 100u);
    }
  // The iterative solvers' time is booked in their two sections only.
  const auto times = this->timer.get_summary_data(TimerOutput::total_wall_time);
  EXPECT_EQ(times.count("Preconditioner setup"), 1u);
  EXPECT_EQ(times.count("Linear solve"), 1u);
  EXPECT_EQ(times.count("Factorization"), 0u);
}



// An iterative solver that does not converge within its maximum number of
// iterations fails the step; two CG iterations cannot reach $10^{-12}$.
TYPED_TEST(LinearSolverTest, NonConvergenceFailsTheStep)
{
  constexpr int                  dim = TypeParam::value;
  const ElasticBody<dim>         body(multilevel_cells[dim - 1]);
  TrilinosWrappers::SparseMatrix matrix;
  body.set_matrix(body.mass_factor(), matrix);
  const TrilinosWrappers::MPI::Vector rhs = body.right_hand_side();
  TrilinosWrappers::MPI::Vector       solution(body.owned_dofs, MPI_COMM_WORLD);
  for (const SolverType type : {SolverType::cg, SolverType::gmres})
    {
      LinearSolver solver(solver_parameters(type, DirectType::klu, 1e-12, 2),
                          1,
                          MPI_COMM_WORLD,
                          this->timer);
      solver.set_near_null_space(body.rigid_body_modes(true));
      solver.prepare(matrix);
      try
        {
          solver.solve(rhs, solution);
          ADD_FAILURE() << "no StepFailure";
        }
      catch (const StepFailure &failure)
        {
          EXPECT_NE(std::string(failure.what())
                      .find("did not converge in 2 "
                            "iterations"),
                    std::string::npos)
            << failure.what();
        }
    }
}



// @sect4{The near null space reaches ML}
//
// The modes go to ML through its parameter list, in the layout that
// deal.II uses for its constant modes. With the translations alone, the
// LinearSolver's hierarchy must therefore be the one deal.II builds from
// the same translations as constant modes: the same CG iterations, and
// the same solution to round-off (the two set up ML identically, so only
// the order of floating-point operations could differ; $10^{-12}$ allows
// for it). With the rotations as well, ML's coarse spaces represent the
// rigid-body motions, and CG needs fewer iterations (in 2D and 3D; in 1D
// the translation is the only mode). The matrix is the stiffness alone,
// as in a static problem: the near null space matters most there (with
// the mass of a time step the iterations are fewer either way, and in 2D
// equal). Tolerance $10^{-10}$.
TYPED_TEST(LinearSolverTest, RigidBodyModesReachMultigrid)
{
  constexpr int                  dim = TypeParam::value;
  const ElasticBody<dim>         body(multilevel_cells[dim - 1]);
  TrilinosWrappers::SparseMatrix matrix;
  body.set_matrix(0., matrix);
  const TrilinosWrappers::MPI::Vector rhs = body.right_hand_side();
  TrilinosWrappers::MPI::Vector       translations_solution(body.owned_dofs,
                                                      MPI_COMM_WORLD),
    rigid_solution(translations_solution), deal_ii_solution(rigid_solution);

  // The solver with the translations, with all rigid-body modes, and
  // deal.II's AMG with the translations as its constant modes.
  LinearSolver translations(solver_parameters(SolverType::cg),
                            1,
                            MPI_COMM_WORLD,
                            this->timer);
  translations.set_near_null_space(body.rigid_body_modes(false));
  translations.prepare(matrix);
  const unsigned int translation_iterations =
    translations.solve(rhs, translations_solution);

  LinearSolver rigid(solver_parameters(SolverType::cg),
                     1,
                     MPI_COMM_WORLD,
                     this->timer);
  rigid.set_near_null_space(body.rigid_body_modes(true));
  rigid.prepare(matrix);
  const unsigned int rigid_iterations = rigid.solve(rhs, rigid_solution);

  TrilinosWrappers::PreconditionAMG deal_ii_amg;
  deal_ii_amg.initialize(matrix, amg_data(body.constant_modes()));
  const unsigned int deal_ii_iterations =
    cg_iterations(matrix, deal_ii_amg, rhs, deal_ii_solution, 1e-10);

  this->log << processes_prefix() << dim << "D CG iterations: translations "
            << translation_iterations << " (deal.II's constant modes "
            << deal_ii_iterations << ", difference of the solutions "
            << relative_difference(translations_solution, deal_ii_solution)
            << "), rigid-body modes " << rigid_iterations << std::endl;
  EXPECT_EQ(translation_iterations, deal_ii_iterations);
  EXPECT_LT(relative_difference(translations_solution, deal_ii_solution),
            1e-12);
  if (dim > 1)
    {
      EXPECT_LT(rigid_iterations, translation_iterations);
    }
  else
    {
      EXPECT_EQ(rigid_iterations, translation_iterations);
    }
}



// @sect4{The recomputed hierarchy}
//
// For a new matrix in the same object the solver recomputes the hierarchy
// on the old aggregates, after clearing the diagonal and the eigenvalue
// estimate that ML caches with the finest level. Two changes of the
// matrix:
// - $\mathbf A\to 256\mathbf A$, exact in floating point. ML's choices
//   depend on the matrix only through ratios of its entries, so the
//   hierarchy of $256\mathbf A$ is that of $\mathbf A$ with all matrices
//   times 256;
// - $\mathbf K + c\mathbf M \to \mathbf K + 256c\mathbf M$, the change of
//   four time-step cut-backs in a row.
//
// ML's hierarchy is then the new one except for ML's estimate of the
// largest eigenvalue of $\mathbf D^{-1}\mathbf A$, which it computes again
// from another random start vector and which is accurate to a few per
// cent (see the next test). So CG must need the same number of iterations
// with the recomputed hierarchy as with a new one built from scratch on a
// copy of the matrix, give or take one. deal.II's reinit() recomputes
// without clearing: with the old diagonal and eigenvalue estimate its
// prolongators and smoother are far off, and CG must need at least twice
// as many iterations, or not converge in 1,000. Tolerance $10^{-10}$; the
// near null space the translations (so that deal.II's AMG is the same).
TYPED_TEST(LinearSolverTest, RecomputedHierarchySolvesLikeANewOne)
{
  constexpr int                       dim = TypeParam::value;
  const ElasticBody<dim>              body(multilevel_cells[dim - 1]);
  const TrilinosWrappers::MPI::Vector rhs = body.right_hand_side();
  const double                        c   = body.mass_factor();

  for (const bool uniform_scaling : {true, false})
    {
      TrilinosWrappers::SparseMatrix matrix, copy, deal_ii_matrix;
      body.set_matrix(c, matrix);
      body.set_matrix(c, deal_ii_matrix);
      TrilinosWrappers::MPI::Vector solution(body.owned_dofs, MPI_COMM_WORLD);

      LinearSolver recomputed(solver_parameters(SolverType::cg),
                              1,
                              MPI_COMM_WORLD,
                              this->timer);
      recomputed.set_near_null_space(body.rigid_body_modes(false));
      recomputed.prepare(matrix);
      const unsigned int first_iterations = recomputed.solve(rhs, solution);
      const double complexity = recomputed.multigrid_operator_complexity();
      // deal.II's AMG for the old matrix, in an object of its own.
      TrilinosWrappers::PreconditionAMG stale;
      stale.initialize(deal_ii_matrix, amg_data(body.constant_modes()));

      if (uniform_scaling)
        {
          matrix *= 256.;
          deal_ii_matrix *= 256.;
        }
      else
        {
          body.set_matrix(256. * c, matrix);
          body.set_matrix(256. * c, deal_ii_matrix);
        }
      // The recomputation, which keeps the size of the hierarchy.
      recomputed.prepare(matrix);
      const unsigned int recomputed_iterations =
        recomputed.solve(rhs, solution);
      EXPECT_EQ(recomputed.multigrid_operator_complexity(), complexity);
      EXPECT_EQ(recomputed.n_preparations(), 2u);

      // A new hierarchy for the new matrix, in another object.
      copy.copy_from(matrix);
      ASSERT_NE(&copy.trilinos_matrix(), &matrix.trilinos_matrix());
      LinearSolver fresh(solver_parameters(SolverType::cg),
                         1,
                         MPI_COMM_WORLD,
                         this->timer);
      fresh.set_near_null_space(body.rigid_body_modes(false));
      fresh.prepare(copy);
      const unsigned int new_iterations = fresh.solve(rhs, solution);

      stale.reinit();
      const unsigned int stale_iterations =
        cg_iterations(deal_ii_matrix, stale, rhs, solution, 1e-10);

      this->log << processes_prefix() << dim << "D "
                << (uniform_scaling ? "A -> 256 A" : "K + cM -> K + 256 cM")
                << ": CG iterations before " << first_iterations
                << ", recomputed " << recomputed_iterations << ", new "
                << new_iterations << ", recomputed without clearing "
                << stale_iterations << " (1001: no convergence)" << std::endl;
      EXPECT_LE(recomputed_iterations, new_iterations + 1);
      EXPECT_GE(recomputed_iterations + 1, new_iterations);
      EXPECT_GE(stale_iterations, 2 * new_iterations);
    }
}



// The same on the level of ML, with deal.II's AMG and the translations as
// near null space, for the two changes of the matrix above. Four
// hierarchies for the changed matrix, applied to one vector: one built
// from scratch; one recomputed as the solver does it; one recomputed
// after clearing only the diagonal and giving ML the eigenvalue estimate
// of the new hierarchy; and one recomputed by deal.II's reinit(). The third
// must be the new hierarchy to the last bit: then the diagonal and the
// eigenvalue estimate are all that ML keeps of the old matrix, and
// clearing them suffices. The second differs from the new one only
// through the eigenvalue estimate, which must agree with the new one's to
// 5 % and give the same result to 2 % (a relative change of the estimate
// changes the smoother and the prolongators by about as much, and the
// cycle's result by less). The last must be off by more than the result
// itself.
TYPED_TEST(LinearSolverTest, RecomputationKeepsOnlyTheFinestLevelsCache)
{
  constexpr int                       dim = TypeParam::value;
  const ElasticBody<dim>              body(multilevel_cells[dim - 1]);
  const TrilinosWrappers::MPI::Vector v = body.right_hand_side();
  const double                        c = body.mass_factor();
  const auto                          finest =
    [](const TrilinosWrappers::PreconditionAMG &amg) -> ML_Operator & {
    auto &multilevel = dynamic_cast<ML_Epetra::MultiLevelPreconditioner &>(
      amg.trilinos_operator());
    ML *ml = const_cast<ML *>(multilevel.GetML());
    return ml->Amat[ml->ML_finest_level];
  };

  for (const bool uniform_scaling : {true, false})
    {
      TrilinosWrappers::SparseMatrix    matrices[3], copy;
      TrilinosWrappers::PreconditionAMG fresh, cleared, given_estimate, stale;
      TrilinosWrappers::PreconditionAMG *const recomputed[3] = {&cleared,
                                                                &given_estimate,
                                                                &stale};
      // Three hierarchies for the old matrix, each in an object of its own;
      // then the change of the matrix; then one hierarchy for the new one.
      for (unsigned int k = 0; k < 3; ++k)
        {
          body.set_matrix(c, matrices[k]);
          recomputed[k]->initialize(matrices[k],
                                    amg_data(body.constant_modes()));
          if (uniform_scaling)
            matrices[k] *= 256.;
          else
            body.set_matrix(256. * c, matrices[k]);
        }
      copy.copy_from(matrices[0]);
      fresh.initialize(copy, amg_data(body.constant_modes()));

      // The recomputations: the solver's, one with the new hierarchy's
      // eigenvalue estimate given, deal.II's.
      LinearSolverInternals::recompute_on_old_aggregates(cleared);
      {
        ML_Operator &level = finest(given_estimate);
        ASSERT_NE(level.diagonal, nullptr);
        ML_DVector_Destroy(&level.diagonal);
        level.diagonal   = nullptr;
        level.lambda_max = finest(fresh).lambda_max;
        level.lambda_min = -666.666;
        auto &multilevel = dynamic_cast<ML_Epetra::MultiLevelPreconditioner &>(
          given_estimate.trilinos_operator());
        ASSERT_EQ(multilevel.ReComputePreconditioner(), 0);
      }
      stale.reinit();

      TrilinosWrappers::MPI::Vector new_result(v), result(v);
      fresh.vmult(new_result, v);
      double differences[3];
      for (unsigned int k = 0; k < 3; ++k)
        {
          recomputed[k]->vmult(result, v);
          differences[k] = relative_difference(result, new_result);
        }
      const double estimate     = finest(cleared).lambda_max;
      const double new_estimate = finest(fresh).lambda_max;
      this->log << processes_prefix() << dim << "D "
                << (uniform_scaling ? "A -> 256 A" : "K + cM -> K + 256 cM")
                << ": relative difference to the new hierarchy: recomputed "
                << differences[0] << " (eigenvalue estimate " << estimate
                << ", new " << new_estimate << "), with the new estimate "
                << differences[1] << ", without clearing " << differences[2]
                << std::endl;
      EXPECT_EQ(differences[1], 0.);
      EXPECT_NEAR(estimate, new_estimate, 0.05 * new_estimate);
      EXPECT_LT(differences[0], 0.02);
      EXPECT_GT(differences[2], 1.);
    }
}



// @sect4{The operator complexity}
//
// The solver counts the nonzeros of all levels from ML's data structure.
// For elasticity the hierarchy has a coarse level, and its levels together
// hold fewer than three times the nonzeros of the finest; a hierarchy of
// the finest level alone has exactly 1; the direct solvers report 0.
//
// ML computes the ratio itself, in MultiLevelPreconditioner::Complexities(),
// which deal.II's wrapper does not offer; the count is checked against it
// on deal.II's AMG with the translations, which is the solver's hierarchy
// with the same modes (see above), so the two counts must also agree
// exactly. ML's own ratio uses the number of nonzeros it records when it
// forms each coarse matrix, which is a few more than the entries the rows
// then hold (in 2D on one process 8,052 against 8,041 on the coarse
// level), so the two agree to 0.2 % only (measured: 0.02 % in 2D on one
// process, 0.08 % on two, less in 1D and 3D). A level left out or counted
// twice would change the ratio by 5 % or more.
TYPED_TEST(LinearSolverTest, OperatorComplexityIsML)
{
  constexpr int                  dim = TypeParam::value;
  const ElasticBody<dim>         large(multilevel_cells[dim - 1]);
  const ElasticBody<dim>         small(single_level_cells[dim - 1]);
  TrilinosWrappers::SparseMatrix large_matrix, small_matrix;
  large.set_matrix(large.mass_factor(), large_matrix);
  small.set_matrix(small.mass_factor(), small_matrix);

  LinearSolver solver(solver_parameters(SolverType::cg),
                      1,
                      MPI_COMM_WORLD,
                      this->timer);
  EXPECT_EQ(solver.multigrid_operator_complexity(), 0.);
  solver.set_near_null_space(large.rigid_body_modes(false));
  solver.prepare(large_matrix);
  const double complexity = solver.multigrid_operator_complexity();

  TrilinosWrappers::PreconditionAMG deal_ii_amg;
  deal_ii_amg.initialize(large_matrix, amg_data(large.constant_modes()));
  const double deal_ii_complexity =
    LinearSolverInternals::operator_complexity(deal_ii_amg,
                                               large_matrix,
                                               MPI_COMM_WORLD);
  double ml_complexity = 0., ml_fine_nonzeros = 0.;
  dynamic_cast<ML_Epetra::MultiLevelPreconditioner &>(
    deal_ii_amg.trilinos_operator())
    .Complexities(ml_complexity, ml_fine_nonzeros);

  solver.set_near_null_space(small.rigid_body_modes(true));
  solver.prepare(small_matrix);
  const double small_complexity = solver.multigrid_operator_complexity();

  LinearSolver direct(solver_parameters(SolverType::direct),
                      1,
                      MPI_COMM_WORLD,
                      this->timer);
  direct.prepare(large_matrix);

  this->log << processes_prefix() << dim << "D operator complexity "
            << complexity << " (ML's own " << ml_complexity << ", of "
            << ml_fine_nonzeros << " nonzeros on the finest level, "
            << large_matrix.n_nonzero_elements()
            << " in the matrix); single level " << small_complexity
            << std::endl;
  EXPECT_GT(complexity, 1.);
  EXPECT_LT(complexity, 3.);
  EXPECT_EQ(complexity, deal_ii_complexity);
  EXPECT_NEAR(complexity, ml_complexity, 2e-3 * ml_complexity);
  EXPECT_EQ(ml_fine_nonzeros,
            static_cast<double>(large_matrix.n_nonzero_elements()));
  EXPECT_EQ(small_complexity, 1.);
  EXPECT_EQ(direct.multigrid_operator_complexity(), 0.);
}



// @sect4{The names of the solvers}
//
// The solver reports the name it gave to Amesos' factory; that is the
// class of the object the factory creates, which is checked here directly.
// The symmetric factorization, which is not Amesos', is "MUMPS
// symmetric" (on one process).
// Before the first prepare() all names are empty.
TYPED_TEST(LinearSolverTest, SolverNamesAreTheSolversInUse)
{
  constexpr int                  dim = TypeParam::value;
  const ElasticBody<dim>         body(single_level_cells[dim - 1]);
  TrilinosWrappers::SparseMatrix matrix;
  body.set_matrix(body.mass_factor(), matrix);

  std::vector<std::pair<Parameters::LinearSolver, std::string>> cases = {
    {solver_parameters(SolverType::direct, DirectType::klu), "Amesos_Klu"},
    {solver_parameters(SolverType::direct, DirectType::mumps), "Amesos_Mumps"},
    {solver_parameters(SolverType::cg), "CG with ML"},
    {solver_parameters(SolverType::gmres), "GMRES with ML"}};
  Parameters::LinearSolver symmetric =
    solver_parameters(SolverType::direct, DirectType::mumps);
  symmetric.symmetric_factorization = true;
  cases.emplace_back(symmetric,
                     dealii::Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) ==
                         1
                       ? "MUMPS symmetric"
                       : "Amesos_Mumps");
  for (const auto &[parameters, name] : cases)
    {
      LinearSolver solver(parameters, 1, MPI_COMM_WORLD, this->timer);
      EXPECT_EQ(solver.solver_in_use(), "");
      solver.set_near_null_space(body.rigid_body_modes(true));
      solver.prepare(matrix);
      EXPECT_EQ(solver.solver_in_use(), name);
    }

  Epetra_LinearProblem problem;
  problem.SetOperator(
    const_cast<Epetra_CrsMatrix *>(&matrix.trilinos_matrix()));
  Amesos                             factory;
  std::unique_ptr<Amesos_BaseSolver> klu(factory.Create("Amesos_Klu", problem));
  std::unique_ptr<Amesos_BaseSolver> mumps(
    factory.Create("Amesos_Mumps", problem));
  EXPECT_NE(dynamic_cast<Amesos_Klu *>(klu.get()), nullptr);
  EXPECT_NE(dynamic_cast<Amesos_Mumps *>(mumps.get()), nullptr);
}



// @sect4{The automatic choice of the direct solver}
//
// `Direct solver = automatic` takes KLU below LinearSolver's threshold and
// MUMPS from it on; both solve a tridiagonal system of either size to
// round-off.
namespace
{
  void
  set_tridiagonal(const unsigned int n, TrilinosWrappers::SparseMatrix &matrix)
  {
    const IndexSet         all = complete_index_set(n);
    DynamicSparsityPattern pattern(n, n);
    for (unsigned int i = 0; i < n; ++i)
      for (unsigned int j = (i > 0 ? i - 1 : 0); j <= std::min(i + 1, n - 1);
           ++j)
        pattern.add(i, j);
    matrix.reinit(all, all, pattern, MPI_COMM_WORLD);
    for (unsigned int i = 0; i < n; ++i)
      {
        matrix.set(i, i, 4.);
        if (i > 0)
          matrix.set(i, i - 1, -1.);
        if (i + 1 < n)
          matrix.set(i, i + 1, -1.);
      }
    matrix.compress(VectorOperation::insert);
  }
} // namespace



TEST(LinearSolverChoice, AutomaticDirectSolverFollowsTheSize)
{
  const unsigned int threshold = LinearSolver::automatic_mumps_threshold;
  TimerOutput        timer(MPI_COMM_WORLD,
                    std::cout,
                    TimerOutput::never,
                    TimerOutput::wall_times);
  for (const auto &[n, name] :
       {std::pair<unsigned int, std::string>{threshold - 1, "Amesos_Klu"},
        std::pair<unsigned int, std::string>{threshold, "Amesos_Mumps"}})
    {
      TrilinosWrappers::SparseMatrix matrix;
      set_tridiagonal(n, matrix);
      const IndexSet                all = complete_index_set(n);
      TrilinosWrappers::MPI::Vector exact(all, MPI_COMM_WORLD);
      for (unsigned int i = 0; i < n; ++i)
        exact(i) = std::sin(0.01 * i);
      exact.compress(VectorOperation::insert);
      TrilinosWrappers::MPI::Vector rhs(exact), solution(exact);
      matrix.vmult(rhs, exact);

      LinearSolver solver(solver_parameters(SolverType::direct,
                                            DirectType::automatic),
                          1,
                          MPI_COMM_WORLD,
                          timer);
      solver.prepare(matrix);
      EXPECT_EQ(solver.solver_in_use(), name) << n << " unknowns";
      solver.solve(rhs, solution);
      solution -= exact;
      EXPECT_LT(solution.linfty_norm(), 1e-12) << n << " unknowns";
    }
}
