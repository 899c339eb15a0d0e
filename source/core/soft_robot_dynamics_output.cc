// @sect3{Output: fields for ParaView and the tip trajectory}
//
// Two kinds of output: VTU files of the whole body at the output interval,
// listed in a PVD record that carries the physical times so that ParaView
// plays them as a time series; and one line per time step in a CSV file
// with the motion of the tip region and the energy balance, the input of
// the spectral analysis.

#include <analysis/spectral_analysis.h>
#include <analysis/spectral_report.h>
#include <core/soft_robot_dynamics.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/numerics/data_out.h>
#include <deal.II/base/timer.h>
#include <iomanip>

namespace SoftRobot
{
  // @sect4{SoftRobotDynamics::setup_tip_weights}
  //
  // The motion of the tip: for a boundary, the area-weighted mean of the
  // displacement and velocity over that surface; for a material region,
  // its centre of mass, i.e. the mass-weighted mean. For the actuator the
  // second is the motion of the rigid tip block that the study tracked with
  // its motion-capture markers.
  //
  // Either mean is a fixed linear functional of the nodal values, $\bar
  // u_d = \sum_i w_{d,i} U_i / W$ with $w_{d,i} = \int \omega\,(\mathbf
  // N_i)_d$ over the surface or region ($\omega$ the area or mass density
  // times the section factor) and $W = \int\omega$. The weights are
  // computed here once, so that the tip motion of every time step costs
  // $2\,\text{dim}$ scalar products.
  template <int dim>
  void
  SoftRobotDynamics<dim>::setup_tip_weights()
  {
    tip_weights.assign(dim,
                       TrilinosWrappers::MPI::Vector(locally_owned_dofs,
                                                     mpi_communicator));
    double             weight        = 0.;
    const unsigned int id            = parameters.tip_region_id;
    const unsigned int dofs_per_cell = fe->n_dofs_per_cell();
    std::vector<Vector<double>> cell_weights(dim,
                                             Vector<double>(dofs_per_cell));
    std::vector<types::global_dof_index> dof_indices(dofs_per_cell);
    // Adds omega N_i(q) JxW to the weights of a cell.
    const auto add_point = [&](const auto  &fe_values,
                               const unsigned int q,
                               const double omega) {
      const double w = fe_values.JxW(q) * omega;
      for (unsigned int i = 0; i < dofs_per_cell; ++i)
        {
          const unsigned int c = fe->system_to_component_index(i).first;
          cell_weights[c](i) += w * fe_values.shape_value_component(i, q, c);
        }
      weight += w;
    };
    const auto add_cell = [&](const auto &cell) {
      cell->get_dof_indices(dof_indices);
      for (unsigned int d = 0; d < dim; ++d)
        {
          constraints.distribute_local_to_global(cell_weights[d],
                                                 dof_indices,
                                                 tip_weights[d]);
          cell_weights[d] = 0.;
        }
    };

    if (parameters.tip_region_type ==
        Parameters::Output::TipRegionType::boundary)
      {
        FEFaceValues<dim> fe_face_values(*mapping,
                                         *fe,
                                         *face_quadrature,
                                         update_values | update_JxW_values);
        for (const auto &cell : dof_handler.active_cell_iterators())
          if (cell->is_locally_owned())
            for (const auto face : cell->face_indices())
              if (cell->face(face)->at_boundary() &&
                  cell->face(face)->boundary_id() == id)
                {
                  fe_face_values.reinit(cell, face);
                  for (const unsigned int q :
                       fe_face_values.quadrature_point_indices())
                    add_point(fe_face_values, q, material_of(cell).section);
                  add_cell(cell);
                }
      }
    else
      {
        FEValues<dim> fe_values(*mapping,
                                *fe,
                                *cell_quadrature,
                                update_values | update_JxW_values);
        for (const auto &cell : dof_handler.active_cell_iterators())
          if (cell->is_locally_owned() && cell->material_id() == id)
            {
              fe_values.reinit(cell);
              const double rho_A =
                densities.at(id) * material_of(cell).section;
              for (const unsigned int q : fe_values.quadrature_point_indices())
                add_point(fe_values, q, rho_A);
              add_cell(cell);
            }
      }
    for (auto &vector : tip_weights)
      vector.compress(VectorOperation::add);
    tip_total_weight = Utilities::MPI::sum(weight, mpi_communicator);
  }



  // @sect4{SoftRobotDynamics::tip_motion}
  //
  // The mean displacement and velocity of the tip, with the weights of
  // setup_tip_weights().
  template <int dim>
  std::pair<Tensor<1, dim>, Tensor<1, dim>>
  SoftRobotDynamics<dim>::tip_motion() const
  {
    Tensor<1, dim> u_tip, v_tip;
    for (unsigned int d = 0; d < dim; ++d)
      {
        u_tip[d] = (tip_weights[d] * current.u) / tip_total_weight;
        v_tip[d] = (tip_weights[d] * current.v) / tip_total_weight;
      }
    return {u_tip, v_tip};
  }



  // @sect4{SoftRobotDynamics::angular_momentum}
  //
  // $\mathbf L = \sum_{\text{cells}}\sum_{n,k} m_{nk}\,\mathbf x_n\times
  // \mathbf v_k$ with the scalar cell mass matrices $m_{nk} = \int\rho_0
  // \varphi_n\varphi_k\,dV$ and the nodal positions and velocities.
  template <int dim>
  Tensor<1, 3>
  SoftRobotDynamics<dim>::angular_momentum() const
  {
    Tensor<1, 3> L;
    if constexpr (dim > 1)
      {
        // The nodal values: in serial runs with fixed components only,
        // straight from the value arrays at the positions the assembly
        // uses (zero for a fixed component); otherwise from copies with
        // the ghost entries.
        const CellGeometry &geometry = cell_geometry;
        const bool direct = !geometry.vector_positions.empty();
        TrilinosWrappers::MPI::Vector u, v;
        if (!direct)
          {
            u.reinit(locally_owned_dofs,
                     locally_relevant_dofs,
                     mpi_communicator);
            v.reinit(u);
            u = current.u;
            v = current.v;
          }
        const double *u_values = current.u.trilinos_vector()[0];
        const double *v_values = current.v.trilinos_vector()[0];
        const unsigned int nodes_per_cell =
          fe->base_element(0).n_dofs_per_cell();
        std::vector<Tensor<1, dim>> x(nodes_per_cell), velocity(nodes_per_cell);
        for (unsigned int cell = 0; cell < geometry.n_cells; ++cell)
          {
            const types::global_dof_index *dofs =
              &geometry.dof_indices[cell * geometry.dofs_per_cell];
            for (unsigned int n = 0; n < nodes_per_cell; ++n)
              for (unsigned int c = 0; c < dim; ++c)
                {
                  const unsigned int i = fe->component_to_system_index(c, n);
                  x[n][c] = cell_node_positions[cell * nodes_per_cell + n][c];
                  if (direct)
                    {
                      const int position =
                        geometry.vector_positions[cell * geometry.dofs_per_cell +
                                                  i];
                      if (position >= 0)
                        {
                          x[n][c] += u_values[position];
                          velocity[n][c] = v_values[position];
                        }
                      else
                        velocity[n][c] = 0.;
                    }
                  else
                    {
                      x[n][c] += u(dofs[i]);
                      velocity[n][c] = v(dofs[i]);
                    }
                }
            const double *m =
              &cell_nodal_mass[cell * nodes_per_cell * nodes_per_cell];
            for (unsigned int n = 0; n < nodes_per_cell; ++n)
              {
                Tensor<1, dim> p;
                for (unsigned int k = 0; k < nodes_per_cell; ++k)
                  p += m[n * nodes_per_cell + k] * velocity[k];
                if constexpr (dim == 3)
                  L += cross_product_3d(x[n], p);
                else
                  L[2] += x[n][0] * p[1] - x[n][1] * p[0];
              }
          }
        for (unsigned int d = 0; d < 3; ++d)
          L[d] = Utilities::MPI::sum(L[d], mpi_communicator);
      }
    return L;
  }



  // @sect4{SoftRobotDynamics::open_trajectory_file}
  //
  // The columns: time, time step, tip displacement and velocity (one
  // component per dimension; x is the actuator's axis), the energies of
  // EnergyAccount and their balance, and the Newton iterations of the
  // step, and the angular momentum about the origin (its three components
  // in 3D, the z-component in 2D, none in 1D). Lines starting with '#' are
  // comments.
  template <int dim>
  void
  SoftRobotDynamics<dim>::open_trajectory_file()
  {
    if (Utilities::MPI::this_mpi_process(mpi_communicator) != 0)
      return;
    const std::string name =
      parameters.output_directory + "/" + parameters.trajectory_file;
    trajectory.open(name);
    AssertThrow(trajectory,
                ExcMessage("Cannot write the trajectory file '" + name + "'."));
    trajectory << "# SoftRobotDynamics<" << dim << "> tip trajectory of "
               << Parameters::name_of(parameters.tip_region_type) << ' ' << parameters.tip_region_id
               << ", from " << parameters.source_name << "\n"
               << "# units: s, mm, mm/s; energies in kg mm^2/s^2 (= 1e-6 J); "
                  "angular momentum in kg mm^2/s\n"
               << "t,dt";
    const char *axis = "xyz";
    for (unsigned int d = 0; d < dim; ++d)
      trajectory << ",u_" << axis[d];
    for (unsigned int d = 0; d < dim; ++d)
      trajectory << ",v_" << axis[d];
    trajectory << ",kinetic,strain,gravity_potential,traction_work,"
                  "damping_dissipation,energy_balance,newton_iterations";
    if (dim == 3)
      trajectory << ",L_x,L_y,L_z";
    else if (dim == 2)
      trajectory << ",L_z";
    trajectory << '\n';
  }



  template <int dim>
  void
  SoftRobotDynamics<dim>::write_trajectory_line()
  {
    const auto [u_tip, v_tip] = tip_motion();
    const Tensor<1, 3> L      = angular_momentum();
    if (Utilities::MPI::this_mpi_process(mpi_communicator) != 0)
      return;
    trajectory << std::setprecision(10) << current.time << ','
               << (step_number == 0 ? 0. : current.time - previous.time);
    for (unsigned int d = 0; d < dim; ++d)
      trajectory << ',' << u_tip[d];
    for (unsigned int d = 0; d < dim; ++d)
      trajectory << ',' << v_tip[d];
    trajectory << ',' << energy.kinetic << ',' << energy.strain << ','
               << energy.gravity_potential << ',' << energy.traction_work << ','
               << energy.damping_dissipation << ','
               << energy.balance(initial_total_energy) << ','
               << (step_number == 0 ? 0 : last_newton_iterations);
    if (dim == 3)
      trajectory << ',' << L[0] << ',' << L[1] << ',' << L[2];
    else if (dim == 2)
      trajectory << ',' << L[2];
    trajectory << '\n';
    trajectory.flush();
  }



  template <int dim>
  struct SoftRobotDynamics<dim>::OutputJob
  {
    DataOut<dim>                                data_out;
    double                                      time         = 0.;
    unsigned int                                output_index = 0;
    std::vector<std::pair<double, std::string>> pvd_records;
    unsigned int                                n_processes = 1;
    unsigned int                                rank        = 0;
  };



  // @sect4{SoftRobotDynamics::output_results}
  //
  // The nodal fields displacement, velocity and acceleration, and per cell
  // the averages over its quadrature points of the volume ratio $J$, the
  // Cauchy stress and its von Mises equivalent, besides the material id and
  // the MPI rank that owns the cell. ParaView's "Warp By Vector" with the
  // displacement shows the deformed body.
  //
  // The work is split in two. The time loop's thread computes the cell
  // data and hands all fields to a DataOut object: deal.II copies the nodal
  // values into vectors of its own there, with the ghost values of the
  // cells at the processes' interfaces, and that copy is a collective MPI
  // operation (even on one process), which only the main thread may do.
  // The rest -- building the patches, compressing and writing the files,
  // most of the work (in the headline case 0.7 s over the run, against
  // 0.12 s for the first part) -- is done by a thread of its own while
  // the time loop goes on: the loop's serial parts (factorizations, back
  // substitutions, vector operations, and in parallel runs the waits for
  // the other process) leave a core free. That thread makes no MPI call and
  // touches no Trilinos object; it only reads the DataOut object, the mesh
  // and the finite element, which nothing changes during the run. Each
  // process writes its own piece of the mesh, and process 0 also the PVTU
  // and PVD records that list the pieces. The next output, the end of the
  // run and the destructor wait for the thread (finish_output()), so that
  // no file is left half written.
  template <int dim>
  void
  SoftRobotDynamics<dim>::output_results(const unsigned int output_index)
  {
    TimerOutput::Scope timer_section(computing_timer, "Output");
    finish_output();

    const std::string stem =
      "solution_" + Utilities::int_to_string(output_index, 5);
    pvd_records.emplace_back(current.time, stem + ".pvtu");
    output_job       = std::make_shared<OutputJob>();
    OutputJob &job   = *output_job;
    job.time         = current.time;
    job.output_index = output_index;
    job.pvd_records  = pvd_records;
    job.n_processes  = Utilities::MPI::n_mpi_processes(mpi_communicator);
    job.rank         = Utilities::MPI::this_mpi_process(mpi_communicator);

    // The displacement with the values at the ghost dofs, for the cell data.
    TrilinosWrappers::MPI::Vector ghosted_u;
    if (job.n_processes > 1)
      {
        ghosted_u.reinit(locally_owned_dofs,
                         locally_relevant_dofs,
                         mpi_communicator);
        ghosted_u = current.u;
      }
    const TrilinosWrappers::MPI::Vector &u =
      (job.n_processes > 1 ? ghosted_u : current.u);

    const unsigned int n_cells = triangulation.n_active_cells();
    Vector<float> volume_ratio(n_cells), von_mises(n_cells), material(n_cells),
      rank(n_cells);
    std::vector<Vector<float>> stress(dim * (dim + 1) / 2,
                                      Vector<float>(n_cells));

    FEValues<dim> fe_values(*mapping,
                            *fe,
                            *cell_quadrature,
                            update_gradients | update_JxW_values);
    const bool    mean_dilatation =
      (dim == 3) && (parameters.volumetric_formulation ==
       Parameters::FiniteElement::VolumetricFormulation::mean_dilatation);
    const FEValuesExtractors::Vector displacements(0);
    std::vector<Tensor<2, dim>>      grad_u(cell_quadrature->size());
    MaterialResponse<dim>            response;
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          fe_values[displacements].get_function_gradients(u, grad_u);
          const NeoHookeanEnergy<dim> &law = materials.at(cell->material_id());
          // With the mean-dilatation formulation, the pressure is that of
          // the cell's mean volume ratio (as in the assembly).
          double pressure = 0.;
          if (mean_dilatation)
            {
              double volume = 0., volume_change = 0.;
              for (const unsigned int q : fe_values.quadrature_point_indices())
                {
                  volume += fe_values.JxW(q);
                  volume_change +=
                    NeoHookeanEnergy<dim>::volume_change(
                      NeoHookeanEnergy<dim>::green_lagrange_strain(grad_u[q])) *
                    fe_values.JxW(q);
                }
              pressure = law.volumetric_pressure(volume_change / volume);
            }
          SymmetricTensor<2, dim> mean_sigma;
          double                  mean_J = 0.;
          for (const auto &G : grad_u)
            {
              Tensor<2, dim> F = G;
              for (unsigned int d = 0; d < dim; ++d)
                F[d][d] += 1.;
              if (mean_dilatation)
                law.evaluate_with_pressure(G, pressure, false, response);
              else
                law.evaluate_stress(G, response);
              mean_sigma += law.cauchy_stress(F, response.second_piola);
              mean_J += determinant(F);
            }
          mean_sigma /= grad_u.size();
          const unsigned int index = cell->active_cell_index();
          volume_ratio[index]      = mean_J / grad_u.size();
          // The von Mises stress of the 3D stress state the model stands
          // for: out-of-plane components vanish in the reduced models.
          SymmetricTensor<2, 3> sigma_3d;
          for (unsigned int i = 0; i < dim; ++i)
            for (unsigned int j = i; j < dim; ++j)
              sigma_3d[i][j] = mean_sigma[i][j];
          von_mises[index] = std::sqrt(1.5) * deviator(sigma_3d).norm();
          material[index]  = cell->material_id();
          rank[index]      = cell->subdomain_id();
          unsigned int c   = 0;
          for (unsigned int i = 0; i < dim; ++i)
            for (unsigned int j = i; j < dim; ++j)
              stress[c++][index] = mean_sigma[i][j];
        }

    DataOut<dim> &data_out = job.data_out;
    data_out.attach_dof_handler(dof_handler);
    const std::vector<DataComponentInterpretation::DataComponentInterpretation>
      vector_field(dim,
                   DataComponentInterpretation::component_is_part_of_vector);
    data_out.add_data_vector(current.u,
                             std::vector<std::string>(dim, "displacement"),
                             DataOut<dim>::type_dof_data,
                             vector_field);
    data_out.add_data_vector(current.v,
                             std::vector<std::string>(dim, "velocity"),
                             DataOut<dim>::type_dof_data,
                             vector_field);
    data_out.add_data_vector(current.a,
                             std::vector<std::string>(dim, "acceleration"),
                             DataOut<dim>::type_dof_data,
                             vector_field);
    data_out.add_data_vector(volume_ratio, "J", DataOut<dim>::type_cell_data);
    data_out.add_data_vector(von_mises,
                             "von_Mises_stress",
                             DataOut<dim>::type_cell_data);
    data_out.add_data_vector(material,
                             "material_id",
                             DataOut<dim>::type_cell_data);
    data_out.add_data_vector(rank, "mpi_rank", DataOut<dim>::type_cell_data);
    const char  *axis = "xyz";
    unsigned int c    = 0;
    for (unsigned int i = 0; i < dim; ++i)
      for (unsigned int j = i; j < dim; ++j)
        data_out.add_data_vector(stress[c++],
                                 std::string("cauchy_stress_") + axis[i] +
                                   axis[j],
                                 DataOut<dim>::type_cell_data);

    // zlib's fastest level: deal.II's default, the best compression, took
    // a seventh of the headline case's run time for files about a third
    // smaller (measured, see doc/performance_discussion.md).
    DataOutBase::VtkFlags flags;
    flags.time              = current.time;
    flags.cycle             = step_number;
    flags.compression_level = DataOutBase::VtkFlags::best_speed;
    data_out.set_flags(flags);

    output_writer = std::thread([this, &job]() {
      Timer timer;
      try
        {
          write_output(job);
        }
      catch (std::exception &error)
        {
          output_error =
            "writing the output at t = " + std::to_string(job.time) +
            " s failed: " + error.what();
        }
      background_output_seconds += timer.wall_time();
    });
  }



  // @sect4{SoftRobotDynamics::write_output}
  //
  // The writing thread's work: builds the patches and writes this
  // process's VTU file and, on process 0, the PVTU and PVD records.
  template <int dim>
  void
  SoftRobotDynamics<dim>::write_output(OutputJob &job) const
  {
    job.data_out.build_patches(*mapping, simplex_mesh ? 1 : parameters.degree);

    // The files deal.II's write_vtu_with_pvtu_record() writes, one piece
    // per process, without its MPI calls.
    const std::string directory = parameters.output_directory + "/";
    const std::string stem =
      "solution_" + Utilities::int_to_string(job.output_index, 5);
    const unsigned int rank_digits =
      Utilities::needed_digits(job.n_processes - 1);
    const auto piece = [&](const unsigned int rank) {
      return stem + "." + Utilities::int_to_string(rank, rank_digits) + ".vtu";
    };
    std::ofstream vtu(directory + piece(job.rank));
    job.data_out.write_vtu(vtu);
    AssertThrow(vtu, ExcIO());
    if (job.rank == 0)
      {
        std::vector<std::string> pieces;
        for (unsigned int rank = 0; rank < job.n_processes; ++rank)
          pieces.push_back(piece(rank));
        std::ofstream pvtu(directory + stem + ".pvtu");
        job.data_out.write_pvtu_record(pvtu, pieces);
        AssertThrow(pvtu, ExcIO());
        std::ofstream pvd(directory + "solution.pvd");
        DataOutBase::write_pvd_record(pvd, job.pvd_records);
        AssertThrow(pvd, ExcIO());
      }
  }



  // @sect4{SoftRobotDynamics::finish_output}
  //
  // Waits for the thread that writes the last VTU output, if any, and
  // reports its failure. Every process calls it at the same point of the
  // run, and a failure on one of them stops all of them.
  template <int dim>
  void
  SoftRobotDynamics<dim>::finish_output()
  {
    if (output_writer.joinable())
      output_writer.join();
    output_job.reset();
    const int failed_somewhere =
      Utilities::MPI::max(output_error.empty() ? 0 : 1, mpi_communicator);
    if (failed_somewhere != 0)
      {
        const std::string message =
          output_error.empty()
            ? "writing the output failed on another MPI process"
            : output_error;
        output_error.clear();
        AssertThrow(false, ExcMessage(message));
      }
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
    const std::string directory = parameters.output_directory + "/";
    const Analysis::TrajectoryAnalysis analysis =
      Analysis::analyse_trajectory(Analysis::read_tip_trajectory(
                                     directory + parameters.trajectory_file),
                                   Analysis::SpectralOptions(),
                                   parameters.spectral_skip);
    std::ofstream(directory + "tip_spectrum.csv")
      << Analysis::spectral_table_csv(analysis);
    std::ofstream(directory + "tip_spectrum_magnitudes.csv")
      << Analysis::spectrum_csv(analysis);
    pcout << "Spectral analysis of the tip motion (" << directory
          << "tip_spectrum.csv):\n"
          << Analysis::spectral_summary(analysis) << std::flush;
  }



#define SOFT_ROBOT_INSTANTIATE(dim)                                 \
  template std::pair<Tensor<1, dim>, Tensor<1, dim>>                \
                SoftRobotDynamics<dim>::tip_motion() const;         \
  template void SoftRobotDynamics<dim>::setup_tip_weights();        \
  template void SoftRobotDynamics<dim>::open_trajectory_file();     \
  template void SoftRobotDynamics<dim>::analyse_trajectory() const; \
  template void SoftRobotDynamics<dim>::write_trajectory_line();    \
  template Tensor<1, 3> SoftRobotDynamics<dim>::angular_momentum() const; \
  template void SoftRobotDynamics<dim>::output_results(const unsigned int); \
  template void SoftRobotDynamics<dim>::finish_output();

  SOFT_ROBOT_INSTANTIATE(1)
  SOFT_ROBOT_INSTANTIATE(2)
  SOFT_ROBOT_INSTANTIATE(3)
#undef SOFT_ROBOT_INSTANTIATE
} // namespace SoftRobot
