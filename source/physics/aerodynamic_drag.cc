// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Aerodynamic drag on the body's surface}
//
// See include/physics/aerodynamic_drag.h for the formulas.

#include <Sacado.hpp>
#include <core/config.h>
#include <deal.II/differentiation/ad.h>
#include <physics/aerodynamic_drag.h>


namespace SoftRobot
{
  namespace
  {
    // $\mathbf t_0(\mathbf F, \mathbf v)$ for any number type, so that
    // Sacado can differentiate it. (In 1D the cofactor of the 1 x 1 matrix
    // is one.)
    template <int dim, typename Number>
    Tensor<1, dim, Number>
    drag_traction(const Tensor<2, dim, Number> &F,
                  const Tensor<1, dim, Number> &v,
                  const Tensor<1, dim>         &N,
                  const double                  coefficient)
    {
      using std::abs;
      // The area vector $\mathbf a = J\mathbf F^{-T}\mathbf N$.
      Tensor<1, dim, Number> a;
      if constexpr (dim == 1)
        a[0] = N[0];
      else
        {
          const Number                 J         = determinant(F);
          const Tensor<2, dim, Number> F_inverse = invert(F);
          for (unsigned int i = 0; i < dim; ++i)
            for (unsigned int k = 0; k < dim; ++k)
              a[i] += J * F_inverse[k][i] * N[k];
        }
      Number normal = 0., area_squared = 0.;
      for (unsigned int i = 0; i < dim; ++i)
        {
          normal += v[i] * a[i];
          area_squared += a[i] * a[i];
        }
      const Number scale = -coefficient * abs(normal) * normal / area_squared;
      Tensor<1, dim, Number> t;
      for (unsigned int i = 0; i < dim; ++i)
        t[i] = scale * a[i];
      return t;
    }
  } // namespace



  // @sect4{AerodynamicDrag::AerodynamicDrag}
  template <int dim>
  AerodynamicDrag<dim>::AerodynamicDrag(
    const Parameters::AllParameters &parameters,
    const CellGeometry<dim>         &geometry,
    const Mapping<dim>              &mapping,
    const DoFHandler<dim>           &dof_handler,
    const Quadrature<dim - 1>       &quadrature,
    const bool                       symmetric_tangent)
    : BoundaryFaces<dim>(parameters,
                         geometry,
                         mapping,
                         dof_handler,
                         quadrature,
                         parameters.drag_boundary_ids)
    , boundary_ids(parameters.drag_boundary_ids)
    , coefficient(0.5 * parameters.air_density * parameters.drag_coefficient)
    , symmetric_tangent(symmetric_tangent)
  {
  }



  // @sect4{AerodynamicDrag::traction}
  template <int dim>
  Tensor<1, dim>
  AerodynamicDrag<dim>::traction(const Tensor<2, dim> &F,
                                 const Tensor<1, dim> &v,
                                 const Tensor<1, dim> &N,
                                 Tensor<3, dim>       *d_dF,
                                 Tensor<2, dim>       *d_dv) const
  {
    if (d_dF == nullptr && d_dv == nullptr)
      return drag_traction(F, v, N, coefficient);

    constexpr unsigned int n_variables = dim * dim + dim;
    using ADNumber = Sacado::CacheFad::SFad<double, n_variables>;
    Tensor<2, dim, ADNumber> F_ad;
    Tensor<1, dim, ADNumber> v_ad;
    for (unsigned int a = 0; a < dim; ++a)
      {
        for (unsigned int b = 0; b < dim; ++b)
          F_ad[a][b] = ADNumber(n_variables, a * dim + b, F[a][b]);
        v_ad[a] = ADNumber(n_variables, dim * dim + a, v[a]);
      }
    const Tensor<1, dim, ADNumber> t =
      drag_traction(F_ad, v_ad, N, coefficient);
    Tensor<1, dim> value;
    for (unsigned int c = 0; c < dim; ++c)
      {
        value[c] = t[c].val();
        for (unsigned int a = 0; a < dim; ++a)
          {
            if (d_dF != nullptr)
              for (unsigned int b = 0; b < dim; ++b)
                (*d_dF)[c][a][b] = t[c].dx(a * dim + b);
            if (d_dv != nullptr)
              (*d_dv)[c][a] = t[c].dx(dim * dim + a);
          }
      }
    return value;
  }



  // @sect4{AerodynamicDrag::add_cell_contribution}
  //
  // At each point of the cell's drag faces: $\mathbf F$ and $\mathbf v$
  // from the cell's nodal values, the traction, its nodal forces, and with a
  // matrix its derivatives.
  template <int dim>
  void
  AerodynamicDrag<dim>::add_cell_contribution(
    CellContribution<dim> &local) const
  {
    if (boundary_ids.empty() ||
        first_face[local.cell] == first_face[local.cell + 1])
      return;
    Assert(local.input_values.size() > 1, ExcInternalError());
    const double      *cell_u       = local.input_values[0];
    const double      *cell_v       = local.input_values[1];
    const unsigned int n            = dofs_per_cell;
    const bool         with_matrix  = local.request.matrix;
    const bool         with_damping = local.request.second_matrix;
    const double       c_v          = local.request.velocity_coefficient;
    for (unsigned int face = first_face[local.cell];
         face < first_face[local.cell + 1];
         ++face)
      for (unsigned int q = 0; q < n_q_points; ++q)
        {
          const unsigned int    point = face * n_q_points + q;
          const double         *phi   = &shape_values[point * n];
          const Tensor<1, dim> *grad  = &shape_gradients[point * n];
          Tensor<2, dim>        F;
          Tensor<1, dim>        v;
          for (unsigned int d = 0; d < dim; ++d)
            F[d][d] = 1.;
          for (unsigned int i = 0; i < n; ++i)
            {
              F[components[i]] += cell_u[i] * grad[i];
              v[components[i]] += cell_v[i] * phi[i];
            }
          Tensor<3, dim>       d_dF;
          Tensor<2, dim>       d_dv;
          const bool           derivatives = with_matrix || with_damping;
          const Tensor<1, dim> t           = traction(F,
                                            v,
                                            normals[point],
                                            derivatives ? &d_dF : nullptr,
                                            derivatives ? &d_dv : nullptr);
          const double         w           = weights[point];
          for (unsigned int i = 0; i < n; ++i)
            local.second_force(i) += phi[i] * t[components[i]] * w;
          if (!derivatives)
            continue;
          for (unsigned int i = 0; i < n; ++i)
            for (unsigned int j = 0; j < n; ++j)
              {
                const unsigned int ci = components[i], cj = components[j];
                const double       damping = phi[i] * d_dv[ci][cj] * phi[j] * w;
                if (with_damping)
                  local.second_matrix(i, j) += damping;
                if (with_matrix)
                  {
                    double value = c_v * damping;
                    if (!symmetric_tangent)
                      value += phi[i] * (d_dF[ci][cj] * grad[j]) * w;
                    local.matrix(i, j) += value;
                  }
              }
        }
  }



#define SOFT_ROBOT_INSTANTIATE(dim) template class AerodynamicDrag<dim>;
  SOFT_ROBOT_FOR_EACH_DIMENSION(SOFT_ROBOT_INSTANTIATE)
#undef SOFT_ROBOT_INSTANTIATE
} // namespace SoftRobot
