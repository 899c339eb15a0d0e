// @sect3{Assembly: internal forces, tangent, external forces}
//
// This file holds the part of SoftRobotDynamics that runs in every Newton
// iteration: the assembly of the elastic internal force vector with its
// tangent matrix and the damping matrix of the state, and of the external
// forces.

#include <core/soft_robot_dynamics.h>
#include <Epetra_Import.h>
#include <Epetra_Vector.h>
#include <deal.II/base/multithread_info.h>
#include <deal.II/base/thread_management.h>
#include <deal.II/base/work_stream.h>
#include <deal.II/fe/fe_values.h>
#include <array>
#include <limits>
#include <numeric>

namespace SoftRobot
{
  // @sect4{SoftRobotDynamics::assemble_internal_force}
  //
  // At each quadrature point the deformation gradient $\mathbf F =
  // \mathbf I + \nabla_0\mathbf u$ gives, through the material's automatic
  // derivatives, the stress $\mathbf S$ and the tangent $\mathcal C$. For a
  // test function $\mathbf N_i = \varphi_i\mathbf e_{c_i}$ the variation of
  // the strain is
  // @f[
  //   \delta\mathbf E_i = \mathrm{sym}(\mathbf F^T\nabla_0\mathbf N_i)
  //   = \mathrm{sym}(\mathbf f_{c_i}\otimes\nabla_0\varphi_i),
  // @f]
  // with $\mathbf f_c$ the row $c$ of $\mathbf F$, and the internal force
  // and the tangent stiffness are
  // @f[
  //   f_i = \int \delta\mathbf E_i : \mathbf S\;dV
  //       = \int \mathbf f_{c_i}\cdot\mathbf S\,\nabla_0\varphi_i\;dV,\qquad
  //   K_{ij} = \int \delta\mathbf E_i : \mathcal C : \delta\mathbf E_j
  //          + \delta_{c_ic_j}\,\nabla_0\varphi_i\cdot\mathbf S\,
  //            \nabla_0\varphi_j \; dV,
  // @f]
  // the first term of $K_{ij}$ being the material part, which times
  // $\zeta$ is the damping matrix of this state (see the class
  // documentation); with `with_damping` it is assembled into
  // `next_damping_matrix` alongside. The gradients $\nabla_0\varphi_i$ and
  // weights come from the cache of setup_cell_geometry(). Without the
  // matrix only first derivatives of the energy are computed
  // (NeoHookeanEnergy::evaluate_stress()), which costs a sixth of the full
  // evaluation.
  //
  // With the matrix, the cells are processed by deal.II's WorkStream: the
  // cell integrals (`local_assemble`, which holds nearly all of the
  // arithmetic) run on all threads, the additions into the global matrices
  // and vectors (`copy_local_to_global`) one after the other, in the order
  // of the cells, so that the result does not depend on the number of
  // threads.
  // The number of threads is deal.II's default -- the cores divided among
  // the MPI processes of the machine -- and can be limited with the
  // environment variable DEAL_II_NUM_THREADS.
  //
  // A quadrature point with $\det\mathbf F\le 0$ has no physical meaning:
  // it is reported (on all processes), and the caller rejects the state.
  namespace
  {
    // The work space of one thread: the material response and the strain
    // variations of a cell's shape functions.
    template <int dim>
    struct AssemblyScratch
    {
      MaterialResponse<dim>                response;
      std::vector<SymmetricTensor<2, dim>> delta_E;
      std::vector<Tensor<2, dim>>          H;
      Vector<double>                       volume_gradient;
    };

    // What one cell contributes: its matrices, force, dof indices, and its
    // part of the results of the assembly.
    struct CellContribution
    {
      FullMatrix<double>                   matrix;
      FullMatrix<double>                   damping;
      Vector<double>                       force;
      std::vector<types::global_dof_index> dof_indices;
      double                               strain_energy = 0.;
      double min_jacobian  = std::numeric_limits<double>::max();
      bool   inverted      = false;
      unsigned int cell    = 0;
      bool   with_matrix   = false;
      bool   with_damping  = false;
    };
  } // namespace



  template <int dim>
  AssemblyResult
  SoftRobotDynamics<dim>::assemble_internal_force(
    const TrilinosWrappers::MPI::Vector &u,
    const bool                           with_matrix,
    TrilinosWrappers::MPI::Vector       &internal_force,
    const bool                           with_damping_matrix)
  {
    TimerOutput::Scope timer_section(computing_timer,
                                     with_matrix ? "Assemble system" :
                                                   "Assemble residual");

    const CellGeometry &geometry      = cell_geometry;
    const unsigned int  dofs_per_cell = geometry.dofs_per_cell;
    const unsigned int  n_q_points    = geometry.n_q_points;
    const std::vector<unsigned int> &component = geometry.components;

    const bool with_damping = with_matrix && has_damping && with_damping_matrix;
    const bool mean_dilatation =
      (dim == 3) &&
      (parameters.volumetric_formulation ==
       Parameters::FiniteElement::VolumetricFormulation::mean_dilatation);
    if (with_matrix)
      system_matrix = 0.;
    if (with_damping)
      next_damping_matrix = 0.;
    internal_force = 0.;

    // The cell matrices go straight to the value arrays of the matrices, at
    // the addresses that setup_cell_geometry() computed (in parallel runs
    // the rows of this process); in serial runs the force vector's entries
    // too.
    const bool direct_addresses = !geometry.matrix_positions.empty();
    const bool direct_vectors   = !geometry.vector_positions.empty();
    const bool distributed_vectors =
      !geometry.distributed_vector_positions.empty();
    double    *matrix_values = nullptr, *damping_values = nullptr;
    if (direct_addresses)
      {
        int *offsets = nullptr, *columns = nullptr;
        system_matrix.trilinos_matrix().ExtractCrsDataPointers(offsets,
                                                               columns,
                                                               matrix_values);
        if (with_damping)
          next_damping_matrix.trilinos_matrix().ExtractCrsDataPointers(
            offsets, columns, damping_values);
      }
    double *force_values = internal_force.trilinos_vector()[0];

    // The displacements of the cells' dofs, read once (in parallel runs
    // with the entries of other processes fetched first), so that the
    // threads only read a plain array.
    std::vector<double> cell_values(geometry.dof_indices.size());
    if (direct_vectors)
      {
        const double *u_values = u.trilinos_vector()[0];
        for (std::size_t k = 0; k < cell_values.size(); ++k)
          cell_values[k] = (geometry.vector_positions[k] >= 0) ?
                             u_values[geometry.vector_positions[k]] :
                             0.;
      }
    else if (distributed_vectors)
      {
        ghost_displacements->Import(u.trilinos_vector(), *ghost_import, Insert);
        ghost_forces->PutScalar(0.); // the sums start here too
        const double *u_values     = u.trilinos_vector()[0];
        const double *ghost_values = ghost_displacements->Values();
        for (std::size_t k = 0; k < cell_values.size(); ++k)
          {
            const int position = geometry.distributed_vector_positions[k];
            cell_values[k]     = (position >= 0)  ? u_values[position] :
                                 (position == -1) ? 0. :
                                                    ghost_values[-2 - position];
          }
      }
    else
      {
        TrilinosWrappers::MPI::Vector u_ghosted(locally_owned_dofs,
                                                locally_relevant_dofs,
                                                mpi_communicator);
        u_ghosted = u;
        for (std::size_t k = 0; k < cell_values.size(); ++k)
          cell_values[k] = u_ghosted(geometry.dof_indices[k]);
      }

    // The integrals over one cell.
    const auto local_assemble = [&](const unsigned int   *cell_pointer,
                                    AssemblyScratch<dim> &scratch,
                                    CellContribution     &local) {
      const unsigned int     cell     = *cell_pointer;
      MaterialResponse<dim> &response = scratch.response;
      scratch.delta_E.resize(dofs_per_cell);
      std::vector<SymmetricTensor<2, dim>> &delta_E = scratch.delta_E;
      if (local.force.size() != dofs_per_cell)
        {
          local.matrix.reinit(dofs_per_cell, dofs_per_cell);
          local.damping.reinit(dofs_per_cell, dofs_per_cell);
          local.force.reinit(dofs_per_cell);
          local.dof_indices.resize(dofs_per_cell);
        }
      local.cell          = cell;
      local.with_matrix   = with_matrix;
      local.with_damping  = with_damping;
      local.strain_energy = 0.;
      local.min_jacobian  = std::numeric_limits<double>::max();
      local.inverted      = false;
      std::copy_n(geometry.dof_indices.begin() + cell * dofs_per_cell,
                  dofs_per_cell,
                  local.dof_indices.begin());
      const double *cell_u = &cell_values[cell * dofs_per_cell];
      const NeoHookeanEnergy<dim> &material = *geometry.material[cell];
      const double                 zeta     = geometry.damping_zeta[cell];

      if (with_matrix)
        {
          local.matrix  = 0.;
          local.damping = 0.;
        }
      local.force = 0.;

      // The displacement gradients at the quadrature points.
      std::vector<Tensor<2, dim>> &H = scratch.H;
      H.assign(n_q_points, Tensor<2, dim>());
      for (unsigned int q = 0; q < n_q_points; ++q)
        {
          const Tensor<1, dim> *grad_phi =
            &geometry.shape_gradients[(cell * n_q_points + q) * dofs_per_cell];
          for (unsigned int i = 0; i < dofs_per_cell; ++i)
            H[q][component[i]] += cell_u[i] * grad_phi[i];
        }

      // The mean-dilatation formulation (see the class documentation): the
      // cell's mean volume ratio $\Theta = 1 + t$, its volumetric energy
      // $V_e\,U(\Theta)$, the pressure $p = U'(\Theta)$ every point of the
      // cell feels, and $U''(\Theta)/V_e$ for the tangent.
      double pressure = 0., volumetric_stiffness = 0., cell_volume = 0.;
      if (mean_dilatation)
        {
          double volume_change = 0.;
          for (unsigned int q = 0; q < n_q_points; ++q)
            {
              const double JxW = geometry.JxW[cell * n_q_points + q];
              cell_volume += JxW;
              volume_change += NeoHookeanEnergy<dim>::volume_change(
                                 NeoHookeanEnergy<dim>::green_lagrange_strain(
                                   H[q])) *
                               JxW;
            }
          const double t = volume_change / cell_volume;
          if (!(t > -1.))
            local.inverted = true;
          else
            {
              pressure             = material.volumetric_pressure(t);
              volumetric_stiffness = material.volumetric_stiffness(t);
              local.strain_energy += material.volumetric_energy(t) * cell_volume;
            }
          if (with_matrix)
            scratch.volume_gradient.reinit(dofs_per_cell);
        }

      for (unsigned int q = 0; q < n_q_points; ++q)
        {
          const unsigned int    point = cell * n_q_points + q;
          const Tensor<1, dim> *grad_phi =
            &geometry.shape_gradients[point * dofs_per_cell];
          const double JxW = geometry.JxW[point];

          Tensor<2, dim> F = H[q];
          for (unsigned int d = 0; d < dim; ++d)
            F[d][d] += 1.;
          const double J     = determinant(F);
          local.min_jacobian = std::min(local.min_jacobian, J);
          if (!(J > 0.) || local.inverted)
            {
              local.inverted = true;
              continue;
            }
          if (mean_dilatation)
            material.evaluate_with_pressure(H[q],
                                            pressure,
                                            with_matrix,
                                            response);
          else if (with_matrix)
            material.evaluate(H[q], response);
          else
            material.evaluate_stress(H[q], response);
          local.strain_energy += response.energy * JxW;

          // The derivative of the cell's volume, $\partial(V_e\Theta)/
          // \partial u_i = \int (\mathrm{cof}\,\mathbf F)_{c_i}\cdot
          // \nabla_0\varphi_i\,dV$, for the rank-one part of the tangent.
          if (mean_dilatation && with_matrix)
            {
              const Tensor<2, dim> cofactor = J * transpose(invert(F));
              for (unsigned int i = 0; i < dofs_per_cell; ++i)
                scratch.volume_gradient(i) +=
                  (cofactor[component[i]] * grad_phi[i]) * JxW;
            }

          const SymmetricTensor<2, dim> &S = response.second_piola;
          for (unsigned int i = 0; i < dofs_per_cell; ++i)
            {
              const Tensor<1, dim> f_c = F[component[i]];
              local.force(i) += (f_c * (S * grad_phi[i])) * JxW;
              if (with_matrix)
                delta_E[i] = symmetrize(outer_product(f_c, grad_phi[i]));
            }
          if (!with_matrix)
            continue;

          // The damping uses the positive semi-definite part of the
          // material tangent (see positive_semidefinite_part()).
          const bool              damped = with_damping && zeta > 0.;
          SymmetricTensor<4, dim> damping_tangent;
          if (damped)
            damping_tangent =
              positive_semidefinite_part(response.material_tangent);
          for (unsigned int i = 0; i < dofs_per_cell; ++i)
            {
              const SymmetricTensor<2, dim> C_dE_i =
                response.material_tangent * delta_E[i];
              const Tensor<1, dim> S_grad_phi_i = S * grad_phi[i];
              for (unsigned int j = 0; j <= i; ++j)
                {
                  double value = C_dE_i * delta_E[j];
                  if (component[i] == component[j])
                    value += S_grad_phi_i * grad_phi[j];
                  local.matrix(i, j) += value * JxW;
                }
              if (damped)
                {
                  const SymmetricTensor<2, dim> D_dE_i =
                    damping_tangent * delta_E[i];
                  for (unsigned int j = 0; j <= i; ++j)
                    local.damping(i, j) += zeta * (D_dE_i * delta_E[j]) * JxW;
                }
            }
        }
      // The condensed pressure and dilatation add $U''(\Theta)/V_e\;
      // \mathbf g\mathbf g^T$ with the volume derivative $\mathbf g$ above;
      // it is positive semi-definite and belongs to the material part, so
      // the damping matrix gets it too.
      if (mean_dilatation && with_matrix && !local.inverted)
        {
          const Vector<double> &g      = scratch.volume_gradient;
          const double          factor = volumetric_stiffness / cell_volume;
          const bool            damped = with_damping && zeta > 0.;
          for (unsigned int i = 0; i < dofs_per_cell; ++i)
            for (unsigned int j = 0; j <= i; ++j)
              {
                local.matrix(i, j) += factor * g(i) * g(j);
                if (damped)
                  local.damping(i, j) += zeta * factor * g(i) * g(j);
              }
        }
      if (with_matrix)
        for (unsigned int i = 0; i < dofs_per_cell; ++i)
          for (unsigned int j = i + 1; j < dofs_per_cell; ++j)
            {
              local.matrix(i, j)  = local.matrix(j, i);
              local.damping(i, j) = local.damping(j, i);
            }
    };

    // The additions of a cell matrix at the direct addresses. A
    // constrained dof's row and column are left out, and its diagonal gets
    // the absolute value of the cell matrix's diagonal entry (if that is
    // zero, the mean absolute diagonal entry), as
    // AffineConstraints::distribute_local_to_global() does: it keeps the
    // matrix regular and of the scale of its other entries. A row of
    // another process (address -2) goes through Epetra, which sends it to
    // its owner when the matrix is compressed.
    const unsigned int dofs_squared = dofs_per_cell * dofs_per_cell;
    const auto add_matrix = [&](const CellContribution         &local,
                                const FullMatrix<double>       &cell_matrix,
                                double                         *values,
                                TrilinosWrappers::SparseMatrix &matrix) {
      const int *matrix_position =
        &geometry.matrix_positions[local.cell * dofs_squared];
      const int *diagonal_position =
        &geometry.diagonal_positions[local.cell * dofs_per_cell];
      const double *entries = &cell_matrix(0, 0);
      for (unsigned int k = 0; k < dofs_squared; ++k)
        if (matrix_position[k] >= 0)
          values[matrix_position[k]] += entries[k];
      double mean_diagonal = 0.;
      for (unsigned int i = 0; i < dofs_per_cell; ++i)
        mean_diagonal += std::abs(cell_matrix(i, i));
      mean_diagonal /= dofs_per_cell;
      if (mean_diagonal == 0.)
        mean_diagonal = cell_matrix.l1_norm() / dofs_per_cell;
      if (mean_diagonal == 0.)
        mean_diagonal = 1.;
      for (unsigned int i = 0; i < dofs_per_cell; ++i)
        {
          const double diagonal = (cell_matrix(i, i) != 0.) ?
                                    std::abs(cell_matrix(i, i)) :
                                    mean_diagonal;
          if (diagonal_position[i] >= 0)
            values[diagonal_position[i]] += diagonal;
          else if (diagonal_position[i] == -2)
            {
              const types::global_dof_index row = local.dof_indices[i];
              if (constraints.is_constrained(row))
                matrix.add(row, row, diagonal);
              else
                for (unsigned int j = 0; j < dofs_per_cell; ++j)
                  if (!constraints.is_constrained(local.dof_indices[j]))
                    matrix.add(row, local.dof_indices[j], cell_matrix(i, j));
            }
        }
    };
    // In serial runs also the force vector's entries.
    const auto add_with_direct_addresses = [&](const CellContribution &local) {
      const int *vector_position =
        &geometry.vector_positions[local.cell * dofs_per_cell];
      for (unsigned int i = 0; i < dofs_per_cell; ++i)
        if (vector_position[i] >= 0)
          force_values[vector_position[i]] += local.force(i);
      if (!local.with_matrix)
        return;
      add_matrix(local, local.matrix, matrix_values, system_matrix);
      if (local.with_damping)
        add_matrix(local, local.damping, damping_values, next_damping_matrix);
    };

    // The additions into the global objects, in the order of the cells.
    AssemblyResult result;
    const auto     copy_local_to_global = [&](const CellContribution &local) {
      result.strain_energy += local.strain_energy;
      result.min_jacobian = std::min(result.min_jacobian, local.min_jacobian);
      result.inverted_point_found =
        result.inverted_point_found || local.inverted;
      if (direct_vectors)
        {
          add_with_direct_addresses(local);
          return;
        }
      if (distributed_vectors)
        {
          const int *position =
            &geometry.distributed_vector_positions[local.cell * dofs_per_cell];
          double *ghost_values = ghost_forces->Values();
          for (unsigned int i = 0; i < dofs_per_cell; ++i)
            if (position[i] >= 0)
              force_values[position[i]] += local.force(i);
            else if (position[i] <= -2)
              ghost_values[-2 - position[i]] += local.force(i);
          if (local.with_matrix)
            add_matrix(local, local.matrix, matrix_values, system_matrix);
          if (local.with_damping)
            add_matrix(local,
                       local.damping,
                       damping_values,
                       next_damping_matrix);
          return;
        }
      if (local.with_matrix)
        constraints.distribute_local_to_global(local.matrix,
                                               local.force,
                                               local.dof_indices,
                                               system_matrix,
                                               internal_force);
      else
        constraints.distribute_local_to_global(local.force,
                                               local.dof_indices,
                                               internal_force);
      if (local.with_damping)
        constraints.distribute_local_to_global(local.damping,
                                               local.dof_indices,
                                               next_damping_matrix);
    };

    // A residual costs about a microsecond per linear tetrahedron, too
    // little for WorkStream's synchronisation per chunk of cells to pay (on
    // the bellows it made the residual assembly slower). In serial runs the
    // cells are instead split into two halves, each summed into its own copy
    // of the force vector, and the two copies are added in a fixed order:
    // with two or more threads the halves run at the same time, and the
    // result does not depend on the number of threads. Parallel runs
    // assemble residuals in one thread.
    std::vector<unsigned int> cells(geometry.n_cells);
    std::iota(cells.begin(), cells.end(), 0U);
    if (with_matrix)
      WorkStream::run(cells.data(),
                      cells.data() + cells.size(),
                      local_assemble,
                      copy_local_to_global,
                      AssemblyScratch<dim>(),
                      CellContribution(),
                      2 * MultithreadInfo::n_threads(),
                      64);
    else if (direct_vectors)
      {
        constexpr unsigned int              n_parts = 2;
        const unsigned int                  n_values = internal_force.locally_owned_size();
        std::array<std::vector<double>, n_parts> part_force;
        std::array<AssemblyResult, n_parts>      part_result;
        const auto assemble_part = [&](const unsigned int part) {
          part_force[part].assign(n_values, 0.);
          AssemblyScratch<dim> scratch;
          CellContribution     local;
          for (unsigned int cell = part * geometry.n_cells / n_parts;
               cell < (part + 1) * geometry.n_cells / n_parts;
               ++cell)
            {
              local_assemble(&cell, scratch, local);
              const int *vector_position =
                &geometry.vector_positions[cell * dofs_per_cell];
              for (unsigned int i = 0; i < dofs_per_cell; ++i)
                if (vector_position[i] >= 0)
                  part_force[part][vector_position[i]] += local.force(i);
              AssemblyResult &r = part_result[part];
              r.strain_energy += local.strain_energy;
              r.min_jacobian = std::min(r.min_jacobian, local.min_jacobian);
              r.inverted_point_found = r.inverted_point_found || local.inverted;
            }
        };
        if (MultithreadInfo::n_threads() > 1)
          {
            Threads::Task<void> first_half =
              Threads::new_task([&assemble_part]() { assemble_part(0); });
            assemble_part(1);
            first_half.join();
          }
        else
          for (unsigned int part = 0; part < n_parts; ++part)
            assemble_part(part);
        for (unsigned int part = 0; part < n_parts; ++part)
          {
            for (unsigned int k = 0; k < n_values; ++k)
              force_values[k] += part_force[part][k];
            result.strain_energy += part_result[part].strain_energy;
            result.min_jacobian =
              std::min(result.min_jacobian, part_result[part].min_jacobian);
            result.inverted_point_found = result.inverted_point_found ||
                                          part_result[part].inverted_point_found;
          }
      }
    else
      {
        AssemblyScratch<dim> scratch;
        CellContribution     local;
        for (const unsigned int &cell : cells)
          {
            local_assemble(&cell, scratch, local);
            copy_local_to_global(local);
          }
      }

    if (with_matrix)
      system_matrix.compress(VectorOperation::add);
    if (with_damping)
      next_damping_matrix.compress(VectorOperation::add);
    // (In serial runs the vector was not touched through deal.II, and one
    // process has nothing to exchange; in parallel runs with direct
    // addresses the forces of other processes' dofs go to their owners in
    // the exchange set up by setup_cell_geometry().)
    if (distributed_vectors)
      {
        const int error =
          internal_force.trilinos_vector().Export(*ghost_forces,
                                                  *ghost_import,
                                                  Add);
        AssertThrow(error == 0,
                    ExcMessage("Sending the interface forces failed."));
      }
    else if (!direct_vectors)
      internal_force.compress(VectorOperation::add);

    result.strain_energy =
      Utilities::MPI::sum(result.strain_energy, mpi_communicator);
    result.min_jacobian =
      Utilities::MPI::min(result.min_jacobian, mpi_communicator);
    result.inverted_point_found =
      Utilities::MPI::max(result.inverted_point_found ? 1 : 0,
                          mpi_communicator) == 1;
    return result;
  }



  // @sect4{SoftRobotDynamics::assemble_external_force}
  //
  // Gravity (assembled once with the mass matrix) plus the nominal
  // tractions $\bar{\mathbf t}(\mathbf X, t)$ on the boundaries the
  // parameter file names and the body force of set_body_force(), if any,
  // all scaled by the load factor of the static solve (one during the time
  // loop).
  template <int dim>
  void
  SoftRobotDynamics<dim>::assemble_external_force(
    const double                   time,
    const double                   load_factor,
    TrilinosWrappers::MPI::Vector &force) const
  {
    force = gravity_force;
    if (!parameters.traction_boundary_ids.empty())
      {
        // The faces and their reference data come from
        // setup_traction_faces(); a face where the traction vanishes at all
        // points adds nothing.
        TimerOutput::Scope timer_section(computing_timer, "Assemble tractions");
        TrilinosWrappers::MPI::Vector traction_force(locally_owned_dofs,
                                                     mpi_communicator);
        const unsigned int dofs_per_cell = fe->n_dofs_per_cell();
        const unsigned int n_q_points    = traction_faces.n_q_points;
        Vector<double>     cell_force(dofs_per_cell);
        std::vector<types::global_dof_index> dof_indices(dofs_per_cell);
        Vector<double>                       value(dim);
        traction_function.set_time(time);
        for (unsigned int face = 0; face < traction_faces.n_faces; ++face)
          {
            bool loaded = false;
            cell_force  = 0.;
            for (unsigned int q = 0; q < n_q_points; ++q)
              {
                traction_function.vector_value(
                  traction_faces.points[face * n_q_points + q], value);
                if (value.l2_norm() == 0.)
                  continue;
                loaded              = true;
                const double *shape = &traction_faces.weighted_shape_values
                                         [(face * n_q_points + q) *
                                          dofs_per_cell];
                for (unsigned int i = 0; i < dofs_per_cell; ++i)
                  cell_force(i) +=
                    shape[i] * value[cell_geometry.components[i]];
              }
            if (!loaded)
              continue;
            std::copy_n(&traction_faces.dof_indices[face * dofs_per_cell],
                        dofs_per_cell,
                        dof_indices.begin());
            constraints.distribute_local_to_global(cell_force,
                                                   dof_indices,
                                                   traction_force);
          }
        traction_force.compress(VectorOperation::add);
        force += traction_force;
      }
    if (body_force)
      {
        TimerOutput::Scope timer_section(computing_timer,
                                         "Assemble body force");
        TrilinosWrappers::MPI::Vector body_force_vector(locally_owned_dofs,
                                                        mpi_communicator);
        FEValues<dim>                 fe_values(*mapping,
                                *fe,
                                *mass_quadrature,
                                update_values | update_quadrature_points |
                                  update_JxW_values);
        const FEValuesExtractors::Vector     displacements(0);
        const unsigned int                   dofs_per_cell = fe->n_dofs_per_cell();
        Vector<double>                       cell_force(dofs_per_cell);
        std::vector<types::global_dof_index> dof_indices(dofs_per_cell);
        Vector<double>                       value(dim);
        body_force->set_time(time);
        for (const auto &cell : dof_handler.active_cell_iterators())
          if (cell->is_locally_owned())
            {
              fe_values.reinit(cell);
              cell_force           = 0.;
              const double section = material_of(cell).section;
              for (const unsigned int q : fe_values.quadrature_point_indices())
                {
                  body_force->vector_value(fe_values.quadrature_point(q), value);
                  Tensor<1, dim> b;
                  for (unsigned int d = 0; d < dim; ++d)
                    b[d] = value[d];
                  for (const unsigned int i : fe_values.dof_indices())
                    cell_force(i) += fe_values[displacements].value(i, q) * b *
                                     fe_values.JxW(q) * section;
                }
              cell->get_dof_indices(dof_indices);
              constraints.distribute_local_to_global(cell_force,
                                                     dof_indices,
                                                     body_force_vector);
            }
        body_force_vector.compress(VectorOperation::add);
        force += body_force_vector;
      }
    force *= load_factor;
  }



#define SOFT_ROBOT_INSTANTIATE(dim)                                           \
  template AssemblyResult SoftRobotDynamics< \
    dim>::assemble_internal_force(const TrilinosWrappers::MPI::Vector &,      \
                                  const bool,                                 \
                                  TrilinosWrappers::MPI::Vector &,            \
                                  const bool);                                \
  template void SoftRobotDynamics<dim>::assemble_external_force(              \
    const double, const double, TrilinosWrappers::MPI::Vector &) const;

  SOFT_ROBOT_INSTANTIATE(1)
  SOFT_ROBOT_INSTANTIATE(2)
  SOFT_ROBOT_INSTANTIATE(3)
#undef SOFT_ROBOT_INSTANTIATE
} // namespace SoftRobot
