// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{The Hilber-Hughes-Taylor time stepper}
//
// The semi-discrete equation of motion of the soft body is
// @f[
//   \mathbf M\mathbf a + \mathbf f_\text{int}(\mathbf u, \mathbf v)
//   = \mathbf f_\text{ext}(t),
// @f]
// where $\mathbf f_\text{int}$ holds the elastic forces and the
// stiffness-proportional damping forces. The HHT-$\alpha$ method
// (Hilber, Hughes and Taylor, 1977) evaluates the forces at a weighted
// time between $t_n$ and $t_{n+1}$,
// @f[
//   \mathbf M\mathbf a_{n+1}
//   + (1+\alpha)\,\mathbf f_\text{int}(\mathbf u_{n+1},\mathbf v_{n+1})
//   - \alpha\,\mathbf f_\text{int}(\mathbf u_n,\mathbf v_n)
//   = (1+\alpha)\,\mathbf f_\text{ext}(t_{n+1}) - \alpha\,\mathbf
//   f_\text{ext}(t_n),
// @f]
// with Newmark's relations between displacement, velocity and acceleration,
// @f{align*}{
//   \mathbf u_{n+1} &= \mathbf u_n + \Delta t\,\mathbf v_n
//     + \Delta t^2\left[\left(\tfrac12-\beta\right)\mathbf a_n
//     + \beta\,\mathbf a_{n+1}\right],
//   \\ \mathbf v_{n+1} &= \mathbf v_n
//     + \Delta t\left[(1-\gamma)\,\mathbf a_n + \gamma\,\mathbf a_{n+1}\right].
// @f}
// With $-1/3\le\alpha\le 0$, $\beta = (1-\alpha)^2/4$ and
// $\gamma = 1/2-\alpha$ the scheme is second-order accurate,
// unconditionally stable for linear problems, and damps the highest
// frequencies with the spectral radius $\rho_\infty = (1+\alpha)/(1-\alpha)$,
// while the low modes that carry the physics get an algorithmic damping
// ratio of only $-\alpha(1+\alpha)^2\Omega^3/8$. $\alpha = 0$ is the trapezoidal rule, which
// conserves the energy of linear systems exactly.
//
// Newton's method solves for $\mathbf u_{n+1}$; the two relations above,
// solved for the acceleration and velocity, give
// @f{align*}{
//   \mathbf a_{n+1} &= \frac{\mathbf u_{n+1} - \mathbf u_n - \Delta t\,\mathbf
//   v_n}{\beta\Delta t^2} - \left(\frac{1}{2\beta} - 1\right)\mathbf a_n,
//   \\ \mathbf v_{n+1} &= \mathbf v_n + \Delta t\left[(1-\gamma)\,\mathbf a_n
//   + \gamma\,\mathbf a_{n+1}\right],
// @f}
// so that $\partial\mathbf a_{n+1}/\partial\mathbf u_{n+1} = 1/(\beta\Delta
// t^2)$ and $\partial\mathbf v_{n+1}/\partial\mathbf u_{n+1} =
// \gamma/(\beta\Delta t)$: these are the two coefficients of the effective
// tangent matrix.

#ifndef soft_robot_time_integration_hht_stepper_h
#define soft_robot_time_integration_hht_stepper_h

#include <deal.II/base/tensor.h>
#include <string>

namespace SoftRobot
{
  using namespace dealii;

  class HHTStepper
  {
  public:
    // The standard member of the family: $\beta$ and $\gamma$ follow from
    // $\alpha$.
    explicit HHTStepper(const double alpha);

    // All three given explicitly, as in the reference study
    // ($\alpha=-0.25$, $\beta=0.4$, $\gamma=0.75$).
    HHTStepper(const double alpha, const double beta, const double gamma);

    double
    alpha() const
    {
      return alpha_;
    }
    double
    beta() const
    {
      return beta_;
    }
    double
    gamma() const
    {
      return gamma_;
    }

    // The weight $1+\alpha$ of the forces at the new time level.
    double
    new_force_weight() const
    {
      return 1. + alpha_;
    }

    // $\partial\mathbf a_{n+1}/\partial\mathbf u_{n+1}$ and
    // $\partial\mathbf v_{n+1}/\partial\mathbf u_{n+1}$.
    double
    acceleration_coefficient(const double dt) const
    {
      return 1. / (beta_ * dt * dt);
    }
    double
    velocity_coefficient(const double dt) const
    {
      return gamma_ / (beta_ * dt);
    }

    // The predictor for Newton's method: the displacement reached if the
    // acceleration stayed constant over the step.
    template <typename VectorType>
    void
    predict_displacement(const VectorType &u_old,
                         const VectorType &v_old,
                         const VectorType &a_old,
                         const double      dt,
                         VectorType       &u_new) const;

    // Newmark's relations: velocity and acceleration at $t_{n+1}$ from the
    // new displacement and the old state.
    template <typename VectorType>
    void
    update_kinematics(const VectorType &u_new,
                      const VectorType &u_old,
                      const VectorType &v_old,
                      const VectorType &a_old,
                      const double      dt,
                      VectorType       &v_new,
                      VectorType       &a_new) const;

    // @sect4{Properties of the scheme on the model problem}
    //
    // For the damped oscillator $\ddot u + 2\xi\omega\dot u + \omega^2 u = 0$
    // one step maps $(u_n, \Delta t\,v_n, \Delta t^2 a_n)$ linearly to the
    // same quantities at $t_{n+1}$. The matrix of that map, the
    // amplification matrix, depends only on $\Omega = \omega\Delta t$ and
    // $\xi$; its eigenvalues give the scheme's stability, period error and
    // algorithmic damping.
    Tensor<2, 3>
    amplification_matrix(const double Omega, const double xi = 0.) const;

    // The spectral radius of the amplification matrix.
    double
    spectral_radius(const double Omega, const double xi = 0.) const;

    // Whether the scheme is stable for every $\Omega$ of the undamped
    // oscillator: checked on the amplification matrix over
    // $\Omega\in[10^{-3},10^{6}]$, not assumed from the formulas, so that
    // user-given $\beta$ and $\gamma$ are judged by what they do.
    bool
    is_unconditionally_stable() const;

    // Whether $\beta$ and $\gamma$ are the standard functions of $\alpha$.
    bool
    is_standard_family() const;

    // A one-line description for the log.
    std::string
    description() const;

  private:
    double alpha_;
    double beta_;
    double gamma_;
  };



  template <typename VectorType>
  void
  HHTStepper::predict_displacement(const VectorType &u_old,
                                   const VectorType &v_old,
                                   const VectorType &a_old,
                                   const double      dt,
                                   VectorType       &u_new) const
  {
    u_new = u_old;
    u_new.add(dt, v_old, 0.5 * dt * dt, a_old);
  }



  template <typename VectorType>
  void
  HHTStepper::update_kinematics(const VectorType &u_new,
                                const VectorType &u_old,
                                const VectorType &v_old,
                                const VectorType &a_old,
                                const double      dt,
                                VectorType       &v_new,
                                VectorType       &a_new) const
  {
    a_new = u_new;
    a_new.add(-1., u_old, -dt, v_old);
    a_new *= acceleration_coefficient(dt);
    a_new.add(-(0.5 / beta_ - 1.), a_old);

    v_new = v_old;
    v_new.add(dt * (1. - gamma_), a_old, dt * gamma_, a_new);
  }
} // namespace SoftRobot

#endif
