// SPDX-License-Identifier: LGPL-2.1-or-later

#include <Sacado.hpp>
#include <algorithm>
#include <array>
#include <cmath>
#include <deal.II/differentiation/ad.h>
#include <material/neo_hookean_energy.h>

namespace SoftRobot
{
  // @sect3{Implementation of NeoHookeanEnergy}

  template <int dim>
  NeoHookeanEnergy<dim>::NeoHookeanEnergy(const double shear_modulus,
                                          const double bulk_modulus)
    : mu(shear_modulus)
    , kappa(bulk_modulus)
  {
  }



  // @sect4{NeoHookeanEnergy::evaluate}
  //
  // The automatic differentiation happens here, at the level of one
  // quadrature point. In 1D and 2D the $n$ = 1 or 3 independent components
  // of $\mathbf E$ are the variables (in 3D the invariants of $\mathbf E$
  // are, see below), and the energy evaluated once with
  // nested forward-mode numbers carries its gradient (the stress) and its
  // Hessian (the tangent). A symmetric tensor's off-diagonal component
  // $E_{ij}$ stands for both $E_{ij}$ and $E_{ji}$, so the derivative with
  // respect to it is twice the tensor component: the factors below undo
  // that.
  //
  // The numbers are Sacado's fixed-size ones (`SFad`, in the variant that
  // caches intermediate values, `CacheFad`). Their derivative arrays live
  // on the stack, which makes the evaluation many times faster than with
  // the dynamically sized numbers of deal.II's Differentiation::AD helper;
  // evaluate_with_ad_helper() keeps the helper route in the components of
  // $\mathbf E$ in every dimension, and the tests check that both agree.
  //
  // Differentiating at the cell level instead (the energy functional of all
  // the cell's degrees of freedom) would be simpler to write, but a nested
  // forward-mode number would then carry 30 to 81 derivative directions
  // instead of 1 to 6, which makes assembly an order of magnitude slower.
  template <int dim>
  SymmetricTensor<2, dim>
  NeoHookeanEnergy<dim>::green_lagrange_strain(const Tensor<2, dim> &H)
  {
    // $E_{ij} = \frac12(H_{ij} + H_{ji}) + \frac12 H_{ki}H_{kj}$, component
    // by component.
    SymmetricTensor<2, dim> E;
    for (unsigned int i = 0; i < dim; ++i)
      for (unsigned int j = i; j < dim; ++j)
        {
          double HtH = 0.;
          for (unsigned int k = 0; k < dim; ++k)
            HtH += H[k][i] * H[k][j];
          E[i][j] = 0.5 * (H[i][j] + H[j][i]) + 0.5 * HtH;
        }
    return E;
  }



  namespace
  {
    // The factor between the derivative with respect to the independent
    // component a and the tensor component it stands for.
    template <int dim>
    double
    symmetric_weight(const unsigned int a)
    {
      const TableIndices<2> indices =
        SymmetricTensor<2, dim>::unrolled_to_component_indices(a);
      return (indices[0] == indices[1]) ? 1. : 0.5;
    }

    // $\mathbf E$ with its independent components as Sacado variables:
    // `variable(a, value)` makes the number of component a.
    template <int dim, typename ADNumber, typename MakeVariable>
    SymmetricTensor<2, dim, ADNumber>
    independent_strain(const SymmetricTensor<2, dim> &E,
                       const MakeVariable            &variable)
    {
      SymmetricTensor<2, dim, ADNumber> E_ad;
      for (unsigned int a = 0;
           a < SymmetricTensor<2, dim>::n_independent_components;
           ++a)
        {
          const TableIndices<2> ij =
            SymmetricTensor<2, dim>::unrolled_to_component_indices(a);
          E_ad[ij] = variable(a, E[ij]);
        }
      return E_ad;
    }



    // The energy `psi` of the strain differentiated twice: value, $\mathbf
    // S$ and $\mathcal C$ into the response.
    template <int dim, typename EnergyFunction>
    void
    differentiate_twice(const SymmetricTensor<2, dim> &E,
                        const EnergyFunction          &psi,
                        MaterialResponse<dim>         &response)
    {
      constexpr unsigned int n =
        SymmetricTensor<2, dim>::n_independent_components;
      using Inner    = Sacado::CacheFad::SFad<double, n>;
      using ADNumber = Sacado::CacheFad::SFad<Inner, n>;

      const ADNumber value = psi(independent_strain<dim, ADNumber>(
        E, [](const unsigned int a, const double component) {
          return ADNumber(n, a, Inner(n, a, component));
        }));
      response.energy      = value.val().val();
      for (unsigned int a = 0; a < n; ++a)
        {
          const TableIndices<2> ij =
            SymmetricTensor<2, dim>::unrolled_to_component_indices(a);
          const double w_a          = symmetric_weight<dim>(a);
          response.second_piola[ij] = w_a * value.dx(a).val();
          for (unsigned int b = 0; b < n; ++b)
            {
              const TableIndices<2> kl =
                SymmetricTensor<2, dim>::unrolled_to_component_indices(b);
              response.material_tangent[ij[0]][ij[1]][kl[0]][kl[1]] =
                w_a * symmetric_weight<dim>(b) * value.dx(a).dx(b);
            }
        }
    }

    // The same with first derivatives only: value and $\mathbf S$.
    template <int dim, typename EnergyFunction>
    void
    differentiate_once(const SymmetricTensor<2, dim> &E,
                       const EnergyFunction          &psi,
                       MaterialResponse<dim>         &response)
    {
      constexpr unsigned int n =
        SymmetricTensor<2, dim>::n_independent_components;
      using ADNumber = Sacado::CacheFad::SFad<double, n>;

      const ADNumber value = psi(independent_strain<dim, ADNumber>(
        E, [](const unsigned int a, const double component) {
          return ADNumber(n, a, component);
        }));
      response.energy      = value.val();
      for (unsigned int a = 0; a < n; ++a)
        response
          .second_piola[SymmetricTensor<2, dim>::unrolled_to_component_indices(
            a)] = symmetric_weight<dim>(a) * value.dx(a);
    }



    // @sect4{The 3D energies through their invariants}
    //
    // In 3D both energies depend on $\mathbf E$ only through its invariants
    // $I_1 = \mathrm{tr}\,\mathbf E$, $I_2 = \frac12(I_1^2 -
    // \mathbf E:\mathbf E)$ and $I_3 = \det\mathbf E$. Sacado then
    // differentiates $\Psi(I_1, I_2, I_3)$ with three variables instead of
    // six, and the invariants themselves, polynomials of $\mathbf E$, are
    // formed in plain numbers: the nested numbers carry 16 instead of 49
    // values, and the determinant's products are no longer among their
    // operations. The chain rule through the invariants is written out:
    // @f[
    //   \mathbf S = \sum_a \psi_a\,\mathbf A_a,\qquad
    //   \mathcal C = \sum_{a,b}\psi_{ab}\,\mathbf A_a\otimes\mathbf A_b
    //     + \psi_2\,(\mathbf I\otimes\mathbf I - \mathbb I)
    //     + \psi_3\,\mathcal K,
    // @f]
    // with $\psi_a = \partial\Psi/\partial I_a$ and $\psi_{ab}$ from
    // Sacado, $\mathbf A_1 = \mathbf I$, $\mathbf A_2 = I_1\mathbf I -
    // \mathbf E$, $\mathbf A_3 = \mathrm{cof}\,\mathbf E$ (by its 2 x 2
    // minors), $\mathbb I$ the symmetric fourth-order identity, and
    // $\mathcal K = \partial\,\mathrm{cof}\,\mathbf E/\partial\mathbf E$,
    // which follows from $\mathrm{cof}\,\mathbf E = \mathbf E^2 -
    // I_1\mathbf E + I_2\mathbf I$ (Cayley-Hamilton):
    // @f[
    //   \mathcal K_{ijkl} = \tfrac12\left(\delta_{ik}E_{jl} + \delta_{il}E_{jk}
    //     + E_{ik}\delta_{jl} + E_{il}\delta_{jk}\right)
    //     - E_{ij}\delta_{kl} - \delta_{ij}E_{kl}
    //     + I_1\left(\delta_{ij}\delta_{kl}
    //     - \tfrac12(\delta_{ik}\delta_{jl} + \delta_{il}\delta_{jk})\right).
    // @f]
    // The tests compare the result with the six-variable route of deal.II's
    // AD helper (NeoHookeanEnergyTest.FixedSizeADEqualsADHelper).
    using Invariants = internal::StrainInvariants<double>;

    // The invariants as Sacado variables 0, 1, 2, and $d$ from them.
    template <typename ADNumber, typename MakeVariable>
    internal::StrainInvariants<ADNumber>
    independent_invariants(const Invariants   &values,
                           const MakeVariable &variable)
    {
      internal::StrainInvariants<ADNumber> invariants;
      invariants.I1 = variable(0, values.I1);
      invariants.I2 = variable(1, values.I2);
      invariants.I3 = variable(2, values.I3);
      invariants.d =
        2. * invariants.I1 + 4. * invariants.I2 + 8. * invariants.I3;
      return invariants;
    }

    SymmetricTensor<2, 3>
    cofactor(const SymmetricTensor<2, 3> &E)
    {
      SymmetricTensor<2, 3> cof;
      cof[0][0] = E[1][1] * E[2][2] - E[1][2] * E[1][2];
      cof[1][1] = E[0][0] * E[2][2] - E[0][2] * E[0][2];
      cof[2][2] = E[0][0] * E[1][1] - E[0][1] * E[0][1];
      cof[0][1] = E[1][2] * E[0][2] - E[0][1] * E[2][2];
      cof[0][2] = E[0][1] * E[1][2] - E[1][1] * E[0][2];
      cof[1][2] = E[0][1] * E[0][2] - E[0][0] * E[1][2];
      return cof;
    }

    // `psi` maps the invariants (of any number type) to the energy; with
    // `with_tangent` the response gets $\mathcal C$ too.
    template <typename EnergyFunction>
    void
    differentiate_through_invariants(const SymmetricTensor<2, 3> &E,
                                     const EnergyFunction        &psi,
                                     const bool                   with_tangent,
                                     MaterialResponse<3>         &response)
    {
      const Invariants values = internal::strain_invariants(E);
      double           psi_a[3], psi_ab[3][3];
      if (with_tangent)
        {
          using Inner          = Sacado::CacheFad::SFad<double, 3>;
          using ADNumber       = Sacado::CacheFad::SFad<Inner, 3>;
          const ADNumber value = psi(independent_invariants<ADNumber>(
            values, [](const unsigned int a, const double x) {
              return ADNumber(3, a, Inner(3, a, x));
            }));
          response.energy      = value.val().val();
          for (unsigned int a = 0; a < 3; ++a)
            {
              psi_a[a] = value.dx(a).val();
              for (unsigned int b = 0; b < 3; ++b)
                psi_ab[a][b] = value.dx(a).dx(b);
            }
        }
      else
        {
          using ADNumber       = Sacado::CacheFad::SFad<double, 3>;
          const ADNumber value = psi(independent_invariants<ADNumber>(
            values, [](const unsigned int a, const double x) {
              return ADNumber(3, a, x);
            }));
          response.energy      = value.val();
          for (unsigned int a = 0; a < 3; ++a)
            psi_a[a] = value.dx(a);
        }

      // The three tensors $\mathbf A_a$ by their six independent components
      // (in the order of unrolled_to_component_indices()), and $\mathbf E$
      // in full.
      static constexpr unsigned int row[6] = {0, 1, 2, 0, 0, 1};
      static constexpr unsigned int col[6] = {0, 1, 2, 1, 2, 2};
      double                        e[3][3];
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = 0; j < 3; ++j)
          e[i][j] = E[i][j];
      const SymmetricTensor<2, 3> cof = cofactor(E);
      double                      A[3][6];
      for (unsigned int m = 0; m < 6; ++m)
        {
          const double identity = (m < 3) ? 1. : 0.;
          A[0][m]               = identity;
          A[1][m]               = values.I1 * identity - e[row[m]][col[m]];
          A[2][m]               = cof.access_raw_entry(m);
          response.second_piola.access_raw_entry(m) =
            psi_a[0] * A[0][m] + psi_a[1] * A[1][m] + psi_a[2] * A[2][m];
        }
      if (!with_tangent)
        return;

      // $\sum_b\psi_{ab}\mathbf A_b$ once per a, then entry by entry: the
      // tangent stores the 6 x 6 pairs of index pairs (its raw entry 6m + n
      // is that of the pairs m and n), and is symmetric.
      double B[3][6];
      for (unsigned int a = 0; a < 3; ++a)
        for (unsigned int m = 0; m < 6; ++m)
          B[a][m] = psi_ab[a][0] * A[0][m] + psi_ab[a][1] * A[1][m] +
                    psi_ab[a][2] * A[2][m];
      const auto delta = [](const unsigned int i, const unsigned int j) {
        return (i == j) ? 1. : 0.;
      };
      for (unsigned int m = 0; m < 6; ++m)
        {
          const unsigned int i = row[m], j = col[m];
          for (unsigned int n = m; n < 6; ++n)
            {
              const unsigned int k = row[n], l = col[n];
              const double       second_invariant_hessian =
                delta(i, j) * delta(k, l) -
                0.5 * (delta(i, k) * delta(j, l) + delta(i, l) * delta(j, k));
              const double K =
                0.5 * (delta(i, k) * e[j][l] + delta(i, l) * e[j][k] +
                       e[i][k] * delta(j, l) + e[i][l] * delta(j, k)) -
                e[i][j] * delta(k, l) - delta(i, j) * e[k][l] +
                values.I1 * second_invariant_hessian;
              const double value = psi_a[1] * second_invariant_hessian +
                                   psi_a[2] * K + A[0][m] * B[0][n] +
                                   A[1][m] * B[1][n] + A[2][m] * B[2][n];
              response.material_tangent.access_raw_entry(6 * m + n) = value;
              response.material_tangent.access_raw_entry(6 * n + m) = value;
            }
        }
    }
  } // namespace



  template <int dim>
  void
  NeoHookeanEnergy<dim>::evaluate(const Tensor<2, dim>  &displacement_gradient,
                                  MaterialResponse<dim> &response) const
  {
    differentiate(displacement_gradient, true, response);
  }



  template <int dim>
  void
  NeoHookeanEnergy<dim>::evaluate_stress(
    const Tensor<2, dim>  &displacement_gradient,
    MaterialResponse<dim> &response) const
  {
    differentiate(displacement_gradient, false, response);
  }



  // The energy in its invariants in 3D, in the components of $\mathbf E$
  // otherwise, differentiated once or twice.
  template <int dim>
  void
  NeoHookeanEnergy<dim>::differentiate(
    const Tensor<2, dim>  &displacement_gradient,
    const bool             with_tangent,
    MaterialResponse<dim> &response) const
  {
    const SymmetricTensor<2, dim> E =
      green_lagrange_strain(displacement_gradient);
    if constexpr (dim == 3)
      differentiate_through_invariants(
        E,
        [this](const auto &invariants) {
          return energy_of_invariants(invariants);
        },
        with_tangent,
        response);
    else if (with_tangent)
      differentiate_twice<dim>(
        E, [this](const auto &E_ad) { return energy(E_ad); }, response);
    else
      differentiate_once<dim>(
        E, [this](const auto &E_ad) { return energy(E_ad); }, response);
  }



  // @sect4{The pieces of the mean-dilatation formulation}
  //
  // The pressure term $p\,(J - 1)$ is differentiated with the isochoric
  // energy, with $J - 1$ written as $d/(1 + \sqrt{1 + d})$ so that it has
  // all its digits at small strain. The energy of the response is then
  // replaced by the isochoric energy alone.
  template <int dim>
  void
  NeoHookeanEnergy<dim>::evaluate_with_pressure(
    const Tensor<2, dim>  &displacement_gradient,
    const double           pressure,
    const bool             with_tangent,
    MaterialResponse<dim> &response) const
  {
    // In 1D and 2D the energy is the isochoric energy, and there is no
    // pressure term. In 3D the energy of the response is the isochoric
    // one, taken from the differentiated energy before the pressure term
    // is added.
    if constexpr (dim != 3)
      {
        (void)pressure;
        differentiate(displacement_gradient, with_tangent, response);
      }
    else
      {
        double isochoric = 0.;
        // (Every intermediate is stored as a number of the AD type: a
        // single expression returned from the lambda would leave Sacado's
        // expression templates referring to destroyed temporaries.)
        differentiate_through_invariants(
          green_lagrange_strain(displacement_gradient),
          [this, pressure, &isochoric](const auto &invariants) {
            using std::sqrt;
            using Number        = std::decay_t<decltype(invariants.d)>;
            const Number root   = sqrt(1. + invariants.d);
            const Number change = invariants.d / (1. + root);
            Number result = mu * internal::isochoric_energy_3d(invariants);
            isochoric     = internal::scalar_value(result);
            result += pressure * change;
            return result;
          },
          with_tangent,
          response);
        response.energy = isochoric;
      }
  }



  template <int dim>
  double
  NeoHookeanEnergy<dim>::volumetric_energy(const double t) const
  {
    return (dim == 3) ? 0.25 * kappa * internal::d_minus_log1p(t * (2. + t))
                      : 0.;
  }



  template <int dim>
  double
  NeoHookeanEnergy<dim>::volumetric_pressure(const double t) const
  {
    return (dim == 3) ? 0.5 * kappa * t * (2. + t) / (1. + t) : 0.;
  }



  template <int dim>
  double
  NeoHookeanEnergy<dim>::volumetric_stiffness(const double t) const
  {
    return (dim == 3) ? 0.5 * kappa * (1. + 1. / ((1. + t) * (1. + t))) : 0.;
  }



  template <int dim>
  double
  NeoHookeanEnergy<dim>::volume_change(const SymmetricTensor<2, dim> &E)
  {
    if constexpr (dim == 3)
      {
        const double d = internal::strain_invariants(E).d;
        return d / (1. + std::sqrt(1. + d));
      }
    else
      return 0.;
  }



  // The helper class ScalarFunction registers the components of $\mathbf
  // E$ as independent variables and takes care of the symmetric storage
  // itself: the gradient with respect to a SymmetricTensor comes back as
  // the tensor $\partial\Psi/\partial\mathbf E$.
  template <int dim>
  void
  NeoHookeanEnergy<dim>::evaluate_with_ad_helper(
    const Tensor<2, dim>  &displacement_gradient,
    MaterialResponse<dim> &response) const
  {
    constexpr Differentiation::AD::NumberTypes ad_type_code =
      Differentiation::AD::NumberTypes::sacado_dfad_dfad;
    using ADHelper =
      Differentiation::AD::ScalarFunction<dim, ad_type_code, double>;
    using ADNumber = typename ADHelper::ad_type;

    const FEValuesExtractors::SymmetricTensor<2> E_extractor(0);
    const SymmetricTensor<2, dim>                E =
      green_lagrange_strain(displacement_gradient);

    ADHelper ad_helper(SymmetricTensor<2, dim>::n_independent_components);
    ad_helper.register_independent_variable(E, E_extractor);
    const SymmetricTensor<2, dim, ADNumber> E_ad =
      ad_helper.get_sensitive_variables(E_extractor);

    ad_helper.register_dependent_variable(energy(E_ad));

    const unsigned int n = SymmetricTensor<2, dim>::n_independent_components;
    Vector<double>     dpsi(n);
    FullMatrix<double> d2psi(n, n);
    response.energy = ad_helper.compute_value();
    ad_helper.compute_gradient(dpsi);
    ad_helper.compute_hessian(d2psi);
    response.second_piola =
      ad_helper.extract_gradient_component(dpsi, E_extractor);
    response.material_tangent =
      ad_helper.extract_hessian_component(d2psi, E_extractor, E_extractor);
  }



  // @sect4{Closed forms for the tests}
  //
  // The first Piola-Kirchhoff stress of the three energies, differentiated
  // by hand:
  // @f[
  //   \mathbf P_{3D} = \mu J^{-2/3}\left(\mathbf F
  //        - \tfrac13\,\mathrm{tr}\,\mathbf C\,\mathbf F^{-T}\right)
  //        + \tfrac{\kappa}{2}\left(J^2 - 1\right)\mathbf F^{-T},\quad
  //   \mathbf P_{2D} = \mu\left(\mathbf F - J^{-2}\mathbf F^{-T}\right),\quad
  //   P_{1D} = \mu\left(\lambda - \lambda^{-2}\right).
  // @f]
  template <int dim>
  Tensor<2, dim>
  NeoHookeanEnergy<dim>::first_piola_closed_form(const Tensor<2, dim> &F) const
  {
    const double         J      = determinant(F);
    const Tensor<2, dim> F_invT = transpose(invert(F));
    if constexpr (dim == 3)
      {
        const double I1 = scalar_product(F, F);
        return mu * std::pow(J, -2. / 3.) * (F - I1 / 3. * F_invT) +
               0.5 * kappa * (J * J - 1.) * F_invT;
      }
    else if constexpr (dim == 2)
      return mu * (F - 1. / (J * J) * F_invT);
    else
      {
        Tensor<2, dim> P;
        P[0][0] = mu * (F[0][0] - 1. / (F[0][0] * F[0][0]));
        return P;
      }
  }



  template <int dim>
  double
  NeoHookeanEnergy<dim>::volume_ratio(const Tensor<2, dim> &F) const
  {
    return (dim == 3) ? determinant(F) : 1.;
  }



  template <int dim>
  SymmetricTensor<2, dim>
  NeoHookeanEnergy<dim>::cauchy_stress(const Tensor<2, dim>          &F,
                                       const SymmetricTensor<2, dim> &S) const
  {
    return symmetrize(F * Tensor<2, dim>(S) * transpose(F)) / volume_ratio(F);
  }



  template <int dim>
  Tensor<4, dim>
  first_piola_tangent(const Tensor<2, dim>          &F,
                      const SymmetricTensor<2, dim> &S,
                      const SymmetricTensor<4, dim> &CC)
  {
    Tensor<4, dim> A;
    for (unsigned int i = 0; i < dim; ++i)
      for (unsigned int J = 0; J < dim; ++J)
        for (unsigned int k = 0; k < dim; ++k)
          for (unsigned int L = 0; L < dim; ++L)
            {
              double value = (i == k) ? S[J][L] : 0.;
              for (unsigned int I = 0; I < dim; ++I)
                for (unsigned int K = 0; K < dim; ++K)
                  value += F[i][I] * CC[I][J][K][L] * F[k][K];
              A[i][J][k][L] = value;
            }
    return A;
  }



  // The eigenvalues and eigenvectors of the at most 6 x 6 matrix, in the
  // way of LAPACK's dsyev but without its calls: a Householder reduction to
  // tridiagonal form, then implicit symmetric QR steps with Wilkinson's
  // shift (Golub and Van Loan, Matrix Computations, sections 8.3.1 and
  // 8.3.5), the orthogonal transformations collected in Q so that M = Q T
  // Q^T throughout. For these matrices that is about ten QR steps, and
  // 2.4 times faster than the cyclic Jacobi method used before
  // (doc/performance_discussion.md, item 38). Nothing is allocated.
  template <int dim>
  SymmetricTensor<4, dim>
  positive_semidefinite_part(const SymmetricTensor<4, dim> &CC)
  {
    constexpr unsigned int n = dim * (dim + 1) / 2;
    // The index pairs of the Mandel vector and their weights.
    std::array<std::pair<unsigned int, unsigned int>, n> pairs;
    std::array<double, n>                                weight;
    for (unsigned int a = 0; a < n; ++a)
      {
        const TableIndices<2> indices =
          SymmetricTensor<2, dim>::unrolled_to_component_indices(a);
        pairs[a]  = {indices[0], indices[1]};
        weight[a] = (pairs[a].first == pairs[a].second) ? 1. : std::sqrt(2.);
      }
    double T[n][n], Q[n][n];
    for (unsigned int a = 0; a < n; ++a)
      for (unsigned int b = 0; b < n; ++b)
        T[a][b] =
          weight[a] * weight[b] *
          CC[pairs[a].first][pairs[a].second][pairs[b].first][pairs[b].second];

    // Most points are in a state where the tangent is positive definite,
    // and then it is its own positive part. A Cholesky factorization of M
    // (a few dozen operations, against a few thousand for the eigenvectors)
    // tells: it succeeds exactly when all eigenvalues are positive.
    {
      double L[n][n]           = {};
      bool   positive_definite = true;
      for (unsigned int j = 0; j < n && positive_definite; ++j)
        {
          double pivot = T[j][j];
          for (unsigned int k = 0; k < j; ++k)
            pivot -= L[j][k] * L[j][k];
          if (!(pivot > 0.))
            {
              positive_definite = false;
              break;
            }
          L[j][j] = std::sqrt(pivot);
          for (unsigned int i = j + 1; i < n; ++i)
            {
              double value = T[i][j];
              for (unsigned int k = 0; k < j; ++k)
                value -= L[i][k] * L[j][k];
              L[i][j] = value / L[j][j];
            }
        }
      if (positive_definite)
        return CC;
    }
    // Otherwise the eigenvectors, from Q = I.
    double norm_square = 0.;
    for (unsigned int a = 0; a < n; ++a)
      for (unsigned int b = 0; b < n; ++b)
        {
          norm_square += T[a][b] * T[a][b];
          Q[a][b] = (a == b) ? 1. : 0.;
        }

    // The reflection $\mathbf H = \mathbf I - \beta\mathbf v\mathbf v^T$ of
    // column k maps its part below the subdiagonal onto the subdiagonal:
    // $\mathbf T \leftarrow \mathbf H\mathbf T\mathbf H = \mathbf T -
    // \mathbf v\mathbf w^T - \mathbf w\mathbf v^T$ with $\mathbf w =
    // \mathbf p - \frac12\beta(\mathbf v\cdot\mathbf p)\mathbf v$,
    // $\mathbf p = \beta\mathbf T\mathbf v$; and $\mathbf Q \leftarrow
    // \mathbf Q\mathbf H$.
    for (unsigned int k = 0; k + 2 < n; ++k)
      {
        double v[n] = {}, below = 0.;
        for (unsigned int i = k + 2; i < n; ++i)
          {
            v[i] = T[i][k];
            below += v[i] * v[i];
          }
        if (!(below > 0.))
          continue;
        const double sub = T[k + 1][k];
        const double alpha =
          (sub > 0. ? -1. : 1.) * std::sqrt(below + sub * sub);
        v[k + 1]          = sub - alpha;
        const double beta = 2. / (below + v[k + 1] * v[k + 1]);
        double       p[n] = {}, v_dot_p = 0.;
        for (unsigned int i = k + 1; i < n; ++i)
          {
            for (unsigned int j = k + 1; j < n; ++j)
              p[i] += T[i][j] * v[j];
            p[i] *= beta;
            v_dot_p += v[i] * p[i];
          }
        for (unsigned int i = k + 1; i < n; ++i)
          p[i] -= 0.5 * beta * v_dot_p * v[i];
        for (unsigned int i = k + 1; i < n; ++i)
          for (unsigned int j = k + 1; j < n; ++j)
            T[i][j] -= v[i] * p[j] + p[i] * v[j];
        T[k + 1][k] = T[k][k + 1] = alpha;
        for (unsigned int i = k + 2; i < n; ++i)
          T[i][k] = T[k][i] = 0.;
        for (unsigned int i = 0; i < n; ++i)
          {
            double q_dot_v = 0.;
            for (unsigned int j = k + 1; j < n; ++j)
              q_dot_v += Q[i][j] * v[j];
            for (unsigned int j = k + 1; j < n; ++j)
              Q[i][j] -= beta * q_dot_v * v[j];
          }
      }

    // QR steps on the trailing unreduced block [l, m], each a chase of the
    // bulge down the diagonal by rotations of rows and columns k and k + 1
    // (only entries k - 1 to k + 2 of them are nonzero; r > 0, since z is
    // first a subdiagonal entry of the unreduced block and then the bulge,
    // s times the next one). A subdiagonal entry below 1e-16 of the
    // matrix's norm is set to zero: its eigenvalues then have all the
    // digits the matrix has.
    const double tolerance = 1e-16 * std::sqrt(norm_square);
    for (unsigned int m = n - 1, steps = 0; m > 0 && steps < 30 * n;)
      {
        if (std::abs(T[m][m - 1]) <= tolerance)
          {
            T[m][m - 1] = T[m - 1][m] = 0.;
            --m;
            continue;
          }
        unsigned int l = m - 1;
        while (l > 0 && std::abs(T[l][l - 1]) > tolerance)
          --l;
        ++steps;
        // Wilkinson's shift: the eigenvalue of the trailing 2 x 2 block
        // nearer to its last diagonal entry.
        const double delta = 0.5 * (T[m - 1][m - 1] - T[m][m]);
        const double e2    = T[m][m - 1] * T[m][m - 1];
        const double shift =
          T[m][m] - e2 / (delta + (delta >= 0. ? 1. : -1.) *
                                    std::sqrt(delta * delta + e2));
        double x = T[l][l] - shift, z = T[l + 1][l];
        for (unsigned int k = l; k < m; ++k)
          {
            const double       r = std::sqrt(x * x + z * z);
            const double       c = x / r, s = z / r;
            const unsigned int first = (k > l) ? k - 1 : l;
            const unsigned int last  = std::min(k + 2, m);
            for (unsigned int j = first; j <= last; ++j)
              {
                const double a = T[k][j], b = T[k + 1][j];
                T[k][j]     = c * a + s * b;
                T[k + 1][j] = c * b - s * a;
              }
            for (unsigned int i = first; i <= last; ++i)
              {
                const double a = T[i][k], b = T[i][k + 1];
                T[i][k]     = c * a + s * b;
                T[i][k + 1] = c * b - s * a;
              }
            for (unsigned int i = 0; i < n; ++i)
              {
                const double a = Q[i][k], b = Q[i][k + 1];
                Q[i][k]     = c * a + s * b;
                Q[i][k + 1] = c * b - s * a;
              }
            if (k + 1 < m)
              {
                x = T[k + 1][k];
                z = T[k + 2][k];
              }
          }
      }

    // Reassemble with the negative eigenvalues dropped: the eigenvectors
    // are the columns of Q.
    SymmetricTensor<4, dim> positive;
    for (unsigned int a = 0; a < n; ++a)
      for (unsigned int b = 0; b < n; ++b)
        {
          double value = 0.;
          for (unsigned int k = 0; k < n; ++k)
            if (T[k][k] > 0.)
              value += Q[a][k] * T[k][k] * Q[b][k];
          positive[pairs[a].first][pairs[a].second][pairs[b].first]
                  [pairs[b].second] = value / (weight[a] * weight[b]);
        }
    return positive;
  }



  // The explicit instantiations for the three dimensions, in one place.
#define SOFT_ROBOT_INSTANTIATE(dim)                                 \
  template class NeoHookeanEnergy<dim>;                             \
  template Tensor<4, dim> first_piola_tangent<dim>(                 \
    const Tensor<2, dim> &,                                         \
    const SymmetricTensor<2, dim> &,                                \
    const SymmetricTensor<4, dim> &);                               \
  template SymmetricTensor<4, dim> positive_semidefinite_part<dim>( \
    const SymmetricTensor<4, dim> &);

  SOFT_ROBOT_INSTANTIATE(1)
  SOFT_ROBOT_INSTANTIATE(2)
  SOFT_ROBOT_INSTANTIATE(3)
#undef SOFT_ROBOT_INSTANTIATE
} // namespace SoftRobot
