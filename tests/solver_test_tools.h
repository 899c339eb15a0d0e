// SPDX-License-Identifier: LGPL-2.1-or-later

// Tools shared by the solver tests: parameter texts for small bodies, and
// the dense linearised eigenproblem of a model.

#ifndef soft_robot_tests_solver_test_tools_h
#define soft_robot_tests_solver_test_tools_h

#include <core/simulator_access.h>
#include <core/soft_robot_dynamics.h>
#include <deal.II/lac/lapack_full_matrix.h>
#include <gtest/gtest.h>
#include <random>
#include <sstream>
#include <string>

namespace SoftRobot::Testing
{
  // A simulator together with its accessor: what the tests construct where
  // a user would construct SoftRobotDynamics<dim>. The simulator is a base
  // class so that it exists before the accessor that refers to it.
  template <int dim>
  struct SimulatorHolder
  {
    SimulatorHolder(const Parameters::AllParameters &parameters,
                    const MPI_Comm                   mpi_communicator)
      : owned_simulator(parameters, mpi_communicator)
    {
    }
    SoftRobotDynamics<dim> owned_simulator;
  };

  template <int dim>
  class Simulation : private SimulatorHolder<dim>, public SimulatorAccess<dim>
  {
  public:
    Simulation(const Parameters::AllParameters &parameters,
               const MPI_Comm                   mpi_communicator)
      : SimulatorHolder<dim>(parameters, mpi_communicator)
      , SimulatorAccess<dim>(this->owned_simulator)
    {
    }

    void
    run()
    {
      this->owned_simulator.run();
    }
  };

  // The dimensions the typed tests run in.
  using Dimensions = ::testing::Types<std::integral_constant<int, 1>,
                                      std::integral_constant<int, 2>,
                                      std::integral_constant<int, 3>>;

  // The dimensions in which a body has directions across its axis, and
  // rotates: for the physics that the 1D column does not have (lateral
  // inertia, angular momentum).
  using Dimensions2And3 = ::testing::Types<std::integral_constant<int, 2>,
                                           std::integral_constant<int, 3>>;

  // The parameters that a parameter text gives.
  inline Parameters::AllParameters
  read(const std::string &text)
  {
    Parameters::AllParameters parameters;
    parameters.read_string(text);
    return parameters;
  }

  // Random nodal values of amplitude `amplitude` (fixed seed), zero at the
  // constrained dofs; for runs on one process.
  template <int dim>
  TrilinosWrappers::MPI::Vector
  random_vector(const SimulatorAccess<dim> &body,
                const double                amplitude,
                const unsigned int          seed)
  {
    TrilinosWrappers::MPI::Vector    u(body.displacement());
    std::mt19937                     generator(seed);
    std::uniform_real_distribution<> uniform(-amplitude, amplitude);
    for (types::global_dof_index i = 0; i < u.size(); ++i)
      u[i] = body.get_constraints().is_constrained(i) ? 0. : uniform(generator);
    u.compress(VectorOperation::insert);
    return u;
  }

  // The parameter text of a small body: everything the tests do not set
  // explicitly has the program's default. `sections` is appended verbatim.
  inline std::string
  parameter_text(const unsigned int dim, const std::string &sections)
  {
    std::ostringstream text;
    text
      << "subsection Problem\n  set Dimension = " << dim
      << "\n  set Output directory = test_output\nend\n"
      << "subsection Output\n  set Write VTU = false\n  set Tip region = boundary 1\n"
      << "  set Progress interval = 0\nend\n"
      << sections;
    return text.str();
  }

  // "n, 1, 1: 0, 0, 0: L, a, a: true" for dim = 3 and its lower-dimensional
  // counterparts: a box of n x m x m cells, colourised so that the faces
  // x = 0, x = L, y = 0, y = a, z = 0, z = a get the ids 0 to 5.
  inline std::string
  box_arguments(const unsigned int dim,
                const unsigned int n_length,
                const unsigned int n_width,
                const double       length,
                const double       width)
  {
    std::ostringstream text;
    const auto         list = [&](const auto first, const auto rest) {
      std::ostringstream out;
      out << first;
      for (unsigned int d = 1; d < dim; ++d)
        out << ", " << rest;
      return out.str();
    };
    text << list(n_length, n_width) << ": " << list(0., 0.) << ": "
         << list(length, width) << ": true";
    return text.str();
  }

  // The eigenfrequencies (rad/s) of the model linearised at its current
  // state, $\mathbf K\boldsymbol\phi = \omega^2\mathbf M\boldsymbol\phi$,
  // with the constrained degrees of freedom removed; ascending.
  template <int dim>
  std::vector<double>
  linearised_frequencies(SimulatorAccess<dim> &model)
  {
    const auto &stiffness   = model.tangent_stiffness_matrix();
    const auto &mass        = model.mass_matrix();
    const auto &constraints = model.get_constraints();
    std::vector<types::global_dof_index> free_dofs;
    for (types::global_dof_index i = 0; i < model.get_dof_handler().n_dofs();
         ++i)
      if (!constraints.is_constrained(i))
        free_dofs.push_back(i);
    const unsigned int       n = free_dofs.size();
    LAPACKFullMatrix<double> K(n, n), M(n, n);
    for (unsigned int i = 0; i < n; ++i)
      for (unsigned int j = 0; j < n; ++j)
        {
          K(i, j) = stiffness.el(free_dofs[i], free_dofs[j]);
          M(i, j) = mass.el(free_dofs[i], free_dofs[j]);
        }
    std::vector<Vector<double>> eigenvectors(n, Vector<double>(n));
    K.compute_generalized_eigenvalues_symmetric(M, eigenvectors);
    std::vector<double> omega(n);
    for (unsigned int i = 0; i < n; ++i)
      omega[i] = std::sqrt(std::real(K.eigenvalue(i)));
    std::sort(omega.begin(), omega.end());
    return omega;
  }

  // The smallest root beta of beta tan(beta) = ratio in (0, pi/2), by
  // bisection: the first axial mode of a rod with a tip mass, where ratio
  // is the rod's mass over the tip mass and beta = omega L / c.
  inline double
  rod_tip_mass_root(const double ratio)
  {
    double low = 0., high = 0.5 * M_PI - 1e-15;
    for (unsigned int i = 0; i < 200; ++i)
      {
        const double mid                           = 0.5 * (low + high);
        (mid * std::tan(mid) < ratio ? low : high) = mid;
      }
    return 0.5 * (low + high);
  }
  // A bar of length L and width 2 in 6 quadratic cells, of one
  // neo-Hookean material (kappa = 20 mu) with the damping coefficient
  // zeta, clamped at x = 0: the Geometry, Finite element and Material 1
  // subsections and the first entry of Loads and constraints, which the
  // caller continues and closes.
  inline std::string
  clamped_bar_sections(const unsigned int dim,
                       const double       mu,
                       const double       rho,
                       const double       L,
                       const double       zeta)
  {
    std::ostringstream text;
    text << "subsection Geometry\n"
            "  set Generator = subdivided_hyper_rectangle\n"
            "  set Generator arguments = "
         << box_arguments(dim, 6, 1, L, 2.) << "\nend\n"
         << "subsection Finite element\n  set Polynomial degree = 2\nend\n"
         << "subsection Material 1\n  set Name = bar\n"
         << "  set Shear modulus = " << mu
         << "\n  set Bulk modulus = " << 20. * mu << "\n  set Density = " << rho
         << "\n  set Damping coefficient = " << zeta << "\nend\n"
         << "subsection Loads and constraints\n"
            "  set Fixed components = 0: "
         << std::string("xyz").substr(0, dim) << "\n";
    return text.str();
  }
} // namespace SoftRobot::Testing

#endif
