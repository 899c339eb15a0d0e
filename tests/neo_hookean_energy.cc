// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Tests of the neo-Hookean strain energy and its derivatives}
//
// NeoHookeanEnergy<dim>::evaluate() returns the energy density $\Psi$, the
// second Piola-Kirchhoff stress $\mathbf S = 2\partial\Psi/\partial\mathbf C$
// and the tangent $\mathcal C = 4\partial^2\Psi/\partial\mathbf C^2$, both by
// automatic differentiation (AD). The tests compare them with what is known
// independently: the closed-form first Piola-Kirchhoff stress, finite
// differences, the energy written out by hand, Hooke's law at $\mathbf F =
// \mathbf I$, and objectivity. Each test runs for dim = 1, 2, 3, which are
// three different models (the uniaxial bar, the incompressible sheet in
// plane stress, the compressible solid).
//
// The deformation gradients are $\mathbf F = \mathbf I + 0.3\,\mathbf R$
// with the entries of $\mathbf R$ uniform in $[-1, 1]$ (fixed seed),
// rejected if $\det\mathbf F < 0.2$: stretches between about 0.5 and 1.6,
// volume changes up to a factor five, well into the nonlinear range. The
// material constants are those of a soft silicone, in kPa: $\mu = 116$, and
// in 3D $\kappa = 11600 = 100\mu$, nearly incompressible.
//
// In all relative comparisons the error is the Frobenius norm of the
// difference divided by the Frobenius norm of the reference value.

#include <algorithm>
#include <cmath>
#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>
#include <deal.II/physics/transformations.h>
#include <gtest/gtest.h>
#include <iostream>
#include <material/neo_hookean_energy.h>
#include <random>
#include <type_traits>
#include <vector>

namespace
{
  using namespace dealii;
  using SoftRobot::MaterialResponse;
  using SoftRobot::NeoHookeanEnergy;

  constexpr double shear_modulus = 116.;   // kPa
  constexpr double bulk_modulus  = 11600.; // kPa

  constexpr unsigned int n_samples = 20;



  // @sect4{Random deformation gradients}
  template <int dim>
  std::vector<Tensor<2, dim>>
  random_deformation_gradients(const unsigned int n, const unsigned int seed)
  {
    std::mt19937                           generator(seed);
    std::uniform_real_distribution<double> uniform(-1., 1.);
    std::vector<Tensor<2, dim>>            gradients;
    while (gradients.size() < n)
      {
        Tensor<2, dim> F = unit_symmetric_tensor<dim>();
        for (unsigned int i = 0; i < dim; ++i)
          for (unsigned int j = 0; j < dim; ++j)
            F[i][j] += 0.3 * uniform(generator);
        if (determinant(F) >= 0.2)
          gradients.push_back(F);
      }
    return gradients;
  }



  // A random rotation: the angle is uniform in $[0, 2\pi)$; in 3D the axis is
  // a normalised vector of uniform components.
  template <int dim>
  Tensor<2, dim>
  random_rotation(std::mt19937 &generator)
  {
    std::uniform_real_distribution<double> uniform(-1., 1.);
    const double angle = numbers::PI * (1. + uniform(generator));
    if constexpr (dim == 2)
      return Physics::Transformations::Rotations::rotation_matrix_2d(angle);
    else if constexpr (dim == 3)
      {
        Tensor<1, 3> axis;
        for (unsigned int d = 0; d < 3; ++d)
          axis[d] = uniform(generator);
        return Physics::Transformations::Rotations::rotation_matrix_3d(
          axis / axis.norm(), angle);
      }
    else
      {
        (void)angle;
        return unit_symmetric_tensor<dim>();
      }
  }



  // evaluate() takes the displacement gradient $\mathbf H = \mathbf F -
  // \mathbf I$ (which keeps small strains exact).
  template <int dim>
  Tensor<2, dim>
  displacement_gradient(const Tensor<2, dim> &F)
  {
    return F - Tensor<2, dim>(unit_symmetric_tensor<dim>());
  }



  // The first Piola-Kirchhoff stress $\mathbf P = \mathbf F\mathbf S$ from
  // the automatic derivatives.
  template <int dim>
  Tensor<2, dim>
  first_piola_from_ad(const NeoHookeanEnergy<dim> &material,
                      const Tensor<2, dim>        &F)
  {
    MaterialResponse<dim> response;
    material.evaluate(displacement_gradient<dim>(F), response);
    return F * Tensor<2, dim>(response.second_piola);
  }



  template <int dim>
  double
  energy_from_ad(const NeoHookeanEnergy<dim> &material, const Tensor<2, dim> &F)
  {
    MaterialResponse<dim> response;
    material.evaluate(displacement_gradient<dim>(F), response);
    return response.energy;
  }



  // @sect4{The energies written out in terms of $\mathbf F$}
  //
  // With $J = \det\mathbf F$ and $I_1 = \mathbf F:\mathbf F$:
  // @f{align*}{
  //   \Psi_{3D} &= \frac{\mu}{2}\left(J^{-2/3}I_1 - 3\right)
  //              + \frac{\kappa}{4}\left(J^2 - 1 - 2\ln J\right),
  //   \\ \Psi_{2D} &= \frac{\mu}{2}\left(I_1 + J^{-2} - 3\right),
  //   \\ \Psi_{1D} &= \frac{\mu}{2}\left(\lambda^2 + 2\lambda^{-1}
  //                   - 3\right),\quad \lambda = F_{11}.
  // @f}
  template <int dim>
  double
  closed_form_energy(const Tensor<2, dim> &F)
  {
    const double mu = shear_modulus, kappa = bulk_modulus;
    const double J  = determinant(F);
    const double I1 = scalar_product(F, F);
    if constexpr (dim == 3)
      return 0.5 * mu * (std::pow(J, -2. / 3.) * I1 - 3.) +
             0.25 * kappa * (J * J - 1. - 2. * std::log(J));
    else if constexpr (dim == 2)
      return 0.5 * mu * (I1 + 1. / (J * J) - 3.);
    else
      return 0.5 * mu * (F[0][0] * F[0][0] + 2. / F[0][0] - 3.);
  }



  template <int dim>
  double
  relative_error(const Tensor<2, dim> &value, const Tensor<2, dim> &reference)
  {
    return (value - reference).norm() / reference.norm();
  }

  template <int dim>
  double
  relative_error(const Tensor<4, dim> &value, const Tensor<4, dim> &reference)
  {
    return (value - reference).norm() / reference.norm();
  }



  // The test fixture only carries the dimension.
  template <typename Dimension>
  class NeoHookeanEnergyTest : public ::testing::Test
  {
  };

  using Dimensions = ::testing::Types<std::integral_constant<int, 1>,
                                      std::integral_constant<int, 2>,
                                      std::integral_constant<int, 3>>;
} // namespace

TYPED_TEST_SUITE(NeoHookeanEnergyTest, Dimensions);



// @sect3{The tests}

// @sect4{The AD stress equals the closed form}
//
// $\mathbf F\mathbf S$ with $\mathbf S$ from AD must equal
// NeoHookeanEnergy::first_piola_closed_form(). AD derivatives are exact up to
// round-off, and both evaluations take a few dozen operations on numbers of
// order one; the worst amplification is the cancellation in the volumetric
// stress $\kappa(J^2-1)/2$, i.e. $\kappa\epsilon/|\mathbf P| \le
// 10^2\epsilon$ relative. The tolerance $10^{-12}$ is about $50$ times that.
// This also checks the factor two of the off-diagonal entries of $\mathbf S$
// when differentiating with respect to a symmetric tensor.
TYPED_TEST(NeoHookeanEnergyTest, StressEqualsClosedForm)
{
  constexpr int               dim = TypeParam::value;
  const NeoHookeanEnergy<dim> material(shear_modulus, bulk_modulus);

  double worst_error = 0.;
  for (const Tensor<2, dim> &F :
       random_deformation_gradients<dim>(n_samples, 1))
    {
      const double error = relative_error(first_piola_from_ad(material, F),
                                          material.first_piola_closed_form(F));
      EXPECT_LE(error, 1e-12) << "F = " << F;
      worst_error = std::max(worst_error, error);
    }
  std::cout << "  dim = " << dim << ": worst relative error of P "
            << worst_error << std::endl;
}



// @sect4{The fixed-size AD agrees with deal.II's AD helper}
//
// evaluate() seeds Sacado's fixed-size numbers itself and undoes the
// factors of the symmetric storage by hand; evaluate_with_ad_helper()
// leaves both to deal.II's Differentiation::AD::ScalarFunction with
// dynamically sized numbers, and evaluate_stress() takes first derivatives
// only. The same operations in the same order give the same numbers up to
// a few units of round-off, so all components must agree to $10^{-13}$
// relative to the largest one; a wrong factor of two in an off-diagonal
// entry or a transposed index would be off by order one.
TYPED_TEST(NeoHookeanEnergyTest, FixedSizeADEqualsADHelper)
{
  constexpr int               dim = TypeParam::value;
  const NeoHookeanEnergy<dim> material(shear_modulus, bulk_modulus);

  double worst_error = 0.;
  for (const Tensor<2, dim> &F :
       random_deformation_gradients<dim>(n_samples, 7))
    {
      MaterialResponse<dim> fast, helper, stress_only;
      material.evaluate(displacement_gradient<dim>(F), fast);
      material.evaluate_with_ad_helper(displacement_gradient<dim>(F), helper);
      material.evaluate_stress(displacement_gradient<dim>(F), stress_only);

      const double energy_error =
        std::abs(fast.energy - helper.energy) / std::abs(helper.energy);
      const double stress_error =
        (fast.second_piola - helper.second_piola).norm() /
        helper.second_piola.norm();
      const double stress_only_error =
        (stress_only.second_piola - helper.second_piola).norm() /
        helper.second_piola.norm();
      const double tangent_error =
        (fast.material_tangent - helper.material_tangent).norm() /
        helper.material_tangent.norm();
      EXPECT_LE(energy_error, 1e-13) << "F = " << F;
      EXPECT_LE(stress_error, 1e-13) << "F = " << F;
      EXPECT_LE(stress_only_error, 1e-13) << "F = " << F;
      EXPECT_LE(tangent_error, 1e-13) << "F = " << F;
      EXPECT_NEAR(stress_only.energy,
                  fast.energy,
                  1e-13 * std::abs(fast.energy));
      worst_error =
        std::max({worst_error, energy_error, stress_error, tangent_error});
    }
  std::cout << "  dim = " << dim
            << ": worst relative difference from the AD helper " << worst_error
            << std::endl;
}



// @sect4{The AD tangent is the derivative of the stress}
//
// SoftRobot::first_piola_tangent() of the AD $\mathbf S$ and $\mathcal C$
// must equal the central difference quotient
// @f[
//   \frac{\partial P_{iJ}}{\partial F_{kL}} \approx
//   \frac{P_{iJ}(\mathbf F + h\,\mathbf e_k\otimes\mathbf e_L)
//        - P_{iJ}(\mathbf F - h\,\mathbf e_k\otimes\mathbf e_L)}{2h}
// @f]
// of the closed-form stress. The truncation error is $h^2|\mathbf
// P'''|/6$, the round-off $\epsilon|\mathbf P|/h$; relative to $|\mathbf
// P'|$, and with the derivatives of $\mathbf P$ growing by at most a factor
// $1/\sigma_\text{min}(\mathbf F)\lesssim 5$ per order, the sum is minimal
// near $h\approx\epsilon^{1/3}\approx 6\cdot 10^{-6}$; we take $h = 10^{-5}$
// ($|\mathbf F|\approx 1$). The total error is then of order
// $25 h^2 + \epsilon/h\approx 3\cdot 10^{-9}$; the tolerance
// $10^{-6}$ leaves ample room for the constants.
TYPED_TEST(NeoHookeanEnergyTest, TangentEqualsFiniteDifference)
{
  constexpr int               dim = TypeParam::value;
  const NeoHookeanEnergy<dim> material(shear_modulus, bulk_modulus);
  const double                h = 1e-5;

  double worst_error = 0.;
  for (const Tensor<2, dim> &F :
       random_deformation_gradients<dim>(n_samples, 2))
    {
      MaterialResponse<dim> response;
      material.evaluate(displacement_gradient<dim>(F), response);
      const Tensor<4, dim> ad_tangent =
        SoftRobot::first_piola_tangent(F,
                                       response.second_piola,
                                       response.material_tangent);

      Tensor<4, dim> fd_tangent;
      for (unsigned int k = 0; k < dim; ++k)
        for (unsigned int L = 0; L < dim; ++L)
          {
            Tensor<2, dim> F_plus = F, F_minus = F;
            F_plus[k][L] += h;
            F_minus[k][L] -= h;
            const Tensor<2, dim> dP =
              (material.first_piola_closed_form(F_plus) -
               material.first_piola_closed_form(F_minus)) /
              (2. * h);
            for (unsigned int i = 0; i < dim; ++i)
              for (unsigned int J = 0; J < dim; ++J)
                fd_tangent[i][J][k][L] = dP[i][J];
          }

      const double error = relative_error(ad_tangent, fd_tangent);
      EXPECT_LE(error, 1e-6) << "F = " << F;
      worst_error = std::max(worst_error, error);
    }
  std::cout << "  dim = " << dim << ": worst relative error of dP/dF "
            << worst_error << std::endl;
}



// @sect4{The reference configuration: no stress, Hooke's law}
//
// At $\mathbf F = \mathbf I$ energy and stress vanish; they are sums of
// terms of size $\mu$ and $\kappa = 100\mu$ that cancel, so we require
// $10^{-12}\mu$ absolute ($\approx 50\,\kappa\epsilon$).
//
// The tangent must be the small-strain elasticity tensor of each model,
// $\mathcal C = \lambda_\text{L}\,\mathbf I\otimes\mathbf I + 2\mu\,
// \mathcal I^\text{sym}$ with the model's Lamé constant:
// - 3D: $\lambda_\text{L} = \kappa - 2\mu/3$.
// - 2D, plane stress of an incompressible solid: $S = \mu(\mathbf I -
//   (\det\mathbf C)^{-1}\mathbf C^{-1})$ and $\mathcal C = 2\mu(\det
//   \mathbf C)^{-1}(\mathbf C^{-1}\otimes\mathbf C^{-1} + \mathcal
//   I_{\mathbf C^{-1}})$, at $\mathbf C = \mathbf I$: $\lambda_\text{L} =
//   2\mu$. This is the plane-stress Hooke tensor $\frac{E}{1-\nu^2}\left(
//   \nu\,\mathbf I\otimes\mathbf I + (1-\nu)\,\mathcal I^\text{sym}\right)$
//   with $E = 3\mu$, $\nu = 1/2$; equivalently, $2\lambda\mu/(\lambda+2\mu)
//   \to 2\mu$ for $\lambda\to\infty$.
// - 1D: $S = 2\,d\Psi/dC = \mu(1 - C^{-3/2})$, $\mathcal C = 2\,dS/dC = 3\mu
//   C^{-5/2} = 3\mu = E$ at $C = 1$ (here $\mathbf I\otimes\mathbf I =
//   \mathcal I^\text{sym} = 1$, and we compare with $3\mu$ directly).
// Since $\mathbf S = \mathbf 0$ there, first_piola_tangent() must return the
// same tensor. AD is exact, so the relative tolerance is $10^{-12}$.
TYPED_TEST(NeoHookeanEnergyTest, LinearisationAtIdentity)
{
  constexpr int               dim = TypeParam::value;
  const NeoHookeanEnergy<dim> material(shear_modulus, bulk_modulus);
  const double                mu = shear_modulus, kappa = bulk_modulus;

  const Tensor<2, dim>  identity = unit_symmetric_tensor<dim>();
  MaterialResponse<dim> response;
  material.evaluate(displacement_gradient<dim>(identity), response);

  EXPECT_LE(std::abs(response.energy), 1e-12 * mu);
  EXPECT_LE(response.second_piola.norm(), 1e-12 * mu);
  EXPECT_LE(material.first_piola_closed_form(identity).norm(), 1e-12 * mu);

  SymmetricTensor<4, dim> hooke;
  if constexpr (dim == 3)
    hooke = (kappa - 2. / 3. * mu) * outer_product(unit_symmetric_tensor<3>(),
                                                   unit_symmetric_tensor<3>()) +
            2. * mu * identity_tensor<3>();
  else if constexpr (dim == 2)
    hooke =
      2. * mu *
        outer_product(unit_symmetric_tensor<2>(), unit_symmetric_tensor<2>()) +
      2. * mu * identity_tensor<2>();
  else
    hooke[0][0][0][0] = 3. * mu;

  const double tangent_error =
    (response.material_tangent - hooke).norm() / hooke.norm();
  EXPECT_LE(tangent_error, 1e-12);

  const double piola_tangent_error =
    relative_error(SoftRobot::first_piola_tangent(identity,
                                                  response.second_piola,
                                                  response.material_tangent),
                   Tensor<4, dim>(hooke));
  EXPECT_LE(piola_tangent_error, 1e-12);

  std::cout << "  dim = " << dim << ": at F = I |Psi|/mu "
            << std::abs(response.energy) / mu << ", |S|/mu "
            << response.second_piola.norm() / mu << ", |P|/mu "
            << material.first_piola_closed_form(identity).norm() / mu
            << ", relative error of CC " << tangent_error << ", of dP/dF "
            << piola_tangent_error << std::endl;
}



// @sect4{Objectivity}
//
// A superposed rotation $\mathbf Q$ must leave the energy unchanged and
// rotate the first Piola-Kirchhoff stress and the first index pair of its
// tangent: $\mathbf P(\mathbf Q\mathbf F) = \mathbf Q\mathbf P(\mathbf F)$,
// $\mathcal A_{iJkL}(\mathbf Q\mathbf F) = Q_{ia}Q_{kb}\mathcal
// A_{aJbL}(\mathbf F)$. The energy depends on $\mathbf C = \mathbf
// F^T\mathbf F$, which $\mathbf Q$ changes only by round-off, so the
// tolerance is the same $10^{-12}$ as above. In 1D the only rotation is
// the identity, and the test is skipped.
TYPED_TEST(NeoHookeanEnergyTest, Objectivity)
{
  constexpr int dim = TypeParam::value;
  if constexpr (dim == 1)
    GTEST_SKIP() << "no rotations other than the identity in 1D";
  else
    {
      const NeoHookeanEnergy<dim> material(shear_modulus, bulk_modulus);
      std::mt19937                generator(3);

      double worst_energy_error = 0., worst_stress_error = 0.,
             worst_tangent_error = 0.;
      for (const Tensor<2, dim> &F :
           random_deformation_gradients<dim>(n_samples, 4))
        {
          const Tensor<2, dim> Q = random_rotation<dim>(generator);

          MaterialResponse<dim> response, rotated_response;
          material.evaluate(displacement_gradient<dim>(F), response);
          material.evaluate(displacement_gradient<dim>(Q * F),
                            rotated_response);

          const double energy_error =
            std::abs(rotated_response.energy - response.energy) /
            std::abs(response.energy);
          const double stress_error =
            relative_error(first_piola_from_ad(material, Tensor<2, dim>(Q * F)),
                           Q * first_piola_from_ad(material, F));

          const Tensor<4, dim> A =
            SoftRobot::first_piola_tangent(F,
                                           response.second_piola,
                                           response.material_tangent);
          const Tensor<4, dim> rotated_A =
            SoftRobot::first_piola_tangent(Q * F,
                                           rotated_response.second_piola,
                                           rotated_response.material_tangent);
          Tensor<4, dim> expected_rotated_A;
          for (unsigned int i = 0; i < dim; ++i)
            for (unsigned int J = 0; J < dim; ++J)
              for (unsigned int k = 0; k < dim; ++k)
                for (unsigned int L = 0; L < dim; ++L)
                  for (unsigned int a = 0; a < dim; ++a)
                    for (unsigned int b = 0; b < dim; ++b)
                      expected_rotated_A[i][J][k][L] +=
                        Q[i][a] * Q[k][b] * A[a][J][b][L];
          const double tangent_error =
            relative_error(rotated_A, expected_rotated_A);

          EXPECT_LE(energy_error, 1e-12) << "F = " << F << ", Q = " << Q;
          EXPECT_LE(stress_error, 1e-12) << "F = " << F << ", Q = " << Q;
          EXPECT_LE(tangent_error, 1e-12) << "F = " << F << ", Q = " << Q;
          worst_energy_error  = std::max(worst_energy_error, energy_error);
          worst_stress_error  = std::max(worst_stress_error, stress_error);
          worst_tangent_error = std::max(worst_tangent_error, tangent_error);
        }
      std::cout << "  dim = " << dim
                << ": worst relative errors under rotation: energy "
                << worst_energy_error << ", P " << worst_stress_error
                << ", dP/dF " << worst_tangent_error << std::endl;
    }
}



// @sect4{The AD energy equals the formula}
//
// The energy returned by evaluate() (a function of $\mathbf E$) must equal
// closed_form_energy() (the same function written in terms of $\mathbf F$).
// Both terms of each energy are non-negative, so there is no cancellation
// between them; within each, the cancellation in e.g. $J^{-2/3}I_1 - 3$
// loses at most a factor $3/(J^{-2/3}I_1-3)\approx 10^2$ for the
// deformations used. The tolerance $10^{-12}$ relative is again about
// $50$ times that.
TYPED_TEST(NeoHookeanEnergyTest, EnergyEqualsClosedForm)
{
  constexpr int               dim = TypeParam::value;
  const NeoHookeanEnergy<dim> material(shear_modulus, bulk_modulus);

  double worst_error = 0.;
  for (const Tensor<2, dim> &F :
       random_deformation_gradients<dim>(n_samples, 5))
    {
      const double reference = closed_form_energy(F);
      const double error =
        std::abs(energy_from_ad(material, F) - reference) / reference;
      EXPECT_LE(error, 1e-12) << "F = " << F;
      worst_error = std::max(worst_error, error);
    }
  std::cout << "  dim = " << dim << ": worst relative error of Psi "
            << worst_error << std::endl;
}



// @sect4{The stress derives from the energy}
//
// The energy is the potential of the AD stress: for a random direction
// $\delta\mathbf F$ (entries uniform in $[-1,1]$),
// @f[
//   \frac{\Psi(\mathbf F + h\,\delta\mathbf F)
//         - \Psi(\mathbf F - h\,\delta\mathbf F)}{2h}
//   = \mathbf P(\mathbf F) : \delta\mathbf F + O(h^2).
// @f]
// The same balance of truncation and round-off as for the tangent gives
// $h = 10^{-5}$ and an error of order $10^{-9}$ relative to $|\mathbf
// P||\delta\mathbf F|$ (which we use as the scale, since $\mathbf P :
// \delta\mathbf F$ itself may be small); the tolerance is $10^{-6}$.
TYPED_TEST(NeoHookeanEnergyTest, StressIsDerivativeOfEnergy)
{
  constexpr int               dim = TypeParam::value;
  const NeoHookeanEnergy<dim> material(shear_modulus, bulk_modulus);
  const double                h = 1e-5;

  std::mt19937                           generator(6);
  std::uniform_real_distribution<double> uniform(-1., 1.);

  double worst_error = 0.;
  for (const Tensor<2, dim> &F :
       random_deformation_gradients<dim>(n_samples, 7))
    {
      Tensor<2, dim> dF;
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = 0; j < dim; ++j)
          dF[i][j] = uniform(generator);

      const double difference_quotient =
        (energy_from_ad(material, F + h * dF) -
         energy_from_ad(material, F - h * dF)) /
        (2. * h);
      const Tensor<2, dim> P = first_piola_from_ad(material, F);

      const double error =
        std::abs(difference_quotient - scalar_product(P, dF)) /
        (P.norm() * dF.norm());
      EXPECT_LE(error, 1e-6) << "F = " << F << ", dF = " << dF;
      worst_error = std::max(worst_error, error);
    }
  std::cout << "  dim = " << dim << ": worst relative error of dPsi/dh - P:dF "
            << worst_error << std::endl;
}



// @sect4{The positive semi-definite part of the tangent}
//
// positive_semidefinite_part() must return the tangent itself where it is
// positive definite (at small strains: to round-off), and everywhere a
// tensor with the symmetries of a tangent whose quadratic form is
// non-negative and never above that of the tangent, i.e. $\mathcal C -
// \mathcal C^+$ negative semi-definite. The large stretches below (up to a
// factor four, and compression to a quarter) make the tangent indefinite
// for some of them in 3D; the test asserts that at least one is, so that
// it cannot pass without testing the projection there. (The tangents of
// the incompressible 1D and 2D models stay positive definite in all of
// these states.)
namespace
{
  // $\mathrm{tr}(\mathbf A\mathbf B)$ of the two tensors as symmetric
  // matrices in Mandel's notation (off-diagonal components times
  // $\sqrt2$); for the symmetric tensors here the Frobenius product of
  // the matrices.
  template <int dim>
  double
  mandel_product(const SymmetricTensor<4, dim> &A,
                 const SymmetricTensor<4, dim> &B)
  {
    constexpr unsigned int n =
      SymmetricTensor<2, dim>::n_independent_components;
    double sum = 0.;
    for (unsigned int a = 0; a < n; ++a)
      for (unsigned int b = 0; b < n; ++b)
        {
          const TableIndices<2> i =
            SymmetricTensor<2, dim>::unrolled_to_component_indices(a);
          const TableIndices<2> j =
            SymmetricTensor<2, dim>::unrolled_to_component_indices(b);
          const double w =
            ((i[0] == i[1]) ? 1. : 2.) * ((j[0] == j[1]) ? 1. : 2.);
          sum += w * A[i[0]][i[1]][j[0]][j[1]] * B[i[0]][i[1]][j[0]][j[1]];
        }
    return sum;
  }
} // namespace

TYPED_TEST(NeoHookeanEnergyTest, PositiveSemidefinitePartOfTangent)
{
  constexpr int                          dim = TypeParam::value;
  const NeoHookeanEnergy<dim>            material(shear_modulus, bulk_modulus);
  MaterialResponse<dim>                  response;
  std::mt19937                           generator(7);
  std::uniform_real_distribution<double> uniform(-1., 1.);
  const auto                             random_strain = [&]() {
    SymmetricTensor<2, dim> E;
    for (unsigned int i = 0; i < dim; ++i)
      for (unsigned int j = i; j < dim; ++j)
        E[i][j] = uniform(generator);
    return E;
  };

  // Small strain: unchanged.
  material.evaluate(1e-3 * displacement_gradient(
                             random_deformation_gradients<dim>(1, 3)[0]),
                    response);
  const SymmetricTensor<4, dim> small =
    SoftRobot::positive_semidefinite_part(response.material_tangent);
  EXPECT_LT((small - response.material_tangent).norm(),
            1e-12 * response.material_tangent.norm());

  // A tangent that is diagonal in Mandel's notation, with eigenvalues of
  // both signs: the positive ones are kept, the others dropped, exactly
  // (no reduction or rotation is needed); the zero tangent stays zero.
  {
    SymmetricTensor<4, dim> diagonal, expected;
    for (unsigned int a = 0;
         a < SymmetricTensor<2, dim>::n_independent_components;
         ++a)
      {
        const TableIndices<2> ij =
          SymmetricTensor<2, dim>::unrolled_to_component_indices(a);
        const double value                   = (a % 2 == 0) ? -1. - a : 2. + a;
        diagonal[ij[0]][ij[1]][ij[0]][ij[1]] = value;
        expected[ij[0]][ij[1]][ij[0]][ij[1]] = std::max(value, 0.);
      }
    EXPECT_LT(
      (SoftRobot::positive_semidefinite_part(diagonal) - expected).norm(),
      1e-14 * diagonal.norm());
    EXPECT_EQ(
      SoftRobot::positive_semidefinite_part(SymmetricTensor<4, dim>()).norm(),
      0.);
  }

  bool found_indefinite = false;
  for (const double stretch : {0.25, 0.5, 2., 3., 4.})
    for (const Tensor<2, dim> &R : random_deformation_gradients<dim>(5, 11))
      {
        // A stretch along the first axis, rotated and perturbed.
        Tensor<2, dim> F = R;
        for (unsigned int i = 0; i < dim; ++i)
          F[i][0] *= stretch;
        material.evaluate(displacement_gradient(F), response);
        const SymmetricTensor<4, dim> &CC = response.material_tangent;
        const SymmetricTensor<4, dim>  CC_plus =
          SoftRobot::positive_semidefinite_part(CC);
        const double scale = CC.norm();
        for (unsigned int k = 0; k < 50; ++k)
          {
            const SymmetricTensor<2, dim> E = random_strain();
            // (Contracted as E * (CC * E): deal.II 9.4 cannot contract a
            // symmetric rank-2 tensor from the left in 1D.)
            const double full = E * (CC * E), plus = E * (CC_plus * E);
            found_indefinite = found_indefinite || full < -1e-10 * scale;
            EXPECT_GE(plus, -1e-10 * scale * E.norm() * E.norm());
            EXPECT_GE(plus - full, -1e-10 * scale * E.norm() * E.norm());
            // Major symmetry.
            const SymmetricTensor<2, dim> G = random_strain();
            EXPECT_NEAR(E * (CC_plus * G),
                        G * (CC_plus * E),
                        1e-10 * scale * E.norm() * G.norm());
          }
        // The spectral projection, not only some positive semi-definite
        // tensor below the tangent: the dropped part $\mathcal C -
        // \mathcal C^+$ and $\mathcal C^+$ are orthogonal in Mandel's
        // notation (they share eigenvectors, with disjoint eigenvalues).
        EXPECT_NEAR(mandel_product(CC_plus, CC - CC_plus),
                    0.,
                    1e-12 * scale * scale);
      }
  if (dim == 3)
    {
      EXPECT_TRUE(found_indefinite)
        << "no indefinite tangent among the states tested";
    }
}



// @sect4{The mean-dilatation pieces add up to the whole energy}
//
// evaluate_with_pressure() differentiates the isochoric energy plus $p\,(J
// - 1)$. With the pressure of the point's own volume ratio, $p = U'(J)$,
// its stress must be the whole energy's stress, and its tangent plus
// $U''(J)\,(J\mathbf C^{-1})\otimes(J\mathbf C^{-1})$ (the second
// derivative of $U(J(\mathbf E))$ beyond the pressure's) the whole
// energy's tangent; its energy plus $U(J)$ the whole energy. evaluate() is
// checked against the AD helper above, so this checks the pressure's route
// through the same independent reference. In 1D and 2D there is no
// volumetric part, and both routes must agree as they are. The inverse of
// $\mathbf C$ and the three volumetric functions are formed in plain
// numbers from $\mathbf F$, and with $\kappa = 100\mu$ the volumetric terms
// dominate and cancel by a factor of up to about 100: the tolerance
// $10^{-12}$ is about 50 times the round-off that leaves.
TYPED_TEST(NeoHookeanEnergyTest, PressureFormAddsUpToTheEnergy)
{
  constexpr int               dim = TypeParam::value;
  const NeoHookeanEnergy<dim> material(shear_modulus, bulk_modulus);

  double worst_error = 0.;
  for (const Tensor<2, dim> &F :
       random_deformation_gradients<dim>(n_samples, 5))
    {
      const Tensor<2, dim>          H = displacement_gradient<dim>(F);
      const SymmetricTensor<2, dim> E =
        NeoHookeanEnergy<dim>::green_lagrange_strain(H);
      const double          t = NeoHookeanEnergy<dim>::volume_change(E);
      MaterialResponse<dim> whole, split, split_stress;
      material.evaluate(H, whole);
      material.evaluate_with_pressure(H,
                                      material.volumetric_pressure(t),
                                      true,
                                      split);
      material.evaluate_with_pressure(H,
                                      material.volumetric_pressure(t),
                                      false,
                                      split_stress);

      SymmetricTensor<4, dim> tangent = split.material_tangent;
      if constexpr (dim == 3)
        {
          const SymmetricTensor<2, dim> J_C_inverse =
            determinant(F) * invert(symmetrize(transpose(F) * F));
          tangent += material.volumetric_stiffness(t) *
                     outer_product(J_C_inverse, J_C_inverse);
        }
      const double energy_error =
        std::abs(split.energy + material.volumetric_energy(t) - whole.energy) /
        std::abs(whole.energy);
      const double stress_error =
        (split.second_piola - whole.second_piola).norm() /
        whole.second_piola.norm();
      const double stress_only_error =
        (split_stress.second_piola - whole.second_piola).norm() /
        whole.second_piola.norm();
      const double tangent_error = (tangent - whole.material_tangent).norm() /
                                   whole.material_tangent.norm();
      EXPECT_LE(energy_error, 1e-12) << "F = " << F;
      EXPECT_LE(stress_error, 1e-12) << "F = " << F;
      EXPECT_LE(stress_only_error, 1e-12) << "F = " << F;
      EXPECT_LE(tangent_error, 1e-12) << "F = " << F;
      worst_error = std::max({worst_error,
                              energy_error,
                              stress_error,
                              stress_only_error,
                              tangent_error});
    }
  std::cout << "  dim = " << dim
            << ": worst relative difference from the whole energy "
            << worst_error << std::endl;
}
