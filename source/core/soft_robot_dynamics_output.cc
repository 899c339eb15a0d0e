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
#include <iomanip>

namespace SoftRobot
{
  // @sect4{SoftRobotDynamics::tip_motion}
  //
  // The motion of the tip: for a boundary, the area-weighted mean of the
  // displacement and velocity over that surface; for a material region,
  // its centre of mass, i.e. the mass-weighted mean. For the actuator the
  // second is the motion of the rigid tip block that the study tracked with
  // its motion-capture markers.
  template <int dim>
  std::pair<Tensor<1, dim>, Tensor<1, dim>>
  SoftRobotDynamics<dim>::tip_motion() const
  {
    TrilinosWrappers::MPI::Vector u(locally_owned_dofs,
                                    locally_relevant_dofs,
                                    mpi_communicator);
    TrilinosWrappers::MPI::Vector v(u);
    u = current.u;
    v = current.v;

    const FEValuesExtractors::Vector displacements(0);
    Tensor<1, dim>                   sum_u, sum_v;
    double                           weight = 0.;
    const unsigned int               id     = parameters.tip_region_id;

    if (parameters.tip_region_type == "boundary")
      {
        FEFaceValues<dim>           fe_face_values(*mapping,
                                         *fe,
                                         *face_quadrature,
                                         update_values | update_JxW_values);
        std::vector<Tensor<1, dim>> u_q(face_quadrature->size()), v_q(u_q);
        for (const auto &cell : dof_handler.active_cell_iterators())
          if (cell->is_locally_owned())
            for (const auto face : cell->face_indices())
              if (cell->face(face)->at_boundary() &&
                  cell->face(face)->boundary_id() == id)
                {
                  fe_face_values.reinit(cell, face);
                  fe_face_values[displacements].get_function_values(u, u_q);
                  fe_face_values[displacements].get_function_values(v, v_q);
                  for (const unsigned int q :
                       fe_face_values.quadrature_point_indices())
                    {
                      const double w =
                        fe_face_values.JxW(q) * material_of(cell).section;
                      sum_u += w * u_q[q];
                      sum_v += w * v_q[q];
                      weight += w;
                    }
                }
      }
    else
      {
        FEValues<dim>               fe_values(*mapping,
                                *fe,
                                *cell_quadrature,
                                update_values | update_JxW_values);
        std::vector<Tensor<1, dim>> u_q(cell_quadrature->size()), v_q(u_q);
        for (const auto &cell : dof_handler.active_cell_iterators())
          if (cell->is_locally_owned() && cell->material_id() == id)
            {
              fe_values.reinit(cell);
              fe_values[displacements].get_function_values(u, u_q);
              fe_values[displacements].get_function_values(v, v_q);
              const double rho_A = densities.at(id) * material_of(cell).section;
              for (const unsigned int q : fe_values.quadrature_point_indices())
                {
                  const double w = fe_values.JxW(q) * rho_A;
                  sum_u += w * u_q[q];
                  sum_v += w * v_q[q];
                  weight += w;
                }
            }
      }
    weight = Utilities::MPI::sum(weight, mpi_communicator);
    sum_u  = Utilities::MPI::sum(sum_u, mpi_communicator);
    sum_v  = Utilities::MPI::sum(sum_v, mpi_communicator);
    return {sum_u / weight, sum_v / weight};
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
        TrilinosWrappers::MPI::Vector u(locally_owned_dofs,
                                        locally_relevant_dofs,
                                        mpi_communicator);
        TrilinosWrappers::MPI::Vector v(u);
        u = current.u;
        v = current.v;
        const unsigned int nodes_per_cell =
          fe->base_element(0).n_dofs_per_cell();
        const CellGeometry &geometry = cell_geometry;
        std::vector<Tensor<1, dim>> x(nodes_per_cell), velocity(nodes_per_cell);
        for (unsigned int cell = 0; cell < geometry.n_cells; ++cell)
          {
            const types::global_dof_index *dofs =
              &geometry.dof_indices[cell * geometry.dofs_per_cell];
            for (unsigned int n = 0; n < nodes_per_cell; ++n)
              for (unsigned int c = 0; c < dim; ++c)
                {
                  const types::global_dof_index dof =
                    dofs[fe->component_to_system_index(c, n)];
                  x[n][c] = cell_node_positions[cell * nodes_per_cell + n][c] +
                            u(dof);
                  velocity[n][c] = v(dof);
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
               << parameters.tip_region_type << ' ' << parameters.tip_region_id
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



  // @sect4{SoftRobotDynamics::output_results}
  //
  // The nodal fields displacement, velocity and acceleration, and per cell
  // the averages over its quadrature points of the volume ratio $J$, the
  // Cauchy stress and its von Mises equivalent, besides the material id and
  // the MPI rank that owns the cell. ParaView's "Warp By Vector" with the
  // displacement shows the deformed body.
  template <int dim>
  void
  SoftRobotDynamics<dim>::output_results(const unsigned int output_index)
  {
    TimerOutput::Scope timer_section(computing_timer, "Output");

    TrilinosWrappers::MPI::Vector u(locally_owned_dofs,
                                    locally_relevant_dofs,
                                    mpi_communicator);
    TrilinosWrappers::MPI::Vector v(u), a(u);
    u = current.u;
    v = current.v;
    a = current.a;

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
      (dim == 3) &&
      (parameters.volumetric_formulation == "mean dilatation");
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

    DataOut<dim> data_out;
    data_out.attach_dof_handler(dof_handler);
    const std::vector<DataComponentInterpretation::DataComponentInterpretation>
      vector_field(dim,
                   DataComponentInterpretation::component_is_part_of_vector);
    data_out.add_data_vector(u,
                             std::vector<std::string>(dim, "displacement"),
                             DataOut<dim>::type_dof_data,
                             vector_field);
    data_out.add_data_vector(v,
                             std::vector<std::string>(dim, "velocity"),
                             DataOut<dim>::type_dof_data,
                             vector_field);
    data_out.add_data_vector(a,
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
    data_out.build_patches(*mapping, simplex_mesh ? 1 : parameters.degree);

    const std::string name =
      data_out.write_vtu_with_pvtu_record(parameters.output_directory + "/",
                                          "solution",
                                          output_index,
                                          mpi_communicator,
                                          5);
    pvd_records.emplace_back(current.time, name);
    if (Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
      {
        std::ofstream pvd(parameters.output_directory + "/solution.pvd");
        DataOutBase::write_pvd_record(pvd, pvd_records);
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
  template void SoftRobotDynamics<dim>::open_trajectory_file();     \
  template void SoftRobotDynamics<dim>::analyse_trajectory() const; \
  template void SoftRobotDynamics<dim>::write_trajectory_line();    \
  template Tensor<1, 3> SoftRobotDynamics<dim>::angular_momentum() const; \
  template void SoftRobotDynamics<dim>::output_results(const unsigned int);

  SOFT_ROBOT_INSTANTIATE(1)
  SOFT_ROBOT_INSTANTIATE(2)
  SOFT_ROBOT_INSTANTIATE(3)
#undef SOFT_ROBOT_INSTANTIATE
} // namespace SoftRobot
