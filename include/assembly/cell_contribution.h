// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{What one cell contributes}
//
// The assembly is split into two parts that know nothing of each other:
// the physics, which integrates over one cell (see HyperelasticSolid), and
// the global addition, which gathers the cell's values from the global
// vectors, runs the physics on all cells (in parallel threads) and adds the
// results into the global matrices and vectors (see SystemAssembler). This
// header is the interface between the two: CellContribution carries the
// cell's input values to the physics and its matrices and vectors back.
//
// Every assembly produces one force vector and, on request, one matrix (the
// tangent) and a second matrix of the same sparsity pattern (the damping
// matrix of the state). A second force vector (for example the damping
// force alone, for the energy account) can be asked for too.
//
// Declared here, used by source/assembly/ and source/physics/.

#ifndef soft_robot_assembly_cell_contribution_h
#define soft_robot_assembly_cell_contribution_h

#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>
#include <deal.II/base/types.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>
#include <limits>
#include <vector>

namespace SoftRobot
{
  using namespace dealii;

  // @sect4{The request}
  //
  // Which of the outputs an assembly computes.
  struct AssemblyRequest
  {
    bool matrix        = false; // the tangent matrix
    bool second_matrix = false; // the damping matrix of the state
    bool second_force  = false; // a second force vector
    // The assembly is that of a state the next time step starts from: the
    // physics records what it keeps fixed during a step (the viscosity of
    // KelvinVoigtDamping).
    bool store_viscosity = false;
    // $\partial\mathbf v/\partial\mathbf u$ of the time integrator
    // ($\gamma/(\beta\Delta t)$ for the HHT step, zero for the tangent of a
    // state): the matrix is the derivative of all forces, velocity-dependent
    // ones included, by the displacement.
    double velocity_coefficient = 0.;
  };



  // @sect4{A cell matrix by shape functions}
  //
  // The storage of physics/point_tangent.h: the cell matrix ordered by
  // shape functions, and the factors of the points added since it was
  // last brought up to date, which are multiplied out together.
  struct TangentBlock
  {
    // Entry ((a dim + c) dim + k) stride + b for the pair of shape
    // functions (a, b) and the components (c, k); stride >= the number of
    // shape functions.
    std::vector<double> values;
    unsigned int        stride = 0;
    // The points' factors: [a][(point, J)] and [(point, J)][(c, k, b)].
    std::vector<double> left;
    std::vector<double> right;
    unsigned int        pending_points = 0;
    // Whether the points added so far are symmetric (only b <= a is kept).
    bool symmetric = false;
  };



  // @sect4{The gradients and forces of a cell as products}
  //
  // The storage of the products of physics/point_tangent.h that give the
  // displacement and velocity gradients at a cell's points and the forces
  // of its stresses.
  struct CellProducts
  {
    // The gradients of the scalar shape functions, [a][(q, J)], in rows of
    // `gradient_stride` >= dim n_q (the rest zero): with `pulled_back`
    // those on the reference cell (CellGeometry's table, the same for
    // every cell), otherwise the cell's own, in `cell_gradients`.
    const double       *gradients       = nullptr;
    unsigned int        gradient_stride = 0;
    bool                pulled_back     = false;
    std::vector<double> cell_gradients;
    // With `pulled_back`: the cell's inverse Jacobians, [q][K][J].
    std::vector<double> inverse_jacobians;
    // The points' stresses times their weights, [(q, J)][column] in rows
    // of `stress_stride`: the first Piola-Kirchhoff stress's component
    // (c, J) in column c, the viscous stress's in column dim + c; with
    // `pulled_back` those of $w\,\mathbf P\mathbf J^{-T}$.
    std::vector<double> stresses;
    unsigned int        stress_stride = 0;
    // The nodal values of the fields and the products.
    std::vector<double> values;
    std::vector<double> result;
  };



  // @sect4{The work space of one thread}
  //
  // Arrays that the integral over a cell needs per shape function or per
  // quadrature point. They live as long as the thread's CellContribution
  // object, so that no cell allocates memory.
  template <int dim>
  struct CellWorkspace
  {
    // The gradients of the cell's shape functions, [q][i] (see
    // CellGeometry::cell_gradients()).
    std::vector<Tensor<1, dim>> shape_gradients;
    std::vector<Tensor<2, dim>> displacement_gradients;
    std::vector<Tensor<2, dim>> velocity_gradients;
    // The projected-dilatation formulations (see HyperelasticSolid): the
    // derivatives $\mathbf G$ of the moments of the volume,
    // [mode][dof], and of the moments of the volume rate, $\partial(\mathbf
    // G\mathbf v)/\partial\mathbf u$ (see KelvinVoigtDamping); per point
    // the projected volume change $\Theta - 1$, the pressure, the
    // volumetric stiffness $U''(\Theta)$ and the viscous pressure; the
    // volume rate and the volumetric viscosity per point, and a buffer for
    // products of a mode matrix with $\mathbf G$.
    FullMatrix<double>  volume_gradients;
    FullMatrix<double>  rate_gradients;
    FullMatrix<double>  mode_products;
    std::vector<double> point_volume_rate;
    std::vector<double> point_viscosity;
    std::vector<double> point_volume_change;
    std::vector<double> point_pressure;
    std::vector<double> point_volumetric_stiffness;
    std::vector<double> point_viscous_pressure;
    // The points' shares of the tangent and of the damping matrix, by
    // shape functions (see physics/point_tangent.h), added in full after
    // the symmetric part has been completed from its lower triangle.
    TangentBlock tangent_block;
    TangentBlock damping_block;
    // The gradients of the fields and the forces of the stresses.
    CellProducts products;
    // The non-symmetric part of a cell matrix, added in full after the
    // symmetric part has been completed from its lower triangle.
    FullMatrix<double> nonsymmetric_matrix;
    bool               has_nonsymmetric_part = false;
  };



  // @sect4{The contribution of one cell}
  template <int dim>
  struct CellContribution
  {
    // Set by the global addition before the cell's integral: the cell (its
    // number in the order of CellGeometry), the request, and per input
    // vector a pointer to the cell's dofs' values (in the order of the
    // cell's dofs; a constrained dof has the value zero).
    unsigned int                cell = 0;
    AssemblyRequest             request;
    std::vector<const double *> input_values;

    // Computed by the integral over the cell.
    FullMatrix<double> matrix;
    FullMatrix<double> second_matrix;
    Vector<double>     force;
    Vector<double>     second_force;
    double             strain_energy = 0.;
    double             min_jacobian  = std::numeric_limits<double>::max();
    bool               inverted      = false;

    // The cell's global dof indices, for the global addition.
    std::vector<types::global_dof_index> dof_indices;

    CellWorkspace<dim> workspace;

    // Sizes the arrays for cells with n dofs and sets the outputs to zero.
    void
    reset(const unsigned int n)
    {
      if (force.size() != n)
        {
          matrix.reinit(n, n);
          second_matrix.reinit(n, n);
          force.reinit(n);
          second_force.reinit(n);
          dof_indices.resize(n);
          workspace.nonsymmetric_matrix.reinit(n, n);
        }
      workspace.has_nonsymmetric_part = false;
      if (request.matrix)
        {
          matrix                        = 0.;
          workspace.nonsymmetric_matrix = 0.;
        }
      if (request.second_matrix)
        second_matrix = 0.;
      force = 0.;
      if (request.second_force)
        second_force = 0.;
      strain_energy = 0.;
      min_jacobian  = std::numeric_limits<double>::max();
      inverted      = false;
    }
  };
} // namespace SoftRobot

#endif
