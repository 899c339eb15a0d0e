// @sect3{The neo-Hookean strain energy and its automatic differentiation}
//
// The silicone rubbers of soft robots (Ecoflex, Dragon Skin) are modelled
// as neo-Hookean solids. Everything the solver needs from the material --
// the second Piola-Kirchhoff stress $\mathbf S$ and its tangent
// $\mathcal C$ -- is derived from one scalar function, the strain energy
// density $\Psi(\mathbf C)$ per unit reference volume, by automatic
// differentiation (Sacado, through deal.II's Differentiation::AD):
// @f[
//   \mathbf S = 2\frac{\partial\Psi}{\partial\mathbf C}, \qquad
//   \mathcal C = 4\frac{\partial^2\Psi}{\partial\mathbf C\,\partial\mathbf C}.
// @f]
// Differentiating with respect to the symmetric right Cauchy-Green tensor
// $\mathbf C=\mathbf F^T\mathbf F$ keeps the number of independent
// variables at 1, 3 or 6 (for dim = 1, 2, 3) and makes the energy
// objective by construction.
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
//
// - dim = 2: a thin sheet in plane stress of the incompressible
//   neo-Hookean solid. Incompressibility fixes the out-of-plane stretch,
//   $\lambda_3^2 = 1/\det\mathbf C$, and the traction-free faces make the
//   out-of-plane stress vanish, which leaves the reduced energy
//   @f[
//     \Psi = \frac{\mu}{2}\left(\mathrm{tr}\,\mathbf C
//            + \frac{1}{\det\mathbf C} - 3\right),\qquad
//     \mathbf P = \mu\left(\mathbf F - J^{-2}\mathbf F^{-T}\right).
//   @f]
//
// - dim = 1: a bar in uniaxial tension or compression of the
//   incompressible neo-Hookean solid; the lateral stretches are
//   $\lambda^{-1/2}$ and
//   @f[
//     \Psi = \frac{\mu}{2}\left(\lambda^2 + \frac{2}{\lambda} - 3\right),
//     \qquad P = \mu\left(\lambda - \lambda^{-2}\right),\qquad
//     C = \lambda^2.
//   @f]
//   Its small-strain Young's modulus is $E = 3\mu$.
//
// The reduced models have no bulk modulus: they are incompressible by
// construction, and $\kappa$ is ignored there.

#ifndef soft_robot_material_neo_hookean_energy_h
#define soft_robot_material_neo_hookean_energy_h

#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>

#include <cmath>

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
    double                    energy = 0.;
    SymmetricTensor<2, dim>   second_piola;
    SymmetricTensor<4, dim>   material_tangent;
  };



  // @sect4{The class NeoHookeanEnergy}
  template <int dim>
  class NeoHookeanEnergy
  {
  public:
    NeoHookeanEnergy(const double shear_modulus, const double bulk_modulus);

    // The strain energy density as a function of $\mathbf C$, written once
    // for any number type so that Sacado can differentiate it.
    template <typename Number>
    Number
    energy(const SymmetricTensor<2, dim, Number> &C) const;

    // Energy, $\mathbf S$ and $\mathcal C$ at the deformation gradient
    // $\mathbf F$, the derivatives by automatic differentiation.
    void
    evaluate(const Tensor<2, dim> &F, MaterialResponse<dim> &response) const;

    // The first Piola-Kirchhoff stress in closed form. Used by the tests
    // to check the automatic derivatives; the solver does not need it.
    Tensor<2, dim>
    first_piola_closed_form(const Tensor<2, dim> &F) const;

    // The Cauchy stress $\sigma = J_{3D}^{-1}\mathbf F\mathbf S\mathbf F^T$;
    // for the incompressible reduced models the three-dimensional volume
    // ratio is one.
    SymmetricTensor<2, dim>
    cauchy_stress(const Tensor<2, dim> &F, const SymmetricTensor<2, dim> &S) const;

    // The determinant of the three-dimensional deformation gradient the
    // model stands for: $\det\mathbf F$ in 3D, one for the incompressible
    // reduced models. The quantity that must stay positive is
    // $\det\mathbf F$ in every dimension (see the solver).
    double
    volume_ratio(const Tensor<2, dim> &F) const;

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

  private:
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
  first_piola_tangent(const Tensor<2, dim> &         F,
                      const SymmetricTensor<2, dim> &S,
                      const SymmetricTensor<4, dim> &CC);



  template <int dim>
  template <typename Number>
  Number
  NeoHookeanEnergy<dim>::energy(const SymmetricTensor<2, dim, Number> &C) const
  {
    using std::log;
    using std::pow;
    using std::sqrt;
    const Number det_C = determinant(C);
    if constexpr (dim == 3)
      {
        const Number J = sqrt(det_C);
        return 0.5 * mu * (pow(J, -2. / 3.) * trace(C) - 3.) +
               0.25 * kappa * (det_C - 1. - 2. * log(J));
      }
    else if constexpr (dim == 2)
      return 0.5 * mu * (trace(C) + 1. / det_C - 3.);
    else
      return 0.5 * mu * (C[0][0] + 2. / sqrt(C[0][0]) - 3.);
  }
} // namespace SoftRobot

#endif
