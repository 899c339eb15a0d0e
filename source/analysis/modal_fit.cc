// @sect3{Fitting damped modes}
//
// The model for a record with $K$ spectral peaks is
// @f[
//   u(t) \approx c_0 + c_1\left(\frac tT-\frac12\right)
//     + \sum_{k=1}^{K} e^{-\sigma_k t}
//     \left(a_k\cos\omega_k t + b_k\sin\omega_k t\right),
//   \qquad 0 \le t < T,
// @f]
// where the linear trend absorbs a residual offset and a slow drift of
// the equilibrium (creep, marker drift), which would otherwise be
// fitted by the modes. The model is linear in $c_0, c_1, a_k, b_k$ and
// nonlinear in
// $\mathbf p = (\sigma_k, \omega_k)_k$. Variable projection (Golub and
// Pereyra) eliminates the linear coefficients: for given $\mathbf p$ they
// are the least-squares solution, computed by a Householder QR
// factorisation of the $N\times(2K+2)$ matrix of basis functions, and
// the residual $\mathbf r(\mathbf p)$ that remains is minimised over the
// $2K$ nonlinear parameters by Levenberg--Marquardt,
// @f[
//   \left(J^TJ + \lambda\,\operatorname{diag}J^TJ\right)\delta\mathbf p
//   = -J^T\mathbf r,
// @f]
// with $J = \partial\mathbf r/\partial\mathbf p$ from central differences.
// The frequencies start at the spectral peaks and the decay rates at $\pi B$
// (the Lorentzian value of the bandwidth $B$), at a third and at a tenth of
// it, because truncation can make $\pi B$ ten times too large; the best of
// the three minima is kept. A mode is accepted only if its frequency stays
// within one bandwidth (or one resolution $1/T$, if that is larger) of the
// peak it started from. As explained in truncation_theory.cc, this is the
// fit of the truncated Lorentzian to the complex spectrum, and for a record
// that is a sum of damped modes it recovers $\sigma_k$ and $\omega_k$
// exactly.

#include <algorithm>
#include <analysis/modal_fit.h>
#include <cmath>
#include <limits>
#include <numeric>

namespace SoftRobot
{
  namespace Analysis
  {
    namespace
    {
      using internal::pi;



      // Least squares for a tall matrix given by its columns; returns the
      // residual in the original coordinates (needed for the Jacobian) and
      // the coefficients. Columns that are linearly dependent on earlier
      // ones to round-off get a zero coefficient.
      //
      // Householder QR: for column $k$, the reflection
      // $H = I - 2\mathbf v\mathbf v^T/\mathbf v^T\mathbf v$ with
      // $\mathbf v = \mathbf a_k - \alpha\mathbf e_k$ (rows $k$ to $N-1$)
      // and $\alpha = -\operatorname{sign}(a_{kk})\|\mathbf a_k\|$ (the sign
      // that avoids cancellation) maps the column onto $\alpha\mathbf e_k$;
      // applied to the later columns and to the right-hand side, the
      // reflections build $R$ and $Q^T\mathbf b$, and back substitution
      // solves $R\mathbf c = (Q^T\mathbf b)_{0..p-1}$. This is slower than
      // the normal equations, but it loses no accuracy to the squared
      // condition number, which matters when two modes are close.
      std::vector<double>
      least_squares_residual(const std::vector<std::vector<double>> &columns,
                             const std::vector<double>              &rhs,
                             std::vector<double> &coefficients)
      {
        const std::size_t                n = rhs.size(), p = columns.size();
        std::vector<std::vector<double>> factor      = columns;
        std::vector<double>              rotated_rhs = rhs;
        std::vector<double>              diagonal(p, 0.);

        for (std::size_t k = 0; k < p; ++k)
          {
            double norm = 0.;
            for (std::size_t i = k; i < n; ++i)
              norm += factor[k][i] * factor[k][i];
            norm = std::sqrt(norm);
            if (norm == 0.)
              continue;

            std::vector<double> &v     = factor[k];
            const double         alpha = (v[k] > 0. ? -norm : norm);
            v[k] -= alpha;
            double v_norm_squared = 0.;
            for (std::size_t i = k; i < n; ++i)
              v_norm_squared += v[i] * v[i];

            const auto reflect = [&](std::vector<double> &x) {
              double projection = 0.;
              for (std::size_t i = k; i < n; ++i)
                projection += v[i] * x[i];
              const double scale = 2. * projection / v_norm_squared;
              for (std::size_t i = k; i < n; ++i)
                x[i] -= scale * v[i];
            };
            for (std::size_t j = k + 1; j < p; ++j)
              reflect(factor[j]);
            reflect(rotated_rhs);
            diagonal[k] = alpha;
          }

        double largest_diagonal = 0.;
        for (const double d : diagonal)
          largest_diagonal = std::max(largest_diagonal, std::abs(d));

        coefficients.assign(p, 0.);
        for (std::size_t k = p; k-- > 0;)
          {
            if (std::abs(diagonal[k]) <= 1e-12 * largest_diagonal)
              continue;
            double sum = rotated_rhs[k];
            for (std::size_t j = k + 1; j < p; ++j)
              sum -= factor[j][k] * coefficients[j];
            coefficients[k] = sum / diagonal[k];
          }

        std::vector<double> residual = rhs;
        for (std::size_t k = 0; k < p; ++k)
          for (std::size_t i = 0; i < n; ++i)
            residual[i] -= coefficients[k] * columns[k][i];
        return residual;
      }



      // The columns of the constant and the linear trend come first.
      constexpr std::size_t first_mode_column = 2;



      // The variable-projection residual for the nonlinear parameters
      // $(\sigma_1,\omega_1,\sigma_2,\omega_2,\dots)$.
      std::vector<double>
      modal_residual(const std::vector<double> &signal,
                     const double               time_step,
                     const std::vector<double> &parameters,
                     std::vector<double>       &coefficients)
      {
        const std::size_t                n       = signal.size();
        const std::size_t                n_modes = parameters.size() / 2;
        std::vector<std::vector<double>> columns(first_mode_column +
                                                   2 * n_modes,
                                                 std::vector<double>(n, 1.));
        for (std::size_t i = 0; i < n; ++i)
          columns[1][i] = (i + 0.5) / n - 0.5;
        for (std::size_t k = 0; k < n_modes; ++k)
          for (std::size_t i = 0; i < n; ++i)
            {
              const double time     = i * time_step;
              const double envelope = std::exp(-parameters[2 * k] * time);
              columns[first_mode_column + 2 * k][i] =
                envelope * std::cos(parameters[2 * k + 1] * time);
              columns[first_mode_column + 2 * k + 1][i] =
                envelope * std::sin(parameters[2 * k + 1] * time);
            }
        return least_squares_residual(columns, signal, coefficients);
      }



      double
      squared_norm(const std::vector<double> &vector)
      {
        return std::inner_product(vector.begin(),
                                  vector.end(),
                                  vector.begin(),
                                  0.);
      }



      // Solve the small dense system $A x = b$ by Gaussian elimination with
      // partial pivoting; returns false if $A$ is singular.
      bool
      solve_dense_system(std::vector<std::vector<double>> matrix,
                         std::vector<double>             &rhs)
      {
        const std::size_t m = rhs.size();
        for (std::size_t k = 0; k < m; ++k)
          {
            std::size_t pivot = k;
            for (std::size_t i = k + 1; i < m; ++i)
              if (std::abs(matrix[i][k]) > std::abs(matrix[pivot][k]))
                pivot = i;
            if (matrix[pivot][k] == 0.)
              return false;
            std::swap(matrix[k], matrix[pivot]);
            std::swap(rhs[k], rhs[pivot]);
            for (std::size_t i = k + 1; i < m; ++i)
              {
                const double factor = matrix[i][k] / matrix[k][k];
                for (std::size_t j = k; j < m; ++j)
                  matrix[i][j] -= factor * matrix[k][j];
                rhs[i] -= factor * rhs[k];
              }
          }
        for (std::size_t k = m; k-- > 0;)
          {
            for (std::size_t j = k + 1; j < m; ++j)
              rhs[k] -= matrix[k][j] * rhs[j];
            rhs[k] /= matrix[k][k];
          }
        return true;
      }



      // Levenberg--Marquardt from one starting point. The parameters are
      // measured in the natural units of the record, $1/T$ for decay rates
      // and $2\pi/T$ for angular frequencies, both for the finite-difference
      // steps and for the convergence test.
      //
      // Each iteration computes the Jacobian by central differences with a
      // step of $10^{-5}$ of those units (a balance between the truncation
      // error $O(h^2)$ and the cancellation error $O(\epsilon/h)$), and then
      // tries steps with increasing damping $\lambda$ until one lowers the
      // cost. An accepted step divides $\lambda$ by 3, a rejected one
      // multiplies it by 4; steps that would make a frequency non-positive
      // or a parameter non-finite are rejected. The iteration ends when no
      // step lowers the cost any more (the minimum has been reached to
      // round-off), when a step changes no parameter by more than
      // $10^{-10}$ of its unit, or after 200 iterations.
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
            std::vector<std::vector<double>> jacobian(m);
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
                jacobian[i].resize(signal.size());
                for (std::size_t n = 0; n < signal.size(); ++n)
                  jacobian[i][n] = (r_plus[n] - r_minus[n]) / (2. * h);
              }

            std::vector<std::vector<double>> normal_matrix(
              m, std::vector<double>(m));
            std::vector<double> gradient(m);
            for (std::size_t i = 0; i < m; ++i)
              {
                gradient[i] = std::inner_product(jacobian[i].begin(),
                                                 jacobian[i].end(),
                                                 residual.begin(),
                                                 0.);
                for (std::size_t j = 0; j < m; ++j)
                  normal_matrix[i][j] = std::inner_product(jacobian[i].begin(),
                                                           jacobian[i].end(),
                                                           jacobian[j].begin(),
                                                           0.);
              }

            bool   improved  = false;
            double step_size = 0.;
            while (lambda < 1e12)
              {
                std::vector<std::vector<double>> damped = normal_matrix;
                for (std::size_t i = 0; i < m; ++i)
                  damped[i][i] +=
                    lambda * std::max(normal_matrix[i][i], 1e-300);
                std::vector<double> step(m);
                for (std::size_t i = 0; i < m; ++i)
                  step[i] = -gradient[i];
                if (!solve_dense_system(damped, step))
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
