// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{The motion of the tip}
//
// The quantity a soft-robot experiment tracks: the motion of the tip. For a
// boundary it is the area-weighted mean of the displacement and velocity
// over that surface; for a material region, its centre of mass, i.e. the
// mass-weighted mean. For the actuator the second is the motion of the
// rigid tip block that the reference study tracked with its motion-capture
// markers.
//
// Either mean is a fixed linear functional of the nodal values, $\bar u_d =
// \sum_i w_{d,i} U_i / W$ with $w_{d,i} = \int \omega\,(\mathbf N_i)_d$ over
// the surface or region ($\omega$ the area or mass density times the
// section factor) and $W = \int\omega$. The weights are computed once, so
// that the tip motion of every time step costs $2\,\text{dim}$ scalar
// products.
//
// Implemented in source/output/tip_region.cc.

#ifndef soft_robot_output_tip_region_h
#define soft_robot_output_tip_region_h

#include <core/parameters.h>
#include <deal.II/base/quadrature.h>
#include <deal.II/base/tensor.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/trilinos_vector.h>
#include <functional>
#include <utility>
#include <vector>

namespace SoftRobot
{
  using namespace dealii;

  template <int dim>
  class TipRegion
  {
  public:
    // The weights of the region `Output/Tip region`; `density` gives the
    // density of a material id.
    void
    reinit(const Parameters::AllParameters &parameters,
           const Mapping<dim>              &mapping,
           const DoFHandler<dim>           &dof_handler,
           const Quadrature<dim>           &cell_quadrature,
           const Quadrature<dim - 1>       &face_quadrature,
           const AffineConstraints<double> &constraints,
           const std::function<double(const types::material_id)> &density,
           const MPI_Comm mpi_communicator);

    // The mean displacement and velocity of the region.
    std::pair<Tensor<1, dim>, Tensor<1, dim>>
    motion(const TrilinosWrappers::MPI::Vector &u,
           const TrilinosWrappers::MPI::Vector &v) const;

  private:
    std::vector<TrilinosWrappers::MPI::Vector> weights;
    double                                     total_weight = 0.;
  };
} // namespace SoftRobot

#endif
