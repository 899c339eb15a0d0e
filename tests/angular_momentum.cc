// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Test of the angular momentum}
//
// A square plate (2D) or a cube (3D) of side a in rigid rotation about its
// centre $\mathbf c$, $\mathbf v = \boldsymbol\omega\times(\mathbf X -
// \mathbf c)$: its angular momentum about the origin is that about the
// centre, $\mathbf L = \rho_0 t\,\omega\,a^4/6$ for the plate of thickness
// $t$ (about its normal) and $\mathbf L = \rho_0\,a^5/6\;\boldsymbol\omega$
// for the cube, whose inertia tensor about its centre is isotropic. The
// linear velocity field and the positions are in the finite element space
// and the mass matrix integrates their product exactly on affine cells, so
// the computed value must agree to round-off, with both degrees, on
// distorted tetrahedra and on undistorted hexahedra. (On distorted
// hexahedra the Jacobian of the trilinear map varies and the mass
// quadrature is no longer exact: the error there is about 1e-5.) The test is
// typed on 2D and 3D only: the 1D column cannot rotate, and its angular
// momentum is zero by construction, so a 1D case would compare 0 with 0.

#include "solver_test_tools.h"

#include <core/soft_robot_dynamics.h>
#include <gtest/gtest.h>

using namespace dealii;
using namespace SoftRobot;
using namespace SoftRobot::Testing;

template <typename T>
class AngularMomentumTest : public ::testing::Test
{
};
TYPED_TEST_SUITE(AngularMomentumTest, Dimensions2And3);

TYPED_TEST(AngularMomentumTest, RigidRotationOfABox)
{
  constexpr int dim = TypeParam::value;
  const double  a = 2., rho = 1e-6, thickness = 0.5;
  const double  omega[3] = {30., -20., 50.};
  // v = omega x (X - c), c = (1, 1, 1); in 2D only omega_z.
  const std::string velocity =
    dim == 3 ? "-20*(z-1) - 50*(y-1); 50*(x-1) - 30*(z-1); 30*(y-1) + 20*(x-1)"
             : "-50*(y-1); 50*(x-1)";
  for (const bool simplices : {false, true})
    for (const unsigned int degree : {1u, 2u})
      {
        std::ostringstream sections;
        sections
          << "subsection Geometry\n  set Generator = subdivided_hyper_rectangle\n"
          << "  set Generator arguments = " << box_arguments(dim, 3, 3, a, a)
          << "\n  set Random distortion = " << (simplices ? 0.2 : 0.) << "\n"
          << "  set Convert to simplices = " << (simplices ? "true" : "false")
          << "\nend\n"
          << "subsection Finite element\n  set Polynomial degree = " << degree
          << "\nend\n"
          << "subsection Material 1\n  set Name = m\n  set Density = " << rho
          << "\n  set Section = " << (dim == 3 ? 1. : thickness) << "\nend\n"
          << "subsection Initial conditions\n  set Velocity = " << velocity
          << "\nend\n"
          << "subsection Linear solver\n  set Solver = Direct\nend\n";
        Parameters::AllParameters parameters;
        parameters.read_string(parameter_text(dim, sections.str()));
        Simulation<dim> body(parameters, MPI_COMM_WORLD);
        body.make_grid();
        body.setup_system();
        body.initialize_state();
        const Tensor<1, 3> L = body.angular_momentum();

        Tensor<1, 3> exact;
        if (dim == 3)
          for (unsigned int d = 0; d < 3; ++d)
            exact[d] = rho * std::pow(a, 5) / 6. * omega[d];
        else
          exact[2] = rho * thickness * std::pow(a, 4) / 6. * omega[2];
        std::cout << dim << "D, " << (simplices ? "simplices" : "hypercubes")
                  << ", p = " << degree << ": L = " << L << ", exact " << exact
                  << std::endl;
        EXPECT_GT(exact.norm(), 0.);
        EXPECT_LE((L - exact).norm(), 1e-12 * exact.norm());
      }
}
