// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Guards against runs without physical meaning}
//
// Newton's method converges for loads no body can carry: a dead load of
// five times the shear modulus sends the actuator's tip 2.9 m away at
// 196 m/s, or pushes the body through the base it is clamped to, and the
// run ends as if all were well. The guards below stop such a run (a
// RunAborted, exit code 2; the output so far is kept) with a message that
// says what happened and at what time:
//
// - A state that is not finite, or beyond what the output can store (the
//   VTU files hold single precision), is never written: the run stops
//   before its trajectory row or fields are.
// - The tip runs away: its displacement exceeds `Problem/Run-away
//   displacement` (by default ten times the diagonal of the mesh's
//   bounding box), or its speed `Problem/Run-away speed` (by default ten
//   times the shear wave speed $c_s = \sqrt{\mu/\rho}$ of the softest
//   material, the speed at which a disturbance crosses the body; a tip far
//   faster than that has no motion of the elastic body behind it).
// - The body passes through a fixed boundary: a plane boundary on which
//   the displacement normal to it is fixed (a clamped base, a symmetry
//   plane) is a wall the body stays on one side of. A node that moves
//   beyond its plane by more than 2 % of the body's size (the tolerance
//   keeps the bulging near a clamped edge clear of it) has gone through
//   the support, or through the other half of a symmetric model. Curved
//   fixed boundaries are not checked.
//
// The defaults trigger in none of the scenes of parameters/, whose tips
// move by less than the body's size at a fraction of $c_s$.
//
// Implemented in source/core/plausibility_guard.cc.

#ifndef soft_robot_core_plausibility_guard_h
#define soft_robot_core_plausibility_guard_h

#include <array>
#include <core/parameters.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/lac/trilinos_vector.h>
#include <functional>
#include <string>
#include <vector>

namespace SoftRobot
{
  using namespace dealii;

  template <int dim>
  class PlausibilityGuard
  {
  public:
    // The scales of the body and its materials (`density` gives the density
    // of a material id) and the plane fixed boundaries.
    void
    reinit(const Parameters::AllParameters                       &parameters,
           const Mapping<dim>                                    &mapping,
           const DoFHandler<dim>                                 &dof_handler,
           const std::function<double(const types::material_id)> &density,
           const MPI_Comm mpi_communicator);

    // Collective. Throws RunAborted if `values` (pairs of a name and a
    // value: norms, energies, the tip motion) are not finite or not
    // storable.
    void
    check_finite(
      const double                                       time,
      const std::vector<std::pair<std::string, double>> &values) const;

    // Collective. Throws RunAborted if the tip runs away or the body passes
    // through a fixed boundary.
    void
    check_motion(const double                         time,
                 const Tensor<1, dim>                &tip_displacement,
                 const Tensor<1, dim>                &tip_velocity,
                 const TrilinosWrappers::MPI::Vector &u) const;

    double
    displacement_limit() const
    {
      return max_displacement;
    }
    double
    speed_limit() const
    {
      return max_speed;
    }

  private:
    struct FixedPlane
    {
      unsigned int   boundary_id;
      Point<dim>     point;
      Tensor<1, dim> outward_normal;
    };

    double      max_displacement = 0.;
    double      max_speed        = 0.;
    std::string displacement_origin, speed_origin;
    double      crossing_tolerance = 0.;
    MPI_Comm    mpi_communicator   = MPI_COMM_SELF;

    std::vector<FixedPlane> planes;
    // The locally owned nodes: reference position and the dofs of the
    // displacement components.
    std::vector<Point<dim>>                               node_positions;
    std::vector<std::array<types::global_dof_index, dim>> node_dofs;
  };
} // namespace SoftRobot

#endif
