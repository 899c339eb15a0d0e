// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{What an assembly reports besides its vectors and matrices}
//
// Newton's method needs more of an evaluation of the residual than the
// vector itself: the size of the forces that balance in it, against which
// round-off is judged; for static problems the total potential energy,
// which its line search decreases; and whether the trial state is physical
// at all.

#ifndef soft_robot_assembly_assembly_result_h
#define soft_robot_assembly_assembly_result_h

#include <limits>

namespace SoftRobot
{
  struct AssemblyResult
  {
    // The strain energy of the state, $\int\Psi\,dV$.
    double strain_energy = 0.;
    // The size of the forces that balance in the residual (internal and
    // inertial), against which round-off is judged.
    double force_scale = 0.;
    // For static problems the total potential energy, which Newton's line
    // search then decreases; not a number for the dynamic steps, whose line
    // search decreases the norm of the residual.
    double potential_energy = std::numeric_limits<double>::quiet_NaN();
    // The smallest $\det\mathbf F$ at a quadrature point, and whether one
    // was not positive: a state with an inverted element has no physical
    // meaning and is rejected.
    double min_jacobian         = std::numeric_limits<double>::max();
    bool   inverted_point_found = false;
  };
} // namespace SoftRobot

#endif
