// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Inertia and gravity}
//
// The body's mass: the densities of its materials, the consistent mass
// matrix
// @f[
//   M_{ij} = \int_{\Omega_0}\rho_0\,\mathbf N_i\cdot\mathbf N_j\,dV
// @f]
// (times the section factor of the reduced models), which does not change
// during the run and is assembled once, and with it the gravity load
// $\mathbf f_g = \int\rho_0\,\mathbf N_i\cdot\mathbf g\,dV$, the mass
// matrix applied to the constant field $\mathbf g$. The class also keeps
// what the angular momentum of the body needs: the scalar mass matrix of
// each cell's nodes and their reference positions.
//
// Implemented in source/physics/inertia.cc.

#ifndef soft_robot_physics_inertia_h
#define soft_robot_physics_inertia_h

#include <core/parameters.h>
#include <deal.II/base/quadrature.h>
#include <deal.II/base/tensor.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>
#include <map>
#include <vector>

namespace SoftRobot
{
  using namespace dealii;

  template <int dim>
  class Inertia
  {
  public:
    // The density of every material, given or from the mass of its region
    // (whose volume is integrated with `volume_quadrature`), then the mass
    // matrix (whose sparsity pattern `mass` must have) and the gravity load
    // (with `mass_quadrature`).
    void
    reinit(const Parameters::AllParameters &parameters,
           const Mapping<dim>              &mapping,
           const DoFHandler<dim>           &dof_handler,
           const Quadrature<dim>           &volume_quadrature,
           const Quadrature<dim>           &mass_quadrature,
           const AffineConstraints<double> &constraints,
           const MPI_Comm                   mpi_communicator);

    // The matrix and the gravity load of the last reinit(), and the
    // matrix of the mass-proportional damping, $\int\alpha\rho_0\,\mathbf
    // N_i\cdot\mathbf N_j\,dV$ with each material's `Mass damping
    // coefficient` $\alpha$ (assembled only if one is nonzero; it must then
    // have the sparsity pattern too).
    TrilinosWrappers::SparseMatrix mass;
    TrilinosWrappers::MPI::Vector  gravity_force;
    TrilinosWrappers::SparseMatrix mass_damping;

    // The same two matrices for products with vectors: without the entries
    // that couple different components, which are zero. The matrices above
    // have the sparsity pattern of the tangent (which every component of a
    // node shares with every other), so that they can be added to it;
    // applied to a vector, two thirds of their entries in 3D are zeros.
    // Their products are the same to the last bit (only exact zeros are
    // left out), at a third of the memory traffic. In 1D they are the
    // matrices above.
    const TrilinosWrappers::SparseMatrix &
    mass_for_products() const
    {
      return compact_mass.m() > 0 ? compact_mass : mass;
    }
    const TrilinosWrappers::SparseMatrix &
    mass_damping_for_products() const
    {
      return compact_mass_damping.m() > 0 ? compact_mass_damping : mass_damping;
    }

    // Whether any material has a mass damping coefficient.
    static bool
    has_mass_damping(const Parameters::AllParameters &parameters);

    // $\rho_0$ of a material.
    double
    density(const types::material_id id) const
    {
      return densities.at(id);
    }

    // The angular momentum about the origin, $\mathbf L = \int\rho_0\,
    // \mathbf x\times\mathbf v\;dV$ with $\mathbf x = \mathbf X +
    // \mathbf u$ (times the section in the reduced models), for the finite
    // element fields $\mathbf x$ and $\mathbf v$ (ghosted vectors): the
    // integral is that of the consistent mass matrix, of which the cells
    // keep their scalar blocks (without the constraints, which would drop
    // the fixed nodes' share); it is exact where the mass quadrature is, on
    // affine cells. In 2D only the z-component is nonzero, in 1D none.
    Tensor<1, 3>
    angular_momentum(const DoFHandler<dim>               &dof_handler,
                     const TrilinosWrappers::MPI::Vector &u,
                     const TrilinosWrappers::MPI::Vector &v,
                     const MPI_Comm mpi_communicator) const;

  private:
    void
    compute_densities(const Parameters::AllParameters &parameters,
                      const Mapping<dim>              &mapping,
                      const DoFHandler<dim>           &dof_handler,
                      const Quadrature<dim>           &quadrature,
                      const MPI_Comm                   mpi_communicator);

    // The nonzero entries of `full` in `compact`, which is left empty if
    // `full` has no zero entries.
    static void
    copy_nonzero_entries(const TrilinosWrappers::SparseMatrix &full,
                         TrilinosWrappers::SparseMatrix       &compact);

    TrilinosWrappers::SparseMatrix compact_mass;
    TrilinosWrappers::SparseMatrix compact_mass_damping;

    std::map<types::material_id, double> densities;
    // Per locally owned cell: the scalar mass matrix of its nodes,
    // [cell][n][k], and the reference positions of its nodes, [cell][n].
    std::vector<double>     cell_nodal_mass;
    std::vector<Point<dim>> cell_node_positions;
  };
} // namespace SoftRobot

#endif
