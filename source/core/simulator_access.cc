// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Access to the simulator's internals}
//
// See include/core/simulator_access.h.

#include <core/config.h>
#include <core/simulator_access.h>

namespace SoftRobot
{
  template <int dim>
  SimulatorAccess<dim>::SimulatorAccess(SoftRobotDynamics<dim> &simulator)
    : simulator(simulator)
  {
  }

  template <int dim>
  void
  SimulatorAccess<dim>::make_grid()
  {
    simulator.make_grid();
  }

  template <int dim>
  void
  SimulatorAccess<dim>::setup_system()
  {
    simulator.setup_system();
  }

  template <int dim>
  void
  SimulatorAccess<dim>::solve_static_equilibrium(const double time)
  {
    simulator.solve_static_equilibrium(time);
  }

  template <int dim>
  void
  SimulatorAccess<dim>::initialize_state()
  {
    simulator.initialize_state();
  }

  template <int dim>
  bool
  SimulatorAccess<dim>::advance_one_step()
  {
    return simulator.advance_one_step();
  }

  template <int dim>
  void
  SimulatorAccess<dim>::set_body_force(
    const std::shared_ptr<Function<dim>> &force)
  {
    simulator.body_force = force;
  }

  template <int dim>
  const DoFHandler<dim> &
  SimulatorAccess<dim>::get_dof_handler() const
  {
    return simulator.dof_handler;
  }

  template <int dim>
  const Mapping<dim> &
  SimulatorAccess<dim>::get_mapping() const
  {
    return *simulator.mapping;
  }

  template <int dim>
  const AffineConstraints<double> &
  SimulatorAccess<dim>::get_constraints() const
  {
    return simulator.constraints;
  }

  template <int dim>
  const CellGeometry<dim> &
  SimulatorAccess<dim>::get_cell_geometry() const
  {
    return simulator.cell_geometry;
  }

  template <int dim>
  const HyperelasticSolid<dim> &
  SimulatorAccess<dim>::get_solid() const
  {
    Assert(simulator.solid != nullptr,
           ExcMessage("The solid exists after setup_system()."));
    return *simulator.solid;
  }

  template <int dim>
  double
  SimulatorAccess<dim>::time() const
  {
    return simulator.current.time;
  }

  template <int dim>
  const TrilinosWrappers::MPI::Vector &
  SimulatorAccess<dim>::displacement() const
  {
    return simulator.current.u;
  }

  template <int dim>
  const TrilinosWrappers::MPI::Vector &
  SimulatorAccess<dim>::velocity() const
  {
    return simulator.current.v;
  }

  template <int dim>
  const TrilinosWrappers::MPI::Vector &
  SimulatorAccess<dim>::acceleration() const
  {
    return simulator.current.a;
  }

  template <int dim>
  std::pair<Tensor<1, dim>, Tensor<1, dim>>
  SimulatorAccess<dim>::tip_motion() const
  {
    return simulator.tip_region.motion(simulator.current.u,
                                       simulator.current.v);
  }

  template <int dim>
  const EnergyAccount &
  SimulatorAccess<dim>::energies() const
  {
    return simulator.energy;
  }

  template <int dim>
  Tensor<1, 3>
  SimulatorAccess<dim>::angular_momentum() const
  {
    return simulator.angular_momentum();
  }

  // The stiffness alone (no damping); the damping matrix of the state is
  // left as it is, and the next step assembles its own matrix.
  template <int dim>
  const TrilinosWrappers::SparseMatrix &
  SimulatorAccess<dim>::tangent_stiffness_matrix()
  {
    TrilinosWrappers::MPI::Vector force(simulator.locally_owned_dofs,
                                        simulator.mpi_communicator);
    simulator.assemble_internal_force(simulator.current.u, true, force);
    simulator.system_matrix_is_state_stiffness = false;
    return simulator.system_matrix;
  }

  template <int dim>
  const TrilinosWrappers::SparseMatrix &
  SimulatorAccess<dim>::tangent_stiffness_matrix(
    const TrilinosWrappers::MPI::Vector &u)
  {
    TrilinosWrappers::MPI::Vector force(simulator.locally_owned_dofs,
                                        simulator.mpi_communicator);
    simulator.assemble_internal_force(u, true, force);
    simulator.system_matrix_is_state_stiffness = false;
    return simulator.system_matrix;
  }

  template <int dim>
  double
  SimulatorAccess<dim>::internal_force(const TrilinosWrappers::MPI::Vector &u,
                                       TrilinosWrappers::MPI::Vector &force)
  {
    return simulator.assemble_internal_force(u, false, force).strain_energy;
  }

  template <int dim>
  const TrilinosWrappers::SparseMatrix &
  SimulatorAccess<dim>::mass_matrix() const
  {
    return simulator.inertia.mass;
  }

  template <int dim>
  void
  SimulatorAccess<dim>::record_damping_state(
    const TrilinosWrappers::MPI::Vector &u)
  {
    SoftRobotDynamics<dim>       &s = simulator;
    TrilinosWrappers::MPI::Vector internal(s.locally_owned_dofs,
                                           s.mpi_communicator);
    TrilinosWrappers::MPI::Vector damping(internal), rest(internal);
    AssemblyRequest               request;
    request.matrix          = true;
    request.second_matrix   = s.solid->has_damping() || s.drag;
    request.second_force    = true;
    request.store_viscosity = true;
    s.assemble_forces(u, &rest, request, internal, &damping);
    if (request.second_matrix)
      s.damping_matrix.copy_from(s.next_damping_matrix);
    s.system_matrix_is_state_stiffness = false;
  }

  template <int dim>
  const TrilinosWrappers::SparseMatrix &
  SimulatorAccess<dim>::damped_forces(const TrilinosWrappers::MPI::Vector &u,
                                      const TrilinosWrappers::MPI::Vector &v,
                                      const double velocity_coefficient,
                                      const bool   with_matrix,
                                      TrilinosWrappers::MPI::Vector &internal,
                                      TrilinosWrappers::MPI::Vector &damping)
  {
    SoftRobotDynamics<dim> &s = simulator;
    AssemblyRequest         request;
    request.matrix               = with_matrix;
    request.second_force         = true;
    request.velocity_coefficient = velocity_coefficient;
    s.assemble_forces(u, &v, request, internal, &damping);
    s.add_global_damping_forces(v, damping);
    if (with_matrix)
      s.add_global_damping_matrices(velocity_coefficient, s.system_matrix);
    s.system_matrix_is_state_stiffness = false;
    return s.system_matrix;
  }



  template <int dim>
  PneumaticLoad<dim> &
  SimulatorAccess<dim>::get_pneumatics()
  {
    Assert(simulator.pneumatics != nullptr,
           ExcMessage("There is a pneumatic load after setup_system() when "
                      "Pneumatics/Pressure boundary ids names boundaries."));
    return *simulator.pneumatics;
  }



  template <int dim>
  double
  SimulatorAccess<dim>::pressure() const
  {
    return simulator.current.pressure;
  }



  template <int dim>
  double
  SimulatorAccess<dim>::gas_volume() const
  {
    return simulator.current.gas_volume;
  }



  template <int dim>
  const TrilinosWrappers::MPI::Vector &
  SimulatorAccess<dim>::pressure_force() const
  {
    return simulator.current.pressure_force;
  }



  template <int dim>
  unsigned int
  SimulatorAccess<dim>::n_steps() const
  {
    return simulator.counters.steps;
  }

  template <int dim>
  unsigned int
  SimulatorAccess<dim>::n_newton_iterations() const
  {
    return simulator.counters.newton_iterations;
  }

  template <int dim>
  unsigned int
  SimulatorAccess<dim>::n_tangent_updates() const
  {
    return simulator.linear_solver.n_preparations();
  }

  template <int dim>
  unsigned int
  SimulatorAccess<dim>::n_linear_iterations() const
  {
    return simulator.counters.linear_iterations;
  }

  template <int dim>
  double
  SimulatorAccess<dim>::multigrid_operator_complexity() const
  {
    return simulator.linear_solver.multigrid_operator_complexity();
  }

  template <int dim>
  std::string
  SimulatorAccess<dim>::linear_solver_in_use() const
  {
    return simulator.linear_solver.solver_in_use();
  }



#define SOFT_ROBOT_INSTANTIATE(dim) template class SimulatorAccess<dim>;
  SOFT_ROBOT_FOR_EACH_DIMENSION(SOFT_ROBOT_INSTANTIATE)
#undef SOFT_ROBOT_INSTANTIATE
} // namespace SoftRobot
