// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{The neo-Hookean strain energy and its automatic differentiation}
//
// The silicone rubbers of soft robots (Ecoflex, Dragon Skin) are modelled
// as neo-Hookean solids. Everything the solver needs from the material --
// the second Piola-Kirchhoff stress $\mathbf S$ and its tangent
// $\mathcal C$ -- is derived from one scalar function, the strain energy
// density $\Psi$ per unit reference volume, by automatic differentiation
// (Sacado, through deal.II's Differentiation::AD):
// @f[
//   \mathbf S = \frac{\partial\Psi}{\partial\mathbf E}, \qquad
//   \mathcal C = \frac{\partial^2\Psi}{\partial\mathbf E\,\partial\mathbf E},
//   \qquad \mathbf E = \tfrac12\left(\mathbf C - \mathbf I\right)
//   = \tfrac12\left(\mathbf H + \mathbf H^T + \mathbf H^T\mathbf H\right).
// @f]
// Differentiating with respect to the symmetric Green-Lagrange strain
// keeps the number of independent variables at 1, 3 or 6 (for dim = 1, 2,
// 3) and makes the energy objective by construction. We use $\mathbf E$,
// computed from the displacement gradient $\mathbf H$, rather than
// $\mathbf C = \mathbf F^T\mathbf F$ because of round-off: $\mathbf C$
// stores $1 + O(\varepsilon)$ and loses the digits of a small strain
// $\varepsilon$, and the textbook forms of $\Psi$ subtract numbers of
// order one to obtain a result of order $\varepsilon^2$. At a strain of
// $10^{-6}$ that leaves four correct digits of the energy and ten of the
// stress. Below, every energy is rearranged so that no term of lower
// order cancels, with the series of the two functions that need it; the
// energy then has full relative precision at any strain, which the tests
// of energy conservation at small amplitude rely on.
//
// The energy depends on the dimension of the model:
//
// - dim = 3: the compressible, decoupled neo-Hookean solid with shear
//   modulus $\mu$ and bulk modulus $\kappa$,
//   @f[
//     \Psi = \frac{\mu}{2}\left(J^{-2/3}\,\mathrm{tr}\,\mathbf C - 3\right)
//          + \frac{\kappa}{4}\left(J^2 - 1 - 2\ln J\right),\qquad
//     J = \sqrt{\det\mathbf C},
//   @f]
//   which is stress free at $\mathbf F=\mathbf I$ and linearises to
//   Hooke's law with shear modulus $\mu$ and bulk modulus $\kappa$.
//   (The reference study's law $\sigma = \mu\mathbf B - \kappa(1-J)\mathbf I$
//   is not stress free at $\mathbf F = \mathbf I$; we do not copy it.)
//   With $d = \det\mathbf C - 1 = 2I_1 + 4I_2 + 8I_3$ in the invariants
//   $I_k$ of $\mathbf E$, $g(d) = (1+d)^{-1/3} - 1$, $h(d) = 3g(d) + d$ and
//   $k(d) = d - \ln(1 + d)$, this is the same as
//   @f[
//     \Psi = \frac{\mu}{2}\left(h(d) - 4I_2 - 8I_3 + 2I_1\,g(d)\right)
//          + \frac{\kappa}{4}\,k(d),
//   @f]
//   where all terms are of second order in the strain.
//
// - dim = 2: a thin sheet in plane stress of the incompressible
//   neo-Hookean solid. Incompressibility fixes the out-of-plane stretch,
//   $\lambda_3^2 = 1/\det\mathbf C$, and the traction-free faces make the
//   out-of-plane stress vanish, which leaves the reduced energy
//   @f[
//     \Psi = \frac{\mu}{2}\left(\mathrm{tr}\,\mathbf C
//            + \frac{1}{\det\mathbf C} - 3\right)
//          = \frac{\mu}{2}\,\frac{2\,\mathrm{tr}\mathbf E\; d
//            - 4\det\mathbf E}{1 + d},\quad d = \det\mathbf C - 1,
//     \qquad \mathbf P = \mu\left(\mathbf F - J^{-2}\mathbf F^{-T}\right).
//   @f]
//
// - dim = 1: a bar in uniaxial tension or compression of the
//   incompressible neo-Hookean solid; the lateral stretches are
//   $\lambda^{-1/2}$ and
//   @f[
//     \Psi = \frac{\mu}{2}\left(\lambda^2 + \frac{2}{\lambda} - 3\right)
//          = \frac{\mu}{2}\,\frac{(\lambda - 1)^2(\lambda + 2)}{\lambda},
//     \qquad P = \mu\left(\lambda - \lambda^{-2}\right),
//   @f]
//   with $\lambda - 1 = 2E/(\lambda + 1)$. Its small-strain Young's
//   modulus is $E = 3\mu$.
//
// The reduced models have no bulk modulus: they are incompressible by
// construction, and $\kappa$ is ignored there.

#ifndef soft_robot_material_neo_hookean_energy_h
#define soft_robot_material_neo_hookean_energy_h

#include <cmath>
#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>
#include <type_traits>

namespace SoftRobot
{
  using namespace dealii;

  // @sect4{The material response at one quadrature point}
  //
  // What the assembly needs at a quadrature point: the energy density, the
  // second Piola-Kirchhoff stress and the material tangent, all with
  // respect to the reference configuration.
  template <int dim>
  struct MaterialResponse
  {
    double                  energy = 0.;
    SymmetricTensor<2, dim> second_piola;
    SymmetricTensor<4, dim> material_tangent;
  };



  namespace internal
  {
    template <typename Number>
    struct StrainInvariants;
  }



  // @sect4{The class NeoHookeanEnergy}
  template <int dim>
  class NeoHookeanEnergy
  {
  public:
    NeoHookeanEnergy(const double shear_modulus, const double bulk_modulus);

    // The strain energy density as a function of the Green-Lagrange strain
    // $\mathbf E$, written once for any number type so that Sacado can
    // differentiate it.
    template <typename Number>
    Number
    energy(const SymmetricTensor<2, dim, Number> &E) const;

    // Energy, $\mathbf S$ and $\mathcal C$ at the displacement gradient
    // $\mathbf H = \mathbf F - \mathbf I$ (given as $\mathbf H$ so that
    // small strains keep their digits), by automatic differentiation with
    // Sacado's fixed-size forward numbers. This is what the solver calls.
    void
    evaluate(const Tensor<2, dim>  &displacement_gradient,
             MaterialResponse<dim> &response) const;

    // Energy and $\mathbf S$ only, with first derivatives: for the
    // residual evaluations that need no tangent. The material tangent of
    // the response is left untouched.
    void
    evaluate_stress(const Tensor<2, dim>  &displacement_gradient,
                    MaterialResponse<dim> &response) const;

    // The same as evaluate(), through deal.II's Differentiation::AD helper
    // with dynamically sized nested Sacado numbers, in the components of
    // $\mathbf E$ in every dimension. It is many times slower (it
    // allocates memory for every derivative), and the tests use it as the
    // independent reference for evaluate().
    void
    evaluate_with_ad_helper(const Tensor<2, dim>  &displacement_gradient,
                            MaterialResponse<dim> &response) const;

    // The Green-Lagrange strain of a displacement gradient, without
    // forming $\mathbf F^T\mathbf F$.
    static SymmetricTensor<2, dim>
    green_lagrange_strain(const Tensor<2, dim> &displacement_gradient);

    // The first Piola-Kirchhoff stress in closed form. Used by the tests
    // to check the automatic derivatives; the solver does not need it.
    Tensor<2, dim>
    first_piola_closed_form(const Tensor<2, dim> &F) const;

    // The Cauchy stress $\sigma = J_{3D}^{-1}\mathbf F\mathbf S\mathbf F^T$;
    // for the incompressible reduced models the three-dimensional volume
    // ratio is one.
    SymmetricTensor<2, dim>
    cauchy_stress(const Tensor<2, dim>          &F,
                  const SymmetricTensor<2, dim> &S) const;

    // The determinant of the three-dimensional deformation gradient the
    // model stands for: $\det\mathbf F$ in 3D, one for the incompressible
    // reduced models. The quantity that must stay positive is
    // $\det\mathbf F$ in every dimension (see the solver).
    double
    volume_ratio(const Tensor<2, dim> &F) const;

    // @sect4{The volumetric part on its own: the mean-dilatation formulation}
    //
    // In 3D the energy splits into an isochoric and a volumetric part,
    // $\Psi = \Psi_{\mathrm{iso}}(\mathbf E) + U(J)$ with $U(J) =
    // \frac{\kappa}{4}(J^2 - 1 - 2\ln J)$. The mean-dilatation
    // formulation of the solver (`Finite element/Volumetric formulation`)
    // evaluates $U$ at the mean volume ratio $\Theta$ of a cell instead of
    // at $J$, and needs the two parts separately. In the reduced models
    // (dim = 1, 2) there is no volumetric part: the isochoric energy is the
    // whole energy there.
    template <typename Number>
    Number
    isochoric_energy(const SymmetricTensor<2, dim, Number> &E) const;

    // $U$, $U'$ and $U''$ at $\Theta = 1 + t$, given $t$ so that states
    // close to the reference keep their digits: $U = \frac{\kappa}{4}\,k(t(2
    // + t))$, $U' = \frac{\kappa}{2}\,t(2+t)/(1+t)$, $U'' =
    // \frac{\kappa}{2}(1 + (1+t)^{-2})$.
    double
    volumetric_energy(const double theta_minus_one) const;
    double
    volumetric_pressure(const double theta_minus_one) const;
    double
    volumetric_stiffness(const double theta_minus_one) const;

    // $J - 1 = d/(1 + \sqrt{1 + d})$ from the strain (no cancellation).
    static double
    volume_change(const SymmetricTensor<2, dim> &E);

    // The isochoric energy plus a constant pressure $p$ times $J - 1$,
    // differentiated: $\mathbf S = \partial\Psi_{\mathrm{iso}}/\partial
    // \mathbf E + p\,J\mathbf C^{-1}$ and its tangent (with
    // `with_tangent`). The energy of the response is $\Psi_{\mathrm{iso}}$
    // alone; the cell adds the volumetric energy of its mean dilatation.
    void
    evaluate_with_pressure(const Tensor<2, dim>  &displacement_gradient,
                           const double           pressure,
                           const bool             with_tangent,
                           MaterialResponse<dim> &response) const;

    double
    shear_modulus() const
    {
      return mu;
    }

    double
    bulk_modulus() const
    {
      return kappa;
    }

    // The 3D energy as a function of the invariants of $\mathbf E$ (see
    // internal::strain_invariants()), which is how evaluate() and
    // evaluate_stress() differentiate it.
    template <typename Number>
    Number
    energy_of_invariants(
      const internal::StrainInvariants<Number> &invariants) const;

  private:
    // What evaluate() and evaluate_stress() share.
    void
    differentiate(const Tensor<2, dim>  &displacement_gradient,
                  const bool             with_tangent,
                  MaterialResponse<dim> &response) const;

    const double mu;
    const double kappa;
  };



  // @sect4{Tangent of the first Piola-Kirchhoff stress}
  //
  // The derivative $\mathcal A = \partial\mathbf P/\partial\mathbf F$ of
  // $\mathbf P = \mathbf F\mathbf S$,
  // @f[
  //   \mathcal A_{iJkL} = \delta_{ik} S_{JL}
  //                     + F_{iI}\,\mathcal C_{IJKL}\,F_{kK},
  // @f]
  // as a full fourth-order tensor. The solver never forms it (it works
  // with $\mathbf S$ and $\mathcal C$ directly), but tests and users
  // checking the linearisation do.
  template <int dim>
  Tensor<4, dim>
  first_piola_tangent(const Tensor<2, dim>          &F,
                      const SymmetricTensor<2, dim> &S,
                      const SymmetricTensor<4, dim> &CC);



  // The positive semi-definite part of a material tangent: with the
  // symmetric strains written as vectors in Mandel's notation (off-diagonal
  // components times $\sqrt2$, so that $\delta\mathbf E:\mathcal
  // C:\delta\mathbf E$ is the quadratic form of a symmetric matrix), the
  // matrix with its negative eigenvalues set to zero. The tangent of the
  // neo-Hookean energy is positive definite at small strains but not at all
  // large ones (strongly stretched or compressed states of the isochoric
  // part); the damping matrix built from it must not be, or it would feed
  // energy into the motion instead of taking it out.
  template <int dim>
  SymmetricTensor<4, dim>
  positive_semidefinite_part(const SymmetricTensor<4, dim> &CC);



  namespace internal
  {
    // The value of a (possibly nested) forward-mode number: Sacado's
    // numbers, static or dynamic, give their value by val().
    template <typename Number>
    double
    scalar_value(const Number &x)
    {
      if constexpr (std::is_arithmetic_v<Number>)
        return x;
      else
        return scalar_value(x.val());
    }

    // $k(d) = d - \ln(1+d)$, $g(d) = (1+d)^{-1/3} - 1$ and $h(d) = 3g(d) +
    // d$, of the orders $d^2$, $d$ and $d^2$: by their Taylor series up to
    // $d^7$ for $|d| < 10^{-3}$, where the remainder is below round-off,
    // and directly elsewhere, where the cancellation costs at most three
    // digits. (Sacado has no log1p or expm1.) The series are the most
    // expensive part of the 3D energy, so they are kept short.
    constexpr double series_limit = 1e-3;

    template <typename Number>
    Number
    d_minus_log1p(const Number &d)
    {
      using std::log;
      if (std::abs(scalar_value(d)) >= series_limit)
        return d - log(1. + d);
      Number sum = 0., power = d * d;
      for (unsigned int k = 2; k <= 7; ++k, power *= -d)
        sum += power / double(k);
      return sum;
    }

    // The binomial series of $(1+d)^{-1/3}$ from the term of order
    // `first_order` on.
    template <typename Number>
    Number
    cube_root_series(const Number &d, const unsigned int first_order)
    {
      Number result = 0., power = 1.;
      double coefficient = 1.;
      for (unsigned int k = 0; k <= 7; ++k)
        {
          if (k >= first_order)
            result += coefficient * power;
          power *= d;
          coefficient *= (-1. / 3. - k) / (k + 1.);
        }
      return result;
    }

  } // namespace internal



  namespace internal
  {
    // The invariants of a 3D strain and $d = \det\mathbf C - 1$.
    template <typename Number>
    struct StrainInvariants
    {
      Number I1, I2, I3, d;
    };

    template <typename Number>
    StrainInvariants<Number>
    strain_invariants(const SymmetricTensor<2, 3, Number> &E)
    {
      StrainInvariants<Number> invariants;
      invariants.I1 = trace(E);
      // the sum of the principal minors, written by components because
      // the static Sacado numbers have no tensor contraction in deal.II
      invariants.I2 = E[0][0] * E[1][1] + E[1][1] * E[2][2] +
                      E[2][2] * E[0][0] - E[0][1] * E[0][1] -
                      E[1][2] * E[1][2] - E[0][2] * E[0][2];
      invariants.I3 = determinant(E);
      invariants.d =
        2. * invariants.I1 + 4. * invariants.I2 + 8. * invariants.I3;
      return invariants;
    }

    // The isochoric neo-Hookean energy per unit shear modulus, with $g$ and
    // $h$ from their series or, outside the series' range, from the one
    // power $(1+d)^{-1/3}$.
    template <typename Number>
    Number
    isochoric_energy_3d(const StrainInvariants<Number> &e)
    {
      using std::pow;
      if (std::abs(scalar_value(e.d)) >= series_limit)
        {
          const Number g = pow(1. + e.d, -1. / 3.) - 1.;
          const Number h = 3. * g + e.d;
          return 0.5 * (h - 4. * e.I2 - 8. * e.I3 + 2. * e.I1 * g);
        }
      const Number g = cube_root_series(e.d, 1);
      const Number h = 3. * cube_root_series(e.d, 2);
      return 0.5 * (h - 4. * e.I2 - 8. * e.I3 + 2. * e.I1 * g);
    }
  } // namespace internal



  template <int dim>
  template <typename Number>
  Number
  NeoHookeanEnergy<dim>::isochoric_energy(
    const SymmetricTensor<2, dim, Number> &E) const
  {
    using std::sqrt;
    if constexpr (dim == 3)
      return mu * internal::isochoric_energy_3d(internal::strain_invariants(E));
    else if constexpr (dim == 2)
      {
        const Number trE  = trace(E);
        const Number detE = determinant(E);
        const Number d    = 2. * trE + 4. * detE;
        return 0.5 * mu * (2. * trE * d - 4. * detE) / (1. + d);
      }
    else
      {
        const Number lambda       = sqrt(1. + 2. * E[0][0]);
        const Number lambda_minus = 2. * E[0][0] / (lambda + 1.);
        return 0.5 * mu * lambda_minus * lambda_minus * (lambda + 2.) / lambda;
      }
  }



  template <int dim>
  template <typename Number>
  Number
  NeoHookeanEnergy<dim>::energy(const SymmetricTensor<2, dim, Number> &E) const
  {
    if constexpr (dim == 3)
      return energy_of_invariants(internal::strain_invariants(E));
    else
      return isochoric_energy(E);
  }



  template <int dim>
  template <typename Number>
  Number
  NeoHookeanEnergy<dim>::energy_of_invariants(
    const internal::StrainInvariants<Number> &invariants) const
  {
    Number result = mu * internal::isochoric_energy_3d(invariants);
    result += 0.25 * kappa * internal::d_minus_log1p(invariants.d);
    return result;
  }
} // namespace SoftRobot

#endif
