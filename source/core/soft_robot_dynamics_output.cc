// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{SoftRobotDynamics: what a run writes}
//
// Three kinds of output: VTU files of the whole body at the output interval
// (FieldOutput), one row per time step in a CSV file with the motion of the
// tip region and the energy balance (TrajectoryWriter), the input of the
// spectral analysis, and at the end the statistics of the run and,
// optionally, the spectral analysis of the tip motion.

#include <analysis/spectral_analysis.h>
#include <analysis/spectral_report.h>
#include <cmath>
#include <core/config.h>
#include <core/soft_robot_dynamics.h>
#include <deal.II/base/multithread_info.h>
#include <deal.II/base/utilities.h>
#include <output/run_statistics.h>
#include <output/safe_file.h>
#include <solvers/blas_kernels.h>
#include <sstream>

namespace SoftRobot
{
  // @sect4{SoftRobotDynamics::angular_momentum}
  template <int dim>
  Tensor<1, 3>
  SoftRobotDynamics<dim>::angular_momentum() const
  {
    TrilinosWrappers::MPI::Vector u(locally_owned_dofs,
                                    locally_relevant_dofs,
                                    mpi_communicator);
    TrilinosWrappers::MPI::Vector v(u);
    u = current.u;
    v = current.v;
    return inertia.angular_momentum(dof_handler, u, v, mpi_communicator);
  }



  // @sect4{SoftRobotDynamics::open_trajectory}
  //
  // The columns: time, time step, tip displacement and velocity (one
  // component per dimension; x is the actuator's axis), the energies of
  // EnergyAccount and their balance, the Newton iterations of the step, and
  // the angular momentum about the origin (its three components in 3D, the
  // z-component in 2D, none in 1D). With a pneumatic load: the gauge
  // pressure, the gas volume of the whole body (if the loaded surface
  // bounds one) and the work of the pressure, which the energy balance
  // holds.
  template <int dim>
  void
  SoftRobotDynamics<dim>::open_trajectory()
  {
    std::vector<std::string> columns = {"t", "dt"};
    const char              *axis    = "xyz";
    for (unsigned int d = 0; d < dim; ++d)
      columns.push_back(std::string("u_") + axis[d]);
    for (unsigned int d = 0; d < dim; ++d)
      columns.push_back(std::string("v_") + axis[d]);
    for (const char *name : {"kinetic",
                             "strain",
                             "gravity_potential",
                             "traction_work",
                             "damping_dissipation",
                             "energy_balance",
                             "newton_iterations"})
      columns.emplace_back(name);
    if (dim == 3)
      columns.insert(columns.end(), {"L_x", "L_y", "L_z"});
    else if (dim == 2)
      columns.emplace_back("L_z");
    if (pneumatics)
      {
        columns.emplace_back("pressure");
        if (pneumatics->has_volume())
          columns.emplace_back("cavity_volume");
        columns.emplace_back("pressure_work");
      }
    // The materials, for the title of a plot (doc/plot_tip_trajectory.py).
    std::ostringstream materials;
    materials << "materials:";
    for (const auto &[id, material] : parameters.by_id)
      {
        materials << (id == parameters.by_id.begin()->first ? " " : "; ") << id
                  << " " << material.name << " (mu = " << material.shear_modulus
                  << " kPa";
        if (dim == 3)
          materials << ", kappa = " << material.bulk_modulus << " kPa";
        materials << ")";
      }
    trajectory.open(
      parameters.output_directory + "/" + parameters.trajectory_file,
      {"SoftRobotDynamics<" + std::to_string(dim) + "> tip trajectory of " +
         Parameters::name_of(parameters.tip_region_type) + ' ' +
         std::to_string(parameters.tip_region_id) + ", from " +
         parameters.source_name,
       materials.str(),
       std::string("units: s, mm, mm/s; energies in kg mm^2/s^2 (= 1e-6 J); "
                   "angular momentum in kg mm^2/s") +
         (pneumatics ? "; gauge pressure in kPa, volume in mm^3" : "")},
      columns);
  }



  // @sect4{SoftRobotDynamics::write_trajectory_row}
  template <int dim>
  void
  SoftRobotDynamics<dim>::write_trajectory_row()
  {
    const auto [u_tip, v_tip] = tip_region.motion(current.u, current.v);
    const Tensor<1, 3>  L     = angular_momentum();
    std::vector<double> row   = {
        current.time, counters.steps == 0 ? 0. : current.time - previous.time};
    for (unsigned int d = 0; d < dim; ++d)
      row.push_back(u_tip[d]);
    for (unsigned int d = 0; d < dim; ++d)
      row.push_back(v_tip[d]);
    row.insert(row.end(),
               {energy.kinetic,
                energy.strain,
                energy.gravity_potential,
                energy.traction_work,
                energy.damping_dissipation,
                energy.balance(initial_total_energy),
                static_cast<double>(
                  counters.steps == 0 ? 0 : counters.last_newton_iterations)});
    if (dim == 3)
      row.insert(row.end(), {L[0], L[1], L[2]});
    else if (dim == 2)
      row.push_back(L[2]);
    if (pneumatics)
      {
        row.push_back(current.pressure);
        if (pneumatics->has_volume())
          row.push_back(current.gas_volume);
        row.push_back(energy.pressure_work);
      }
    trajectory.write_row(row);
  }



  // @sect4{SoftRobotDynamics::output_results}
  //
  // The fields at t = 0 and then whenever the output interval has passed.
  template <int dim>
  void
  SoftRobotDynamics<dim>::output_results()
  {
    if ((!field_output && !xdmf_output) ||
        current.time < next_output_time - 1e-9 * parameters.time_step)
      return;
    write_fields();
    next_output_time += parameters.output_interval;
  }



  // @sect4{SoftRobotDynamics::write_fields}
  template <int dim>
  void
  SoftRobotDynamics<dim>::write_fields()
  {
    TimerOutput::Scope timer_section(computing_timer, "Output");
    if (field_output)
      {
        auto [data_out, cell_data] = field_data();
        field_output->write(std::move(data_out),
                            std::move(cell_data),
                            current.time);
      }
    if (xdmf_output)
      {
        auto [data_out, cell_data] = field_data();
        xdmf_output->write(*data_out, cell_data, current.time);
      }
    last_output_time = current.time;
  }



  // @sect4{SoftRobotDynamics::write_final_fields}
  //
  // A run whose end time is not a multiple of the output interval, or that
  // stopped between two outputs, still ends with its last state; one that
  // stopped right after an output does not write it twice.
  template <int dim>
  void
  SoftRobotDynamics<dim>::write_final_fields()
  {
    if ((field_output || xdmf_output) && current_is_finite &&
        current.time > last_output_time + 1e-9 * parameters.time_step)
      write_fields();
  }



  // @sect4{SoftRobotDynamics::state_values}
  template <int dim>
  std::vector<std::pair<std::string, double>>
  SoftRobotDynamics<dim>::state_values() const
  {
    const auto [u_tip, v_tip] = tip_region.motion(current.u, current.v);
    return {{"largest displacement", current.u.linfty_norm()},
            {"largest velocity", current.v.linfty_norm()},
            {"largest acceleration", current.a.linfty_norm()},
            {"tip displacement", u_tip.norm()},
            {"tip velocity", v_tip.norm()},
            {"kinetic energy", energy.kinetic},
            {"strain energy", energy.strain},
            {"gravitational energy", energy.gravity_potential},
            {"traction work", energy.traction_work},
            {"damping dissipation", energy.damping_dissipation},
            {"pressure", current.pressure},
            {"gas volume", current.gas_volume},
            {"pressure work", energy.pressure_work}};
  }



  // @sect4{SoftRobotDynamics::field_data}
  //
  // The nodal fields displacement, velocity and acceleration, and per cell
  // the averages over its quadrature points of the volume ratio $J$ (in
  // the reduced models the stretch of the 1D column or the area ratio of
  // the 2D strip, named so), the Cauchy stress and its von Mises
  // equivalent, besides the material id and the MPI rank that owns the
  // cell. ParaView's "Warp By Vector" with the displacement shows the
  // deformed body. The cell averages come from the material laws at the
  // cell's quadrature points (HyperelasticSolid); they are written as cell
  // data (output/cell_data.h). With a pneumatic load, the pressure on the
  // cavity surface: the gauge pressure on the cells that carry loaded
  // faces (zero on the others), and the nodal pressure forces $p\,\mathbf
  // g$ (mN), a vector field on the loaded surface.
  template <int dim>
  std::pair<std::unique_ptr<DataOut<dim>>, CellData>
  SoftRobotDynamics<dim>::field_data() const
  {
    TrilinosWrappers::MPI::Vector ghosted_u(locally_owned_dofs,
                                            locally_relevant_dofs,
                                            mpi_communicator);
    ghosted_u                  = current.u;
    const unsigned int n_cells = triangulation.n_active_cells();
    Vector<float> volume_ratio(n_cells), von_mises(n_cells), material(n_cells),
      rank(n_cells), cavity_pressure(n_cells);
    std::vector<Vector<float>> stress(dim * (dim + 1) / 2,
                                      Vector<float>(n_cells));
    const unsigned int         n = cell_geometry.dofs_per_cell;
    std::vector<double>        cell_u(n);
    unsigned int               cell_number = 0;
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          for (unsigned int i = 0; i < n; ++i)
            cell_u[i] =
              ghosted_u(cell_geometry.dof_indices[cell_number * n + i]);
          const auto [mean_J, mean_sigma] =
            solid->cell_averages(cell_number, cell_u.data());
          const unsigned int index = cell->active_cell_index();
          volume_ratio[index]      = mean_J;
          // The von Mises stress of the 3D stress state the model stands
          // for: out-of-plane components vanish in the reduced models.
          SymmetricTensor<2, 3> sigma_3d;
          for (unsigned int i = 0; i < dim; ++i)
            for (unsigned int j = i; j < dim; ++j)
              sigma_3d[i][j] = mean_sigma[i][j];
          von_mises[index] = std::sqrt(1.5) * deviator(sigma_3d).norm();
          material[index]  = cell->material_id();
          if (pneumatics && pneumatics->surface().loads_cell(cell_number))
            cavity_pressure[index] = current.pressure;
          rank[index]    = cell->subdomain_id();
          unsigned int c = 0;
          for (unsigned int i = 0; i < dim; ++i)
            for (unsigned int j = i; j < dim; ++j)
              stress[c++][index] = mean_sigma[i][j];
          ++cell_number;
        }

    CellData cell_data;
    cell_data.add((dim == 1)   ? "stretch"
                  : (dim == 2) ? "area_ratio"
                               : "J",
                  volume_ratio);
    cell_data.add("von_Mises_stress", von_mises);
    cell_data.add("material_id", material);
    cell_data.add("mpi_rank", rank);
    if (pneumatics)
      cell_data.add("cavity_pressure", cavity_pressure);
    const char  *axis = "xyz";
    unsigned int c    = 0;
    for (unsigned int i = 0; i < dim; ++i)
      for (unsigned int j = i; j < dim; ++j)
        cell_data.add(std::string("cauchy_stress_") + axis[i] + axis[j],
                      stress[c++]);

    auto data_out = std::make_unique<DataOut<dim>>();
    data_out->attach_dof_handler(dof_handler);
    const std::vector<DataComponentInterpretation::DataComponentInterpretation>
      vector_field(dim,
                   DataComponentInterpretation::component_is_part_of_vector);
    for (const auto &[field, name] :
         {std::make_pair(&current.u, "displacement"),
          std::make_pair(&current.v, "velocity"),
          std::make_pair(&current.a, "acceleration")})
      data_out->add_data_vector(*field,
                                std::vector<std::string>(dim, name),
                                DataOut<dim>::type_dof_data,
                                vector_field);
    if (pneumatics)
      data_out->add_data_vector(current.pressure_force,
                                std::vector<std::string>(dim, "pressure_force"),
                                DataOut<dim>::type_dof_data,
                                vector_field);
    // zlib's fastest level: deal.II's default, the best compression, takes
    // twice the time for files of the same size (doc/performance_discussion.md).
    DataOutBase::VtkFlags flags;
    flags.time              = current.time;
    flags.cycle             = counters.steps;
    flags.compression_level = DataOutBase::VtkFlags::best_speed;
    data_out->set_flags(flags);
    return {std::move(data_out), std::move(cell_data)};
  }



  // @sect4{SoftRobotDynamics::analyse_trajectory}
  //
  // The spectral analysis of the tip trajectory at the end of a run, the
  // same as the program tip-spectrum with its default options: peak
  // frequency and damping ratio per direction (vertical, and for pendulum
  // motions horizontal and depth in the best-fit plane through the axis).
  template <int dim>
  void
  SoftRobotDynamics<dim>::analyse_trajectory() const
  {
    if (Utilities::MPI::this_mpi_process(mpi_communicator) != 0)
      return;
    // (Process 0 alone; finish_run() makes a failure known to all.)
    const std::string            directory = parameters.output_directory + "/";
    Analysis::TrajectoryAnalysis analysis;
    try
      {
        analysis = Analysis::analyse_trajectory(
          Analysis::read_tip_trajectory(directory + parameters.trajectory_file),
          Analysis::SpectralOptions(),
          parameters.spectral_skip);
      }
    catch (std::invalid_argument &reason)
      {
        pcout << "No spectral analysis of the tip motion: " << reason.what()
              << " (Output/Spectral analysis skip = "
              << parameters.spectral_skip << " s)" << std::endl;
        return;
      }
    write_file_atomically(directory + "tip_spectrum.csv",
                          [&](std::ostream &out) {
                            out << Analysis::spectral_table_csv(analysis);
                          });
    write_file_atomically(directory + "tip_spectrum_magnitudes.csv",
                          [&](std::ostream &out) {
                            out << Analysis::spectrum_csv(analysis);
                          });
    pcout << "Spectral analysis of the tip motion (" << directory
          << "tip_spectrum.csv):\n"
          << Analysis::spectral_summary(analysis) << std::flush;
  }



  // @sect4{SoftRobotDynamics::write_run_statistics}
  template <int dim>
  void
  SoftRobotDynamics<dim>::write_run_statistics(const double wall_time) const
  {
    Utilities::System::MemoryStats memory;
    Utilities::System::get_memory_stats(memory);
    RunStatistics statistics;
    statistics.peak_memory_mb =
      Utilities::MPI::sum(static_cast<double>(memory.VmHWM), mpi_communicator) /
      1024.;
    statistics.sections =
      computing_timer.get_summary_data(TimerOutput::total_wall_time);
    // (The same sections on every process: the maxima below are collective.)
    const double background =
      field_output ? field_output->background_seconds() : 0.;
    if (Utilities::MPI::max(background, mpi_communicator) > 0.)
      statistics.sections["Output (writing thread)"] = background;
    for (auto &[name, seconds] : statistics.sections)
      seconds = Utilities::MPI::max(seconds, mpi_communicator);
    std::string error;
    if (Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
      try
        {
          fill_and_write_statistics(statistics, wall_time);
        }
      catch (WriteFailure &failure)
        {
          error = failure.what();
        }
    fail_everywhere(error, mpi_communicator);
  }



  // The part of the statistics that process 0 fills in, and the file.
  template <int dim>
  void
  SoftRobotDynamics<dim>::fill_and_write_statistics(
    RunStatistics &statistics,
    const double   wall_time) const
  {
    statistics.dimension       = dim;
    statistics.cells           = triangulation.n_global_active_cells();
    statistics.dofs            = dof_handler.n_dofs();
    statistics.matrix_nonzeros = system_matrix.n_nonzero_elements();
    statistics.multigrid_operator_complexity =
      linear_solver.multigrid_operator_complexity();
    statistics.degree = parameters.degree;
    statistics.mpi_processes =
      Utilities::MPI::n_mpi_processes(mpi_communicator);
    statistics.threads_per_process = MultithreadInfo::n_threads();
    statistics.blas_kernels        = BlasKernels::in_use();
    statistics.linear_solver  = Parameters::name_of(parameters.linear_solver);
    statistics.solver_in_use  = linear_solver.solver_in_use();
    statistics.tangent_update = Parameters::name_of(parameters.tangent_update);
    statistics.end_time       = current.time;
    statistics.steps          = counters.steps;
    statistics.newton_iterations = counters.newton_iterations;
    statistics.linear_iterations = counters.linear_iterations;
    statistics.factorizations    = linear_solver.n_preparations();
    statistics.cutbacks          = step_controller.n_cutbacks();
    statistics.wall_seconds      = wall_time;
    statistics.write(parameters.output_directory + "/run_statistics.json");
  }



  // @sect4{SoftRobotDynamics::finish_run}
  //
  // The last output is waited for, the cost of the run reported, and the
  // tip motion analysed if asked.
  template <int dim>
  void
  SoftRobotDynamics<dim>::finish_run(const double wall_time)
  {
    if (field_output)
      field_output->finish();
    pcout << "Finished " << counters.steps << " steps in " << wall_time
          << " s: " << counters.newton_iterations << " Newton iterations, "
          << counters.linear_iterations << " linear iterations, "
          << linear_solver.n_preparations()
          << " matrix factorizations or multigrid set-ups, "
          << step_controller.n_cutbacks() << " time-step cutbacks."
          << std::endl;
    computing_timer.print_summary();
    write_run_statistics(wall_time);
    trajectory.close();
    if (parameters.spectral_analysis)
      {
        std::string error;
        try
          {
            analyse_trajectory();
          }
        catch (WriteFailure &failure)
          {
            error = failure.what();
          }
        fail_everywhere(error, mpi_communicator);
      }
  }



  // The explicit instantiations of this file's member functions.
#define SOFT_ROBOT_INSTANTIATE(dim)                                        \
  template Tensor<1, 3> SoftRobotDynamics<dim>::angular_momentum() const;  \
  template void         SoftRobotDynamics<dim>::open_trajectory();         \
  template void         SoftRobotDynamics<dim>::write_trajectory_row();    \
  template void         SoftRobotDynamics<dim>::output_results();          \
  template std::pair<std::unique_ptr<DataOut<dim>>, CellData>              \
                SoftRobotDynamics<dim>::field_data() const;                \
  template void SoftRobotDynamics<dim>::write_fields();                    \
  template void SoftRobotDynamics<dim>::write_final_fields();              \
  template std::vector<std::pair<std::string, double>>                     \
                SoftRobotDynamics<dim>::state_values() const;              \
  template void SoftRobotDynamics<dim>::analyse_trajectory() const;        \
  template void SoftRobotDynamics<dim>::write_run_statistics(const double) \
    const;                                                                 \
  template void SoftRobotDynamics<dim>::fill_and_write_statistics(         \
    RunStatistics &, const double) const;                                  \
  template void SoftRobotDynamics<dim>::finish_run(const double);
  SOFT_ROBOT_FOR_EACH_DIMENSION(SOFT_ROBOT_INSTANTIATE)
#undef SOFT_ROBOT_INSTANTIATE
} // namespace SoftRobot
