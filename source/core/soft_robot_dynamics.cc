// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{SoftRobotDynamics: set-up and the run}
//
// This file holds the phases of SoftRobotDynamics that run once, before the
// time loop -- the constructor, make_grid() and setup_system() -- and
// run(), which strings all phases together. The time step is in
// soft_robot_dynamics_time_step.cc, the output in
// soft_robot_dynamics_output.cc.

#include <assembly/direct_address_assembler.h>
#include <core/config.h>
#include <core/expression_function.h>
#include <core/input_checks.h>
#include <core/mesh.h>
#include <core/soft_robot_dynamics.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/utilities.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_simplex_p.h>
#include <deal.II/fe/mapping_fe.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/sparsity_tools.h>
#include <deal.II/numerics/vector_tools.h>
#include <iomanip>
#include <output/output_directory.h>

namespace SoftRobot
{
  namespace
  {
    // The HHT stepper as the parameter file describes it: $\beta$ and
    // $\gamma$ from $\alpha$ unless both are given.
    HHTStepper
    make_stepper(const Parameters::TimeIntegration &p)
    {
      return (p.beta < 0) ? HHTStepper(p.alpha)
                          : HHTStepper(p.alpha, p.beta, p.gamma);
    }



    // The rigid-body modes (translations and rotations) at the support
    // points of the degrees of freedom, one vector of the locally owned
    // entries per mode: ML builds its coarse spaces from them, which keeps
    // the number of CG iterations of elasticity low.
    template <int dim>
    std::vector<std::vector<double>>
    rigid_body_modes(const Mapping<dim>    &mapping,
                     const DoFHandler<dim> &dof_handler)
    {
      const IndexSet &owned = dof_handler.locally_owned_dofs();
      std::map<types::global_dof_index, Point<dim>> support_points;
      DoFTools::map_dofs_to_support_points(mapping,
                                           dof_handler,
                                           support_points);
      const unsigned int               n_rotations = dim * (dim - 1) / 2;
      std::vector<std::vector<double>> modes(
        dim + n_rotations, std::vector<double>(owned.n_elements(), 0.));
      const FiniteElement<dim>            &fe = dof_handler.get_fe();
      std::vector<types::global_dof_index> dof_indices(fe.n_dofs_per_cell());
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            cell->get_dof_indices(dof_indices);
            for (unsigned int i = 0; i < dof_indices.size(); ++i)
              if (owned.is_element(dof_indices[i]))
                {
                  const unsigned int local =
                    owned.index_within_set(dof_indices[i]);
                  const unsigned int c = fe.system_to_component_index(i).first;
                  const Point<dim>  &x = support_points[dof_indices[i]];
                  modes[c][local]      = 1.;
                  if constexpr (dim == 2)
                    modes[2][local] = (c == 0) ? -x[1] : x[0];
                  if constexpr (dim == 3)
                    {
                      // Rotations about x, y and z: (0,-z,y), (z,0,-x),
                      // (-y,x,0).
                      const double rx[3] = {0., -x[2], x[1]};
                      const double ry[3] = {x[2], 0., -x[0]};
                      const double rz[3] = {-x[1], x[0], 0.};
                      modes[3][local]    = rx[c];
                      modes[4][local]    = ry[c];
                      modes[5][local]    = rz[c];
                    }
                }
          }
      return modes;
    }
  } // namespace



  // @sect4{SoftRobotDynamics::SoftRobotDynamics}
  //
  // The triangulation is a parallel::shared::Triangulation: every process
  // holds the whole (small) mesh, and deal.II partitions the cells (with
  // METIS in Debian's build). Unlike the p4est-based distributed
  // triangulation it supports 1D meshes and tetrahedral meshes from gmsh,
  // which the actuator needs. The expressions of the parameter file are
  // parsed here; main() has checked them (InputChecks::check_expression_syntax())
  // before, so that a mistake in them is reported before any member with
  // MPI communication in its destructor (the timer) exists.
  template <int dim>
  SoftRobotDynamics<dim>::SoftRobotDynamics(
    const Parameters::AllParameters &parameters,
    const MPI_Comm                   mpi_communicator)
    : parameters(parameters)
    , mpi_communicator(mpi_communicator)
    , pcout(std::cout, Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
    , computing_timer(mpi_communicator,
                      pcout,
                      TimerOutput::never,
                      TimerOutput::wall_times)
    , triangulation(mpi_communicator)
    , dof_handler(triangulation)
    , traction(this->parameters)
    , initial_displacement(dim)
    , initial_velocity(dim)
    , stepper(make_stepper(parameters))
    , newton_solver(this->parameters, pcout)
    , step_controller(this->parameters, pcout)
    , linear_solver(this->parameters,
                    parameters.degree,
                    mpi_communicator,
                    computing_timer)
    , trajectory(mpi_communicator)
  {
    AssertThrow(parameters.dimension == dim,
                ExcMessage("The parameter file asks for dimension " +
                           std::to_string(parameters.dimension) +
                           ", but this is SoftRobotDynamics<" +
                           std::to_string(dim) + ">."));
    initialize_vector_function(initial_displacement,
                               parameters.displacement_expression,
                               parameters.constants,
                               "Initial conditions/Displacement");
    initialize_vector_function(initial_velocity,
                               parameters.velocity_expression,
                               parameters.constants,
                               "Initial conditions/Velocity");
  }



  template <int dim>
  SoftRobotDynamics<dim>::~SoftRobotDynamics()
  {
    field_output.reset();
    dof_handler.clear();
  }



  // @sect4{SoftRobotDynamics::make_grid}
  //
  // The mesh (see create_mesh()), then the finite element, mapping and
  // quadrature, which follow the cell shape. The quadrature of the
  // stiffness is the cheapest that integrates the stiffness of a linear
  // problem exactly on affine cells (its integrand, a product of two
  // gradients, has degree 2(p-1) on simplices and 2p per direction on
  // hypercubes): QGaussSimplex(p) -- one point for linear tetrahedra, which
  // makes them constant-strain elements -- and QGauss with p + 1 points per
  // direction. The mass matrix (degree 2p) always gets one point more on
  // simplices.
  template <int dim>
  void
  SoftRobotDynamics<dim>::make_grid()
  {
    TimerOutput::Scope timer_section(computing_timer, "Make grid");
    MidEdgeNodes<dim>  mid_edge_nodes;
    {
      Triangulation<dim> serial;
      create_mesh(parameters, serial, &mid_edge_nodes);
      triangulation.copy_triangulation(serial);
    }
    InputChecks::check_refinement_size(parameters,
                                       dim,
                                       triangulation.n_active_cells());
    triangulation.refine_global(parameters.global_refinements);
    const unsigned int n_materials = check_mesh_ids(parameters, triangulation);

    const unsigned int p = parameters.degree;
    simplex_mesh = (dim > 1) && triangulation.all_reference_cells_are_simplex();
    AssertThrow(simplex_mesh ||
                  triangulation.all_reference_cells_are_hyper_cube(),
                ExcMessage("Meshes that mix cell shapes are not supported."));
    const unsigned int n_q = parameters.quadrature_points > 0
                               ? parameters.quadrature_points
                               : (simplex_mesh ? p : p + 1);
    if (simplex_mesh)
      {
        fe = std::make_unique<FESystem<dim>>(FE_SimplexP<dim>(p), dim);
        if (mid_edge_nodes.empty())
          mapping = std::make_unique<MappingFE<dim>>(FE_SimplexP<dim>(1));
        else
          {
            curved_geometry =
              std::make_unique<CurvedGeometry<dim>>(triangulation,
                                                    mid_edge_nodes);
            mapping = curved_geometry->create_mapping();
          }
        cell_quadrature = std::make_unique<QGaussSimplex<dim>>(n_q);
        mass_quadrature = std::make_unique<QGaussSimplex<dim>>(p + 1);
        face_quadrature = std::make_unique<QGaussSimplex<dim - 1>>(p + 1);
      }
    else
      {
        fe = std::make_unique<FESystem<dim>>(FE_Q<dim>(p), dim);
        // A mesh with curved manifolds (the bellows) gets the isoparametric
        // mapping, which places the support points on them.
        bool curved = false;
        for (const auto &cell : triangulation.active_cell_iterators())
          curved = curved || (cell->manifold_id() != numbers::flat_manifold_id);
        mapping         = std::make_unique<MappingQ<dim>>(curved ? p : 1);
        cell_quadrature = std::make_unique<QGauss<dim>>(n_q);
        mass_quadrature = std::make_unique<QGauss<dim>>(p + 1);
        face_quadrature = std::make_unique<QGauss<dim - 1>>(p + 1);
      }

    InputChecks::check_mesh_geometry(
      parameters, triangulation, *mapping, *fe, *cell_quadrature);

    pcout << "Mesh: " << triangulation.n_global_active_cells() << ' '
          << (simplex_mesh ? "simplex" : "hypercube") << " cells, "
          << n_materials << " material(s)";
    if (curved_geometry)
      pcout << ", curved (second order, mid-edge nodes up to "
            << curved_geometry->largest_offset() << " from the straight edges)";
    pcout << std::endl;
  }



  // @sect4{SoftRobotDynamics::setup_system}
  //
  // Degrees of freedom, the constraints of the fixed boundaries, the
  // sparsity pattern shared by the tangent, damping and mass matrices, the
  // state vectors; then the physics (cell geometry, materials, mass and
  // gravity, tractions, the pneumatic load), the global addition, the near
  // null space of the multigrid solver and the tip region.
  template <int dim>
  void
  SoftRobotDynamics<dim>::setup_system()
  {
    TimerOutput::Scope timer_section(computing_timer, "Setup system");

    dof_handler.distribute_dofs(*fe);
    locally_owned_dofs = dof_handler.locally_owned_dofs();
    DoFTools::extract_locally_relevant_dofs(dof_handler, locally_relevant_dofs);

    constraints.clear();
    constraints.reinit(locally_relevant_dofs);
    for (const auto &[boundary_id, letters] : parameters.fixed_components)
      {
        std::vector<bool> mask(dim, false);
        for (const char letter : letters)
          mask[letter - 'x'] = true;
        VectorTools::interpolate_boundary_values(*mapping,
                                                 dof_handler,
                                                 boundary_id,
                                                 Functions::ZeroFunction<dim>(
                                                   dim),
                                                 constraints,
                                                 ComponentMask(mask));
      }
    constraints.close();

    DynamicSparsityPattern dsp(locally_relevant_dofs);
    DoFTools::make_sparsity_pattern(dof_handler, dsp, constraints, false);
    SparsityTools::distribute_sparsity_pattern(dsp,
                                               locally_owned_dofs,
                                               mpi_communicator,
                                               locally_relevant_dofs);
    const auto reinit_matrix = [&](TrilinosWrappers::SparseMatrix &matrix) {
      matrix.reinit(locally_owned_dofs,
                    locally_owned_dofs,
                    dsp,
                    mpi_communicator);
    };
    reinit_matrix(system_matrix);
    reinit_matrix(inertia.mass);
    for (State *state : {&current, &previous})
      for (TrilinosWrappers::MPI::Vector *vector : {&state->u,
                                                    &state->v,
                                                    &state->a,
                                                    &state->internal_force,
                                                    &state->external_force,
                                                    &state->damping_force})
        vector->reinit(locally_owned_dofs, mpi_communicator);

    const auto section = [this](const types::material_id id) {
      return parameters.by_id.at(id).section;
    };
    cell_geometry.reinit(*mapping, dof_handler, *cell_quadrature, section);
    // CG and the symmetric factorization need a symmetric matrix: the
    // non-symmetric parts of the damping's tangent are then left out (see
    // KelvinVoigtDamping).
    const bool symmetric_tangent =
      LinearSolver::needs_symmetric_matrix(parameters,
                                           dof_handler.n_dofs(),
                                           mpi_communicator);
    solid = std::make_unique<HyperelasticSolid<dim>>(parameters,
                                                     cell_geometry,
                                                     symmetric_tangent);
    if (!parameters.drag_boundary_ids.empty())
      drag = std::make_unique<AerodynamicDrag<dim>>(parameters,
                                                    cell_geometry,
                                                    *mapping,
                                                    dof_handler,
                                                    *face_quadrature,
                                                    symmetric_tangent);
    lagged_matrix = solid->has_damping() && !solid->has_viscous_stress();
    damped        = solid->has_damping() || drag ||
             Inertia<dim>::has_mass_damping(parameters);
    const bool damping_matrices = solid->has_damping() || drag;
    if (damping_matrices)
      {
        reinit_matrix(damping_matrix);
        reinit_matrix(next_damping_matrix);
      }
    if (Inertia<dim>::has_mass_damping(parameters))
      reinit_matrix(inertia.mass_damping);
    inertia.reinit(parameters,
                   *mapping,
                   dof_handler,
                   *cell_quadrature,
                   *mass_quadrature,
                   constraints,
                   mpi_communicator);
    traction.reinit(*mapping, dof_handler, *face_quadrature);
    rotated_tangent.reset();
    if (parameters.rotated_tangent && dim > 1)
      {
        if (Utilities::MPI::n_mpi_processes(mpi_communicator) == 1)
          rotated_tangent =
            std::make_unique<RotatedTangent<dim>>(*mapping, dof_handler);
        else
          pcout << "Rotated tangent: off (serial runs only)" << std::endl;
      }
    if (parameters.has_pressure())
      {
        pneumatics = std::make_unique<PneumaticLoad<dim>>(parameters,
                                                          triangulation,
                                                          cell_geometry,
                                                          *mapping,
                                                          dof_handler,
                                                          *face_quadrature,
                                                          constraints,
                                                          locally_owned_dofs,
                                                          locally_relevant_dofs,
                                                          mpi_communicator,
                                                          symmetric_tangent);
        for (State *state : {&current, &previous})
          {
            state->pressure_force.reinit(locally_owned_dofs, mpi_communicator);
            state->volume_gradient.reinit(locally_owned_dofs, mpi_communicator);
          }
        pcout << pneumatics->description() << std::endl;
      }
    if (parameters.direct_addresses)
      assembler =
        DirectAddressAssembler<dim>::create(cell_geometry,
                                            constraints,
                                            locally_owned_dofs,
                                            locally_relevant_dofs,
                                            system_matrix,
                                            damping_matrices ? &damping_matrix
                                                             : nullptr,
                                            current.u,
                                            mpi_communicator);
    else
      assembler = std::make_unique<SystemAssembler<dim>>(cell_geometry,
                                                         constraints,
                                                         locally_owned_dofs,
                                                         locally_relevant_dofs,
                                                         mpi_communicator);
    linear_solver.set_near_null_space(rigid_body_modes(*mapping, dof_handler));
    tip_region.reinit(
      parameters,
      *mapping,
      dof_handler,
      *cell_quadrature,
      *face_quadrature,
      constraints,
      [this](const types::material_id id) { return inertia.density(id); },
      mpi_communicator);
    guard.reinit(
      parameters,
      *mapping,
      dof_handler,
      [this](const types::material_id id) { return inertia.density(id); },
      mpi_communicator);

    pcout << "Degrees of freedom: " << dof_handler.n_dofs() << " ("
          << fe->get_name() << ", "
          << Utilities::MPI::n_mpi_processes(mpi_communicator)
          << " MPI process(es))" << std::endl;
  }



  // @sect4{SoftRobotDynamics::check_initial_state}
  //
  // The input, the mesh and the initial fields have been checked; what is
  // left is the state computed from them (the static equilibrium, the
  // initial acceleration, the energies), which must be finite and within
  // what the output can store before anything is written.
  template <int dim>
  void
  SoftRobotDynamics<dim>::check_initial_state() const
  {
    InputChecks::check_initial_state(parameters, state_values());
  }



  // @sect4{SoftRobotDynamics::check_state_is_finite}
  template <int dim>
  void
  SoftRobotDynamics<dim>::check_state_is_finite()
  {
    try
      {
        guard.check_finite(current.time, state_values());
      }
    catch (RunAborted &)
      {
        current_is_finite = false;
        throw;
      }
  }



  // @sect4{SoftRobotDynamics::check_motion}
  template <int dim>
  void
  SoftRobotDynamics<dim>::check_motion() const
  {
    const auto [u_tip, v_tip] = tip_region.motion(current.u, current.v);
    guard.check_motion(current.time, u_tip, v_tip, current.u);
  }



  // @sect4{SoftRobotDynamics::run}
  //
  // The whole simulation. Everything the input determines is checked
  // before the output directory is touched (core/input_checks.h): the
  // parameter file, the mesh, the expressions, the materials, the initial
  // fields and the initial state computed from them. A run that fails its
  // input leaves an existing output directory byte for byte as it was.
  // A run that cannot continue, or whose motion has lost its physical
  // meaning (core/plausibility_guard.h), ends with RunAborted; its last
  // finite state is written first. The final state is always written.
  // A run interrupted by a signal writes a checkpoint and stops
  // (checkpoint_or_stop(), RunInterrupted); a restart continues it.
  template <int dim>
  void
  SoftRobotDynamics<dim>::run()
  {
    Timer wall_clock;
    pcout << "SoftRobotDynamics<" << dim << ">: " << parameters.source_name
          << "\n"
          << stepper.description() << std::endl;
    if (!stepper.is_unconditionally_stable())
      pcout << "Warning: these HHT parameters are not unconditionally "
               "stable; the spectral radius exceeds one for some omega*dt."
            << std::endl;
    else if (std::abs(stepper.gamma() - (0.5 - stepper.alpha())) > 1e-12)
      pcout << "Note: gamma differs from 1/2 - alpha; the scheme is then "
               "only first-order accurate."
            << std::endl;

    InputChecks::check_output_names(parameters);
    make_grid();
    setup_system();
    for (const std::string &warning :
         InputChecks::check_materials_and_loads(parameters, triangulation))
      pcout << warning << std::endl;
    InputChecks::check_initial_fields(parameters,
                                      *mapping,
                                      dof_handler,
                                      *cell_quadrature,
                                      constraints,
                                      mpi_communicator);
    // A restart continues from the state of its checkpoint, in the output
    // directory of the run it continues, which it does not prepare anew.
    const bool     restart = !parameters.restart_directory.empty();
    CheckpointData checkpoint;
    if (restart)
      checkpoint = restore_checkpoint();
    else
      {
        initialize_state();
        check_initial_state();
      }

    // Only now is anything written.
    if (restart)
      trajectory.reopen(parameters.output_directory + "/" +
                          parameters.trajectory_file,
                        checkpoint.trajectory_length);
    else
      {
        prepare_output_directory(parameters, mpi_communicator);
        open_trajectory();
      }
    const unsigned int subdivisions = simplex_mesh ? 1 : parameters.degree;
    if (parameters.write_vtu)
      field_output =
        std::make_unique<FieldOutput<dim>>(parameters.output_directory,
                                           triangulation,
                                           *mapping,
                                           subdivisions,
                                           mpi_communicator,
                                           checkpoint.pvd_records);
    if (parameters.write_hdf5)
      xdmf_output =
        std::make_unique<XdmfOutput<dim>>(parameters.output_directory,
                                          triangulation,
                                          *mapping,
                                          subdivisions,
                                          mpi_communicator,
                                          checkpoint.xdmf_records);

    if (!restart)
      {
        write_trajectory_row();
        output_results();
      }
    const InterruptionHandler interruption_handler;
    const double              start_time = current.time;
    try
      {
        while (advance_one_step())
          {
            check_state_is_finite();
            write_trajectory_row();
            output_results();
            check_motion();
            checkpoint_or_stop();
            if (parameters.progress_interval > 0 &&
                counters.steps % parameters.progress_interval == 0)
              {
                const double elapsed = wall_clock.wall_time();
                const double left    = elapsed / (current.time - start_time) *
                                    (parameters.end_time - current.time);
                pcout << "step " << std::setw(5) << counters.steps
                      << "  t = " << std::fixed << std::setprecision(4)
                      << current.time << " s  dt = " << std::scientific
                      << std::setprecision(2) << step_controller.current_step()
                      << "  Newton " << counters.last_newton_iterations
                      << " (|r| = " << counters.last_residual << ")  elapsed "
                      << std::fixed << std::setprecision(1) << elapsed
                      << " s  left ~" << left << " s" << std::defaultfloat
                      << std::setprecision(6) << std::endl;
              }
          }
      }
    catch (RunAborted &)
      {
        write_final_fields();
        if (field_output)
          field_output->finish();
        throw;
      }
    write_final_fields();
    finish_run(wall_clock.wall_time());
  }



  // The explicit instantiations of this file's member functions.
#define SOFT_ROBOT_INSTANTIATE(dim)                                  \
  template SoftRobotDynamics<dim>::SoftRobotDynamics(                \
    const Parameters::AllParameters &, const MPI_Comm);              \
  template SoftRobotDynamics<dim>::~SoftRobotDynamics();             \
  template void SoftRobotDynamics<dim>::make_grid();                 \
  template void SoftRobotDynamics<dim>::setup_system();              \
  template void SoftRobotDynamics<dim>::check_initial_state() const; \
  template void SoftRobotDynamics<dim>::check_state_is_finite();     \
  template void SoftRobotDynamics<dim>::check_motion() const;        \
  template void SoftRobotDynamics<dim>::run();
  SOFT_ROBOT_FOR_EACH_DIMENSION(SOFT_ROBOT_INSTANTIATE)
#undef SOFT_ROBOT_INSTANTIATE
} // namespace SoftRobot
