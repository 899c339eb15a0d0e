// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{How a cavity is closed, and along which axis its volume is taken}
//
// A gas cavity needs its volume, and the volume of a region is an integral
// over its whole boundary. By the divergence theorem with the field
// $(x_k - c)\,\mathbf e_k$, whose divergence is one,
// @f[
//   V = \oint_{\partial G} (x_k - c)\,n_k\,da
//     = \int_{\Gamma_c} (x_k - c)\,n_k\,da + \int_{\Gamma_\text{close}}
//       (x_k - c)\,n_k\,da ,
// @f]
// with $\mathbf n$ the outer normal of the gas region $G$. Only the cavity
// surface $\Gamma_c$ is meshed (boundary 2 of the bellows); the rest of
// $\partial G$ closes it: the symmetry planes of a quarter or half model,
// the inlet opening at the clamped base. The second integral vanishes
// where the closing surface is parallel to the axis $\mathbf e_k$ ($n_k =
// 0$) or lies in the plane $x_k = c$. The program therefore requires that
// every open edge of the cavity surface -- an edge of one cavity face only
// -- lies on a coordinate plane $x_j = \text{const}$ on which the normal
// displacement $u_j$ is fixed (`Fixed components`: a symmetry plane, or a
// clamped face), so that the closing surface is that plane and stays
// there, and it chooses an axis $k$ and the origin $c$ such that
// - the planes with $j \neq k$ are parallel to $\mathbf e_k$ and add
//   nothing, and
// - all open edges on planes normal to $\mathbf e_k$ lie in one plane,
//   $x_k = c$, which adds nothing either (an edge of a clamped face lies
//   in several coordinate planes; the one normal to $\mathbf e_k$ is taken
//   for it, the plane of the opening).
// For the bellows (quarter model) that is $k = x$ and $c = -15.25$, the
// plane of the clamped base, which holds the inlet's rim; the symmetry
// planes $y = 0$ and $z = 0$ are parallel to $x$. A cavity without open
// edges is closed by itself, and then $V$ does not depend on $c$ at all;
// $c = 0$ is taken. A cavity whose closing planes normal to $\mathbf e_k$
// are not given (a piston in a channel, whose far end is a rigid wall that
// is not meshed) gets $c = 0$ too: its volume is then counted from the plane
// $x_k = 0$, and the Dead volume holds the rest.
//
// A cavity surface with an edge on no such plane -- on a free surface, or
// on a plane whose normal displacement is free -- is not closed: its
// closing surface would move in a way nothing determines, and the volume
// computed from the cavity surface alone would depend on the origin of
// the integral. That is an input error, found before anything is written,
// which names the entry and the place of such an edge.
//
// In 2D the open "edges" are the end points of the cavity's boundary
// curve; in 1D there are none.
//
// Implemented in source/physics/cavity_closure.cc.

#ifndef soft_robot_physics_cavity_closure_h
#define soft_robot_physics_cavity_closure_h

#include <core/parameters.h>
#include <deal.II/base/point.h>
#include <deal.II/grid/tria.h>
#include <string>

namespace SoftRobot
{
  using namespace dealii;

  struct CavityClosure
  {
    // Whether every open edge lies on a fixed coordinate plane.
    bool closed = true;
    // The axis $k$ and the origin $c$ of the volume integral.
    unsigned int axis   = 0;
    double       origin = 0.;
    // The number of open edges, and where the first one that is not
    // closed lies (if any), for the messages.
    unsigned int n_open_edges = 0;
    std::string  open_edge;
    // The coordinate planes that close the cavity, e.g. "y = 0, x = -15.25".
    std::string closing_planes;
  };

  // The closure of the surface of `Pneumatics/Pressure boundary ids` in the
  // mesh, with the fixed components of `Loads and constraints/Fixed
  // components`. Every process holds the whole mesh
  // (parallel::shared::Triangulation), so every process finds the same.
  template <int dim>
  CavityClosure
  find_cavity_closure(const Parameters::AllParameters &parameters,
                      const Triangulation<dim>        &triangulation);
} // namespace SoftRobot

#endif
