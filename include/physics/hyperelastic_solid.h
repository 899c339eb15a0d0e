// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{The hyperelastic solid: what one cell contributes}
//
// This class is the physics of the body's interior: for the displacement of
// one cell it computes the cell's elastic internal force, its tangent
// stiffness and the damping matrix of the state. It knows the materials and
// the volumetric formulation, and nothing of the global matrices and
// vectors: the global addition (SystemAssembler) hands it the cell's values
// and takes its results.
//
// At each quadrature point the deformation gradient $\mathbf F = \mathbf I
// + \nabla_0\mathbf u$ gives, through the material's automatic derivatives,
// the stress $\mathbf S$ and the tangent $\mathcal C$. For a test function
// $\mathbf N_i = \varphi_i\mathbf e_{c_i}$ the variation of the strain is
// @f[
//   \delta\mathbf E_i = \mathrm{sym}(\mathbf F^T\nabla_0\mathbf N_i)
//   = \mathrm{sym}(\mathbf f_{c_i}\otimes\nabla_0\varphi_i),
// @f]
// with $\mathbf f_c$ the row $c$ of $\mathbf F$, and the internal force and
// the tangent stiffness are
// @f[
//   f_i = \int \delta\mathbf E_i : \mathbf S\;dV
//       = \int \mathbf f_{c_i}\cdot\mathbf S\,\nabla_0\varphi_i\;dV,\qquad
//   K_{ij} = \int \delta\mathbf E_i : \mathcal C : \delta\mathbf E_j
//          + \delta_{c_ic_j}\,\nabla_0\varphi_i\cdot\mathbf S\,
//            \nabla_0\varphi_j \; dV,
// @f]
// the first term of $K_{ij}$ being the material part. The damping matrix of
// the stiffness-proportional damping,
// @f[
//   C_{ij} = \int_{\Omega_0} \zeta\;\delta\mathbf E_i : \mathcal
//   C^+ : \delta\mathbf E_j\,dV,
// @f]
// is the material part with each material's own $\zeta$ and the positive
// semi-definite part $\mathcal C^+$ of the material tangent (which at large
// strains can have negative eigenvalues; with them, the Ecoflex actuator's
// damping fed energy into mesh-scale motions until elements inverted). It
// is symmetric and positive semi-definite, so the damping only dissipates,
// and it leaves the rigid-body modes of the state it is built at undamped,
// also the rotations of a prestressed body (which the geometric part of
// $\mathbf K$ would damp).
//
// For the reduced models every integral carries the material's `Section`
// factor (cross-section area in 1D, thickness in 2D), which CellGeometry
// has multiplied into the weights.
//
// In 3D, `Finite element/Volumetric formulation = mean dilatation` or
// `linear dilatation` replaces the volumetric energy $U(J)$ at each
// quadrature point by $\int_e U(\Theta)\,dV$ with the projection $\Theta =
// \Pi J$ of the volume ratio on one mode per cell (the mean volume ratio)
// or on $1 + $dim (a linear field; see DilatationProjection): the
// three-field formulation with pressure and dilatation from the same
// discontinuous space, condensed cell by cell (see doc/introduction.md).
// With quadratic elements it does not lock as $\kappa/\mu$ grows. The
// pressure $\bar p = \Pi\,U'(\Theta)$ enters the stress at every point,
// $\mathbf S = \partial\Psi_{\mathrm{iso}}/\partial\mathbf E + \bar p
// J\mathbf C^{-1}$, and the tangent gets the rank-n term $\mathbf
// G^T\mathbf A\mathbf G$ with the derivatives $G_{mi} = \int
// N_m\,\mathrm{cof}\,\mathbf F:\nabla_0\mathbf N_i\,dV$ of the volume's
// moments and $\mathbf A = \mathbf M^{-1}\int U''(\Theta)\mathbf N\mathbf
// N^T dV\,\mathbf M^{-1}$; with one mode that is $U''(\Theta_e)/V_e\;\mathbf
// g\mathbf g^T$ with the derivative $\mathbf g$ of the cell's volume.
//
// A quadrature point with $\det\mathbf F\le 0$ has no physical meaning: it
// is reported in the contribution, and the caller rejects the state.
//
// Implemented in source/physics/hyperelastic_solid.cc.

#ifndef soft_robot_physics_hyperelastic_solid_h
#define soft_robot_physics_hyperelastic_solid_h

#include <assembly/cell_contribution.h>
#include <core/parameters.h>
#include <map>
#include <material/neo_hookean_energy.h>
#include <memory>
#include <physics/cell_geometry.h>
#include <physics/dilatation_projection.h>
#include <physics/kelvin_voigt_damping.h>
#include <physics/point_tangent.h>
#include <utility>
#include <vector>

namespace SoftRobot
{
  template <int dim>
  class HyperelasticSolid
  {
  public:
    // The materials of the parameter file, on the cells of `geometry`
    // (which must outlive this object).
    // With `symmetric_tangent` the matrix is kept symmetric (for CG), and
    // the non-symmetric parts of the damping's tangent are left out.
    HyperelasticSolid(const Parameters::AllParameters &parameters,
                      const CellGeometry<dim>         &geometry,
                      const bool                       symmetric_tangent);
    ~HyperelasticSolid();

    // Whether any material has a damping coefficient.
    bool
    has_damping() const
    {
      return damped;
    }

    // Whether the damping is the Kelvin-Voigt stress (rather than a matrix
    // the simulator applies to the velocity): then the cell integral needs
    // the velocity and returns the damping force.
    bool
    has_viscous_stress() const
    {
      return viscous != nullptr;
    }

    // The integral over the cell `local.cell`, whose displacement values
    // are `local.input_values[0]` and velocity values (with the viscous
    // stress) `local.input_values[1]`: the elastic internal force into
    // `force`, the viscous one into `second_force`, and as requested the
    // tangent (`matrix`, the derivative of both forces by the displacement,
    // see AssemblyRequest) and the damping matrix of the state
    // (`second_matrix`).
    void
    cell_contribution(CellContribution<dim> &local) const;

    // The averages over the cell's quadrature points of the volume ratio
    // $J$ and of the Cauchy stress, for the output (with a projected
    // dilatation the pressure is the projected one, as in the assembly).
    std::pair<double, SymmetricTensor<2, dim>>
    cell_averages(const unsigned int cell, const double *cell_u) const;

    // The law of a material id.
    const NeoHookeanEnergy<dim> &
    material(const types::material_id id) const
    {
      return laws.at(id);
    }


  private:
    // Whether the cell integral includes the viscous stress: with the
    // velocity given and the Kelvin-Voigt damping.
    bool
    viscous_cell(const CellContribution<dim> &local) const
    {
      return viscous && local.input_values.size() > 1;
    }

    // Whether the cell's matrices need the derivatives $\mathbf G$ of the
    // volume's moments (projected dilatation): the tangent, or the damping
    // matrix of the volumetric viscosity. The forces are formed at the
    // points without them.
    bool
    needs_volume_gradients(const CellContribution<dim> &local) const
    {
      return local.request.matrix ||
             (viscous_cell(local) && local.request.second_matrix);
    }

    // Whether the cell's shape gradients by dof are needed: by the
    // matrices' point tangents and volume derivatives only.
    static bool
    shape_gradients_by_dof(const CellContribution<dim> &local)
    {
      return local.request.matrix || local.request.second_matrix;
    }

    // Whether the cell's tangent block is symmetric: unless the viscous
    // stress adds its non-symmetric part.
    Symmetry
    tangent_symmetry(const CellContribution<dim> &local) const
    {
      return (!viscous_cell(local) || viscous->has_symmetric_tangent())
               ? Symmetry::symmetric
               : Symmetry::general;
    }

    // The number of dilatation modes of the parameters' formulation.
    static unsigned int
    dilatation_modes(const Parameters::AllParameters &parameters,
                     const CellGeometry<dim>         &geometry);

    // The projected dilatation of a cell: the inverse Gram matrix of the
    // modes, the stiffness of the moments $\mathbf A$ and for the
    // Kelvin-Voigt damping the matrix $\mathbf A_v$ of the viscous
    // pressure (both only when the cell's matrices are asked for); the
    // point values (volume change, pressure, $U''$, viscous pressure) are
    // in the work space.
    struct CellDilatation
    {
      typename DilatationProjection<dim>::ModeMatrix inverse_gram{};
      typename DilatationProjection<dim>::ModeMatrix stiffness{};
      typename DilatationProjection<dim>::ModeMatrix viscous_stiffness{};
    };
    CellDilatation
    cell_dilatation(const unsigned int                 cell,
                    const std::vector<Tensor<2, dim>> &H,
                    CellContribution<dim>             &local) const;

    // The contribution of quadrature point q.
    void
    add_point_contribution(const unsigned int     q,
                           const Tensor<2, dim>  &H,
                           MaterialResponse<dim> &response,
                           CellContribution<dim> &local) const;

    const CellGeometry<dim>                            &geometry;
    const DilatationProjection<dim>                     projection;
    bool                                                damped = false;
    std::map<types::material_id, NeoHookeanEnergy<dim>> laws;
    // Per cell: its law and damping coefficient $\zeta$.
    std::vector<const NeoHookeanEnergy<dim> *> cell_law;
    std::vector<double>                        cell_zeta;
    std::unique_ptr<KelvinVoigtDamping<dim>>   viscous;
  };
} // namespace SoftRobot

#endif
