// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Fitting damped modes}
//
// The model for a record with $K$ spectral peaks is
// @f[
//   u(t) \approx c_0 + c_1\left(\frac tT-\frac12\right)
//     + \sum_{k=1}^{K} e^{-\sigma_k t}
//     \left(a_k\cos\omega_k t + b_k\sin\omega_k t\right),
//   \qquad 0 \le t < T,
// @f]
// where the linear trend absorbs a residual offset and a slow drift of the
// equilibrium (creep, marker drift), which would otherwise be fitted by the
// modes. The model is linear in $c_0, c_1, a_k, b_k$ and nonlinear in
// $\mathbf p = (\sigma_k, \omega_k)_k$.
//
// <i>Variable projection</i> (Golub and Pereyra) eliminates the linear
// coefficients: for given $\mathbf p$ they are the least-squares solution
// for the $N\times(2K+2)$ matrix $\Phi(\mathbf p)$ of basis functions,
// computed by a QR factorisation with column pivoting (LAPACK's
// <code>dgelsy</code>, see dense_linear_algebra.cc), and the residual
// $\mathbf r(\mathbf p) = \mathbf u - \Phi\mathbf c$ that remains is
// minimised over the $2K$ nonlinear parameters.
//
// <i>Levenberg--Marquardt</i> minimises $\|\mathbf r(\mathbf p)\|^2$ with
// the steps
// @f[
//   \delta\mathbf p = \arg\min_{\mathbf d}
//   \left\| \begin{pmatrix} J \\ \sqrt\lambda\,D \end{pmatrix}\mathbf d
//     + \begin{pmatrix} \mathbf r \\ \mathbf 0 \end{pmatrix} \right\|^2,
//   \qquad D^2 = \operatorname{diag}J^TJ,
// @f]
// with $J = \partial\mathbf r/\partial\mathbf p$ from central differences.
// The normal equations of this problem are Marquardt's
// $(J^TJ + \lambda\,\operatorname{diag}J^TJ)\,\delta\mathbf p =
// -J^T\mathbf r$, but the step is computed from the stacked matrix by a
// Householder QR factorisation (<code>dgels</code>), which works with the
// condition number of $J$ instead of its square. This matters when two modes
// are close and their columns of $J$ nearly parallel.
//
// <i>Starting points.</i> The frequencies start at the spectral peaks and
// the decay rates at $\pi B$ (the Lorentzian value of the bandwidth $B$), at
// a third and at a tenth of it, because truncation can make $\pi B$ ten
// times too large; the best of the three minima is kept. A mode is accepted
// only if its frequency stays within one bandwidth (or one resolution
// $1/T$, if that is larger) of the peak it started from. As explained in
// truncation_theory.cc, this is the fit of the truncated Lorentzian to the
// complex spectrum, and for a record that is a sum of damped modes it
// recovers $\sigma_k$ and $\omega_k$ exactly.

#include <algorithm>
#include <analysis/dense_linear_algebra.h>
#include <analysis/modal_fit.h>
#include <cmath>
#include <limits>
#include <numeric>
#include <utility>

namespace SoftRobot
{
  namespace Analysis
  {
    namespace
    {
      using internal::pi;



      // @sect4{The variable-projection residual}
      //
      // The columns of the constant and the linear trend come first, then
      // the cosine and the sine of each mode. The trend is evaluated at the
      // sample centres, $(i+\tfrac12)/N - \tfrac12$, so that it is
      // orthogonal to the constant. Columns that are linear combinations of
      // others to within $10^{-12}$ (two modes that a trial step made
      // equal, a decay so fast that a column vanishes) do not spoil the
      // residual, which is what the cost needs; see solve_least_squares().
      constexpr std::size_t first_mode_column = 2;



      ColumnMajorMatrix
      modal_basis(const std::size_t          n,
                  const double               time_step,
                  const std::vector<double> &parameters)
      {
        const std::size_t n_modes = parameters.size() / 2;
        ColumnMajorMatrix basis(n, first_mode_column + 2 * n_modes, 1.);
        for (std::size_t i = 0; i < n; ++i)
          basis(i, 1) = (i + 0.5) / n - 0.5;
        for (std::size_t k = 0; k < n_modes; ++k)
          for (std::size_t i = 0; i < n; ++i)
            {
              const double time     = i * time_step;
              const double envelope = std::exp(-parameters[2 * k] * time);
              basis(i, first_mode_column + 2 * k) =
                envelope * std::cos(parameters[2 * k + 1] * time);
              basis(i, first_mode_column + 2 * k + 1) =
                envelope * std::sin(parameters[2 * k + 1] * time);
            }
        return basis;
      }



      // The residual $\mathbf r(\mathbf p)$ for the nonlinear parameters
      // $(\sigma_1,\omega_1,\sigma_2,\omega_2,\dots)$; the linear
      // coefficients are returned in <code>coefficients</code>.
      std::vector<double>
      modal_residual(const std::vector<double> &signal,
                     const double               time_step,
                     const std::vector<double> &parameters,
                     std::vector<double>       &coefficients)
      {
        LeastSquaresSolution solution =
          solve_least_squares(modal_basis(signal.size(), time_step, parameters),
                              signal,
                              1e-12);
        coefficients = std::move(solution.coefficients);
        return std::move(solution.residual);
      }



      double
      squared_norm(const std::vector<double> &vector)
      {
        return std::inner_product(vector.begin(),
                                  vector.end(),
                                  vector.begin(),
                                  0.);
      }



      // @sect4{The Jacobian}
      //
      // Central differences with a step of $10^{-5}$ of the natural unit of
      // each parameter (<code>scale</code>), a balance between the
      // truncation error $O(h^2)$ and the cancellation error
      // $O(\epsilon/h)$. Column $i$ holds $\partial\mathbf r/\partial p_i$;
      // each column costs two residuals, i.e. two least-squares solves.
      ColumnMajorMatrix
      residual_jacobian(const std::vector<double> &signal,
                        const double               time_step,
                        const std::vector<double> &parameters,
                        const std::vector<double> &scale)
      {
        const std::size_t   m = parameters.size();
        ColumnMajorMatrix   jacobian(signal.size(), m);
        std::vector<double> coefficients;
        for (std::size_t i = 0; i < m; ++i)
          {
            const double        h     = 1e-5 * scale[i];
            std::vector<double> plus  = parameters;
            std::vector<double> minus = parameters;
            plus[i] += h;
            minus[i] -= h;
            const std::vector<double> r_plus =
              modal_residual(signal, time_step, plus, coefficients);
            const std::vector<double> r_minus =
              modal_residual(signal, time_step, minus, coefficients);
            for (std::size_t n = 0; n < signal.size(); ++n)
              jacobian(n, i) = (r_plus[n] - r_minus[n]) / (2. * h);
          }
        return jacobian;
      }



      // @sect4{The damped step}
      //
      // The stacked least-squares problem of the introduction for one
      // value of $\lambda$: $J$ on top of the diagonal
      // $\sqrt{\lambda\max(d_i, 10^{-300})}$, where $d_i = \|J_{:,i}\|^2$ is
      // the diagonal of $J^TJ$ (the lower bound keeps a parameter that the
      // residual does not depend on from making the matrix singular), and
      // the right-hand side $(-\mathbf r, \mathbf 0)$. Returns false if the
      // stacked matrix is singular nonetheless.
      bool
      damped_step(const ColumnMajorMatrix   &jacobian,
                  const std::vector<double> &residual,
                  const std::vector<double> &jacobian_column_norms_squared,
                  const double               lambda,
                  std::vector<double>       &step)
      {
        const std::size_t n = jacobian.n_rows(), m = jacobian.n_columns();
        ColumnMajorMatrix stacked(n + m, m, 0.);
        for (std::size_t i = 0; i < m; ++i)
          {
            std::copy(jacobian.column(i),
                      jacobian.column(i) + n,
                      stacked.column(i));
            stacked(n + i, i) = std::sqrt(
              lambda * std::max(jacobian_column_norms_squared[i], 1e-300));
          }

        std::vector<double> rhs(n + m, 0.);
        for (std::size_t k = 0; k < n; ++k)
          rhs[k] = -residual[k];
        return solve_full_rank_least_squares(stacked, rhs, step);
      }



      // @sect4{Levenberg--Marquardt from one starting point}
      //
      // The parameters are measured in the natural units of the record,
      // $1/T$ for decay rates and $2\pi/T$ for angular frequencies, both for
      // the finite-difference steps and for the convergence test.
      //
      // Each iteration computes the Jacobian and then tries steps with
      // increasing damping $\lambda$ until one lowers the cost. An accepted
      // step divides $\lambda$ by 3, a rejected one multiplies it by 4;
      // steps that would make a frequency non-positive or a parameter
      // non-finite are rejected. The iteration ends when no step lowers the
      // cost any more (the minimum has been reached to round-off), when a
      // step changes no parameter by more than $10^{-10}$ of its unit or
      // lowers the cost by no more than $10^{-15}$ of itself, or after 200
      // iterations.
      std::vector<double>
      levenberg_marquardt(const std::vector<double> &signal,
                          const double               time_step,
                          std::vector<double>        parameters,
                          double                    &cost)
      {
        const std::size_t   m        = parameters.size();
        const double        duration = signal.size() * time_step;
        std::vector<double> scale(m);
        for (std::size_t i = 0; i < m; ++i)
          scale[i] = (i % 2 == 0 ? 1. : 2. * pi) / duration;

        std::vector<double> coefficients;
        std::vector<double> residual =
          modal_residual(signal, time_step, parameters, coefficients);
        cost = squared_norm(residual);

        double lambda = 1e-3;
        for (unsigned int iteration = 0; iteration < 200; ++iteration)
          {
            const ColumnMajorMatrix jacobian =
              residual_jacobian(signal, time_step, parameters, scale);
            std::vector<double> column_norms_squared(m);
            for (std::size_t i = 0; i < m; ++i)
              column_norms_squared[i] =
                std::inner_product(jacobian.column(i),
                                   jacobian.column(i) + signal.size(),
                                   jacobian.column(i),
                                   0.);

            bool   improved  = false;
            double step_size = 0.;
            while (lambda < 1e12)
              {
                std::vector<double> step;
                if (!damped_step(
                      jacobian, residual, column_norms_squared, lambda, step))
                  {
                    lambda *= 4.;
                    continue;
                  }

                std::vector<double> trial      = parameters;
                bool                admissible = true;
                for (std::size_t i = 0; i < m; ++i)
                  {
                    trial[i] += step[i];
                    admissible = admissible && std::isfinite(trial[i]);
                  }
                for (std::size_t i = 1; i < m; i += 2)
                  admissible = admissible && trial[i] > 0.;
                if (admissible)
                  {
                    std::vector<double> trial_coefficients;
                    std::vector<double> trial_residual = modal_residual(
                      signal, time_step, trial, trial_coefficients);
                    const double trial_cost = squared_norm(trial_residual);
                    if (trial_cost < cost)
                      {
                        step_size = 0.;
                        for (std::size_t i = 0; i < m; ++i)
                          step_size =
                            std::max(step_size, std::abs(step[i]) / scale[i]);
                        const double decrease = cost - trial_cost;
                        parameters            = trial;
                        residual              = trial_residual;
                        cost                  = trial_cost;
                        lambda                = std::max(lambda / 3., 1e-12);
                        improved              = true;
                        if (decrease <= 1e-15 * cost)
                          step_size = 0.;
                        break;
                      }
                  }
                lambda *= 4.;
              }

            // No descent direction left (the minimum is reached to
            // round-off), or the last step was negligible.
            if (!improved || step_size < 1e-10)
              break;
          }
        return parameters;
      }
    } // namespace



    // @sect4{The fit proper}
    //
    // Scale the signal, start from the peaks with three initial decay
    // rates, keep the best result, and check it. The signal is scaled to
    // unit root mean square about its mean, so that the costs (and the
    // thresholds of the convergence test) are of order one whatever the
    // units of the displacement; the amplitudes are scaled back at the end.
    ModalFit
    fit_damped_modes(const std::vector<double>       &signal,
                     const double                     sample_rate,
                     const std::vector<SpectralPeak> &peaks)
    {
      const double time_step = 1. / sample_rate;
      const double duration  = signal.size() * time_step;

      const double mean        = internal::mean_of(signal);
      double       mean_square = 0.;
      for (const double value : signal)
        mean_square += (value - mean) * (value - mean) / signal.size();
      const double        rms = std::sqrt(mean_square);
      std::vector<double> scaled(signal.size());
      for (std::size_t i = 0; i < signal.size(); ++i)
        scaled[i] = signal[i] / rms;

      ModalFit            fit;
      std::vector<double> best_parameters;
      double              best_cost = std::numeric_limits<double>::max();
      for (const double fraction : {1., 1. / 3., 1. / 10.})
        {
          std::vector<double> parameters;
          for (const SpectralPeak &peak : peaks)
            {
              parameters.push_back(fraction * pi * peak.bandwidth);
              parameters.push_back(2. * pi * peak.frequency);
            }
          double                    cost = 0.;
          const std::vector<double> fitted =
            levenberg_marquardt(scaled, time_step, parameters, cost);
          if (cost < best_cost)
            {
              best_cost       = cost;
              best_parameters = fitted;
            }
        }

      std::vector<double> coefficients;
      modal_residual(scaled, time_step, best_parameters, coefficients);
      // The scaled signal has unit mean square about its mean.
      fit.relative_residual = std::sqrt(best_cost / scaled.size());

      // The checks of each mode: finite parameters and a positive
      // amplitude, and a frequency within the band of its peak. The last
      // failure found is the one reported.
      fit.valid = true;
      for (std::size_t k = 0; k < peaks.size(); ++k)
        {
          const double sigma = best_parameters[2 * k];
          const double omega = best_parameters[2 * k + 1];
          const double amplitude =
            rms * std::hypot(coefficients[first_mode_column + 2 * k],
                             coefficients[first_mode_column + 2 * k + 1]);
          fit.decay_rates.push_back(sigma);
          fit.angular_frequencies.push_back(omega);
          fit.amplitudes.push_back(amplitude);

          const double allowed_shift =
            std::max(peaks[k].bandwidth, 1. / duration);
          if (!std::isfinite(sigma) || !std::isfinite(omega) ||
              !(amplitude > 0.))
            {
              fit.valid  = false;
              fit.reason = "the fit did not produce finite parameters";
            }
          else if (std::abs(omega / (2. * pi) - peaks[k].frequency) >
                   allowed_shift)
            {
              fit.valid  = false;
              fit.reason = "the mode started at " +
                           internal::format_number(peaks[k].frequency, 4) +
                           " Hz moved to " +
                           internal::format_number(omega / (2. * pi), 4) +
                           " Hz, outside its half-power band";
            }
        }
      return fit;
    }
  } // namespace Analysis
} // namespace SoftRobot
