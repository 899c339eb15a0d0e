// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Checking the input before anything is written}
//
// See include/core/input_checks.h.

#include <cmath>
#include <core/config.h>
#include <core/expression_function.h>
#include <core/input_checks.h>
#include <core/parameter_file.h>
#include <deal.II/base/exceptions.h>
#include <deal.II/base/utilities.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/vector.h>
#include <deal.II/numerics/vector_tools.h>
#include <deal.II/physics/elasticity/standard_tensors.h>
#include <iomanip>
#include <iostream>
#include <limits>
#include <output/output_directory.h>
#include <regex>
#include <set>
#include <sstream>
#include <tuple>

namespace SoftRobot
{
  namespace InputChecks
  {
    namespace
    {
      std::string
      number_text(const double value)
      {
        std::ostringstream text;
        text << std::setprecision(6) << value;
        return text.str();
      }

      // What muparser said, without deal.II's frame around it.
      std::string
      parser_reason(const ExceptionBase &error)
      {
        std::ostringstream info;
        error.print_info(info);
        const std::string       text = Parameters::one_line(info.str());
        static const std::regex said("The parser said: (.*)");
        std::smatch             match;
        std::string             reason =
          std::regex_search(text, match, said) ? match[1].str() : text;
        while (!reason.empty() && reason.back() == '.')
          reason.pop_back();
        return reason;
      }

      bool
      storable(const double value)
      {
        return std::isfinite(value) && std::abs(value) <= largest_output_value;
      }

      // The evaluation behind check_expression() and
      // check_expression_syntax(); with `check_values` false, only whether
      // the expression can be parsed.
      template <int dim>
      void
      evaluate(FunctionParser<dim>             &function,
               const Parameters::AllParameters &parameters,
               const std::string               &entry,
               const std::string               &expression,
               const std::vector<Point<dim>>   &points,
               const std::vector<double>       &times,
               const bool                       check_values)
      {
        const std::string   stated = entry + " = '" + expression + "'";
        SilencedErrorStream silence;
        Vector<double>      value(function.n_components);
        for (const double time : times)
          {
            function.set_time(time);
            for (const Point<dim> &point : points)
              {
                try
                  {
                    function.vector_value(point, value);
                  }
                catch (ExceptionBase &error)
                  {
                    AssertThrow(false,
                                ExcMessage(parameters.where() + stated +
                                           " cannot be parsed: " +
                                           parser_reason(error) + "."));
                  }
                if (!check_values)
                  continue;
                for (unsigned int c = 0; c < value.size(); ++c)
                  AssertThrow(
                    storable(value[c]),
                    ExcMessage(parameters.where() + stated + " gives " +
                               number_text(value[c]) +
                               (value.size() > 1
                                  ? " in component " + std::to_string(c + 1)
                                  : std::string()) +
                               " at " + point_text(point) +
                               (times.size() > 1 ? ", t = " + number_text(time)
                                                 : std::string()) +
                               (std::isfinite(value[c])
                                  ? ", beyond the largest value the output can "
                                    "store (3.4e38)."
                                  : ", which is not a finite number.")));
              }
          }
      }
    } // namespace



    // @sect4{fail_everywhere_on_input}
    void
    fail_everywhere_on_input(const std::string &local_error,
                             const MPI_Comm     mpi_communicator)
    {
      const unsigned int n_processes =
        Utilities::MPI::n_mpi_processes(mpi_communicator);
      const unsigned int first_failed =
        Utilities::MPI::min(local_error.empty()
                              ? n_processes
                              : Utilities::MPI::this_mpi_process(
                                  mpi_communicator),
                            mpi_communicator);
      if (first_failed == n_processes)
        return;
      const std::string message =
        (n_processes == 1) ? local_error
                           : Utilities::MPI::broadcast(mpi_communicator,
                                                       local_error,
                                                       first_failed);
      AssertThrow(false, ExcMessage(message));
    }



    // @sect4{check_output_names}
    //
    // The trajectory is one file in the output directory, beside the files
    // of the field output, which it must not overwrite (a trajectory named
    // `solution.pvd` and the PVD record would overwrite each other).
    void
    check_output_names(const Parameters::AllParameters &parameters)
    {
      const std::string &name = parameters.trajectory_file;
      AssertThrow(!name.empty() && name.find('/') == std::string::npos &&
                    name != "." && name != "..",
                  ExcMessage(parameters.where() + "Output/Trajectory file = '" +
                             name +
                             "' must be the name of a file (without a "
                             "directory) in the Output directory, e.g. "
                             "'tip_trajectory.csv'."));
      AssertThrow(
        !is_reserved_output_name(name) &&
          !(name.size() > 4 && name.substr(name.size() - 4) == ".tmp"),
        ExcMessage(parameters.where() + "Output/Trajectory file = '" + name +
                   "' is a name the field output, the run "
                   "statistics or the spectra use (solution.pvd, "
                   "solution.xdmf, solution_*, run_statistics.json, "
                   "tip_spectrum*.csv, *.tmp); choose another, e.g. "
                   "'tip_trajectory.csv'."));
    }



    // @sect4{check_refinement_size}
    //
    // Each uniform refinement splits a cell into 2^dim (hypercubes and
    // simplices alike). Some 20 million cells need tens of gigabytes for
    // the mesh, the matrices and the factorization; beyond that the run
    // ends in std::bad_alloc after minutes of refining.
    void
    check_refinement_size(const Parameters::AllParameters &parameters,
                          const unsigned int               dim,
                          const unsigned int               n_cells)
    {
      constexpr double largest_mesh = 2e7;
      const double     refined =
        n_cells * std::pow(2., 1. * dim * parameters.global_refinements);
      AssertThrow(refined <= largest_mesh,
                  ExcMessage(parameters.where() +
                             "Geometry/Global refinements = " +
                             std::to_string(parameters.global_refinements) +
                             " would make " + number_text(refined) +
                             " cells of the mesh's " + std::to_string(n_cells) +
                             " (each refinement multiplies them by " +
                             std::to_string(1u << dim) + "); at most " +
                             number_text(largest_mesh) +
                             " are allowed. Use fewer refinements."));
    }



    // @sect4{check_mesh_geometry}
    //
    // The Jacobian of the mapping at the quadrature points, without the
    // volume elements (whose computation stops a Debug build at the first
    // distorted cell, without naming the mesh).
    template <int dim>
    void
    check_mesh_geometry(const Parameters::AllParameters &parameters,
                        const Triangulation<dim>        &triangulation,
                        const Mapping<dim>              &mapping,
                        const FiniteElement<dim>        &fe,
                        const Quadrature<dim>           &quadrature)
    {
      FEValues<dim> fe_values(mapping, fe, quadrature, update_jacobians);
      unsigned int  n_bad = 0;
      std::string   first_bad;
      for (const auto &cell : triangulation.active_cell_iterators())
        {
          fe_values.reinit(cell);
          double smallest = std::numeric_limits<double>::max();
          for (const unsigned int q : fe_values.quadrature_point_indices())
            smallest =
              std::min(smallest,
                       determinant(Tensor<2, dim>(fe_values.jacobian(q))));
          if (smallest > 0)
            continue;
          if (n_bad++ == 0)
            first_bad =
              "cell " + std::to_string(cell->active_cell_index()) +
              " (material " + std::to_string(cell->material_id()) +
              ", centre " + point_text(cell->center()) +
              ") is inverted or degenerate: det J = " + number_text(smallest) +
              " at a quadrature point";
        }
      const std::string source =
        (parameters.mesh_source == Parameters::Geometry::MeshSource::generator)
          ? "the mesh of Geometry/Generator '" + parameters.generator_name + "'"
          : "Geometry/Mesh file '" + parameters.mesh_file + "'";
      AssertThrow(n_bad == 0,
                  ExcMessage(parameters.where() + source + ": " + first_bad +
                             (n_bad > 1 ? " (and " + std::to_string(n_bad - 1) +
                                            " more cells)"
                                        : std::string()) +
                             ". Its vertices must be numbered for a positive "
                             "volume, and no cell may be flat."));
    }



    // @sect4{check_expression}
    template <int dim>
    void
    check_expression(FunctionParser<dim>             &function,
                     const Parameters::AllParameters &parameters,
                     const std::string               &entry,
                     const std::string               &expression,
                     const std::vector<Point<dim>>   &points,
                     const std::vector<double>       &times)
    {
      evaluate(function, parameters, entry, expression, points, times, true);
    }



    template <int dim>
    void
    initialize_checked(FunctionParser<dim>             &function,
                       const Parameters::AllParameters &parameters,
                       const std::string               &entry,
                       const std::string               &expression)
    {
      try
        {
          initialize_vector_function(function,
                                     expression,
                                     parameters.constants,
                                     entry);
        }
      catch (ExceptionBase &error)
        {
          std::ostringstream info;
          error.print_info(info);
          AssertThrow(false,
                      ExcMessage(parameters.where() +
                                 Parameters::one_line(info.str())));
        }
    }



    // @sect4{check_expression_syntax}
    template <int dim>
    void
    check_expression_syntax(const Parameters::AllParameters &parameters)
    {
      for (const auto &[entry, expression] :
           {std::make_pair("Initial conditions/Displacement",
                           parameters.displacement_expression),
            std::make_pair("Initial conditions/Velocity",
                           parameters.velocity_expression),
            std::make_pair("Loads and constraints/Traction",
                           parameters.traction_expression)})
        {
          FunctionParser<dim> function(dim);
          initialize_checked(function, parameters, entry, expression);
          evaluate(function,
                   parameters,
                   entry,
                   expression,
                   {Point<dim>()},
                   {0.},
                   false);
        }
    }



    // @sect4{check_materials_and_loads}
    //
    // A material without mass makes the mass matrix singular: the initial
    // acceleration and every time step divide by it. A bulk modulus below
    // the shear modulus is a Poisson's ratio below 1/8; real (if unusual)
    // for some foams, but for the silicones of soft robots (kappa of 100 mu
    // and more) almost always two entries swapped or a unit wrong, so it is
    // a warning. (The reduced 1D and 2D models are incompressible and use
    // no bulk modulus.)
    template <int dim>
    std::vector<std::string>
    check_materials_and_loads(const Parameters::AllParameters &parameters,
                              const Triangulation<dim>        &triangulation)
    {
      std::vector<std::string>     warnings;
      std::set<types::material_id> used;
      for (const auto &cell : triangulation.active_cell_iterators())
        used.insert(cell->material_id());
      for (const types::material_id id : used)
        {
          const Parameters::Material &material = parameters.by_id.at(id);
          const std::string           name =
            "Material " + std::to_string(id) + " ('" + material.name + "')";
          AssertThrow(material.density > 0 || material.mass > 0,
                      ExcMessage(parameters.where() + name +
                                 ": Density = 0 and no Mass: a body without "
                                 "mass has no motion to compute. Give a "
                                 "positive Density (kg/mm^3) or Mass (kg)."));
          if (dim == 3 && material.bulk_modulus < material.shear_modulus)
            {
              const double kappa = material.bulk_modulus;
              const double mu    = material.shear_modulus;
              warnings.push_back(
                "Warning: " + name + ": the bulk modulus (" +
                number_text(kappa) + " kPa) is below the shear modulus (" +
                number_text(mu) + " kPa), a Poisson's ratio of " +
                number_text((3 * kappa - 2 * mu) / (2 * (3 * kappa + mu))) +
                "; silicones have kappa of 100 mu and more. Check the two "
                "entries (or the Silicone library's Bulk-to-shear ratio).");
            }
        }

      // The mean dilatation on quadratic hexahedra (Q2-P0) runs, but has
      // spurious soft modes in bending (doc/introduction.md); on the
      // first hexahedral mesh of the bellows its static stretch is 70 %
      // too large (doc/reference_hex.md).
      using Formulation = Parameters::FiniteElement::VolumetricFormulation;
      if (dim == 3 &&
          parameters.volumetric_formulation == Formulation::mean_dilatation &&
          parameters.degree > 1 && triangulation.n_active_cells() > 0 &&
          triangulation.begin_active()->reference_cell().is_hyper_cube())
        warnings.push_back(
          "Warning: Finite element/Volumetric formulation = mean dilatation "
          "on hexahedra of degree 2 has spurious soft bending modes; "
          "'linear dilatation' does not.");

      if (parameters.traction_boundary_ids.empty())
        {
          if (!parameters.traction_expression.empty())
            warnings.push_back("Warning: Loads and constraints/Traction is "
                               "given, but Traction boundary ids is empty: "
                               "the traction acts nowhere.");
          return warnings;
        }
      const std::set<types::boundary_id> loaded(
        parameters.traction_boundary_ids.begin(),
        parameters.traction_boundary_ids.end());
      std::set<unsigned int>  seen;
      std::vector<Point<dim>> points;
      for (const auto &cell : triangulation.active_cell_iterators())
        for (const auto &face : cell->face_iterators())
          if (face->at_boundary() && loaded.count(face->boundary_id()) == 1)
            for (const unsigned int v : face->vertex_indices())
              if (seen.insert(face->vertex_index(v)).second)
                points.push_back(face->vertex(v));
      FunctionParser<dim> traction(dim);
      initialize_checked(traction,
                         parameters,
                         "Loads and constraints/Traction",
                         parameters.traction_expression);
      check_expression(traction,
                       parameters,
                       "Loads and constraints/Traction",
                       parameters.traction_expression,
                       points,
                       {0., parameters.end_time});
      return warnings;
    }



    // @sect4{check_initial_fields}
    //
    // The expressions at the support points of the locally owned cells,
    // then the deformation gradient of the interpolated initial
    // displacement at the quadrature points. Each process checks its own
    // cells; the smallest $\det\mathbf F$ and the first failure are made
    // known to all.
    template <int dim>
    void
    check_initial_fields(const Parameters::AllParameters &parameters,
                         const Mapping<dim>              &mapping,
                         const DoFHandler<dim>           &dof_handler,
                         const Quadrature<dim>           &quadrature,
                         const AffineConstraints<double> &constraints,
                         const MPI_Comm                   mpi_communicator)
    {
      const FiniteElement<dim> &fe = dof_handler.get_fe();
      const Quadrature<dim>     support(
        fe.base_element(0).get_unit_support_points());
      FEValues<dim>           support_values(mapping,
                                   fe,
                                   support,
                                   update_quadrature_points);
      std::vector<Point<dim>> points;
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            support_values.reinit(cell);
            const auto &cell_points = support_values.get_quadrature_points();
            points.insert(points.end(), cell_points.begin(), cell_points.end());
          }

      FunctionParser<dim> displacement(dim), velocity(dim);
      std::string         error;
      try
        {
          for (auto [function, entry, expression] :
               {std::make_tuple(&displacement,
                                "Initial conditions/Displacement",
                                parameters.displacement_expression),
                std::make_tuple(&velocity,
                                "Initial conditions/Velocity",
                                parameters.velocity_expression)})
            {
              initialize_checked(*function, parameters, entry, expression);
              check_expression(
                *function, parameters, entry, expression, points, {0.});
            }
        }
      catch (ExceptionBase &failure)
        {
          std::ostringstream info;
          failure.print_info(info);
          error = Parameters::one_line(info.str());
        }
      fail_everywhere_on_input(error, mpi_communicator);

      // det F of the displacement the simulator starts from.
      const IndexSet &owned = dof_handler.locally_owned_dofs();
      IndexSet        relevant;
      DoFTools::extract_locally_relevant_dofs(dof_handler, relevant);
      TrilinosWrappers::MPI::Vector u(owned, mpi_communicator);
      VectorTools::interpolate(mapping, dof_handler, displacement, u);
      constraints.set_zero(u);
      TrilinosWrappers::MPI::Vector ghosted(owned, relevant, mpi_communicator);
      ghosted = u;
      FEValues<dim>                    fe_values(mapping,
                              fe,
                              quadrature,
                              update_gradients | update_quadrature_points);
      const FEValuesExtractors::Vector displacements(0);
      std::vector<Tensor<2, dim>>      gradients(quadrature.size());
      double                           smallest = 1.;
      Point<dim>                       where_smallest;
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            fe_values.reinit(cell);
            fe_values[displacements].get_function_gradients(ghosted, gradients);
            for (const unsigned int q : fe_values.quadrature_point_indices())
              {
                const double J = determinant(
                  Physics::Elasticity::StandardTensors<dim>::I + gradients[q]);
                if (!(J >= smallest))
                  {
                    smallest       = std::isnan(J) ? -1. : J;
                    where_smallest = fe_values.quadrature_point(q);
                  }
              }
          }
      const std::string inverted =
        (smallest > 0)
          ? std::string()
          : parameters.where() + "Initial conditions/Displacement = '" +
              parameters.displacement_expression +
              "' inverts the body: det F = " + number_text(smallest) + " at " +
              point_text(where_smallest) +
              " (the volume ratio must be positive everywhere).";
      fail_everywhere_on_input(inverted, mpi_communicator);
    }



    // @sect4{check_initial_state}
    void
    check_initial_state(
      const Parameters::AllParameters                   &parameters,
      const std::vector<std::pair<std::string, double>> &values)
    {
      for (const auto &[name, value] : values)
        AssertThrow(storable(value),
                    ExcMessage(parameters.where() + "the initial state is " +
                               (std::isfinite(value)
                                  ? "beyond the range the output can store"
                                  : "not finite") +
                               ": its " + name + " is " + number_text(value) +
                               ". Check Initial conditions/Displacement and "
                               "Velocity, and the loads at t = 0."));
    }



#define SOFT_ROBOT_INSTANTIATE(dim)                                          \
  template void check_mesh_geometry<dim>(const Parameters::AllParameters &,  \
                                         const Triangulation<dim> &,         \
                                         const Mapping<dim> &,               \
                                         const FiniteElement<dim> &,         \
                                         const Quadrature<dim> &);           \
  template void check_expression<dim>(FunctionParser<dim> &,                 \
                                      const Parameters::AllParameters &,     \
                                      const std::string &,                   \
                                      const std::string &,                   \
                                      const std::vector<Point<dim>> &,       \
                                      const std::vector<double> &);          \
  template void check_expression_syntax<dim>(                                \
    const Parameters::AllParameters &);                                      \
  template void initialize_checked<dim>(FunctionParser<dim> &,               \
                                        const Parameters::AllParameters &,   \
                                        const std::string &,                 \
                                        const std::string &);                \
  template std::vector<std::string> check_materials_and_loads<dim>(          \
    const Parameters::AllParameters &, const Triangulation<dim> &);          \
  template void check_initial_fields<dim>(const Parameters::AllParameters &, \
                                          const Mapping<dim> &,              \
                                          const DoFHandler<dim> &,           \
                                          const Quadrature<dim> &,           \
                                          const AffineConstraints<double> &, \
                                          const MPI_Comm);
    SOFT_ROBOT_FOR_EACH_DIMENSION(SOFT_ROBOT_INSTANTIATE)
#undef SOFT_ROBOT_INSTANTIATE
  } // namespace InputChecks
} // namespace SoftRobot
