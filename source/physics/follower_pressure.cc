// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{A pressure on the deformed surface: the follower load}
//
// See include/physics/follower_pressure.h for the formulas.

#include <Sacado.hpp>
#include <core/config.h>
#include <deal.II/base/mpi.h>
#include <deal.II/differentiation/ad.h>
#include <physics/follower_pressure.h>

namespace SoftRobot
{
  namespace
  {
    // $\mathbf a(\mathbf F)$ for any number type, so that Sacado can
    // differentiate it: $-J\mathbf F^{-T}\mathbf N$ in 3D, $-\mathbf
    // F^{-T}\mathbf N$ in the reduced models.
    template <int dim, typename Number>
    Tensor<1, dim, Number>
    gas_area_vector(const Tensor<2, dim, Number> &F, const Tensor<1, dim> &N)
    {
      const Tensor<2, dim, Number> F_inverse = invert(F);
      const Number                 J = (dim == 3) ? determinant(F) : Number(1.);
      Tensor<1, dim, Number>       a;
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int K = 0; K < dim; ++K)
          a[i] -= J * F_inverse[K][i] * N[K];
      return a;
    }
  } // namespace



  // @sect4{FollowerPressure::FollowerPressure}
  //
  // The reference data of the loaded faces are collected by BoundaryFaces;
  // the end load of the reduced models needs their area.
  template <int dim>
  FollowerPressure<dim>::FollowerPressure(
    const Parameters::AllParameters &parameters,
    const CellGeometry<dim>         &geometry,
    const Mapping<dim>              &mapping,
    const DoFHandler<dim>           &dof_handler,
    const Quadrature<dim - 1>       &quadrature,
    const CavityClosure             &closure,
    const bool                       symmetric_tangent)
    : BoundaryFaces<dim>(parameters,
                         geometry,
                         mapping,
                         dof_handler,
                         quadrature,
                         parameters.pressure_boundary_ids)
    , end_load(parameters.equivalent_area > 0.)
    , axis(closure.axis)
    , origin(closure.origin)
    , symmetric_tangent(symmetric_tangent)
    , n_cells(geometry.n_cells)
    , dof_indices(geometry.dof_indices)
  {
    if (end_load)
      {
        const double area = reference_area(dof_handler.get_communicator());
        AssertThrow(area > 0.,
                    ExcMessage(parameters.where() +
                               "Pneumatics/Pressure boundary ids: the "
                               "boundaries carry no area for the end load "
                               "of the Equivalent area."));
        end_load_factor = parameters.equivalent_area / area;
      }
  }



  // @sect4{FollowerPressure::reference_area}
  template <int dim>
  double
  FollowerPressure<dim>::reference_area(const MPI_Comm mpi_communicator) const
  {
    double area = 0.;
    for (const double w : weights)
      area += w;
    return Utilities::MPI::sum(area, mpi_communicator);
  }



  // @sect4{FollowerPressure::area_vector}
  template <int dim>
  Tensor<1, dim>
  FollowerPressure<dim>::area_vector(const Tensor<2, dim> &F,
                                     const Tensor<1, dim> &N,
                                     Tensor<3, dim>       *d_dF) const
  {
    if (end_load)
      {
        if (d_dF != nullptr)
          *d_dF = Tensor<3, dim>();
        return end_load_factor * N;
      }
    if (d_dF == nullptr)
      return gas_area_vector(F, N);

    constexpr unsigned int n_variables = dim * dim;
    using ADNumber = Sacado::CacheFad::SFad<double, n_variables>;
    Tensor<2, dim, ADNumber> F_ad;
    for (unsigned int a = 0; a < dim; ++a)
      for (unsigned int b = 0; b < dim; ++b)
        F_ad[a][b] = ADNumber(n_variables, a * dim + b, F[a][b]);
    const Tensor<1, dim, ADNumber> area = gas_area_vector(F_ad, N);
    Tensor<1, dim>                 value;
    for (unsigned int c = 0; c < dim; ++c)
      {
        value[c] = area[c].val();
        for (unsigned int a = 0; a < dim; ++a)
          for (unsigned int b = 0; b < dim; ++b)
            (*d_dF)[c][a][b] = area[c].dx(a * dim + b);
      }
    return value;
  }



  // @sect4{FollowerPressure::integrate}
  //
  // One pass over the loaded faces: at each point $\mathbf F$ and $\mathbf
  // x$ from the cell's nodal values, the area vector, its share of the
  // volume and of $\mathbf g$.
  template <int dim>
  double
  FollowerPressure<dim>::integrate(const TrilinosWrappers::MPI::Vector &u,
                                   const AffineConstraints<double> &constraints,
                                   TrilinosWrappers::MPI::Vector   &gradient,
                                   const MPI_Comm mpi_communicator) const
  {
    const unsigned int                   n = dofs_per_cell;
    std::vector<double>                  cell_u(n);
    Vector<double>                       cell_gradient(n);
    std::vector<types::global_dof_index> cell_dofs(n);
    double                               volume = 0.;
    gradient                                    = 0.;
    for (unsigned int cell = 0; cell < n_cells; ++cell)
      {
        if (first_face[cell] == first_face[cell + 1])
          continue;
        for (unsigned int i = 0; i < n; ++i)
          {
            cell_dofs[i] = dof_indices[cell * n + i];
            cell_u[i]    = u(cell_dofs[i]);
          }
        cell_gradient = 0.;
        for (unsigned int face = first_face[cell]; face < first_face[cell + 1];
             ++face)
          for (unsigned int q = 0; q < n_q_points; ++q)
            {
              const unsigned int    point = face * n_q_points + q;
              const double         *phi   = &shape_values[point * n];
              const Tensor<1, dim> *grad  = &shape_gradients[point * n];
              Tensor<2, dim>        F;
              Tensor<1, dim>        displacement;
              for (unsigned int d = 0; d < dim; ++d)
                F[d][d] = 1.;
              for (unsigned int i = 0; i < n; ++i)
                {
                  F[components[i]] += cell_u[i] * grad[i];
                  displacement[components[i]] += cell_u[i] * phi[i];
                }
              const Tensor<1, dim> a = area_vector(F, normals[point]);
              const double         w = weights[point];
              volume +=
                end_load ? (displacement * a) * w
                         : (points[point][axis] + displacement[axis] - origin) *
                             a[axis] * w;
              for (unsigned int i = 0; i < n; ++i)
                cell_gradient(i) += phi[i] * a[components[i]] * w;
            }
        constraints.distribute_local_to_global(cell_gradient,
                                               cell_dofs,
                                               gradient);
      }
    gradient.compress(VectorOperation::add);
    return Utilities::MPI::sum(volume, mpi_communicator);
  }



  // @sect4{FollowerPressure::add_cell_contribution}
  template <int dim>
  void
  FollowerPressure<dim>::add_cell_contribution(CellContribution<dim> &local,
                                               const double pressure) const
  {
    if (end_load || !local.request.matrix || pressure == 0. ||
        first_face[local.cell] == first_face[local.cell + 1])
      return;
    const double      *cell_u = local.input_values[0];
    const unsigned int n      = dofs_per_cell;
    for (unsigned int face = first_face[local.cell];
         face < first_face[local.cell + 1];
         ++face)
      for (unsigned int q = 0; q < n_q_points; ++q)
        {
          const unsigned int    point = face * n_q_points + q;
          const double         *phi   = &shape_values[point * n];
          const Tensor<1, dim> *grad  = &shape_gradients[point * n];
          Tensor<2, dim>        F;
          for (unsigned int d = 0; d < dim; ++d)
            F[d][d] = 1.;
          for (unsigned int i = 0; i < n; ++i)
            F[components[i]] += cell_u[i] * grad[i];
          Tensor<3, dim> d_dF;
          area_vector(F, normals[point], &d_dF);
          const double w = -pressure * weights[point];
          for (unsigned int i = 0; i < n; ++i)
            for (unsigned int j = 0; j < n; ++j)
              {
                const unsigned int ci = components[i], cj = components[j];
                double             value = phi[i] * (d_dF[ci][cj] * grad[j]);
                if (symmetric_tangent)
                  value = 0.5 * (value + phi[j] * (d_dF[cj][ci] * grad[i]));
                local.matrix(i, j) += value * w;
              }
        }
  }



#define SOFT_ROBOT_INSTANTIATE(dim) template class FollowerPressure<dim>;
  SOFT_ROBOT_FOR_EACH_DIMENSION(SOFT_ROBOT_INSTANTIATE)
#undef SOFT_ROBOT_INSTANTIATE
} // namespace SoftRobot
