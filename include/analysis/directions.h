// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Directions of motion}
//
// Implemented in source/analysis/directions.cc.
//
// The vertical direction is $x$. The horizontal and depth directions are
// defined by the plane that contains the $x$ axis and best fits the $(y,z)$
// motion: the horizontal direction is the principal direction of the
// covariance of $(u_y, u_z)$, at the angle <code>plane_angle</code> from
// $+y$ towards $+z$ (in $(-\pi/2,\pi/2]$), and the depth direction is the
// plane's normal, such that (vertical, horizontal, depth) is right-handed. A
// one-component record has only the vertical direction, a two-component
// record the vertical and horizontal ($=u_y$) ones.

#ifndef soft_robot_analysis_directions_h
#define soft_robot_analysis_directions_h

#include <analysis/uniform_sampling.h>
#include <string>
#include <vector>

namespace SoftRobot
{
  namespace Analysis
  {
    // One signal per direction, with its name ("vertical", "horizontal",
    // "depth").
    struct DirectionalSignals
    {
      std::vector<std::string>         names;
      std::vector<std::vector<double>> samples;
      double                           plane_angle = 0.;
      // Root mean square of the depth motion over that of the horizontal
      // motion: zero for a motion in a plane through the axis, one for a
      // motion without a preferred plane (then the angle is arbitrary).
      double out_of_plane_ratio = 0.;
    };

    DirectionalSignals
    split_into_directions(const UniformTrajectory &trajectory);
  } // namespace Analysis
} // namespace SoftRobot

#endif
