// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{The pneumatic load: pressure, cavity and gas together}
//
// See include/physics/pneumatic_load.h.

#include <core/config.h>
#include <iomanip>
#include <physics/pneumatic_load.h>
#include <sstream>

namespace SoftRobot
{
  namespace
  {
    std::string
    ids_text(const std::vector<unsigned int> &ids)
    {
      std::string text;
      for (const unsigned int id : ids)
        text += (text.empty() ? "" : ", ") + std::to_string(id);
      return text;
    }
  } // namespace



  // @sect4{PneumaticLoad::PneumaticLoad}
  //
  // The closure first: a gas needs a closed cavity, and the volume's axis
  // and origin are the closure's. Then the faces, and the expressions
  // evaluated at 17 times over the run.
  template <int dim>
  PneumaticLoad<dim>::PneumaticLoad(
    const Parameters::AllParameters &parameters,
    const Triangulation<dim>        &triangulation,
    const CellGeometry<dim>         &geometry,
    const Mapping<dim>              &mapping,
    const DoFHandler<dim>           &dof_handler,
    const Quadrature<dim - 1>       &face_quadrature,
    const AffineConstraints<double> &constraints,
    const IndexSet                  &locally_owned_dofs,
    const IndexSet                  &locally_relevant_dofs,
    const MPI_Comm                   mpi_communicator,
    const bool                       symmetric_tangent)
    : parameters(parameters)
    , constraints(constraints)
    , mpi_communicator(mpi_communicator)
    , cavity_closure(find_cavity_closure(parameters, triangulation))
    , rank_one_tangent(parameters.rank_one_tangent)
    , ghosted_u(locally_owned_dofs, locally_relevant_dofs, mpi_communicator)
  {
    const bool gas_model =
      (parameters.pressure_model == Parameters::Pneumatics::PressureModel::gas);
    AssertThrow(
      !gas_model || dim == 1 || parameters.equivalent_area > 0. ||
        cavity_closure.closed,
      ExcMessage(parameters.where() + "Pneumatics/Pressure boundary ids = " +
                 ids_text(parameters.pressure_boundary_ids) +
                 ": the cavity of the gas is not closed: " +
                 (cavity_closure.open_edge.front() == '('
                    ? "its surface has an edge at " + cavity_closure.open_edge +
                        " that lies on no coordinate plane whose normal "
                        "displacement Loads and constraints/Fixed components "
                        "fixes"
                    : "its open edges lie on " + cavity_closure.open_edge) +
                 ", so the volume the surface encloses depends on the "
                 "origin of the volume integral. Close the cavity by "
                 "symmetry planes (fix the displacement normal to them), "
                 "or name all of its surface."));
    follower = std::make_unique<FollowerPressure<dim>>(parameters,
                                                       geometry,
                                                       mapping,
                                                       dof_handler,
                                                       face_quadrature,
                                                       cavity_closure,
                                                       symmetric_tangent);
    std::vector<double> times;
    for (unsigned int k = 0; k <= 16; ++k)
      times.push_back(parameters.end_time * k / 16.);
    if (gas_model)
      {
        gas = std::make_unique<GasCavity>(parameters);
        gas->check(parameters.end_time);
      }
    else
      {
        prescribed = std::make_unique<PressureHistory>(
          PressureHistory::prescribed_pressure(parameters));
        prescribed->check(times);
      }
  }



  template <int dim>
  bool
  PneumaticLoad<dim>::has_volume() const
  {
    return parameters.equivalent_area > 0. ||
           (dim == 3 && cavity_closure.closed);
  }



  // @sect4{PneumaticLoad::evaluate}
  template <int dim>
  typename PneumaticLoad<dim>::Evaluation
  PneumaticLoad<dim>::integrate(const TrilinosWrappers::MPI::Vector &u,
                                TrilinosWrappers::MPI::Vector       &gradient,
                                double &mesh_volume)
  {
    ghosted_u = u;
    mesh_volume =
      follower->integrate(ghosted_u, constraints, gradient, mpi_communicator);
    Evaluation evaluation;
    if (has_volume())
      evaluation.volume =
        mesh_volume / parameters.model_fraction + parameters.dead_volume;
    return evaluation;
  }



  template <int dim>
  typename PneumaticLoad<dim>::Evaluation
  PneumaticLoad<dim>::evaluate(const TrilinosWrappers::MPI::Vector &u,
                               const double                         time,
                               TrilinosWrappers::MPI::Vector       &gradient)
  {
    if (gas && !gas->is_sealed())
      return evaluate_at_pressure(u, initial_pressure(), gradient);
    double     mesh_volume = 0.;
    Evaluation evaluation  = integrate(u, gradient, mesh_volume);
    if (gas)
      {
        evaluation.pressure = gas->gauge_pressure(evaluation.volume, time);
        evaluation.stiffness =
          -gas->pressure_derivative(evaluation.volume, time) /
          parameters.model_fraction;
      }
    else
      evaluation.pressure = prescribed->value(time);
    assembly_pressure = evaluation.pressure;
    return evaluation;
  }



  template <int dim>
  typename PneumaticLoad<dim>::Evaluation
  PneumaticLoad<dim>::evaluate_at_pressure(
    const TrilinosWrappers::MPI::Vector &u,
    const double                         pressure,
    TrilinosWrappers::MPI::Vector       &gradient)
  {
    double     mesh_volume = 0.;
    Evaluation evaluation  = integrate(u, gradient, mesh_volume);
    evaluation.pressure    = pressure;
    assembly_pressure      = pressure;
    return evaluation;
  }



  template <int dim>
  double
  PneumaticLoad<dim>::initial_pressure(const double time) const
  {
    return gas ? parameters.initial_gas_pressure : prescribed->value(time);
  }



  // @sect4{PneumaticLoad::seal}
  template <int dim>
  void
  PneumaticLoad<dim>::seal(const TrilinosWrappers::MPI::Vector &u)
  {
    if (!gas)
      return;
    TrilinosWrappers::MPI::Vector gradient(u);
    double                        mesh_volume = 0.;
    const Evaluation evaluation = integrate(u, gradient, mesh_volume);
    gas->seal(evaluation.volume, mesh_volume / parameters.model_fraction);
  }



  template <int dim>
  std::vector<double>
  PneumaticLoad<dim>::gas_seal() const
  {
    return gas ? gas->sealed_state() : std::vector<double>();
  }



  template <int dim>
  void
  PneumaticLoad<dim>::restore_gas_seal(const std::vector<double> &state)
  {
    if (gas)
      gas->restore_seal(state);
  }



  template <int dim>
  void
  PneumaticLoad<dim>::add_cell_contribution(CellContribution<dim> &local) const
  {
    follower->add_cell_contribution(local, assembly_pressure);
  }



  // @sect4{PneumaticLoad::description}
  template <int dim>
  std::string
  PneumaticLoad<dim>::description() const
  {
    std::ostringstream text;
    text << "Pneumatics: ";
    if (gas)
      text << "a gas (gamma = " << parameters.gas_exponent
           << ", initial gauge pressure " << parameters.initial_gas_pressure
           << " kPa, dead volume " << parameters.dead_volume << " mm^3)";
    else
      text << "a prescribed pressure"
           << (prescribed->is_table() ? " (table)" : "");
    text << " on boundary id(s) " << ids_text(parameters.pressure_boundary_ids);
    if (parameters.equivalent_area > 0.)
      text << " as the end load of the equivalent area "
           << parameters.equivalent_area << " mm^2";
    else if (has_volume())
      text << ", a cavity closed by the planes "
           << cavity_closure.closing_planes << " (volume along "
           << "xyz"[cavity_closure.axis] << " from " << cavity_closure.origin
           << ")";
    else
      text << ", a surface that bounds no volume (the load stiffness is not "
              "symmetric there"
           << (dim < 3 ? "" : "; open edge at " + cavity_closure.open_edge)
           << ")";
    return text.str();
  }



#define SOFT_ROBOT_INSTANTIATE(dim) template class PneumaticLoad<dim>;
  SOFT_ROBOT_FOR_EACH_DIMENSION(SOFT_ROBOT_INSTANTIATE)
#undef SOFT_ROBOT_INSTANTIATE
} // namespace SoftRobot
