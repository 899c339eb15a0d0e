// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Checking the input before anything is written}
//
// A run must never destroy an earlier result, and an error in the input
// must not be found after the output directory has been written to. So
// everything the input determines is checked before the first byte of
// output (SoftRobotDynamics::run() calls these checks in this order, and
// prepares the output directory only after the last one):
//
// 1. The parameter file on its own: ranges and types (ParameterHandler's
//    patterns), combinations of entries (AllParameters), the names of the
//    output files (check_output_names()).
// 2. The mesh: the ids the scene names exist (check_mesh_ids()), the size
//    that the refinements would give (check_refinement_size()), and every
//    cell's orientation and volume (check_mesh_geometry()).
// 3. The expressions. deal.II's FunctionParser parses its expressions at
//    their first evaluation, not when it is initialized, so an expression
//    is only known to be valid once it has been evaluated. Every
//    expression is therefore evaluated where it is used -- the traction at
//    the vertices of the loaded boundaries at t = 0 and at the end time,
//    the initial fields at the support points of the degrees of freedom,
//    the material-id function at the cell centres -- and a syntax error, an
//    unknown variable or a value that is not finite is an input error that
//    names the file, the entry and the value (check_expression()).
// 4. The materials and loads, for what has no physical reading or is
//    probably a mistake (check_materials_and_loads()).
// 5. The initial fields: finite, and an initial displacement that inverts
//    no element (check_initial_fields()), then the initial state that the
//    simulator computes from them (check_initial_state()).
//
// Values beyond the range of single precision (3.4e38) are rejected like
// values that are not finite: the VTU files store the fields in single
// precision, and such a value would be written as infinity.
//
// On several MPI processes, a check that looks at the process's own part
// of the mesh reports its failure to all of them (fail_everywhere_on_input),
// so that every process throws the same error.
//
// Implemented in source/core/input_checks.cc.

#ifndef soft_robot_core_input_checks_h
#define soft_robot_core_input_checks_h

#include <core/parameters.h>
#include <deal.II/base/function_parser.h>
#include <deal.II/base/point.h>
#include <deal.II/base/quadrature.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/trilinos_vector.h>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace SoftRobot
{
  using namespace dealii;

  namespace InputChecks
  {
    // deal.II's FunctionParser prints muparser's report of an error to
    // std::cerr before it throws; the input errors say the same in one
    // line, with the file and the entry. This silences std::cerr for as
    // long as it lives.
    class SilencedErrorStream
    {
    public:
      SilencedErrorStream()
        : saved(std::cerr.rdbuf(sink.rdbuf()))
      {
      }
      ~SilencedErrorStream()
      {
        std::cerr.rdbuf(saved);
      }

    private:
      std::ostringstream sink;
      std::streambuf    *saved;
    };

    // A point as the messages print it, "(x, y, z)" to six digits.
    template <int dim>
    std::string
    point_text(const Point<dim> &point)
    {
      std::ostringstream text;
      text << std::setprecision(6) << '(';
      for (unsigned int d = 0; d < dim; ++d)
        text << (d == 0 ? "" : ", ") << point[d];
      text << ')';
      return text.str();
    }

    // The largest magnitude the output can store (single precision).
    constexpr double largest_output_value = 3.4e38;

    // Collective: if `local_error` is not empty on some process, every
    // process throws the input error of the lowest such process.
    void
    fail_everywhere_on_input(const std::string &local_error,
                             const MPI_Comm     mpi_communicator);

    // @sect4{The parameter file}
    void
    check_output_names(const Parameters::AllParameters &parameters);

    // @sect4{The mesh}
    //
    // The number of cells after `Global refinements`, which must not
    // exceed what the program can hold, from the cells before them.
    void
    check_refinement_size(const Parameters::AllParameters &parameters,
                          const unsigned int               dim,
                          const unsigned int               n_cells);

    // Every cell's Jacobian determinant at the quadrature points must be
    // positive: a cell whose vertices are numbered in the wrong orientation,
    // or that is degenerate, has no volume to integrate over. The message
    // names the mesh file (or the generator).
    template <int dim>
    void
    check_mesh_geometry(const Parameters::AllParameters &parameters,
                        const Triangulation<dim>        &triangulation,
                        const Mapping<dim>              &mapping,
                        const FiniteElement<dim>        &fe,
                        const Quadrature<dim>           &quadrature);

    // @sect4{The expressions}
    //
    // Evaluates `function`, initialized from `expression` of the entry
    // `entry`, at every point and time; throws an input error naming the
    // entry if the expression cannot be parsed or a value is not finite or
    // beyond largest_output_value.
    template <int dim>
    void
    check_expression(FunctionParser<dim>             &function,
                     const Parameters::AllParameters &parameters,
                     const std::string               &entry,
                     const std::string               &expression,
                     const std::vector<Point<dim>>   &points,
                     const std::vector<double>       &times);

    // The expressions of the initial fields and the traction, each
    // initialized and evaluated once at the origin at t = 0, for syntax
    // errors and unknown variables only (the values are checked where the
    // expressions are used). Called before the simulator is constructed,
    // which initializes its own parsers from the same expressions.
    template <int dim>
    void
    check_expression_syntax(const Parameters::AllParameters &parameters);

    // Initializes `function` from an expression of dim components, with an
    // input error naming the file and the entry if that fails.
    template <int dim>
    void
    initialize_checked(FunctionParser<dim>             &function,
                       const Parameters::AllParameters &parameters,
                       const std::string               &entry,
                       const std::string               &expression);

    // @sect4{Materials and loads}
    //
    // Errors for what has no physical reading (a material of the mesh
    // without mass); warnings, returned as text, for what is probably a
    // mistake (a bulk modulus below the shear modulus, a traction on no
    // boundary). Evaluates the traction at the vertices of the loaded
    // boundaries at t = 0 and at the end time.
    template <int dim>
    std::vector<std::string>
    check_materials_and_loads(const Parameters::AllParameters &parameters,
                              const Triangulation<dim>        &triangulation);

    // @sect4{The initial state}
    //
    // Collective. The initial displacement and velocity at the support
    // points of the locally owned cells (finite, within the output's
    // range), and $\det\mathbf F > 0$ of the initial displacement (with the
    // fixed components set to zero, as the simulator sets them) at the
    // quadrature points.
    template <int dim>
    void
    check_initial_fields(const Parameters::AllParameters &parameters,
                         const Mapping<dim>              &mapping,
                         const DoFHandler<dim>           &dof_handler,
                         const Quadrature<dim>           &quadrature,
                         const AffineConstraints<double> &constraints,
                         const MPI_Comm                   mpi_communicator);

    // The initial state as the simulator computed it: every vector and
    // energy finite and within the output's range. `values` are pairs of a
    // name and a value (norms of vectors, energies).
    void
    check_initial_state(
      const Parameters::AllParameters                   &parameters,
      const std::vector<std::pair<std::string, double>> &values);
  } // namespace InputChecks
} // namespace SoftRobot

#endif
