// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Tests of the linearisation and of the mean-dilatation formulation}
//
// The solver's internal force must be the gradient of its strain energy,
// and its tangent stiffness the derivative of the force, in every
// dimension and with both volumetric formulations; the mean-dilatation
// formulation must reduce to the displacement formulation where the
// volume ratio is constant in each cell (linear tetrahedra), reproduce a
// uniform stretch, and cure the volumetric locking of the displacement
// formulation in a nearly incompressible bending problem.

#include "solver_test_tools.h"

#include <cmath>
#include <core/soft_robot_dynamics.h>
#include <gtest/gtest.h>

using namespace dealii;
using namespace SoftRobot;
using namespace SoftRobot::Testing;

template <typename T>
class VolumetricFormulationTest : public ::testing::Test
{
};
TYPED_TEST_SUITE(VolumetricFormulationTest, Dimensions);

namespace
{
  // A box of 3 x 2 x 2 cells, clamped at x = 0, of one material; hexahedra
  // or tetrahedra of degree p, in the given volumetric formulation.
  std::string
  clamped_box(const unsigned int dim,
              const bool         simplices,
              const unsigned int degree,
              const std::string &formulation,
              const double       mu,
              const double       kappa,
              const unsigned int n_length = 3,
              const double       length   = 3.,
              const unsigned int n_width  = 2)
  {
    std::ostringstream sections;
    sections
      << "subsection Geometry\n  set Generator = subdivided_hyper_rectangle\n"
      << "  set Generator arguments = "
      << box_arguments(dim, n_length, n_width, length, 1.)
      << "\n  set Random distortion = 0.15\n"
      << "  set Convert to simplices = " << (simplices ? "true" : "false")
      << "\nend\n"
      << "subsection Finite element\n  set Polynomial degree = " << degree
      << "\n  set Volumetric formulation = " << formulation << "\nend\n"
      << "subsection Material 1\n  set Name = silicone\n"
      << "  set Shear modulus = " << mu << "\n  set Bulk modulus = " << kappa
      << "\n  set Density = 1e-6\nend\n"
      << "subsection Loads and constraints\n  set Fixed components = 0: "
      << std::string("xyz").substr(0, dim) << "\nend\n"
      << "subsection Linear solver\n  set Solver = Direct\nend\n";
    return parameter_text(dim, sections.str());
  }

  // Central differences of the energy along w against f . w, and of the
  // force along w against K w: the relative errors.
  template <int dim>
  std::pair<double, double>
  linearisation_errors(Simulation<dim>                     &body,
                       const TrilinosWrappers::MPI::Vector &u,
                       const TrilinosWrappers::MPI::Vector &w)
  {
    const double                  h = 1e-6;
    TrilinosWrappers::MPI::Vector force(u), force_plus(u), force_minus(u),
      u_plus(u), u_minus(u), K_w(u);
    u_plus.add(h, w);
    u_minus.add(-h, w);
    const double energy_plus  = body.internal_force(u_plus, force_plus);
    const double energy_minus = body.internal_force(u_minus, force_minus);
    body.internal_force(u, force);
    body.tangent_stiffness_matrix(u).vmult(K_w, w);

    const double directional = force * w;
    const double energy_error =
      std::abs((energy_plus - energy_minus) / (2. * h) - directional) /
      std::abs(directional);

    TrilinosWrappers::MPI::Vector difference(force_plus);
    difference -= force_minus;
    difference /= 2. * h;
    difference -= K_w;
    return {energy_error, difference.l2_norm() / K_w.l2_norm()};
  }

  template <int dim>
  void
  check_linearisation(const bool         simplices,
                      const unsigned int degree,
                      const std::string &formulation)
  {
    Simulation<dim> body(
      read(clamped_box(dim, simplices, degree, formulation, 10., 1000.)),
      MPI_COMM_WORLD);
    body.make_grid();
    body.setup_system();
    // Strains of about 10 %: large enough for every nonlinear term.
    const TrilinosWrappers::MPI::Vector u    = random_vector(body, 0.03, 1);
    const TrilinosWrappers::MPI::Vector w    = random_vector(body, 1., 2);
    const auto [energy_error, tangent_error] = linearisation_errors(body, u, w);
    std::cout << dim << "D, " << (simplices ? "simplices" : "hypercubes")
              << ", p = " << degree << ", " << formulation
              << ": force against energy differences " << energy_error
              << ", tangent against force differences " << tangent_error
              << std::endl;
    // Central differences with h = 1e-6 of functions of order one: the
    // truncation error is O(h^2) ~ 1e-12, the round-off O(1e-16/h) ~ 1e-10
    // relative to the force scale.
    EXPECT_LT(energy_error, 1e-7);
    EXPECT_LT(tangent_error, 1e-7);
  }
} // namespace



// @sect4{The force is the gradient of the energy, the tangent its Hessian}
TYPED_TEST(VolumetricFormulationTest, LinearisationIsConsistent)
{
  constexpr int dim = TypeParam::value;
  check_linearisation<dim>(false, 1, "displacement");
  check_linearisation<dim>(false, 2, "displacement");
  if constexpr (dim > 1)
    check_linearisation<dim>(true, 2, "displacement");
  if constexpr (dim == 3)
    {
      check_linearisation<dim>(false, 1, "mean dilatation");
      check_linearisation<dim>(false, 2, "mean dilatation");
      check_linearisation<dim>(true, 2, "mean dilatation");
      check_linearisation<dim>(false, 1, "linear dilatation");
      check_linearisation<dim>(false, 2, "linear dilatation");
      check_linearisation<dim>(true, 2, "linear dilatation");
    }
}



// @sect4{Mean dilatation only in 3D}
//
// The reduced models are incompressible by construction; asking for the
// mean-dilatation formulation there is an input error that names the entry.
TYPED_TEST(VolumetricFormulationTest, ReducedModelsRejectMeanDilatation)
{
  constexpr int dim = TypeParam::value;
  if constexpr (dim < 3)
    {
      try
        {
          read(clamped_box(dim, false, 1, "mean dilatation", 10., 1000.));
          ADD_FAILURE() << "mean dilatation accepted in " << dim << "D";
        }
      catch (dealii::ExceptionBase &error)
        {
          std::ostringstream message;
          error.print_info(message);
          EXPECT_NE(message.str().find(
                      "Finite element/Volumetric formulation must be "
                      "'displacement' in " +
                      std::to_string(dim) + "D"),
                    std::string::npos)
            << message.str();
        }
    }
  else
    EXPECT_NO_THROW(
      read(clamped_box(dim, false, 1, "mean dilatation", 10., 1000.)));
}



// @sect4{Linear tetrahedra: both formulations are the same}
//
// The volume ratio of a linear tetrahedron is constant, so its mean is the
// pointwise value and the two formulations must give the same energy and
// force up to round-off.
// 3D only: the mean-dilatation formulation exists in 3D only.
TEST(MeanDilatation, EqualsDisplacementFormulationOnLinearTetrahedra)
{
  std::vector<double>                        energies;
  std::vector<TrilinosWrappers::MPI::Vector> forces;
  for (const std::string formulation : {"displacement", "mean dilatation"})
    {
      Simulation<3> body(read(clamped_box(3, true, 1, formulation, 10., 1000.)),
                         MPI_COMM_WORLD);
      body.make_grid();
      body.setup_system();
      const TrilinosWrappers::MPI::Vector u = random_vector(body, 0.03, 1);
      forces.emplace_back(u);
      energies.push_back(body.internal_force(u, forces.back()));
    }
  TrilinosWrappers::MPI::Vector difference(forces[0]);
  difference -= forces[1];
  std::cout << "linear tetrahedra: energies " << energies[0] << ", "
            << energies[1] << "; force difference "
            << difference.l2_norm() / forces[0].l2_norm() << std::endl;
  EXPECT_NEAR(energies[1], energies[0], 1e-12 * energies[0]);
  EXPECT_LT(difference.l2_norm(), 1e-12 * forces[0].l2_norm());
}



// @sect4{Locking in bending and its cure}
//
// A clamped block of 4 x 1 x 1 (four cubes, or each cut into tetrahedra)
// of degree 2, bending in its lowest mode. Of the moduli only Young's
// modulus $E = 9\kappa\mu/(3\kappa + \mu)$ matters for a slender beam in
// bending, so raising $\kappa/\mu$ from $10^2$ to $10^4$ should raise the
// frequency by about $\sqrt{E(10^4)/E(10^2)} - 1 = 0.17\,\%$. The
// displacement formulation stiffens by 1.6 % on tetrahedra and 2 % on
// hexahedra (it locks: at $\kappa/\mu = 10^2$ it is already 10 % above
// the formulations that do not). The mean dilatation on tetrahedra and the
// linear dilatation on hexahedra must stay within 1 % of the beam ratio,
// closer than the displacement formulation, and agree with each other.
// (The linear dilatation on quadratic tetrahedra, with four quadrature
// points and four modes, is the displacement formulation.)
// 3D only: the projected-dilatation formulations exist in 3D only.
TEST(MeanDilatation, CuresLockingInBending)
{
  const double mu             = 10.;
  const auto   youngs_modulus = [mu](const double kappa) {
    return 9. * kappa * mu / (3. * kappa + mu);
  };
  const double beam_ratio =
    std::sqrt(youngs_modulus(1e4 * mu) / youngs_modulus(1e2 * mu));

  // (cell shape, formulation) -> stiffening, and the lowest frequency at
  // kappa = 100 mu
  std::map<std::pair<bool, std::string>, double> stiffening, lowest;
  for (const bool simplices : {true, false})
    for (const std::string formulation :
         {"displacement", "mean dilatation", "linear dilatation"})
      {
        std::vector<double> omega;
        for (const double ratio : {1e2, 1e4})
          {
            Simulation<3> body(
              read(clamped_box(
                3, simplices, 2, formulation, mu, ratio * mu, 4, 4., 1)),
              MPI_COMM_WORLD);
            body.make_grid();
            body.setup_system();
            omega.push_back(linearised_frequencies(body)[0]);
          }
        stiffening[{simplices, formulation}] = omega[1] / omega[0];
        lowest[{simplices, formulation}]     = omega[0];
        std::cout << (simplices ? "tetrahedra, " : "hexahedra, ") << formulation
                  << ": lowest frequency " << omega[0] << " and " << omega[1]
                  << " rad/s for kappa/mu = 1e2 and 1e4, ratio "
                  << omega[1] / omega[0] << " (beam theory " << beam_ratio
                  << ")" << std::endl;
      }
  for (const auto &[simplices, formulation] :
       {std::make_pair(true, std::string("mean dilatation")),
        std::make_pair(false, std::string("linear dilatation"))})
    {
      const double error =
        std::abs(stiffening[{simplices, formulation}] - beam_ratio);
      EXPECT_LT(error, 0.01) << formulation;
      EXPECT_LT(error,
                std::abs(stiffening[{simplices, "displacement"}] - beam_ratio))
        << formulation;
    }
  // The two formulations that do not lock agree on the frequency itself.
  const double hexahedra  = lowest[{false, "linear dilatation"}];
  const double tetrahedra = lowest[{true, "mean dilatation"}];
  EXPECT_LT(std::abs(hexahedra / tetrahedra - 1.), 0.01);
  // The hexahedra's mean dilatation is no cure: one cell across the beam
  // leaves a deformation mode that changes the volume pointwise but not on
  // average and that the isochoric energy hardly resists; it is the
  // lowest mode, far below the beam's bending, whatever kappa.
  const double spurious = lowest[{false, "mean dilatation"}];
  EXPECT_LT(spurious, 0.5 * hexahedra);
}
