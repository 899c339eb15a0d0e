// SPDX-License-Identifier: LGPL-2.1-or-later

#include <cmath>
#include <deal.II/base/exceptions.h>
#include <deal.II/lac/lapack_full_matrix.h>
#include <sstream>
#include <time_integration/hht_stepper.h>

namespace SoftRobot
{
  // @sect3{Implementation of HHTStepper}

  HHTStepper::HHTStepper(const double alpha)
    : HHTStepper(alpha, (1. - alpha) * (1. - alpha) / 4., 0.5 - alpha)
  {
  }



  HHTStepper::HHTStepper(const double alpha,
                         const double beta,
                         const double gamma)
    : alpha_(alpha)
    , beta_(beta)
    , gamma_(gamma)
  {
    AssertThrow(alpha >= -1. / 3. && alpha <= 0.,
                ExcMessage("The HHT parameter alpha must lie in [-1/3, 0], "
                           "but is " +
                           std::to_string(alpha) + "."));
    AssertThrow(beta > 0. && beta <= 1.,
                ExcMessage("The Newmark parameter beta must lie in (0, 1], "
                           "but is " +
                           std::to_string(beta) + "."));
    AssertThrow(gamma >= 0. && gamma <= 1.5,
                ExcMessage("The Newmark parameter gamma must lie in [0, 1.5], "
                           "but is " +
                           std::to_string(gamma) + "."));
  }



  // @sect4{HHTStepper::amplification_matrix}
  //
  // With the scaled state $(d, w, s) = (u, \Delta t\,v, \Delta t^2 a)$ the
  // equation of motion at the HHT time level, multiplied by $\Delta t^2$,
  // reads
  // @f[
  //   s_{n+1} + (1+\alpha)\left(2\xi\Omega\,w_{n+1} + \Omega^2 d_{n+1}\right)
  //   - \alpha\left(2\xi\Omega\,w_n + \Omega^2 d_n\right) = 0,
  // @f]
  // and Newmark's relations $d_{n+1} = d_n + w_n + (1/2-\beta)s_n + \beta
  // s_{n+1}$, $w_{n+1} = w_n + (1-\gamma)s_n + \gamma s_{n+1}$. Inserting
  // the latter into the former gives $s_{n+1}$ as a linear function of the
  // old state, and then $d_{n+1}$ and $w_{n+1}$. Each column of the matrix
  // is the image of one unit state.
  Tensor<2, 3>
  HHTStepper::amplification_matrix(const double Omega, const double xi) const
  {
    const double c = 2. * xi * Omega; // damping per unit scaled velocity
    const double k = Omega * Omega;   // stiffness per unit displacement
    const double denominator = 1. + (1. + alpha_) * (c * gamma_ + k * beta_);

    Tensor<2, 3> A;
    for (unsigned int column = 0; column < 3; ++column)
      {
        const double d0 = (column == 0), w0 = (column == 1), s0 = (column == 2);
        const double w_known = w0 + (1. - gamma_) * s0;
        const double d_known = d0 + w0 + (0.5 - beta_) * s0;
        const double s1      = (-(1. + alpha_) * (c * w_known + k * d_known) +
                           alpha_ * (c * w0 + k * d0)) /
                          denominator;
        A[0][column] = d_known + beta_ * s1;
        A[1][column] = w_known + gamma_ * s1;
        A[2][column] = s1;
      }
    return A;
  }



  double
  HHTStepper::spectral_radius(const double Omega, const double xi) const
  {
    const Tensor<2, 3>       A = amplification_matrix(Omega, xi);
    LAPACKFullMatrix<double> matrix(3, 3);
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        matrix(i, j) = A[i][j];
    matrix.compute_eigenvalues();
    double radius = 0.;
    for (unsigned int i = 0; i < 3; ++i)
      radius = std::max(radius, std::abs(matrix.eigenvalue(i)));
    return radius;
  }



  // The check scans $\Omega$ logarithmically, 20 points per decade. The
  // tolerance $10^{-10}$ accepts the round-off in the eigenvalues of a
  // matrix whose radius is exactly one (the trapezoidal rule).
  bool
  HHTStepper::is_unconditionally_stable() const
  {
    for (double log_Omega = -3.; log_Omega <= 6.; log_Omega += 0.05)
      if (spectral_radius(std::pow(10., log_Omega)) > 1. + 1e-10)
        return false;
    return true;
  }



  bool
  HHTStepper::is_standard_family() const
  {
    return std::abs(beta_ - (1. - alpha_) * (1. - alpha_) / 4.) < 1e-12 &&
           std::abs(gamma_ - (0.5 - alpha_)) < 1e-12;
  }



  std::string
  HHTStepper::description() const
  {
    std::ostringstream out;
    out << "HHT-alpha: alpha = " << alpha_ << ", beta = " << beta_
        << ", gamma = " << gamma_
        << ", spectral radius at infinity = " << spectral_radius(1e8)
        << (is_standard_family() ? " (standard family)"
                                 : " (user-given beta, gamma)");
    return out.str();
  }
} // namespace SoftRobot
