// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Directions of motion}
//
// A pendulum swing of the robot happens in a plane through its vertical
// axis. Among the planes through the $x$ axis, the one with normal
// $\mathbf n = (0,-\sin\theta,\cos\theta)$ fits the motion best if it
// minimises the mean square of the out-of-plane displacement
// $\mathbf n\cdot\mathbf u$, i.e. if $\mathbf n$ is the eigenvector of the
// smaller eigenvalue of the $(y,z)$ covariance
// @f[
//   C = \begin{pmatrix}C_{yy}&C_{yz}\\C_{yz}&C_{zz}\end{pmatrix}, \qquad
//   C_{ab} = \frac1N\sum_{i}(u_{a,i}-\bar u_a)(u_{b,i}-\bar u_b).
// @f]
// The in-plane (horizontal) direction $(\cos\theta,\sin\theta)$ is then the
// eigenvector of the larger eigenvalue, the principal direction, at the
// angle
// @f[
//   \theta = \tfrac12\operatorname{atan2}(2C_{yz},\,C_{yy}-C_{zz})
//   \in (-\pi/2, \pi/2].
// @f]
// The covariance is taken about the mean, i.e. about the static offset that
// the spectral analysis removes anyway; for a swing about the axis this is
// the same as the second moment about the axis.
//
// The eigenvalues $\lambda_- \le \lambda_+$ are the mean squares of the
// depth and the horizontal motion; their ratio tells how planar the motion
// is. The sign of the horizontal direction is fixed by the range of
// $\theta$: its $y$ component is positive (or, for $\theta=\pi/2$, it
// points along $+z$). The depth direction $(-\sin\theta, \cos\theta)$ is
// the horizontal one turned by $+90^\circ$ about $x$, so that
// $\mathbf e_x \times \mathbf e_\text{horizontal} = \mathbf e_\text{depth}$.

#include <algorithm>
#include <analysis/directions.h>
#include <analysis/utilities.h>
#include <cmath>
#include <stdexcept>

namespace SoftRobot
{
  namespace Analysis
  {
    namespace
    {
      // @sect4{The principal direction of the (y,z) motion}
      //
      // For a symmetric $2\times2$ matrix the eigenproblem has the closed
      // form above: the angle of the principal direction from
      // $\operatorname{atan2}$, which is accurate for any ratio of its
      // arguments and already lies in the required range, and the
      // eigenvalues
      // @f[
      //   \lambda_\pm = \tfrac12(C_{yy}+C_{zz}) \pm
      //   \sqrt{\tfrac14(C_{yy}-C_{zz})^2 + C_{yz}^2}.
      // @f]
      // The smaller one loses digits to cancellation when the motion is
      // nearly planar, $\lambda_- \ll \lambda_+$; its absolute error is then
      // of order $\epsilon\lambda_+$, i.e. the ratio of the rms values is
      // accurate to about $10^{-8}$, far more than the three digits it is
      // reported with. Without any $(y,z)$ motion, or for a circular one,
      // the angle is arbitrary ($\operatorname{atan2}(0,0)$ gives
      // $\theta = 0$); the ratio then says so.
      //
      // This is the one eigenproblem of the analysis, and unlike the least
      // squares problems it is not handed to LAPACK: the closed form is
      // exact up to the rounding of a few operations, needs no iteration,
      // and fixes the orientation of the direction and the degenerate case
      // by itself, both of which would have to be added to the eigenvectors
      // that <code>dsyev</code> returns. Its result would also not be the
      // same to the last bit, and the depth signal of a nearly planar
      // motion, a small difference of large products, would show that in
      // its spectrum.
      struct PrincipalDirection
      {
        double angle;
        double out_of_plane_ratio;
      };



      PrincipalDirection
      principal_direction(const double c_yy,
                          const double c_zz,
                          const double c_yz)
      {
        const double half_trace = 0.5 * (c_yy + c_zz);
        const double radius =
          std::sqrt(0.25 * (c_yy - c_zz) * (c_yy - c_zz) + c_yz * c_yz);
        const double major = half_trace + radius;
        const double minor = std::max(0., half_trace - radius);

        PrincipalDirection direction;
        direction.angle = 0.5 * std::atan2(2. * c_yz, c_yy - c_zz);
        direction.out_of_plane_ratio =
          (major > 0. ? std::sqrt(minor / major) : 0.);
        return direction;
      }
    } // namespace



    // @sect4{Splitting a trajectory into directions}
    //
    // The vertical signal is $u_x$ for every record; a planar record adds
    // $u_y$ as the horizontal one. A three-component record is projected
    // onto the principal direction and the normal of the best-fit plane.
    DirectionalSignals
    split_into_directions(const UniformTrajectory &trajectory)
    {
      const std::size_t n = trajectory.displacement.size();
      if (trajectory.n_components < 1 || trajectory.n_components > 3)
        throw std::invalid_argument(
          "A trajectory has one, two or three displacement components, not " +
          std::to_string(trajectory.n_components) + ".");

      DirectionalSignals signals;
      const auto         component = [&](const unsigned int d) {
        std::vector<double> values(n);
        for (std::size_t i = 0; i < n; ++i)
          values[i] = trajectory.displacement[i][d];
        return values;
      };

      signals.names.push_back("vertical");
      signals.samples.push_back(component(0));
      if (trajectory.n_components == 1)
        return signals;

      const std::vector<double> u_y = component(1);
      if (trajectory.n_components == 2)
        {
          signals.names.push_back("horizontal");
          signals.samples.push_back(u_y);
          return signals;
        }

      const std::vector<double> u_z    = component(2);
      const double              mean_y = internal::mean_of(u_y);
      const double              mean_z = internal::mean_of(u_z);
      double                    c_yy = 0., c_zz = 0., c_yz = 0.;
      for (std::size_t i = 0; i < n; ++i)
        {
          c_yy += (u_y[i] - mean_y) * (u_y[i] - mean_y) / n;
          c_zz += (u_z[i] - mean_z) * (u_z[i] - mean_z) / n;
          c_yz += (u_y[i] - mean_y) * (u_z[i] - mean_z) / n;
        }

      const PrincipalDirection direction =
        principal_direction(c_yy, c_zz, c_yz);
      const double theta         = direction.angle;
      signals.plane_angle        = theta;
      signals.out_of_plane_ratio = direction.out_of_plane_ratio;

      std::vector<double> horizontal(n), depth(n);
      for (std::size_t i = 0; i < n; ++i)
        {
          horizontal[i] = std::cos(theta) * u_y[i] + std::sin(theta) * u_z[i];
          depth[i]      = -std::sin(theta) * u_y[i] + std::cos(theta) * u_z[i];
        }
      signals.names.push_back("horizontal");
      signals.samples.push_back(horizontal);
      signals.names.push_back("depth");
      signals.samples.push_back(depth);
      return signals;
    }
  } // namespace Analysis
} // namespace SoftRobot
