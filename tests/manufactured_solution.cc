// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Convergence for a manufactured solution of finite-strain elastodynamics}
//
// We choose a smooth motion of the box $[0, L]^{dim}$ that vanishes on its
// boundary,
// @f[
//   u_c(\mathbf X, t) = A_c \sin(\omega t)\,\phi(\mathbf X),\qquad
//   \phi(\mathbf X) = \prod_{i} \sin\left(\frac{\pi X_i}{L}\right),
// @f]
// with amplitudes that stretch and compress the material by up to 25 %,
// clamp the whole boundary, and impose the body force that makes it a
// solution of the balance of momentum $\rho_0\ddot{\mathbf u} =
// \mathrm{Div}\,\mathbf P(\mathbf F) + \mathbf b$ of the model's own
// material law (the compressible neo-Hookean solid in 3D, the reduced
// incompressible ones in 1D and 2D):
// @f[
//   \mathbf b = \rho_0\ddot{\mathbf u} - \mathrm{Div}\,\mathbf P(\mathbf I +
//   \nabla_0\mathbf u),
// @f]
// with the divergence taken by central differences of the closed-form
// $\mathbf P$ (step $10^{-5} L$, error about $10^{-10}$ relative). The
// frequency $\omega$ is about 60 % of the lowest eigenfrequency of the
// clamped box, so that inertia is a third of the elastic force. The run
// starts from $\mathbf u = 0$ with the exact velocity and ends at a quarter
// period, $t = \pi/(2\omega)$, at the largest displacement.
//
// In space, with Lagrange elements of degree $p$ on uniformly refined
// meshes and time steps small enough that the error of the time stepping
// is negligible, the $L^2$ error must fall as $h^{p+1}$ and the $H^1$
// seminorm error as $h^p$. In time, on a fixed mesh, the HHT-α scheme is of
// second order: the difference to a run with a much smaller step must fall
// as $\Delta t^2$.

#include "solver_test_tools.h"

#include <cmath>
#include <core/soft_robot_dynamics.h>
#include <deal.II/base/function.h>
#include <deal.II/lac/vector.h>
#include <deal.II/numerics/vector_tools.h>
#include <gtest/gtest.h>

using namespace dealii;
using namespace SoftRobot;
using namespace SoftRobot::Testing;

template <typename T>
class ManufacturedSolutionTest : public ::testing::Test
{
};
TYPED_TEST_SUITE(ManufacturedSolutionTest, Dimensions);

namespace
{
  constexpr double mu = 10., kappa = 100., rho = 1e-6, L = 1., omega = 1e4;
  const double     end_time = 0.5 * M_PI / omega;

  // The manufactured displacement, with its gradient.
  template <int dim>
  class ExactDisplacement : public Function<dim>
  {
  public:
    ExactDisplacement()
      : Function<dim>(dim)
    {
    }

    Tensor<1, dim>
    amplitude() const
    {
      const double   a[3] = {0.08, -0.06, 0.05};
      Tensor<1, dim> A;
      for (unsigned int c = 0; c < dim; ++c)
        A[c] = a[c] * L;
      return A;
    }

    double
    value(const Point<dim> &X, const unsigned int c) const override
    {
      return amplitude()[c] * std::sin(omega * this->get_time()) * phi(X);
    }

    Tensor<1, dim>
    gradient(const Point<dim> &X, const unsigned int c) const override
    {
      return amplitude()[c] * std::sin(omega * this->get_time()) * grad_phi(X);
    }

    static double
    phi(const Point<dim> &X)
    {
      double value = 1.;
      for (unsigned int i = 0; i < dim; ++i)
        value *= std::sin(M_PI * X[i] / L);
      return value;
    }

    static Tensor<1, dim>
    grad_phi(const Point<dim> &X)
    {
      Tensor<1, dim> gradient;
      for (unsigned int j = 0; j < dim; ++j)
        {
          gradient[j] = M_PI / L;
          for (unsigned int i = 0; i < dim; ++i)
            gradient[j] *=
              (i == j) ? std::cos(M_PI * X[i] / L) : std::sin(M_PI * X[i] / L);
        }
      return gradient;
    }
  };

  // The body force that makes it a solution.
  template <int dim>
  class ManufacturedBodyForce : public Function<dim>
  {
  public:
    ManufacturedBodyForce()
      : Function<dim>(dim)
      , material(mu, kappa)
    {
    }

    void
    vector_value(const Point<dim> &X, Vector<double> &values) const override
    {
      exact.set_time(this->get_time());
      const double   h = 1e-5 * L;
      Tensor<1, dim> divergence;
      for (unsigned int J = 0; J < dim; ++J)
        {
          Point<dim> plus = X, minus = X;
          plus[J] += h;
          minus[J] -= h;
          const Tensor<2, dim> P_plus  = stress(plus);
          const Tensor<2, dim> P_minus = stress(minus);
          for (unsigned int i = 0; i < dim; ++i)
            divergence[i] += (P_plus[i][J] - P_minus[i][J]) / (2. * h);
        }
      for (unsigned int c = 0; c < dim; ++c)
        values[c] = -rho * omega * omega * exact.value(X, c) - divergence[c];
    }

  private:
    Tensor<2, dim>
    stress(const Point<dim> &X) const
    {
      Tensor<2, dim> F;
      for (unsigned int c = 0; c < dim; ++c)
        {
          F[c] = exact.gradient(X, c);
          F[c][c] += 1.;
        }
      return material.first_piola_closed_form(F);
    }

    mutable ExactDisplacement<dim> exact;
    const NeoHookeanEnergy<dim>    material;
  };

  // The box of n cells per direction, clamped on all faces, degree p,
  // HHT-alpha with the given number of steps to the end time.
  template <int dim>
  std::unique_ptr<Simulation<dim>>
  run(const unsigned int degree,
      const unsigned int n_cells,
      const unsigned int n_steps,
      const double       alpha)
  {
    ExactDisplacement<dim> exact;
    std::ostringstream     sections, velocity, fixed;
    const Tensor<1, dim>   A = exact.amplitude();
    for (unsigned int c = 0; c < dim; ++c)
      {
        velocity << (c > 0 ? "; " : "") << std::setprecision(17)
                 << A[c] * omega;
        for (unsigned int i = 0; i < dim; ++i)
          velocity << "*sin(" << M_PI / L << "*"
                   << "xyz"[i] << ")";
      }
    for (unsigned int face = 0; face < 2 * dim; ++face)
      fixed << (face > 0 ? ", " : "") << face << ": "
            << std::string("xyz").substr(0, dim);
    const double section = (dim == 3) ? 1. : (dim == 2 ? 0.5 : 0.25);
    sections
      << "subsection Geometry\n  set Generator = subdivided_hyper_rectangle\n"
      << "  set Generator arguments = "
      << box_arguments(dim, n_cells, n_cells, L, L) << "\nend\n"
      << "subsection Finite element\n  set Polynomial degree = " << degree
      << "\nend\n"
      << "subsection Material 1\n  set Name = m\n  set Shear modulus = " << mu
      << "\n  set Bulk modulus = " << kappa << "\n  set Density = " << rho
      << "\n  set Section = " << section << "\nend\n"
      << "subsection Loads and constraints\n  set Gravity = 0, 0, 0\n"
      << "  set Fixed components = " << fixed.str() << "\nend\n"
      << "subsection Initial conditions\n  set Velocity = " << velocity.str()
      << "\nend\n"
      << "subsection Time integration\n  set Alpha = " << alpha
      << "\n  set Time step = " << std::setprecision(17) << end_time / n_steps
      << "\n  set Minimum time step = " << end_time / n_steps / 16.
      << "\n  set End time = " << end_time << "\nend\n"
      << "subsection Nonlinear solver\n  set Absolute tolerance = 0\n"
      << "  set Relative tolerance = 1e-11\nend\n"
      << "subsection Linear solver\n  set Solver = Direct\nend\n";
    Parameters::AllParameters parameters;
    parameters.read_string(parameter_text(dim, sections.str()));
    auto body = std::make_unique<Simulation<dim>>(parameters, MPI_COMM_WORLD);
    body->make_grid();
    body->setup_system();
    body->set_body_force(std::make_shared<ManufacturedBodyForce<dim>>());
    body->initialize_state();
    while (body->advance_one_step())
      ;
    EXPECT_NEAR(body->time(), end_time, 1e-9 * end_time);
    EXPECT_EQ(body->n_steps(), n_steps);
    return body;
  }

  // The L2 and H1-seminorm errors of the final displacement.
  template <int dim>
  std::pair<double, double>
  errors_against_exact(const Simulation<dim> &body, const unsigned int degree)
  {
    ExactDisplacement<dim> exact;
    exact.set_time(end_time);
    Vector<double> u(body.displacement());
    Vector<float>  cellwise(
      body.get_dof_handler().get_triangulation().n_active_cells());
    const QGauss<dim>         quadrature(degree + 3);
    std::pair<double, double> result;
    VectorTools::integrate_difference(body.get_mapping(),
                                      body.get_dof_handler(),
                                      u,
                                      exact,
                                      cellwise,
                                      quadrature,
                                      VectorTools::L2_norm);
    result.first = VectorTools::compute_global_error(
      body.get_dof_handler().get_triangulation(),
      cellwise,
      VectorTools::L2_norm);
    VectorTools::integrate_difference(body.get_mapping(),
                                      body.get_dof_handler(),
                                      u,
                                      exact,
                                      cellwise,
                                      quadrature,
                                      VectorTools::H1_seminorm);
    result.second = VectorTools::compute_global_error(
      body.get_dof_handler().get_triangulation(),
      cellwise,
      VectorTools::H1_seminorm);
    return result;
  }

  template <int dim>
  void
  check_spatial_rates(const unsigned int               degree,
                      const std::vector<unsigned int> &levels,
                      const unsigned int               n_steps)
  {
    std::vector<std::pair<double, double>> errors;
    for (const unsigned int n : levels)
      {
        const auto body = run<dim>(degree, n, n_steps, -0.1);
        errors.push_back(errors_against_exact(*body, degree));
        std::cout << dim << "D, p = " << degree << ", " << n
                  << " cells per direction: L2 error " << errors.back().first
                  << ", H1 error " << errors.back().second;
        if (errors.size() > 1)
          {
            const double ratio = double(n) / levels[errors.size() - 2];
            std::cout << "; rates "
                      << std::log(errors[errors.size() - 2].first /
                                  errors.back().first) /
                           std::log(ratio)
                      << ", "
                      << std::log(errors[errors.size() - 2].second /
                                  errors.back().second) /
                           std::log(ratio);
          }
        std::cout << std::endl;
      }
    const double ratio = double(levels.back()) / levels[levels.size() - 2];
    const double rate_L2 =
      std::log(errors[errors.size() - 2].first / errors.back().first) /
      std::log(ratio);
    const double rate_H1 =
      std::log(errors[errors.size() - 2].second / errors.back().second) /
      std::log(ratio);
    EXPECT_GT(rate_L2, degree + 1 - 0.25);
    EXPECT_GT(rate_H1, degree - 0.2);
  }
} // namespace



// @sect4{Spatial rates}
//
// The number of steps keeps the time error (relative $(\omega\Delta t)^2/12$
// or less) at least an order of magnitude below the finest spatial error.
TYPED_TEST(ManufacturedSolutionTest, SpatialRates)
{
  constexpr int dim = TypeParam::value;
  if constexpr (dim == 1)
    {
      check_spatial_rates<dim>(1, {8, 16, 32}, 200);
      check_spatial_rates<dim>(2, {4, 8, 16}, 400);
    }
  else if constexpr (dim == 2)
    {
      check_spatial_rates<dim>(1, {4, 8, 16}, 100);
      check_spatial_rates<dim>(2, {2, 4, 8}, 200);
    }
  else
    {
      check_spatial_rates<dim>(1, {2, 4, 8}, 25);
      check_spatial_rates<dim>(2, {2, 4}, 50);
    }
}



// @sect4{Temporal rate}
//
// On a fixed mesh of linear elements, the difference of the final
// displacement to that of a run with 512 steps, for 16, 32 and 64 steps to
// the end time ($\omega\Delta t$ = 0.1 to 0.025; with fewer steps the error
// is not yet in its asymptotic range). The reference's own error is 1/64 of
// the last difference.
TYPED_TEST(ManufacturedSolutionTest, TemporalRate)
{
  constexpr int                   dim     = TypeParam::value;
  const unsigned int              n_cells = (dim == 3) ? 3 : 6;
  const std::vector<unsigned int> steps   = {16, 32, 64};
  const auto          reference = run<dim>(1, n_cells, 8 * steps.back(), -0.1);
  std::vector<double> differences;
  for (const unsigned int n : steps)
    {
      const auto                    body = run<dim>(1, n_cells, n, -0.1);
      TrilinosWrappers::MPI::Vector difference(body->displacement());
      difference -= reference->displacement();
      differences.push_back(difference.l2_norm() /
                            reference->displacement().l2_norm());
      std::cout << dim << "D, " << n << " steps: relative difference "
                << differences.back();
      if (differences.size() > 1)
        std::cout << "; rate "
                  << std::log2(differences[differences.size() - 2] /
                               differences.back());
      std::cout << std::endl;
    }
  for (unsigned int k = 1; k < differences.size(); ++k)
    EXPECT_GT(std::log2(differences[k - 1] / differences[k]), 1.8);
}
