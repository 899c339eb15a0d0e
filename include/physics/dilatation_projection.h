// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{The dilatation projected on a few modes per cell}
//
// The three-field formulations of nearly incompressible materials condense
// a pressure and a dilatation from a small space on each cell (step-44).
// With the same space for both, the condensation amounts to replacing the
// volume ratio $J$ at the quadrature points by its $L^2$ projection
// $\Theta = \Pi J$ on the cell's modes $N_m$,
// @f[
//   \Theta(\mathbf X) = \sum_m N_m(\mathbf X)\,\theta_m,\qquad
//   \boldsymbol\theta = \mathbf M^{-1}\mathbf b,\qquad
//   M_{mk} = \int_e N_mN_k\,dV,\quad b_m = \int_e N_m J\,dV,
// @f]
// and the volumetric energy by $\int_e U(\Theta)\,dV$. This class holds
// the modes and does the projections: one mode, $N_0 = 1$, gives the cell's
// mean volume ratio (the mean-dilatation formulation, pressure constant per
// cell); $1 + $ dim modes, the constant and the reference cell's
// coordinates less those of its centre, give a dilatation linear on the
// reference cell (step-44's discontinuous $P_1$ pressure with $Q_2$
// displacements). The constant is among the modes, so the projection of a
// constant is exact and $\Theta - 1 = \Pi(J - 1)$, which keeps the digits
// of states close to the reference.
//
// What HyperelasticSolid makes of it (the pressure field $\bar p =
// \Pi\,U'(\Theta)$ in the stress, the rank-$n$ term $\mathbf G^T\mathbf
// A\mathbf G$ in the tangent with $\mathbf A = \mathbf M^{-1}\int
// U''(\Theta)\mathbf N\mathbf N^T dV\,\mathbf M^{-1}$ and the moments'
// derivatives $G_{mi} = \partial b_m/\partial u_i$) is documented there.
//
// Implemented in source/physics/dilatation_projection.cc.

#ifndef soft_robot_physics_dilatation_projection_h
#define soft_robot_physics_dilatation_projection_h

#include <array>
#include <deal.II/lac/full_matrix.h>
#include <physics/cell_geometry.h>
#include <vector>

namespace SoftRobot
{
  using namespace dealii;

  template <int dim>
  class DilatationProjection
  {
  public:
    static constexpr unsigned int max_modes = dim + 1;
    using ModeVector                        = std::array<double, max_modes>;
    using ModeMatrix                        = std::array<ModeVector, max_modes>;

    // The modes at the quadrature points of `geometry` (which must outlive
    // this object): none (`n_modes` = 0, the displacement formulation), the
    // constant (1) or the linear ones (dim + 1).
    DilatationProjection(const CellGeometry<dim> &geometry,
                         const unsigned int       n_modes);

    unsigned int
    n_modes() const
    {
      return n;
    }

    // $N_m$ at quadrature point q.
    double
    mode(const unsigned int q, const unsigned int m) const
    {
      return values[q * n + m];
    }

    // The inverse Gram matrix $\mathbf M^{-1}$ of a cell.
    ModeMatrix
    inverse_gram(const unsigned int cell) const;

    // The coefficients $\mathbf M^{-1}\int_e \mathbf N f\,dV$ of the
    // projection of the values f at the cell's points.
    ModeVector
    project(const unsigned int         cell,
            const ModeMatrix          &inverse_gram,
            const std::vector<double> &f) const;

    // $\sum_m N_m(\mathbf X_q)\,c_m$.
    double
    value(const unsigned int q, const ModeVector &coefficients) const;

    // $\mathbf M^{-1}\int_e g\,\mathbf N\mathbf N^T dV\,\mathbf M^{-1}$ for
    // the values g at the cell's points.
    ModeMatrix
    weighted_stiffness(const unsigned int         cell,
                       const ModeMatrix          &inverse_gram,
                       const std::vector<double> &g) const;

    // The lower triangle of the rank-n term $\mathbf G^T\mathbf A\mathbf G$
    // for the moments' derivatives G ([mode][dof], as many modes as rows):
    // `scale_1` times it
    // added to `matrix_1`, `scale_2` times it to `matrix_2` (either may be
    // null). `AG` is a buffer for $\mathbf A\mathbf G$, resized here.
    static void
    add_rank_n_term(const ModeMatrix         &A,
                    const FullMatrix<double> &G,
                    FullMatrix<double>       &AG,
                    FullMatrix<double>       *matrix_1,
                    const double              scale_1,
                    FullMatrix<double>       *matrix_2,
                    const double              scale_2);

    // One point's share of the moments' derivatives, $G_{mi} \mathrel{+}=
    // w_m\,\mathbf T_{c_i}\cdot\nabla_0\varphi_i$, with $\mathbf T$ the
    // derivative of the point's integrand with respect to $\mathbf F$ (the
    // cofactor for the volume) and the weights $w_m = N_m\,dV$. The dot
    // product is formed once per shape function and then weighted by each
    // of the first n_modes weights.
    static void
    add_point_derivatives(const Tensor<2, dim>            &T,
                          const Tensor<1, dim>            *grad_phi,
                          const std::vector<unsigned int> &components,
                          const ModeVector                &weights,
                          const unsigned int               n_modes,
                          FullMatrix<double>              &G);

  private:
    const CellGeometry<dim> &geometry;
    const unsigned int       n;
    std::vector<double>      values;
  };
} // namespace SoftRobot

#endif
