// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Tests of NewtonSolver and AndersonAcceleration}
//
// The solver is run on small systems $\mathbf r(\mathbf u) = \mathbf 0$
// whose behaviour under Newton's method is known in closed form, and what
// it does is compared with that theory, number by number:
// - Newton's method proper on the cubic system $\mathbf r(\mathbf u) =
//   \mathbf A\mathbf u + \mathbf c\circ\mathbf u^3 - \mathbf b$ (cubes and
//   products $\circ$ entry by entry) takes exact Newton steps, whose errors
//   obey $\mathbf e_{k+1} = \mathbf J_k^{-1}[\mathbf c\circ(2\mathbf u_k +
//   \mathbf u^*)\circ\mathbf e_k\circ\mathbf e_k]$: quadratic convergence.
// - The modified variant with the matrix $\mathbf K = \mathbf
//   J^*/(1-\rho)$ is a fixed-point iteration whose linearization is
//   $\rho\mathbf I$: it converges linearly at the rate $\rho$, and rebuilds
//   its matrix when $\rho > 1/2$, after `Max iterations` iterations, or
//   when the full step fails ($\rho < -1$).
// - Anderson acceleration of a linear fixed-point iteration is GMRES in
//   disguise (Walker and Ni 2011), and with a depth of at least the number
//   $n$ of unknowns terminates in $n+1$ iterations.
// - The line search halves an overshooting step of $\arctan$ and accepts a
//   step that raises the residual but lowers the potential energy; a
//   run-away iteration, a non-finite residual, an inverted state, too many
//   iterations and a line search without an admissible step throw
//   StepFailure; the iteration ends at round-off level.
//
// The problems are handed to the solver as it gets them from the program:
// TrilinosWrappers vectors and a TrilinosWrappers::SparseMatrix for the
// tangent, which the linear solve factorizes (densely, with LAPACK).

// Not typed on the dimension: the systems here are algebraic, with no mesh.

#include <cmath>
#include <core/exceptions.h>
#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/householder.h>
#include <deal.II/lac/lapack_full_matrix.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>
#include <functional>
#include <gtest/gtest.h>
#include <iostream>
#include <limits>
#include <solvers/anderson_acceleration.h>
#include <solvers/newton_solver.h>
#include <sstream>
#include <string>
#include <vector>

namespace
{
  using namespace dealii;
  using namespace SoftRobot;
  using DistributedVector = TrilinosWrappers::MPI::Vector;

  constexpr double nan = std::numeric_limits<double>::quiet_NaN();



  // @sect4{The test problems as the solver sees them}
  //
  // A model computes, for a state $\mathbf u$, the residual, the tangent
  // and what an assembly reports. TestProblem turns it into the three
  // functions of NewtonSolver::Problem and records every evaluation (the
  // state, whether a tangent was asked for, the residual norm) and how
  // often the tangent was prepared.
  struct Evaluation
  {
    Vector<double>     residual;
    FullMatrix<double> tangent;
    AssemblyResult     assembly;
  };
  using Model = std::function<void(const Vector<double> &u, Evaluation &)>;

  struct Call
  {
    Vector<double> u;
    bool           with_tangent;
    double         residual_norm;
  };

  class TestProblem
  {
  public:
    TestProblem(const unsigned int n, const Model &model)
      : n(n)
      , owned(complete_index_set(n))
      , model(model)
    {
      DynamicSparsityPattern pattern(n, n);
      for (unsigned int i = 0; i < n; ++i)
        for (unsigned int j = 0; j < n; ++j)
          pattern.add(i, j);
      tangent.reinit(owned, owned, pattern, MPI_COMM_WORLD);
    }

    DistributedVector
    vector(const Vector<double> &values) const
    {
      DistributedVector result(owned, MPI_COMM_WORLD);
      for (unsigned int i = 0; i < n; ++i)
        result[i] = values[i];
      result.compress(VectorOperation::insert);
      return result;
    }

    Vector<double>
    values(const DistributedVector &vector) const
    {
      Vector<double> result(n);
      for (unsigned int i = 0; i < n; ++i)
        result[i] = vector[i];
      return result;
    }

    // What the caller of the modified variant does before the solve: the
    // matrix of the iterations is prepared (here any matrix the test
    // chooses).
    void
    prepare(const FullMatrix<double> &matrix)
    {
      set_tangent(matrix);
      factorize();
    }

    NewtonSolver::Problem
    problem()
    {
      NewtonSolver::Problem problem;
      problem.evaluate = [this](const DistributedVector &u,
                                const bool               with_tangent,
                                DistributedVector       &residual) {
        Evaluation evaluation;
        evaluation.residual.reinit(n);
        evaluation.tangent.reinit(n, n);
        const Vector<double> state = values(u);
        model(state, evaluation);
        residual = vector(evaluation.residual);
        if (with_tangent)
          set_tangent(evaluation.tangent);
        calls.push_back({state, with_tangent, residual.l2_norm()});
        return evaluation.assembly;
      };
      problem.prepare_tangent = [this]() {
        factorize();
        ++n_prepared;
      };
      problem.solve = [this](const DistributedVector &rhs,
                             DistributedVector       &x) {
        Vector<double> solution = values(rhs);
        factorization.solve(solution);
        x = vector(solution);
        return 1u;
      };
      return problem;
    }

    // The evaluations, in order, and the preparations of a tangent.
    std::vector<Call> calls;
    unsigned int      n_prepared = 0;

    // The iterates: the starting point and the state after every iteration.
    // In Newton's method proper with full steps these are all evaluations;
    // in general the test picks them from `calls` itself.
    std::vector<Vector<double>>
    evaluated_states() const
    {
      std::vector<Vector<double>> states;
      for (const Call &call : calls)
        states.push_back(call.u);
      return states;
    }

  private:
    void
    set_tangent(const FullMatrix<double> &matrix)
    {
      for (unsigned int i = 0; i < n; ++i)
        for (unsigned int j = 0; j < n; ++j)
          tangent.set(i, j, matrix(i, j));
      tangent.compress(VectorOperation::insert);
    }

    void
    factorize()
    {
      factorization.reinit(n, n);
      for (unsigned int i = 0; i < n; ++i)
        for (unsigned int j = 0; j < n; ++j)
          factorization(i, j) = tangent.el(i, j);
      factorization.compute_lu_factorization();
    }

    const unsigned int             n;
    const IndexSet                 owned;
    const Model                    model;
    TrilinosWrappers::SparseMatrix tangent;
    LAPACKFullMatrix<double>       factorization;
  };



  // The program's defaults (read through the parameter declarations, so
  // that they are the ones a user gets), with the output of every iteration
  // on, and Newton's method proper.
  Parameters::NonlinearSolver
  default_parameters()
  {
    ParameterHandler prm;
    Parameters::NonlinearSolver::declare_parameters(prm);
    Parameters::NonlinearSolver parameters;
    parameters.parse_parameters(prm);
    parameters.tangent_update =
      Parameters::NonlinearSolver::TangentUpdate::every_iteration;
    parameters.verbose = true;
    return parameters;
  }

  // The parameters of the modified variant's tests: the caller's matrix
  // for all iterations (`every step`), Anderson acceleration of the given
  // depth, and only the relative tolerance.
  Parameters::NonlinearSolver
  modified_parameters(const double       relative_tolerance,
                      const unsigned int acceleration_depth = 0)
  {
    Parameters::NonlinearSolver parameters = default_parameters();
    parameters.tangent_update =
      Parameters::NonlinearSolver::TangentUpdate::every_step;
    parameters.acceleration_depth        = acceleration_depth;
    parameters.newton_absolute_tolerance = 0.;
    parameters.newton_relative_tolerance = relative_tolerance;
    return parameters;
  }



  // Dense helpers for the theory: $\mathbf M^{-1}\mathbf v$, norms.
  Vector<double>
  solve_dense(const FullMatrix<double> &matrix, const Vector<double> &rhs)
  {
    FullMatrix<double> inverse(matrix.m(), matrix.n());
    inverse.invert(matrix);
    Vector<double> result(rhs.size());
    inverse.vmult(result, rhs);
    return result;
  }

  Vector<double>
  difference(const Vector<double> &a, const Vector<double> &b)
  {
    Vector<double> result(a);
    result -= b;
    return result;
  }

  unsigned int
  count(const std::string &text, const std::string &word)
  {
    unsigned int n = 0;
    for (std::size_t i = text.find(word); i != std::string::npos;
         i             = text.find(word, i + 1))
      ++n;
    return n;
  }



  // @sect4{The cubic system}
  //
  // $\mathbf r(\mathbf u) = \mathbf A\mathbf u + \mathbf c\circ\mathbf u^3 -
  // \mathbf b$ with $\mathbf A$ = tridiag(-1, 4, -1), whose eigenvalues are
  // $4 - 2\cos(k\pi/(n+1))$, $\mathbf c\ge 0$, and $\mathbf b$ made from a
  // chosen solution $\mathbf u^*$. The tangent $\mathbf J(\mathbf u) =
  // \mathbf A + 3\,\mathrm{diag}(\mathbf c\circ\mathbf u^2)$ is symmetric
  // with eigenvalues no smaller than $\lambda_\text{min}(\mathbf A)$. The
  // force scale an assembly reports is the norm of the "internal forces"
  // $\mathbf A\mathbf u + \mathbf c\circ\mathbf u^3$; the potential energy
  // is not a number (a dynamic problem) unless asked for.
  struct CubicSystem
  {
    static constexpr unsigned int n = 4;

    Vector<double> c{1., 2., 0.5, 1.};
    Vector<double> exact{1., 0.5, 1.5, -0.5};
    Vector<double> b;

    CubicSystem()
      : b(n)
    {
      for (unsigned int i = 0; i < n; ++i)
        b[i] = internal_force(exact)[i];
    }

    static double
    a(const unsigned int i, const unsigned int j)
    {
      return (i == j) ? 4. : (i + 1 == j || j + 1 == i) ? -1. : 0.;
    }

    static double
    lambda_min()
    {
      return 4. - 2. * std::cos(M_PI / (n + 1));
    }

    Vector<double>
    internal_force(const Vector<double> &u) const
    {
      Vector<double> f(n);
      for (unsigned int i = 0; i < n; ++i)
        {
          for (unsigned int j = 0; j < n; ++j)
            f[i] += a(i, j) * u[j];
          f[i] += c[i] * u[i] * u[i] * u[i];
        }
      return f;
    }

    FullMatrix<double>
    tangent(const Vector<double> &u) const
    {
      FullMatrix<double> J(n, n);
      for (unsigned int i = 0; i < n; ++i)
        {
          for (unsigned int j = 0; j < n; ++j)
            J(i, j) = a(i, j);
          J(i, i) += 3. * c[i] * u[i] * u[i];
        }
      return J;
    }

    // Near the solution, $\mathbf r(\mathbf u^*+\mathbf e) = \mathbf J^*
    // \mathbf e + \mathbf q(\mathbf e)$ with $q_i = c_i(3u^*_i + e_i)e_i^2$,
    // and $\|\mathbf q\| \le Q(\mathbf e) = \max_i|c_i(3u^*_i + e_i)|\,
    // \|\mathbf e\|_\infty\|\mathbf e\|$, the bound returned here for the
    // state $\mathbf u$.
    double
    second_order_bound(const Vector<double> &u) const
    {
      Vector<double> e(u);
      e -= exact;
      double factor = 0.;
      for (unsigned int i = 0; i < n; ++i)
        factor = std::max(factor, std::abs(c[i] * (3. * exact[i] + e[i])));
      return factor * e.linfty_norm() * e.l2_norm();
    }

    // The round-off of a computed residual: each entry is a sum of $n+2$
    // terms (the row of $\mathbf A\mathbf u$, the cube, $b_i$), each of
    // which is rounded, so the error is at most $(n+4)\epsilon$ times the
    // sum of their magnitudes; and the state itself is rounded (by $\epsilon
    // |u_i|$), which changes the residual by up to $\epsilon\,|\mathbf
    // J||\mathbf u|$ more.
    double
    roundoff(const Vector<double> &u) const
    {
      const double   eps = std::numeric_limits<double>::epsilon();
      Vector<double> magnitudes(n), tangent_magnitudes(n);
      for (unsigned int i = 0; i < n; ++i)
        {
          for (unsigned int j = 0; j < n; ++j)
            magnitudes[i] += std::abs(a(i, j) * u[j]);
          tangent_magnitudes[i] = magnitudes[i];
          magnitudes[i] += std::abs(c[i] * u[i] * u[i] * u[i]) + std::abs(b[i]);
          tangent_magnitudes[i] += 3. * std::abs(c[i] * u[i] * u[i] * u[i]);
        }
      return (n + 4) * eps * magnitudes.l2_norm() +
             eps * tangent_magnitudes.l2_norm();
    }

    // With the matrix $\mathbf J^*/(1-\rho)$ the errors obey $\mathbf
    // e_{k+1} = \rho\mathbf e_k - (1-\rho)\mathbf J^{*-1}\mathbf q_k$, so
    // $\mathbf r_{k+1} = \rho\mathbf r_k - \mathbf q_k + \mathbf q_{k+1}$:
    // the ratio of the residual norms differs from $|\rho|$ by at most
    // $(Q_k + Q_{k+1})/\|\mathbf r_k\|$, and by the round-off of the two
    // residuals, which this returns for the evaluations `before` and
    // `after`. (The round-off of the linear solve changes the step by a
    // relative $10^{-15}$ and is negligible beside these.)
    double
    rate_tolerance(const Call &before, const Call &after) const
    {
      return (second_order_bound(before.u) + second_order_bound(after.u) +
              roundoff(before.u) + roundoff(after.u)) /
             before.residual_norm;
    }

    Model
    model() const
    {
      return [this](const Vector<double> &u, Evaluation &evaluation) {
        const Vector<double> f = internal_force(u);
        evaluation.residual    = f;
        evaluation.residual -= b;
        evaluation.tangent              = tangent(u);
        evaluation.assembly.force_scale = f.l2_norm();
      };
    }
  };



  // @sect4{Newton's method proper converges quadratically}
  //
  // From $\mathbf u_0 = \mathbf 0$ every step is the full Newton step, so
  // the iterates are the evaluations. With $\mathbf e_k = \mathbf u_k -
  // \mathbf u^*$, $\mathbf r(\mathbf u_k) - \mathbf J_k\mathbf e_k$ is, entry
  // by entry, $c_i[u^3 - u^{*3} - 3u^2(u-u^*)] = -c_i(2u+u^*)(u-u^*)^2$
  // (with $u = u_{k,i}$), so
  // @f[
  //   \mathbf e_{k+1} = \mathbf J_k^{-1}\,[\mathbf c\circ(2\mathbf u_k +
  //   \mathbf u^*)\circ\mathbf e_k\circ\mathbf e_k],
  //   \qquad
  //   \|\mathbf e_{k+1}\| \le \frac{\max_i|c_i(2u_{k,i} + u^*_i)|}
  //   {\lambda_\text{min}(\mathbf A)}\,\|\mathbf e_k\|_\infty\|\mathbf
  //   e_k\|.
  // @f]
  // The test checks the identity to round-off (relative to $\|\mathbf
  // e_k\|^2$ plus the round-off of $\mathbf u$ itself) and the bound. In the
  // maximum norm, $\varepsilon_k = \|\mathbf e_k\|_\infty$, the ratios $C_k
  // = \varepsilon_{k+1}/\varepsilon_k^2$ then lie between
  // @f[
  //   m_k = \frac{\min_i|c_i(2u_{k,i} + u^*_i)|}{\sqrt n\,\lambda_\text{max}
  //   (\mathbf J_k)} \quad\text{and}\quad
  //   M_k = \frac{\sqrt n\max_i|c_i(2u_{k,i} + u^*_i)|}{\lambda_\text{min}
  //   (\mathbf A)}
  // @f]
  // ($\|\mathbf J_k^{-1}\mathbf w\| \ge \|\mathbf w\|/\lambda_\text{max}$,
  // with Gershgorin's bound for $\lambda_\text{max}$), and the computed
  // order $p_k = \log(\varepsilon_{k+1}/\varepsilon_k)/\log(\varepsilon_k/
  // \varepsilon_{k-1}) = 2 + \log(C_k/C_{k-1})/\log(\varepsilon_k/
  // \varepsilon_{k-1})$ lies within $\log(\max M/\min m)/|\log(
  // \varepsilon_k/\varepsilon_{k-1})|$ of 2, a bound that shrinks as the
  // errors fall.
  // Last, the iteration stops at the first iterate whose residual is below
  // the relative tolerance times the largest force scale so far.
  TEST(NewtonSolverTest, NewtonsMethodConvergesQuadratically)
  {
    const CubicSystem           system;
    TestProblem                 test(CubicSystem::n, system.model());
    std::ostringstream          output;
    ConditionalOStream          pcout(output, true);
    Parameters::NonlinearSolver parameters = default_parameters();
    parameters.newton_absolute_tolerance   = 0.;
    parameters.newton_relative_tolerance   = 1e-13;
    const NewtonSolver solver(parameters, pcout);

    DistributedVector          u = test.vector(Vector<double>(CubicSystem::n));
    const NewtonSolver::Result result =
      solver.solve(u, test.problem(), system.b.l2_norm(), false);
    std::cout << output.str();

    // Full steps only: one evaluation (with tangent) per iterate, one
    // preparation per iteration.
    ASSERT_EQ(test.calls.size(), result.iterations + 1);
    EXPECT_EQ(test.n_prepared, result.iterations);
    EXPECT_EQ(result.linear_iterations, result.iterations);
    EXPECT_EQ(count(output.str(), "step length 1\n"), result.iterations);
    for (const Call &call : test.calls)
      EXPECT_TRUE(call.with_tangent);

    std::vector<double> errors;
    for (unsigned int k = 0; k < test.calls.size(); ++k)
      {
        const Vector<double> &u_k = test.calls[k].u;
        const Vector<double>  e_k = difference(u_k, system.exact);
        errors.push_back(e_k.l2_norm());
        if (k + 1 == test.calls.size())
          break;
        Vector<double> w(CubicSystem::n);
        double         K = 0.;
        for (unsigned int i = 0; i < CubicSystem::n; ++i)
          {
            w[i] =
              system.c[i] * (2. * u_k[i] + system.exact[i]) * e_k[i] * e_k[i];
            K =
              std::max(K,
                       std::abs(system.c[i] * (2. * u_k[i] + system.exact[i])) /
                         CubicSystem::lambda_min());
          }
        const Vector<double> predicted = solve_dense(system.tangent(u_k), w);
        const Vector<double> e_next =
          difference(test.calls[k + 1].u, system.exact);
        EXPECT_LE(difference(e_next, predicted).l2_norm(),
                  1e-13 * e_k.norm_sqr() + 1e-15 * system.exact.l2_norm())
          << "iteration " << k;
        EXPECT_LE(e_next.l2_norm(),
                  K * e_k.linfty_norm() * e_k.l2_norm() * (1. + 1e-12) +
                    1e-15 * system.exact.l2_norm())
          << "iteration " << k;
      }

    // The orders, in the maximum norm: $\varepsilon_k = \|\mathbf
    // e_k\|_\infty$, $C_k = \varepsilon_{k+1}/\varepsilon_k^2 \in [m_k, M_k]$,
    // for the steps whose errors are above round-off.
    const unsigned int  n = CubicSystem::n;
    std::vector<double> max_errors, lower, upper;
    for (unsigned int k = 0; k < test.calls.size(); ++k)
      {
        const Vector<double> &u_k = test.calls[k].u;
        max_errors.push_back(difference(u_k, system.exact).linfty_norm());
        double smallest = std::numeric_limits<double>::max(), largest = 0.,
               gershgorin = 0.;
        for (unsigned int i = 0; i < n; ++i)
          {
            const double w =
              std::abs(system.c[i] * (2. * u_k[i] + system.exact[i]));
            smallest = std::min(smallest, w);
            largest  = std::max(largest, w);
            gershgorin =
              std::max(gershgorin, 6. + 3. * system.c[i] * u_k[i] * u_k[i]);
          }
        lower.push_back(smallest / (std::sqrt(n) * gershgorin));
        upper.push_back(std::sqrt(n) * largest / CubicSystem::lambda_min());
      }
    std::cout << "errors:";
    for (const double e : errors)
      std::cout << ' ' << e;
    std::cout << "\norders (bound on |p - 2|):";
    double last_bound = std::numeric_limits<double>::max();
    for (unsigned int k = 1; k + 1 < max_errors.size(); ++k)
      {
        if (max_errors[k + 1] < 1e-14)
          break;
        const double C_k   = max_errors[k + 1] / std::pow(max_errors[k], 2);
        const double C_old = max_errors[k] / std::pow(max_errors[k - 1], 2);
        EXPECT_GE(C_k, lower[k]);
        EXPECT_LE(C_k, upper[k]);
        EXPECT_GE(C_old, lower[k - 1]);
        EXPECT_LE(C_old, upper[k - 1]);
        const double p = std::log(max_errors[k + 1] / max_errors[k]) /
                         std::log(max_errors[k] / max_errors[k - 1]);
        last_bound = std::log(std::max(upper[k], upper[k - 1]) /
                              std::min(lower[k], lower[k - 1])) /
                     std::abs(std::log(max_errors[k] / max_errors[k - 1]));
        std::cout << ' ' << p << " (" << last_bound << ")";
        EXPECT_NEAR(p, 2., last_bound) << "iteration " << k;
      }
    std::cout << std::endl;
    // The last of these bounds says something: the order is 2, not 1 or 3.
    EXPECT_LT(last_bound, 0.6);

    // The convergence test: the residual of the last iterate, and of no
    // earlier one, is below the relative tolerance times the force scale
    // (here the external forces', which the internal forces approach).
    double reference = system.b.l2_norm();
    for (unsigned int k = 0; k < test.calls.size(); ++k)
      {
        reference =
          std::max({reference,
                    test.calls[0].residual_norm,
                    system.internal_force(test.calls[k].u).l2_norm()});
        const bool below = test.calls[k].residual_norm <=
                           parameters.newton_relative_tolerance * reference;
        EXPECT_EQ(below, k + 1 == test.calls.size()) << "iterate " << k;
      }
    EXPECT_EQ(result.residual, test.calls.back().residual_norm);
    EXPECT_LE((difference(test.values(u), system.exact)).l2_norm(),
              1e-12 * system.exact.l2_norm());
  }



  // @sect4{The force scale follows the iterates}
  //
  // The scalar $r(u) = (u-1)^2$ has a double root, where Newton's method
  // converges linearly: from $u_0 = 0$ the iterates are $u_k = 1-2^{-k}$ and
  // the residuals $4^{-k}$, exactly in binary. The assembly reports the
  // force scale $100u$. With the relative tolerance $10^{-6}$ the
  // reference grows from the first residual, 1, to $100u_k$: the iteration
  // stops at the first $k$ with $4^{-k} \le 10^{-4}(1-2^{-k})$, $k = 7$,
  // not at $k = 10$ ($4^{-10}\le 10^{-6}$), as it would against the first
  // residual alone.
  TEST(NewtonSolverTest, ForceScaleFollowsTheIterates)
  {
    TestProblem test(1, [](const Vector<double> &u, Evaluation &evaluation) {
      evaluation.residual[0]          = (u[0] - 1.) * (u[0] - 1.);
      evaluation.tangent(0, 0)        = 2. * (u[0] - 1.);
      evaluation.assembly.force_scale = 100. * u[0];
    });
    std::ostringstream          output;
    ConditionalOStream          pcout(output, true);
    Parameters::NonlinearSolver parameters = default_parameters();
    parameters.newton_absolute_tolerance   = 0.;
    parameters.newton_relative_tolerance   = 1e-6;
    const NewtonSolver solver(parameters, pcout);

    DistributedVector          u = test.vector(Vector<double>(1));
    const NewtonSolver::Result result =
      solver.solve(u, test.problem(), 0., false);
    EXPECT_EQ(result.iterations, 7u);
    EXPECT_EQ(result.residual, std::pow(4., -7.));
    EXPECT_EQ(u[0], 1. - std::pow(2., -7.));
    EXPECT_EQ(result.assembly.force_scale, 100. * u[0]);
  }



  // @sect4{The modified variant converges at the rate of its matrix}
  //
  // With the matrix $\mathbf K = \mathbf J^*/(1-\rho)$, $\mathbf J^* =
  // \mathbf J(\mathbf u^*)$, and $\mathbf r(\mathbf u^* + \mathbf e) =
  // \mathbf J^*\mathbf e + \mathbf c\circ(3\mathbf u^* + \mathbf e)\circ
  // \mathbf e\circ\mathbf e$, a full step gives
  // @f[
  //   \mathbf e_{k+1} = \rho\,\mathbf e_k - (1-\rho)\,\mathbf J^{*-1}
  //   [\mathbf c\circ(3\mathbf u^*+\mathbf e_k)\circ\mathbf e_k\circ\mathbf
  //   e_k],
  //   \qquad
  //   \|\mathbf e_{k+1} - \rho\,\mathbf e_k\| \le (1-\rho)\frac{\max_i
  //   |c_i(3u^*_i + e_{k,i})|}{\lambda_\text{min}(\mathbf A)}\|\mathbf
  //   e_k\|_\infty\|\mathbf e_k\|:
  // @f]
  // linear convergence at the rate $\rho$, up to a term of second order.
  // Run with $\rho = 0.3$ (no rebuild: every iteration reduces the residual
  // by more than two), `Max iterations` = 40 and no acceleration, from
  // $\mathbf u^* + 0.05\,(1, -1, 1, 1)$. The number of iterations is then
  // the one the rate predicts, within one.
  TEST(NewtonSolverTest, ModifiedNewtonConvergesAtTheRateOfItsMatrix)
  {
    const CubicSystem           system;
    TestProblem                 test(CubicSystem::n, system.model());
    std::ostringstream          output;
    ConditionalOStream          pcout(output, true);
    Parameters::NonlinearSolver parameters = modified_parameters(1e-12);
    parameters.newton_max_iterations       = 40;
    const NewtonSolver solver(parameters, pcout);

    const double       rho = 0.3;
    FullMatrix<double> K   = system.tangent(system.exact);
    K *= 1. / (1. - rho);
    test.prepare(K);
    Vector<double>       start(system.exact);
    const Vector<double> perturbation{0.05, -0.05, 0.05, 0.05};
    start += perturbation;
    DistributedVector          u = test.vector(start);
    const NewtonSolver::Result result =
      solver.solve(u, test.problem(), system.b.l2_norm(), true);

    // One old matrix throughout: no tangent assembled, none prepared.
    EXPECT_EQ(test.n_prepared, 0u);
    ASSERT_EQ(test.calls.size(), result.iterations + 1);
    for (const Call &call : test.calls)
      EXPECT_FALSE(call.with_tangent);
    EXPECT_EQ(count(output.str(), "old tangent"), result.iterations);

    std::cout << "rates:";
    for (unsigned int k = 0; k + 1 < test.calls.size(); ++k)
      {
        const Vector<double> e_k = difference(test.calls[k].u, system.exact);
        const Vector<double> e_next =
          difference(test.calls[k + 1].u, system.exact);
        const double bound = (1. - rho) / CubicSystem::lambda_min() *
                             system.second_order_bound(test.calls[k].u);
        Vector<double> deviation(e_next);
        deviation.add(-rho, e_k);
        EXPECT_LE(deviation.l2_norm(),
                  bound * (1. + 1e-10) + 1e-15 * system.exact.l2_norm())
          << "iteration " << k;
        const double rate =
          test.calls[k + 1].residual_norm / test.calls[k].residual_norm;
        EXPECT_NEAR(rate,
                    rho,
                    system.rate_tolerance(test.calls[k], test.calls[k + 1]))
          << "iteration " << k;
        std::cout << ' ' << rate;
      }
    std::cout << std::endl;

    // The predicted count: the residual falls by rho per iteration (to
    // first order), from the first residual to the tolerance times the
    // external forces.
    const double predicted =
      std::log(parameters.newton_relative_tolerance * system.b.l2_norm() /
               test.calls[0].residual_norm) /
      std::log(rho);
    std::cout << "iterations " << result.iterations << ", predicted "
              << predicted << std::endl;
    EXPECT_NEAR(result.iterations, predicted, 1.);
  }



  // @sect4{The modified variant rebuilds its matrix when it is too slow}
  //
  // With $\rho = 0.7$ the first iteration reduces the residual by about
  // 0.7, less than a factor of two: the second iteration assembles the
  // tangent at $\mathbf u_1$ and prepares it, and converges like Newton's
  // method from there. That matrix stays for the following iterations,
  // whose rate is the change of the tangent between the iterates, far
  // below one half from this close: it is the only rebuild.
  TEST(NewtonSolverTest, ModifiedNewtonRebuildsWhenSlowerThanOneHalf)
  {
    const CubicSystem           system;
    TestProblem                 test(CubicSystem::n, system.model());
    std::ostringstream          output;
    ConditionalOStream          pcout(output, true);
    Parameters::NonlinearSolver parameters = modified_parameters(1e-12);
    const NewtonSolver          solver(parameters, pcout);

    const double       rho = 0.7;
    FullMatrix<double> K   = system.tangent(system.exact);
    K *= 1. / (1. - rho);
    test.prepare(K);
    Vector<double> start(system.exact);
    start.add(0.01, Vector<double>{1., -1., 1., 1.});
    DistributedVector          u = test.vector(start);
    const NewtonSolver::Result result =
      solver.solve(u, test.problem(), system.b.l2_norm(), true);
    std::cout << output.str();

    // Evaluations: u_0, u_1 (rate about 0.7), u_1 again with the tangent,
    // then one per iteration.
    ASSERT_GE(test.calls.size(), 4u);
    const double first_rate =
      test.calls[1].residual_norm / test.calls[0].residual_norm;
    const double tolerance =
      system.rate_tolerance(test.calls[0], test.calls[1]);
    std::cout << "first rate " << first_rate << " (rho " << rho << " +- "
              << tolerance << ")" << std::endl;
    EXPECT_NEAR(first_rate, rho, tolerance);
    EXPECT_GT(first_rate, 0.5);
    EXPECT_FALSE(test.calls[1].with_tangent);
    EXPECT_TRUE(test.calls[2].with_tangent);
    EXPECT_EQ(test.calls[2].u, test.calls[1].u);
    EXPECT_EQ(test.n_prepared, 1u);
    EXPECT_EQ(test.calls.size(), result.iterations + 2);
    for (unsigned int k = 3; k < test.calls.size(); ++k)
      {
        EXPECT_FALSE(test.calls[k].with_tangent);
        EXPECT_LT(test.calls[k].residual_norm,
                  0.5 * test.calls[k - 1].residual_norm);
      }
  }



  // @sect4{... and not when `Rebuild threshold` allows its rate}
  //
  // The system of the previous test, whose old matrix converges at the rate
  // $\rho = 0.7$. With `Rebuild threshold` = 0.8 that rate is accepted:
  // the caller's matrix serves every iteration, each reducing the residual
  // by about $\rho$, to the tolerance. With 0.6 the same first iteration
  // is too slow and the tangent is rebuilt at $\mathbf u_1$, as with the
  // default 0.5. Both end at the same solution.
  TEST(NewtonSolverTest, ModifiedNewtonKeepsItsMatrixWithinTheRebuildThreshold)
  {
    const CubicSystem system;
    const double      rho = 0.7;
    Vector<double>    start(system.exact);
    start.add(0.01, Vector<double>{1., -1., 1., 1.});
    std::vector<Vector<double>> solutions;
    for (const double threshold : {0.8, 0.6})
      {
        TestProblem                 test(CubicSystem::n, system.model());
        std::ostringstream          output;
        ConditionalOStream          pcout(output, true);
        Parameters::NonlinearSolver parameters = modified_parameters(1e-8);
        parameters.rebuild_threshold           = threshold;
        parameters.newton_max_iterations       = 60;
        const NewtonSolver solver(parameters, pcout);

        FullMatrix<double> K = system.tangent(system.exact);
        K *= 1. / (1. - rho);
        test.prepare(K);
        DistributedVector          u = test.vector(start);
        const NewtonSolver::Result result =
          solver.solve(u, test.problem(), system.b.l2_norm(), true);
        std::cout << "threshold " << threshold << ": " << result.iterations
                  << " iterations, " << test.n_prepared << " matrices prepared"
                  << std::endl;
        if (threshold > rho)
          {
            EXPECT_EQ(test.n_prepared, 0u);
            ASSERT_EQ(test.calls.size(), result.iterations + 1);
            for (unsigned int k = 0; k + 1 < test.calls.size(); ++k)
              {
                EXPECT_FALSE(test.calls[k + 1].with_tangent);
                EXPECT_NEAR(test.calls[k + 1].residual_norm /
                              test.calls[k].residual_norm,
                            rho,
                            system.rate_tolerance(test.calls[k],
                                                  test.calls[k + 1]))
                  << "iteration " << k;
              }
          }
        else
          {
            EXPECT_EQ(test.n_prepared, 1u);
            ASSERT_GE(test.calls.size(), 3u);
            EXPECT_TRUE(test.calls[2].with_tangent);
          }
        solutions.push_back(test.values(u));
        EXPECT_LE(difference(solutions.back(), system.exact).l2_norm(),
                  1e-6 * system.exact.l2_norm());
      }
    EXPECT_LE(difference(solutions[0], solutions[1]).l2_norm(),
              1e-6 * system.exact.l2_norm());
  }



  // @sect4{... after `Max iterations` iterations with one matrix}
  //
  // With $\rho = 0.3$ and `Max iterations` = 4, the caller's matrix serves
  // iterations 0 to 3 (each reducing the residual by about 0.3), and
  // iteration 4 rebuilds the tangent at $\mathbf u_4$. The rebuilt matrix
  // would again serve four iterations; the iteration converges before.
  TEST(NewtonSolverTest, ModifiedNewtonRebuildsAfterMaxIterations)
  {
    const CubicSystem           system;
    TestProblem                 test(CubicSystem::n, system.model());
    std::ostringstream          output;
    ConditionalOStream          pcout(output, true);
    Parameters::NonlinearSolver parameters = modified_parameters(1e-12);
    parameters.newton_max_iterations       = 4;
    const NewtonSolver solver(parameters, pcout);

    FullMatrix<double> K = system.tangent(system.exact);
    K *= 1. / (1. - 0.3);
    test.prepare(K);
    Vector<double> start(system.exact);
    start.add(0.01, Vector<double>{1., -1., 1., 1.});
    DistributedVector          u = test.vector(start);
    const NewtonSolver::Result result =
      solver.solve(u, test.problem(), system.b.l2_norm(), true);
    std::cout << output.str();

    ASSERT_GE(test.calls.size(), 7u);
    for (unsigned int k = 0; k < test.calls.size(); ++k)
      EXPECT_EQ(test.calls[k].with_tangent, k == 5) << "evaluation " << k;
    for (unsigned int k = 1; k <= 4; ++k)
      {
        const double rate =
          test.calls[k].residual_norm / test.calls[k - 1].residual_norm;
        const double tolerance =
          system.rate_tolerance(test.calls[k - 1], test.calls[k]);
        std::cout << "rate " << rate << " (0.3 +- " << tolerance << ")"
                  << std::endl;
        EXPECT_NEAR(rate, 0.3, tolerance);
        EXPECT_LT(rate, 0.5);
      }
    EXPECT_EQ(test.calls[5].u, test.calls[4].u);
    EXPECT_EQ(test.n_prepared, 1u);
    EXPECT_LE(result.iterations, 4u + 4u);
  }



  // @sect4{... and when its full step fails}
  //
  // With $\rho = -2$ ($\mathbf K = \mathbf J^*/3$) the full step overshoots
  // to twice the residual with the opposite sign. A step from an old matrix
  // is not halved: the iteration (it counts) ends with the trial rejected,
  // the iterate unchanged, and the next iteration rebuilds the tangent at
  // $\mathbf u_0$ and takes Newton steps from there.
  TEST(NewtonSolverTest, ModifiedNewtonRebuildsWhenItsFullStepFails)
  {
    const CubicSystem           system;
    TestProblem                 test(CubicSystem::n, system.model());
    std::ostringstream          output;
    ConditionalOStream          pcout(output, true);
    Parameters::NonlinearSolver parameters = modified_parameters(1e-12);
    const NewtonSolver          solver(parameters, pcout);

    FullMatrix<double> K = system.tangent(system.exact);
    K *= 1. / 3.;
    test.prepare(K);
    Vector<double> start(system.exact);
    start.add(0.01, Vector<double>{1., -1., 1., 1.});
    DistributedVector          u = test.vector(start);
    const NewtonSolver::Result result =
      solver.solve(u, test.problem(), system.b.l2_norm(), true);
    std::cout << output.str();

    ASSERT_GE(test.calls.size(), 4u);
    const double tolerance =
      system.rate_tolerance(test.calls[0], test.calls[1]);
    std::cout << "first rate "
              << test.calls[1].residual_norm / test.calls[0].residual_norm
              << " (2 +- " << tolerance << ")" << std::endl;
    EXPECT_NEAR(test.calls[1].residual_norm / test.calls[0].residual_norm,
                2.,
                tolerance);
    EXPECT_FALSE(test.calls[1].with_tangent);
    EXPECT_TRUE(test.calls[2].with_tangent);
    EXPECT_EQ(test.calls[2].u, test.calls[0].u);
    EXPECT_EQ(test.n_prepared, 1u);
    // The rejected iteration is counted and reported (with the step length
    // that would have come next, had halving been allowed).
    EXPECT_EQ(test.calls.size(), result.iterations + 2);
    EXPECT_NE(output.str().find("Newton 0: |r| = "), std::string::npos);
    EXPECT_NE(output.str().find("step length 0.5, old tangent"),
              std::string::npos);
    EXPECT_LE((difference(test.values(u), system.exact)).l2_norm(),
              1e-11 * system.exact.l2_norm());
  }



  // The GMRES iterates $\mathbf x_k$, $k = 0\ldots n$, for $\mathbf
  // P\mathbf x = \mathbf q$ from $\mathbf x_0$: $\mathbf x_k$ minimizes
  // $\|\mathbf q - \mathbf P\mathbf x\|$ over $\mathbf x_0 + \mathcal
  // K_k(\mathbf P, \mathbf r_0)$. The orthonormal basis of the Krylov space
  // comes from Gram-Schmidt (applied twice, which makes it orthogonal to
  // round-off), the least-squares problem from deal.II's Householder QR.
  std::vector<Vector<double>>
  gmres_iterates(const FullMatrix<double> &P,
                 const Vector<double>     &q,
                 const Vector<double>     &x0)
  {
    const unsigned int n = q.size();
    Vector<double>     r0(q), Px(n);
    P.vmult(Px, x0);
    r0 -= Px;

    std::vector<Vector<double>> iterates{x0};
    std::vector<Vector<double>> basis;
    Vector<double>              v = r0;
    for (unsigned int k = 1; k <= n; ++k)
      {
        for (unsigned int pass = 0; pass < 2; ++pass)
          for (const Vector<double> &w : basis)
            v.add(-(v * w), w);
        v /= v.l2_norm();
        basis.push_back(v);
        FullMatrix<double> W(n, k);
        for (unsigned int j = 0; j < k; ++j)
          {
            Vector<double> Pv(n);
            P.vmult(Pv, basis[j]);
            for (unsigned int i = 0; i < n; ++i)
              W(i, j) = Pv[i];
          }
        Vector<double>            y(k);
        const Householder<double> qr(W);
        qr.least_squares(y, r0);
        Vector<double> x(x0);
        for (unsigned int j = 0; j < k; ++j)
          x.add(y[j], basis[j]);
        iterates.push_back(x);
        P.vmult(v, basis.back());
      }
    return iterates;
  }



  // @sect4{Anderson acceleration is GMRES in disguise}
  //
  // For the linear fixed-point map $g(\mathbf x) = \mathbf x + \mathbf
  // d(\mathbf x)$, $\mathbf d(\mathbf x) = \mathbf K^{-1}(\mathbf b -
  // \mathbf A\mathbf x)$, Anderson acceleration with a history that is never
  // truncated gives $\mathbf x_{k+1} = g(\mathbf x^\text{G}_k)$, with the
  // $k$-th GMRES iterate for $\mathbf K^{-1}\mathbf A\mathbf x = \mathbf
  // K^{-1}\mathbf b$ from the same $\mathbf x_0$ (Walker and Ni 2011,
  // theorem 2.2, for GMRES that does not stagnate). Since $\mathbf
  // d(g(\mathbf x)) = (\mathbf I - \mathbf K^{-1}\mathbf A)\mathbf
  // d(\mathbf x)$, the updates of the accelerated iteration are the GMRES
  // residuals times that matrix. GMRES ends at the exact solution after
  // $n$ iterations, and the accelerated iteration after $n+1$.
  //
  // Here $n = 5$, $\mathbf A$ is a nonsymmetric matrix and $\mathbf K$ its
  // diagonal (Jacobi), and the accelerated step is always taken (the class
  // alone, without NewtonSolver's test). GMRES is computed independently,
  // above. The two agree to round-off, amplified by the conditioning of the
  // least-squares problems (squared in the normal equations of
  // AndersonAcceleration): $10^{-12}$ of $\|\mathbf d_0\|$ is allowed.
  TEST(NewtonSolverTest, AndersonAccelerationIsGMRESInDisguise)
  {
    constexpr unsigned int n = 5;
    FullMatrix<double>     A(n, n);
    for (unsigned int i = 0; i < n; ++i)
      for (unsigned int j = 0; j < n; ++j)
        A(i, j) = (i == j) ? 3. + i : 1. / (1. + i + 2. * j) - 0.2 * (j > i);
    Vector<double> b(n), x0(n);
    for (unsigned int i = 0; i < n; ++i)
      {
        b[i]  = 1. + i;
        x0[i] = 0.5 * std::cos(1. + i);
      }
    // The preconditioned system P x = q with P = K^{-1} A, q = K^{-1} b.
    FullMatrix<double> P(n, n);
    Vector<double>     q(n);
    for (unsigned int i = 0; i < n; ++i)
      {
        for (unsigned int j = 0; j < n; ++j)
          P(i, j) = A(i, j) / A(i, i);
        q[i] = b[i] / A(i, i);
      }
    // d(x) = q - P x.
    const auto update = [&](const Vector<double> &x) {
      Vector<double> d(q), Px(n);
      P.vmult(Px, x);
      d -= Px;
      return d;
    };

    const std::vector<Vector<double>> gmres = gmres_iterates(P, q, x0);

    const IndexSet owned          = complete_index_set(n);
    const auto     to_distributed = [&](const Vector<double> &values) {
      DistributedVector result(owned, MPI_COMM_WORLD);
      for (unsigned int i = 0; i < n; ++i)
        result[i] = values[i];
      result.compress(VectorOperation::insert);
      return result;
    };
    AndersonAcceleration anderson(n);
    DistributedVector    x  = to_distributed(x0), step(x);
    const double         d0 = update(x0).l2_norm();
    for (unsigned int k = 0; k <= n; ++k)
      {
        Vector<double> x_values(n);
        for (unsigned int i = 0; i < n; ++i)
          x_values[i] = x[i];
        const Vector<double>    d        = update(x_values);
        const DistributedVector d_vector = to_distributed(d);
        const bool have_step = anderson.accelerated_step(x, d_vector, step);
        EXPECT_EQ(have_step, k > 0);
        EXPECT_EQ(anderson.n_differences(), k);
        // d(x_k) = (I - P) d(x^G_{k-1}) for k >= 1.
        if (k > 0)
          {
            const Vector<double> gmres_residual = update(gmres[k - 1]);
            Vector<double>       predicted(n);
            P.vmult(predicted, gmres_residual);
            predicted.sadd(-1., 1., gmres_residual);
            const double error = difference(d, predicted).l2_norm();
            std::cout << "k = " << k << ": |d_k| / |d_0| = " << d.l2_norm() / d0
                      << ", difference to GMRES " << error / d0 << std::endl;
            EXPECT_LE(error, 1e-12 * d0);
          }
        if (have_step)
          x += step;
        else
          x += d_vector;
      }
    // After n+1 iterations: the solution, to round-off.
    Vector<double> x_values(n);
    for (unsigned int i = 0; i < n; ++i)
      x_values[i] = x[i];
    const Vector<double> solution = solve_dense(A, b);
    EXPECT_LE(difference(x_values, solution).l2_norm(),
              1e-12 * solution.l2_norm());
    EXPECT_LE(update(x_values).l2_norm(), 1e-12 * d0);

    // Forgetting the differences keeps the last iterate and update: the next
    // call has one difference again. Forgetting everything leaves none.
    anderson.clear_differences();
    EXPECT_EQ(anderson.n_differences(), 0u);
    EXPECT_TRUE(
      anderson.accelerated_step(x, to_distributed(update(x_values)), step));
    EXPECT_EQ(anderson.n_differences(), 1u);
    anderson.clear();
    EXPECT_FALSE(anderson.accelerated_step(x, x, step));
    EXPECT_EQ(anderson.n_differences(), 0u);
  }



  // @sect4{Anderson acceleration inside the modified Newton method}
  //
  // The linear problem $\mathbf A\mathbf u = \mathbf b$ with the symmetric
  // $\mathbf A = \mathbf Q\,\mathrm{diag}(\lambda_i)\mathbf Q^T$,
  // $\lambda_i\in[1.1, 1.8]$, and the matrix $\mathbf K = 2\mathbf I$: the
  // plain iteration's residuals are $\mathbf r_{k+1} = (\mathbf I -
  // \mathbf A/2)\,\mathbf r_k$, with eigenvalues $1-\lambda_i/2 \in [0.1,
  // 0.45]$, so it never slows below a factor of two, and the number of its
  // iterations follows from the eigen-decomposition of $\mathbf r_0$. The
  // accelerated iteration with depth $m\ge n$ ends after at most $n + 1$
  // iterations, as GMRES; with depth 2 it needs fewer iterations than the
  // plain one.
  TEST(NewtonSolverTest, AccelerationOfModifiedNewton)
  {
    constexpr unsigned int n = 5;
    // Q: a Householder reflection I - 2 v v^T / |v|^2.
    Vector<double>     v{1., -2., 0.5, 1.5, -1.};
    const double       v2 = v.norm_sqr();
    FullMatrix<double> A(n, n);
    const double       lambda[n] = {1.1, 1.3, 1.45, 1.6, 1.8};
    for (unsigned int i = 0; i < n; ++i)
      for (unsigned int j = 0; j < n; ++j)
        for (unsigned int k = 0; k < n; ++k)
          {
            const double Qik = (i == k) - 2. * v[i] * v[k] / v2;
            const double Qjk = (j == k) - 2. * v[j] * v[k] / v2;
            A(i, j) += Qik * lambda[k] * Qjk;
          }
    Vector<double> b{1., 2., -1., 0.5, 3.};
    const Model linear = [&](const Vector<double> &u, Evaluation &evaluation) {
      A.vmult(evaluation.residual, u);
      evaluation.assembly.force_scale = evaluation.residual.l2_norm();
      evaluation.residual -= b;
      evaluation.tangent = A;
    };
    FullMatrix<double> K(n, n);
    for (unsigned int i = 0; i < n; ++i)
      K(i, i) = 2.;

    const auto run = [&](const unsigned int depth, std::string &output_text) {
      TestProblem                 test(n, linear);
      std::ostringstream          output;
      ConditionalOStream          pcout(output, true);
      Parameters::NonlinearSolver parameters =
        modified_parameters(1e-10, depth);
      parameters.newton_max_iterations = 100;
      const NewtonSolver solver(parameters, pcout);
      test.prepare(K);
      DistributedVector          u = test.vector(Vector<double>(n));
      const NewtonSolver::Result result =
        solver.solve(u, test.problem(), b.l2_norm(), true);
      EXPECT_EQ(test.n_prepared, 0u) << "depth " << depth;
      EXPECT_LE(difference(test.values(u), solve_dense(A, b)).l2_norm(),
                1e-9 * b.l2_norm());
      output_text = output.str();
      return result.iterations;
    };

    // The plain iteration: r_k = (I - A/2)^k b, until |r_k| <= 1e-10 |b|
    // (the reference is |b|: the first residual, and the forces' limit).
    unsigned int predicted = 0;
    {
      Vector<double> r(b), Ar(n);
      while (r.l2_norm() > 1e-10 * b.l2_norm())
        {
          A.vmult(Ar, r);
          r.add(-0.5, Ar);
          ++predicted;
        }
    }
    std::string        text;
    const unsigned int plain = run(0, text);
    EXPECT_EQ(count(text, "accelerated"), 0u);
    const unsigned int deep              = run(n, text);
    const unsigned int accelerated_steps = count(text, "(accelerated)");
    std::cout << text;
    const unsigned int shallow = run(2, text);
    std::cout << "iterations: plain " << plain << " (predicted " << predicted
              << "), depth 2: " << shallow << ", depth " << n << ": " << deep
              << " (" << accelerated_steps << " accelerated)" << std::endl;
    EXPECT_NEAR(plain, predicted, 1.);
    EXPECT_LE(deep, n + 1);
    EXPECT_GE(accelerated_steps, 1u);
    EXPECT_LT(shallow, plain);
  }



  // @sect4{The line search}
  //
  // The scalar $r(u) = \arctan u$ for $u<0$ and $2\arctan u$ for $u\ge 0$
  // (a stiffer right side) with the root 0, the potential energy
  // $\Pi(u) = k(u\arctan u - \frac12\ln(1+u^2))$ ($k$ = 1 or 2), from $u_0
  // = -1$. The Newton step $d_0 = -(1+u_0^2)\arctan u_0 = \pi/2$ overshoots
  // to $u = \pi/2 - 1 = 0.5708$, where $|r| = 1.037 > \pi/4$: in a dynamic
  // problem (no energy) it is halved, to $u = \pi/4 - 1$ with $|r| =
  // 0.2114$. There $\Pi = 0.3099 < \Pi(-1) = 0.4388$, so in a static problem
  // the full step is accepted although the residual grew.
  Model
  one_sided_arctan(const bool static_problem)
  {
    return [static_problem](const Vector<double> &u, Evaluation &evaluation) {
      const double k                  = (u[0] < 0.) ? 1. : 2.;
      evaluation.residual[0]          = k * std::atan(u[0]);
      evaluation.tangent(0, 0)        = k / (1. + u[0] * u[0]);
      evaluation.assembly.force_scale = std::abs(evaluation.residual[0]);
      evaluation.assembly.potential_energy =
        static_problem
          ? k * (u[0] * std::atan(u[0]) - 0.5 * std::log(1. + u[0] * u[0]))
          : nan;
    };
  }

  TEST(NewtonSolverTest, LineSearchHalvesAnOvershootingStep)
  {
    TestProblem                 test(1, one_sided_arctan(false));
    std::ostringstream          output;
    ConditionalOStream          pcout(output, true);
    Parameters::NonlinearSolver parameters = default_parameters();
    parameters.newton_absolute_tolerance   = 1e-14;
    parameters.newton_relative_tolerance   = 1e-14;
    const NewtonSolver solver(parameters, pcout);

    DistributedVector          u = test.vector(Vector<double>{-1.});
    const NewtonSolver::Result result =
      solver.solve(u, test.problem(), 0., false);
    std::cout << output.str();

    ASSERT_GE(test.calls.size(), 3u);
    EXPECT_NEAR(test.calls[1].u[0], M_PI / 2. - 1., 1e-15);
    EXPECT_NEAR(test.calls[1].residual_norm,
                2. * std::atan(M_PI / 2. - 1.),
                1e-15);
    EXPECT_NEAR(test.calls[2].u[0], M_PI / 4. - 1., 1e-15);
    EXPECT_NE(output.str().find("Newton 0: |r| = 0.211"), std::string::npos);
    EXPECT_NE(output.str().find("step length 0.5\n"), std::string::npos);
    // From there full steps, with the cubic convergence of arctan's Newton
    // map $u - (1+u^2)\arctan u = \frac23 u^3 + O(u^5)$.
    EXPECT_EQ(count(output.str(), "step length 1\n"), result.iterations - 1);
    EXPECT_LE(std::abs(u[0]), 1e-14);
  }

  TEST(NewtonSolverTest, StaticLineSearchAcceptsLowerPotentialEnergy)
  {
    TestProblem                 test(1, one_sided_arctan(true));
    std::ostringstream          output;
    ConditionalOStream          pcout(output, true);
    Parameters::NonlinearSolver parameters = default_parameters();
    parameters.newton_absolute_tolerance   = 1e-14;
    parameters.newton_relative_tolerance   = 1e-14;
    const NewtonSolver solver(parameters, pcout);

    DistributedVector          u = test.vector(Vector<double>{-1.});
    const NewtonSolver::Result result =
      solver.solve(u, test.problem(), 0., false);
    std::cout << output.str();

    ASSERT_GE(test.calls.size(), 3u);
    EXPECT_NEAR(test.calls[1].u[0], M_PI / 2. - 1., 1e-15);
    EXPECT_GT(test.calls[1].residual_norm, test.calls[0].residual_norm);
    // The second evaluation is the Newton step from the accepted trial.
    const double u1 = M_PI / 2. - 1.;
    EXPECT_NEAR(test.calls[2].u[0], u1 - (1. + u1 * u1) * std::atan(u1), 1e-15);
    EXPECT_NE(output.str().find("Newton 0: |r| = 1.037"), std::string::npos);
    EXPECT_EQ(count(output.str(), "step length 1\n"), result.iterations);
    EXPECT_LE(std::abs(u[0]), 1e-14);
  }



  // @sect4{Failures}
  //
  // Newton's method without line search on $\arctan u$ from $u_0 = 1.5$
  // diverges: the iterates $u_{k+1} = u_k - (1+u_k^2)\arctan u_k$ alternate
  // in sign and grow ($-1.69$, $2.32$, $-5.11$, $32.3$, $-1575$). The
  // assembly reports $|u|$ as its force scale; the initial scale is
  // $\max(|u_0|, \arctan u_0) = 1.5$, and the iteration is declared
  // run-away at the first iterate with $|u_k| > 1500$, which the test
  // computes from the same map.
  TEST(NewtonSolverTest, RunAwayIterationThrows)
  {
    TestProblem test(1, [](const Vector<double> &u, Evaluation &evaluation) {
      evaluation.residual[0]          = std::atan(u[0]);
      evaluation.tangent(0, 0)        = 1. / (1. + u[0] * u[0]);
      evaluation.assembly.force_scale = std::abs(u[0]);
    });
    std::ostringstream          output;
    ConditionalOStream          pcout(output, true);
    Parameters::NonlinearSolver parameters = default_parameters();
    parameters.line_search                 = false;
    const NewtonSolver solver(parameters, pcout);

    unsigned int expected_evaluations = 1;
    for (double x = 1.5; std::abs(x) <= 1e3 * 1.5; ++expected_evaluations)
      x -= (1. + x * x) * std::atan(x);

    DistributedVector u = test.vector(Vector<double>{1.5});
    try
      {
        solver.solve(u, test.problem(), 0., false);
        ADD_FAILURE() << "no StepFailure";
      }
    catch (const StepFailure &failure)
      {
        std::cout << failure.what() << std::endl;
        EXPECT_EQ(std::string(failure.what())
                    .rfind("the iteration ran away (forces 1575.", 0),
                  0u);
        EXPECT_NE(
          std::string(failure.what()).find("against 1.500000 at its start"),
          std::string::npos);
      }
    EXPECT_EQ(expected_evaluations, 6u);
    EXPECT_EQ(test.calls.size(), expected_evaluations);
  }

  // A residual that is not finite, and an inverted starting state.
  TEST(NewtonSolverTest, NonFiniteResidualAndInvertedStartThrow)
  {
    std::ostringstream output;
    ConditionalOStream pcout(output, true);
    const NewtonSolver solver(default_parameters(), pcout);
    {
      TestProblem test(1, [](const Vector<double> &, Evaluation &evaluation) {
        evaluation.residual[0]   = nan;
        evaluation.tangent(0, 0) = 1.;
      });
      DistributedVector u = test.vector(Vector<double>{1.});
      try
        {
          solver.solve(u, test.problem(), 1., false);
          ADD_FAILURE() << "no StepFailure";
        }
      catch (const StepFailure &failure)
        {
          EXPECT_EQ(std::string(failure.what()), "the residual is not finite");
        }
      EXPECT_EQ(test.calls.size(), 1u);
      EXPECT_EQ(test.n_prepared, 0u);
    }
    {
      TestProblem test(1, [](const Vector<double> &u, Evaluation &evaluation) {
        evaluation.residual[0]                   = u[0];
        evaluation.tangent(0, 0)                 = 1.;
        evaluation.assembly.min_jacobian         = -0.5;
        evaluation.assembly.inverted_point_found = true;
      });
      DistributedVector u = test.vector(Vector<double>{1.});
      try
        {
          solver.solve(u, test.problem(), 1., true);
          ADD_FAILURE() << "no StepFailure";
        }
      catch (const StepFailure &failure)
        {
          EXPECT_EQ(std::string(failure.what()),
                    "the predicted state has an inverted element (det F = "
                    "-0.500000)");
        }
    }
  }

  // The state is "inverted" (det F = u - 0.99 < 0) for u < 0.99, and the
  // root is 0: from u = 1 the step -1 and its halvings down to 1/32 all end
  // in inverted states (1 - 1/32 = 0.96875), and the line search fails with
  // the last trial's det F.
  TEST(NewtonSolverTest, LineSearchWithoutAdmissibleStepThrows)
  {
    TestProblem test(1, [](const Vector<double> &u, Evaluation &evaluation) {
      evaluation.residual[0]                   = u[0];
      evaluation.tangent(0, 0)                 = 1.;
      evaluation.assembly.min_jacobian         = u[0] - 0.99;
      evaluation.assembly.inverted_point_found = (u[0] < 0.99);
    });
    std::ostringstream          output;
    ConditionalOStream          pcout(output, true);
    Parameters::NonlinearSolver parameters = default_parameters();
    ASSERT_EQ(parameters.max_line_search_steps, 5u);
    const NewtonSolver solver(parameters, pcout);
    DistributedVector  u = test.vector(Vector<double>{1.});
    try
      {
        solver.solve(u, test.problem(), 1., false);
        ADD_FAILURE() << "no StepFailure";
      }
    catch (const StepFailure &failure)
      {
        EXPECT_EQ(std::string(failure.what()),
                  "the line search found no admissible step (min det F = "
                  "-0.021250)");
      }
    EXPECT_EQ(test.calls.size(), 1u + 6u);
    EXPECT_EQ(test.calls.back().u[0], 1. - 1. / 32.);
  }

  // The double root of $r(u) = u^2$: Newton's method halves $u$ in every
  // iteration, exactly, and the residual falls by four; the tolerance of
  // $10^{-30}$ is out of reach. Newton's method proper fails after `Max
  // iterations` = 5 iterations with the residual $4^{-5}$; the modified
  // variant after twice as many.
  TEST(NewtonSolverTest, TooManyIterationsThrow)
  {
    const Model double_root = [](const Vector<double> &u,
                                 Evaluation           &evaluation) {
      evaluation.residual[0]          = u[0] * u[0];
      evaluation.tangent(0, 0)        = 2. * u[0];
      evaluation.assembly.force_scale = evaluation.residual[0];
    };
    std::ostringstream          output;
    ConditionalOStream          pcout(output, true);
    Parameters::NonlinearSolver parameters = default_parameters();
    parameters.newton_max_iterations       = 5;
    parameters.newton_absolute_tolerance   = 1e-30;
    parameters.newton_relative_tolerance   = 1e-30;
    for (const bool modified : {false, true})
      {
        TestProblem test(1, double_root);
        if (modified)
          test.prepare(
            FullMatrix<double>(1, 1, std::vector<double>{2.}.data()));
        const NewtonSolver solver(parameters, pcout);
        DistributedVector  u = test.vector(Vector<double>{1.});
        try
          {
            solver.solve(u, test.problem(), 1., modified);
            ADD_FAILURE() << "no StepFailure";
          }
        catch (const StepFailure &failure)
          {
            if (modified)
              EXPECT_EQ(std::string(failure.what())
                          .rfind("Newton's method did not converge in 10 "
                                 "iterations (residual ",
                                 0),
                        0u);
            else
              EXPECT_EQ(std::string(failure.what()),
                        "Newton's method did not converge in 5 iterations "
                        "(residual 0.000976562)");
          }
      }
  }



  // @sect4{The end at round-off level}
  //
  // Stagnation: $r(u) = (u-1) + \varepsilon\,\mathrm{sign}(u-1)$ (sign(0) =
  // 1) has $|r| = |u-1| + \varepsilon \ge \varepsilon$, a floor like that of
  // round-off. From $u_0 = 0$: $u_1 = 1+\varepsilon$ ($|r| = 2\varepsilon$),
  // then the full step $-2\varepsilon$ is rejected and its half, $u_2 = 1$
  // ($|r| = \varepsilon$), accepted; from there no step lowers the residual.
  // With $\varepsilon = 2^{-30} \le 10^{-6}$ times the force scale (1) the
  // last trial, $1 - \varepsilon/32$, is accepted after iteration 2; with
  // $\varepsilon = 2^{-10}$ the line search fails. (Both tolerances are
  // zero: only these rules end the iteration.)
  TEST(NewtonSolverTest, StagnationAtRoundOffLevelIsAccepted)
  {
    std::ostringstream          output;
    ConditionalOStream          pcout(output, true);
    Parameters::NonlinearSolver parameters = default_parameters();
    parameters.newton_absolute_tolerance   = 0.;
    parameters.newton_relative_tolerance   = 0.;
    const NewtonSolver solver(parameters, pcout);
    for (const double epsilon : {std::pow(2., -30.), std::pow(2., -10.)})
      {
        TestProblem       test(1,
                         [epsilon](const Vector<double> &u,
                                   Evaluation           &evaluation) {
                           evaluation.residual[0] =
                             (u[0] - 1.) + (u[0] >= 1. ? epsilon : -epsilon);
                           evaluation.tangent(0, 0) = 1.;
                         });
        DistributedVector u = test.vector(Vector<double>{0.});
        if (epsilon < 1e-6)
          {
            const NewtonSolver::Result result =
              solver.solve(u, test.problem(), 1., false);
            EXPECT_EQ(result.iterations, 2u);
            EXPECT_EQ(u[0], 1. - epsilon / 32.);
            EXPECT_EQ(result.residual, epsilon * (1. + 1. / 32.));
            EXPECT_EQ(test.calls.size(), 1u + 1u + 2u + 6u);
          }
        else
          EXPECT_THROW(solver.solve(u, test.problem(), 1., false), StepFailure);
      }
  }

  // The update at round-off level: $r(u) = u - u^* + 10^{-10}\cos(10^7u)$
  // with $u^* = 10^6$ has a residual floor of about $10^{-10}$, and after
  // the first step the update, of that size, is below $10^{-14}|u| =
  // 10^{-8}$: the iteration ends there, without a line search, after one
  // iteration, with the residual left as it is.
  TEST(NewtonSolverTest, UpdateAtRoundOffLevelEndsTheIteration)
  {
    TestProblem test(1, [](const Vector<double> &u, Evaluation &evaluation) {
      evaluation.residual[0]   = u[0] - 1e6 + 1e-10 * std::cos(1e7 * u[0]);
      evaluation.tangent(0, 0) = 1.;
    });
    std::ostringstream          output;
    ConditionalOStream          pcout(output, true);
    Parameters::NonlinearSolver parameters = default_parameters();
    parameters.newton_absolute_tolerance   = 0.;
    parameters.newton_relative_tolerance   = 0.;
    const NewtonSolver         solver(parameters, pcout);
    DistributedVector          u = test.vector(Vector<double>{0.});
    const NewtonSolver::Result result =
      solver.solve(u, test.problem(), 1., false);
    EXPECT_EQ(result.iterations, 1u);
    EXPECT_EQ(test.calls.size(), 2u);
    EXPECT_EQ(test.n_prepared, 2u);
    EXPECT_GT(result.residual, 0.);
    // (|u - u*| is at most the spacing of the doubles at 1e6, 1.2e-10.)
    EXPECT_LE(result.residual, 1.2e-10 + 1e-10);
    EXPECT_NEAR(u[0], 1e6, 1e-9);
  }
} // namespace
