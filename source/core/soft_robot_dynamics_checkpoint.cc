// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{SoftRobotDynamics: checkpoints and restarts}
//
// This file holds the phases of SoftRobotDynamics that stop a run so that
// it can be continued, and continue it: the checkpoint after a step, and
// the state restored from one in place of the initial state. What a
// checkpoint holds, and why that is enough for the continued run to
// compute the same steps, is explained in include/output/checkpoint.h.

#include <core/config.h>
#include <core/soft_robot_dynamics.h>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace SoftRobot
{
  namespace
  {
    // The vectors a checkpoint holds, by name: the state of the HHT method,
    // and the HHT forces the energy account's sums go on from (the
    // pressure's only with a pneumatic load).
    template <class State>
    std::vector<std::pair<std::string, TrilinosWrappers::MPI::Vector *>>
    checkpoint_vectors(State                         &current,
                       TrilinosWrappers::MPI::Vector &hht_damping_force,
                       TrilinosWrappers::MPI::Vector &hht_traction_force,
                       TrilinosWrappers::MPI::Vector *hht_pressure_force)
    {
      std::vector<std::pair<std::string, TrilinosWrappers::MPI::Vector *>>
        vectors = {{"u", &current.u},
                   {"v", &current.v},
                   {"a", &current.a},
                   {"internal_force", &current.internal_force},
                   {"external_force", &current.external_force},
                   {"damping_force", &current.damping_force},
                   {"hht_damping_force", &hht_damping_force},
                   {"hht_traction_force", &hht_traction_force}};
      if (hht_pressure_force != nullptr)
        vectors.emplace_back("hht_pressure_force", hht_pressure_force);
      return vectors;
    }
  } // namespace


  // @sect4{SoftRobotDynamics::checkpoint_or_stop}
  //
  // Called after every step, when its trajectory row and fields are
  // written. The signal flag is agreed on by all processes (a reduction),
  // so that all of them write the checkpoint of the same step and stop.
  template <int dim>
  void
  SoftRobotDynamics<dim>::checkpoint_or_stop()
  {
    InterruptionHandler::test_hook(counters.steps, mpi_communicator);
    const int signal_number = InterruptionHandler::requested(mpi_communicator);
    if (signal_number != 0 ||
        (parameters.checkpoint_interval > 0 &&
         counters.steps % parameters.checkpoint_interval == 0))
      write_checkpoint();
    if (signal_number == 0)
      return;

    trajectory.close();
    const std::string directory =
      Checkpoint::directory_of(parameters.output_directory);
    std::ostringstream message;
    message << (signal_number == SIGINT ? "SIGINT" : "SIGTERM")
            << " at t = " << current.time << " s, step " << counters.steps
            << "; the checkpoint of this step is in '" << directory
            << "'. Continue the run with: soft-robot " << parameters.source_name
            << " --restart " << directory
            << " (and the same --set options, if any).";
    throw RunInterrupted(message.str());
  }



  // @sect4{SoftRobotDynamics::write_checkpoint}
  //
  // The field output of the step is waited for first, so that every file
  // the checkpoint's PVD record names is complete on disk.
  template <int dim>
  void
  SoftRobotDynamics<dim>::write_checkpoint()
  {
    TimerOutput::Scope timer_section(computing_timer, "Checkpoint");
    if (field_output)
      field_output->finish();

    CheckpointData data;
    data.dimension   = dim;
    data.n_processes = Utilities::MPI::n_mpi_processes(mpi_communicator);
    data.rank        = Utilities::MPI::this_mpi_process(mpi_communicator);
    data.n_dofs      = dof_handler.n_dofs();
    data.n_cells     = triangulation.n_global_active_cells();
    data.parameters  = parameters.fingerprint;

    data.time                   = current.time;
    data.steps                  = counters.steps;
    data.newton_iterations      = counters.newton_iterations;
    data.linear_iterations      = counters.linear_iterations;
    data.last_newton_iterations = counters.last_newton_iterations;
    data.last_residual          = counters.last_residual;
    data.factorizations         = linear_solver.n_preparations();
    const TimeStepController::State controller = step_controller.state();
    data.time_step                             = controller.time_step;
    data.steps_since_cutback                   = controller.steps_since_cutback;
    data.total_cutbacks                        = controller.total_cutbacks;

    data.energies             = {energy.kinetic,
                                 energy.strain,
                                 energy.gravity_potential,
                                 energy.traction_work,
                                 energy.damping_dissipation,
                                 energy.pressure_work};
    data.initial_total_energy = initial_total_energy;

    data.trajectory_length = trajectory.length();
    data.next_output_time  = next_output_time;
    data.last_output_time  = last_output_time;
    if (field_output)
      data.pvd_records = field_output->records();
    if (xdmf_output)
      data.xdmf_records = xdmf_output->records();

    for (const auto &[name, vector] :
         checkpoint_vectors(current,
                            hht_damping_force,
                            hht_traction_force,
                            pneumatics ? &hht_pressure_force : nullptr))
      data.vectors[name] = Checkpoint::local_values(*vector);
    if (pneumatics)
      data.gas_seal = pneumatics->gas_seal();
    // $\mathbf K_{n-1}$, from which the next step extrapolates (the next
    // step moves it to `older` and records $\mathbf K_n$ as `newer`).
    if (stiffness_history.newer)
      {
        data.has_older_stiffness  = true;
        data.older_stiffness_time = stiffness_history.newer_time;
        data.older_stiffness =
          Checkpoint::local_values(*stiffness_history.newer);
      }

    // The matrix the next step keeps, so that a restarted run iterates as
    // the uninterrupted one.
    if (kept_matrix_dt > 0.)
      {
        data.kept_matrix_dt = kept_matrix_dt;
        data.kept_matrix    = Checkpoint::local_values(system_matrix);
        if (rank_one.active())
          {
            data.kept_rank_one_factor = rank_one.factor();
            data.vectors["kept rank-one vector"] =
              Checkpoint::local_values(rank_one.vector());
          }
        // The state the kept matrix was built at, from which the rotated
        // tangent turns it.
        if (rotated_tangent && rotated_tangent->get_matrix_state().size() > 0)
          data.vectors["kept matrix state"] =
            Checkpoint::local_values(rotated_tangent->get_matrix_state());
      }

    Checkpoint::write(Checkpoint::directory_of(parameters.output_directory),
                      data,
                      mpi_communicator);
  }



  // @sect4{SoftRobotDynamics::restore_checkpoint}
  //
  // The checkpoint is checked against the run first (parameters, mesh,
  // processes), then its state is set. What the state determines -- the
  // stiffness $\mathbf K_n$ in system_matrix, the damping matrix and the
  // Kelvin-Voigt viscosity -- is assembled again by assemble_state(), as
  // at the end of the step that the checkpoint followed. That assembly also
  // gives the state's internal and damping forces, which are compared with
  // the stored ones: equal bits show that the assembled quantities are the
  // interrupted run's. The stored forces are kept in any case.
  template <int dim>
  CheckpointData
  SoftRobotDynamics<dim>::restore_checkpoint()
  {
    TimerOutput::Scope   timer_section(computing_timer, "Restart");
    const CheckpointData data =
      Checkpoint::read(parameters.restart_directory, mpi_communicator);
    Checkpoint::check_compatible(data,
                                 parameters,
                                 dim,
                                 dof_handler.n_dofs(),
                                 triangulation.n_global_active_cells());

    current.time                    = data.time;
    counters.steps                  = data.steps;
    counters.newton_iterations      = data.newton_iterations;
    counters.linear_iterations      = data.linear_iterations;
    counters.last_newton_iterations = data.last_newton_iterations;
    counters.last_residual          = data.last_residual;
    linear_solver.set_n_preparations(data.factorizations);
    step_controller.set_state(
      {data.time_step, data.steps_since_cutback, data.total_cutbacks});
    AssertThrow(data.energies.size() == 6, ExcInternalError());
    energy.kinetic             = data.energies[0];
    energy.strain              = data.energies[1];
    energy.gravity_potential   = data.energies[2];
    energy.traction_work       = data.energies[3];
    energy.damping_dissipation = data.energies[4];
    energy.pressure_work       = data.energies[5];
    initial_total_energy       = data.initial_total_energy;
    next_output_time           = data.next_output_time;
    last_output_time           = data.last_output_time;

    for (const auto &[name, vector] :
         checkpoint_vectors(current,
                            hht_damping_force,
                            hht_traction_force,
                            pneumatics ? &hht_pressure_force : nullptr))
      {
        const auto values = data.vectors.find(name);
        AssertThrow(values != data.vectors.end(),
                    ExcMessage("The checkpoint has no vector '" + name + "'."));
        vector->reinit(locally_owned_dofs, mpi_communicator);
        Checkpoint::set_local_values(values->second, *vector);
      }

    // The sealed gas, before the state's pressure is evaluated again.
    if (pneumatics)
      pneumatics->restore_gas_seal(data.gas_seal);

    // What the state determines, assembled again and checked.
    const TrilinosWrappers::MPI::Vector stored_internal(current.internal_force);
    const TrilinosWrappers::MPI::Vector stored_damping(current.damping_force);
    assemble_state();
    TrilinosWrappers::MPI::Vector difference(current.internal_force);
    difference -= stored_internal;
    double deviation = difference.linfty_norm();
    difference       = current.damping_force;
    difference -= stored_damping;
    deviation              = std::max(deviation, difference.linfty_norm());
    current.internal_force = stored_internal;
    current.damping_force  = stored_damping;

    stiffness_history = StiffnessHistory();
    if (data.has_older_stiffness)
      {
        stiffness_history.newer =
          std::make_unique<TrilinosWrappers::SparseMatrix>();
        stiffness_history.newer->copy_from(system_matrix);
        Checkpoint::set_local_values(data.older_stiffness,
                                     *stiffness_history.newer);
        stiffness_history.newer_time = data.older_stiffness_time;
      }
    // The kept matrix of the interrupted run, prepared again: the
    // factorization of the same values is the same, and the counters are
    // those of the interrupted run.
    if (data.kept_matrix_dt > 0.)
      {
        Checkpoint::set_local_values(data.kept_matrix, system_matrix);
        if (data.kept_rank_one_factor > 0.)
          {
            TrilinosWrappers::MPI::Vector g(locally_owned_dofs,
                                            mpi_communicator);
            Checkpoint::set_local_values(
              data.vectors.at("kept rank-one vector"), g);
            rank_one.set(g, data.kept_rank_one_factor);
          }
        else
          rank_one.clear();
        if (rotated_tangent && data.vectors.count("kept matrix state") > 0)
          {
            TrilinosWrappers::MPI::Vector state(locally_owned_dofs,
                                                mpi_communicator);
            Checkpoint::set_local_values(data.vectors.at("kept matrix state"),
                                         state);
            rotated_tangent->set_matrix_state(state);
          }
        prepare_linear_solver();
        linear_solver.set_n_preparations(data.factorizations);
        counters.linear_iterations       = data.linear_iterations;
        system_matrix_is_state_stiffness = false;
        kept_matrix_dt                   = data.kept_matrix_dt;
      }
    previous = current;

    pcout << "Restarted from the checkpoint of step " << counters.steps
          << " at t = " << current.time << " s in '"
          << parameters.restart_directory
          << "'; the forces of its state assembled again differ from the "
             "stored ones by "
          << deviation << "." << std::endl;
    return data;
  }



  // The explicit instantiations of this file's member functions.
#define SOFT_ROBOT_INSTANTIATE(dim)                                     \
  template void           SoftRobotDynamics<dim>::checkpoint_or_stop(); \
  template void           SoftRobotDynamics<dim>::write_checkpoint();   \
  template CheckpointData SoftRobotDynamics<dim>::restore_checkpoint();
  SOFT_ROBOT_FOR_EACH_DIMENSION(SOFT_ROBOT_INSTANTIATE)
#undef SOFT_ROBOT_INSTANTIATE
} // namespace SoftRobot
