// @sect3{Setting up: mesh, finite element, constraints, matrices}
//
// This file holds the phases of SoftRobotDynamics that run once, before the
// time loop: the constructor, make_grid(), setup_system() and the mass
// matrix, and run(), which strings all phases together.

#include <core/soft_robot_dynamics.h>
#include <deal.II/base/function_parser.h>
#include <deal.II/base/multithread_info.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/utilities.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_simplex_p.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_fe.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_in.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/sparsity_tools.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <Amesos_BaseSolver.h>
#include <Epetra_CrsMatrix.h>
#include <Epetra_Import.h>
#include <Epetra_LinearProblem.h>
#include <Epetra_Map.h>
#include <Epetra_Vector.h>
#include <deal.II/numerics/vector_tools.h>
#include <filesystem>
#include <iomanip>
#include <set>
#include <sstream>

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

    // The names of the coordinate variables of the expressions.
    template <int dim>
    std::string
    coordinate_names()
    {
      return FunctionParser<dim>::default_variable_names() + ",t";
    }

    // Constants of the expressions as a map, from 'a=1, b=2'.
    std::map<std::string, double>
    parse_constants(const std::string &text)
    {
      std::map<std::string, double> constants;
      for (const auto &entry : Utilities::split_string_list(text, ','))
        {
          const auto pair = Utilities::split_string_list(entry, '=');
          AssertThrow(pair.size() == 2,
                      ExcMessage("Loads and constraints/Function constants: "
                                 "expected 'name=value', got '" +
                                 entry + "'."));
          constants[pair[0]] = Utilities::string_to_double(pair[1]);
        }
      return constants;
    }
  } // namespace



  // A vector function of space and time with one component per dimension,
  // from an expression as the parameter file gives it; an empty one is
  // zero. The error message names the entry.
  template <int dim>
  void
  initialize_vector_function(FunctionParser<dim> &function,
                             const std::string   &expression,
                             const std::string   &constants,
                             const std::string   &entry_name)
  {
    std::string text = expression;
    if (text.empty())
      {
        text = "0";
        for (unsigned int d = 1; d < dim; ++d)
          text += "; 0";
      }
    const unsigned int n_components =
      Utilities::split_string_list(text, ';').size();
    AssertThrow(n_components == dim,
                ExcMessage(entry_name + " must have " + std::to_string(dim) +
                           " components separated by ';' in " +
                           std::to_string(dim) + "D, but '" + expression +
                           "' has " + std::to_string(n_components) + "."));
    try
      {
        function.initialize(coordinate_names<dim>(),
                            text,
                            parse_constants(constants),
                            /*time_dependent=*/true);
      }
    catch (ExceptionBase &error)
      {
        std::ostringstream reason;
        error.print_info(reason);
        AssertThrow(false,
                    ExcMessage(entry_name + ": cannot parse '" + expression +
                               "': " + reason.str()));
      }
  }



  // @sect4{SoftRobotDynamics::SoftRobotDynamics}
  //
  // The triangulation is a parallel::shared::Triangulation: every process
  // holds the whole (small) mesh, and deal.II partitions the cells (with
  // METIS in Debian's build).
  // Unlike the p4est-based distributed triangulation it supports 1D meshes
  // and tetrahedral meshes from gmsh, which the actuator needs.
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
    , stepper(make_stepper(parameters))
    , traction_function(dim)
    , initial_displacement(dim)
    , initial_velocity(dim)
    , time_step(parameters.time_step)
  {
    AssertThrow(parameters.dimension == dim,
                ExcMessage("The parameter file asks for dimension " +
                           std::to_string(parameters.dimension) +
                           ", but this is SoftRobotDynamics<" +
                           std::to_string(dim) + ">."));
    // All expressions are parsed here, before anything is computed or
    // written, so that a mistake in any of them stops the program at once.
    initialize_vector_function(traction_function,
                               parameters.traction_expression,
                               parameters.constants,
                               "Loads and constraints/Traction");
    initialize_vector_function(initial_displacement,
                               parameters.displacement_expression,
                               parameters.constants,
                               "Initial conditions/Displacement");
    initialize_vector_function(initial_velocity,
                               parameters.velocity_expression,
                               parameters.constants,
                               "Initial conditions/Velocity");
    for (unsigned int d = 0; d < dim; ++d)
      gravity[d] = parameters.gravity[d];
    for (const auto &[id, material] : parameters.by_id)
      materials.emplace(id,
                        NeoHookeanEnergy<dim>(material.shear_modulus,
                                              material.bulk_modulus));
  }



  template <int dim>
  SoftRobotDynamics<dim>::~SoftRobotDynamics()
  {
    if (output_writer.joinable())
      output_writer.join();
    dof_handler.clear();
  }



  // @sect4{SoftRobotDynamics::make_grid}
  //
  // The mesh is first built in a serial triangulation, where it can be
  // converted to simplices or distorted, and then copied into the shared
  // triangulation, which partitions it. Every material id of the mesh
  // must have its `Material <id>` subsection, and every boundary id the
  // parameter file names must exist: both mistakes are caught here, before
  // anything is written.
  template <int dim>
  void
  SoftRobotDynamics<dim>::make_grid()
  {
    TimerOutput::Scope timer_section(computing_timer, "Make grid");

    Triangulation<dim> serial;
    if (parameters.mesh_source ==
        Parameters::Geometry::MeshSource::generator)
      {
        Triangulation<dim> generated;
        try
          {
            GridGenerator::generate_from_name_and_arguments(
              generated,
              parameters.generator_name,
              parameters.generator_arguments);
          }
        catch (ExceptionBase &error)
          {
            std::ostringstream reason;
            error.print_info(reason);
            AssertThrow(false,
                        ExcMessage("In '" + parameters.source_name +
                                   "': Geometry/Generator '" +
                                   parameters.generator_name +
                                   "' does not accept the arguments '" +
                                   parameters.generator_arguments + "' in " +
                                   std::to_string(dim) + "D: " + reason.str()));
          }
        if (parameters.convert_to_simplices && dim > 1)
          GridGenerator::convert_hypercube_to_simplex_mesh(generated, serial);
        else
          serial.copy_triangulation(generated);
      }
    else
      {
        GridIn<dim> grid_in;
        grid_in.attach_triangulation(serial);
        std::ifstream input(parameters.mesh_file);
        grid_in.read_msh(input);
      }

    if (parameters.distortion > 0)
      GridTools::distort_random(parameters.distortion, serial, true);

    // Generators number materials in their own ways (colorized boxes by
    // octant); a generated mesh is of material 1 unless the parameter
    // file's function says otherwise.
    if (parameters.mesh_source ==
        Parameters::Geometry::MeshSource::generator)
      for (const auto &cell : serial.active_cell_iterators())
        cell->set_material_id(1);
    if (!parameters.material_id_function.empty())
      {
        FunctionParser<dim> id_function(1);
        id_function.initialize(FunctionParser<dim>::default_variable_names(),
                               parameters.material_id_function,
                               parse_constants(parameters.constants));
        for (const auto &cell : serial.active_cell_iterators())
          cell->set_material_id(static_cast<types::material_id>(
            std::lround(id_function.value(cell->center()))));
      }

    triangulation.copy_triangulation(serial);
    triangulation.refine_global(parameters.global_refinements);

    std::set<types::material_id> mesh_materials;
    std::set<types::boundary_id> mesh_boundaries;
    for (const auto &cell : triangulation.active_cell_iterators())
      {
        mesh_materials.insert(cell->material_id());
        for (const auto &face : cell->face_iterators())
          if (face->at_boundary())
            mesh_boundaries.insert(face->boundary_id());
      }
    for (const types::material_id id : mesh_materials)
      AssertThrow(parameters.by_id.count(id) == 1,
                  ExcMessage("In '" + parameters.source_name +
                             "': the mesh has cells with material id " +
                             std::to_string(id) +
                             ", but the file has no subsection 'Material " +
                             std::to_string(id) + "' with a Name."));
    std::vector<std::pair<unsigned int, std::string>> named_boundaries;
    for (const auto &entry : parameters.fixed_components)
      named_boundaries.emplace_back(entry.first,
                                    "Loads and constraints/Fixed components");
    for (const unsigned int id : parameters.traction_boundary_ids)
      named_boundaries.emplace_back(
        id, "Loads and constraints/Traction boundary ids");
    if (parameters.tip_region_type ==
        Parameters::Output::TipRegionType::boundary)
      named_boundaries.emplace_back(parameters.tip_region_id,
                                    "Output/Tip region");
    else
      AssertThrow(mesh_materials.count(parameters.tip_region_id) == 1,
                  ExcMessage("In '" + parameters.source_name +
                             "': Output/Tip region names material " +
                             std::to_string(parameters.tip_region_id) +
                             ", which no cell of the mesh has."));
    for (const auto &[id, entry] : named_boundaries)
      {
        std::string present;
        for (const auto b : mesh_boundaries)
          present += " " + std::to_string(b);
        AssertThrow(mesh_boundaries.count(id) == 1,
                    ExcMessage("In '" + parameters.source_name + "': " + entry +
                               " names boundary id " + std::to_string(id) +
                               ", which the mesh does not have (it has:" +
                               present + ")."));
      }

    // The finite element, mapping and quadrature follow the cell shape.
    // The quadrature of the stiffness is the cheapest that integrates the
    // stiffness of a linear problem exactly on affine cells (its integrand,
    // a product of two gradients, has degree 2(p-1) on simplices and 2p per
    // direction on hypercubes): QGaussSimplex(p) -- one point for linear
    // tetrahedra, which makes them constant-strain elements -- and QGauss
    // with p + 1 points per direction. The mass matrix (degree 2p) always
    // gets one point more on simplices.
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
        fe      = std::make_unique<FESystem<dim>>(FE_SimplexP<dim>(p), dim);
        mapping = std::make_unique<MappingFE<dim>>(FE_SimplexP<dim>(1));
        cell_quadrature = std::make_unique<QGaussSimplex<dim>>(n_q);
        mass_quadrature = std::make_unique<QGaussSimplex<dim>>(p + 1);
        face_quadrature = std::make_unique<QGaussSimplex<dim - 1>>(p + 1);
      }
    else
      {
        fe              = std::make_unique<FESystem<dim>>(FE_Q<dim>(p), dim);
        mapping         = std::make_unique<MappingQ<dim>>(1);
        cell_quadrature = std::make_unique<QGauss<dim>>(n_q);
        mass_quadrature = std::make_unique<QGauss<dim>>(p + 1);
        face_quadrature = std::make_unique<QGauss<dim - 1>>(p + 1);
      }

    pcout << "Mesh: " << triangulation.n_global_active_cells() << ' '
          << (simplex_mesh ? "simplex" : "hypercube") << " cells, "
          << mesh_materials.size() << " material(s)" << std::endl;
  }



  // @sect4{SoftRobotDynamics::setup_system}
  //
  // Degrees of freedom, the constraints of the fixed boundaries, the
  // sparsity pattern shared by the tangent and the mass matrix, the state
  // vectors, the densities and the near null space for algebraic multigrid.
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
    const FEValuesExtractors::Vector displacements(0);
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
    system_matrix.reinit(locally_owned_dofs,
                         locally_owned_dofs,
                         dsp,
                         mpi_communicator);
    mass.reinit(locally_owned_dofs, locally_owned_dofs, dsp, mpi_communicator);
    has_damping = false;
    for (const auto &entry : parameters.by_id)
      has_damping = has_damping || (entry.second.damping_zeta > 0.);
    if (has_damping)
      for (TrilinosWrappers::SparseMatrix *matrix :
           {&damping_matrix, &next_damping_matrix})
        matrix->reinit(locally_owned_dofs,
                       locally_owned_dofs,
                       dsp,
                       mpi_communicator);

    for (State *state : {&current, &previous})
      for (TrilinosWrappers::MPI::Vector *vector : {&state->u,
                                                    &state->v,
                                                    &state->a,
                                                    &state->internal_force,
                                                    &state->external_force,
                                                    &state->damping_force})
        vector->reinit(locally_owned_dofs, mpi_communicator);

    // Densities: given, or from the mass of the region. The meshed volume
    // of a region times its section is the volume of the modelled part of
    // the body; dividing by the model fraction gives the whole body's.
    std::map<types::material_id, double> region_volume;
    {
      FEValues<dim> fe_values(*mapping,
                              *fe,
                              *cell_quadrature,
                              update_JxW_values);
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            fe_values.reinit(cell);
            for (const unsigned int q : fe_values.quadrature_point_indices())
              region_volume[cell->material_id()] += fe_values.JxW(q);
          }
    }
    for (const auto &[id, material] : parameters.by_id)
      {
        const double volume =
          Utilities::MPI::sum(region_volume[id], mpi_communicator);
        if (material.mass > 0)
          {
            AssertThrow(volume > 0,
                        ExcMessage("In '" + parameters.source_name +
                                   "': Material " + std::to_string(id) +
                                   "/Mass is given, but no "
                                   "cell of the mesh has this material id."));
            densities[id] = material.mass * parameters.model_fraction /
                            (volume * material.section);
          }
        else
          densities[id] = material.density;
        if (volume > 0)
          pcout << "Material " << id << " (" << material.name
                << "): mu = " << material.shear_modulus
                << " kPa, density = " << densities[id]
                << " kg/mm^3, mass in the model = "
                << densities[id] * volume * material.section << " kg"
                << std::endl;
      }

    // The rigid-body modes (translations and rotations) at the support
    // points of the degrees of freedom: ML builds its coarse spaces from
    // them, which keeps the number of CG iterations of elasticity low.
    {
      std::map<types::global_dof_index, Point<dim>> support_points;
      DoFTools::map_dofs_to_support_points(*mapping,
                                           dof_handler,
                                           support_points);
      const unsigned int n_rotations = dim * (dim - 1) / 2;
      rigid_body_modes.assign(
        dim + n_rotations,
        std::vector<double>(locally_owned_dofs.n_elements(), 0.));
      std::vector<types::global_dof_index> dof_indices(fe->n_dofs_per_cell());
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            cell->get_dof_indices(dof_indices);
            for (unsigned int i = 0; i < dof_indices.size(); ++i)
              if (locally_owned_dofs.is_element(dof_indices[i]))
                {
                  const unsigned int local =
                    locally_owned_dofs.index_within_set(dof_indices[i]);
                  const unsigned int c = fe->system_to_component_index(i).first;
                  const Point<dim>  &x = support_points[dof_indices[i]];
                  rigid_body_modes[c][local] = 1.;
                  if constexpr (dim == 2)
                    rigid_body_modes[2][local] = (c == 0) ? -x[1] : x[0];
                  if constexpr (dim == 3)
                    {
                      // Rotations about x, y and z: (0,-z,y), (z,0,-x), (-y,x,0).
                      const double rx[3]         = {0., -x[2], x[1]};
                      const double ry[3]         = {x[2], 0., -x[0]};
                      const double rz[3]         = {-x[1], x[0], 0.};
                      rigid_body_modes[3][local] = rx[c];
                      rigid_body_modes[4][local] = ry[c];
                      rigid_body_modes[5][local] = rz[c];
                    }
                }
          }
    }

    assemble_mass_matrix();
    setup_cell_geometry();
    setup_traction_faces();
    setup_tip_weights();

    pcout << "Degrees of freedom: " << dof_handler.n_dofs() << " ("
          << fe->get_name() << ", "
          << Utilities::MPI::n_mpi_processes(mpi_communicator)
          << " MPI process(es))" << std::endl;
  }



  // @sect4{SoftRobotDynamics::setup_cell_geometry}
  //
  // The data described at the declaration of CellGeometry, in the order in
  // which the loop over the locally owned cells visits them.
  template <int dim>
  void
  SoftRobotDynamics<dim>::setup_cell_geometry()
  {
    CellGeometry &geometry = cell_geometry;
    geometry               = CellGeometry();
    geometry.dofs_per_cell = fe->n_dofs_per_cell();
    geometry.n_q_points    = cell_quadrature->size();
    for (unsigned int i = 0; i < geometry.dofs_per_cell; ++i)
      geometry.components.push_back(fe->system_to_component_index(i).first);

    FEValues<dim> fe_values(*mapping,
                            *fe,
                            *cell_quadrature,
                            update_gradients | update_JxW_values);
    std::vector<types::global_dof_index> dof_indices(geometry.dofs_per_cell);
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          cell->get_dof_indices(dof_indices);
          geometry.dof_indices.insert(geometry.dof_indices.end(),
                                      dof_indices.begin(),
                                      dof_indices.end());
          const Parameters::Material &material = material_of(cell);
          for (unsigned int q = 0; q < geometry.n_q_points; ++q)
            {
              geometry.JxW.push_back(fe_values.JxW(q) * material.section);
              for (unsigned int i = 0; i < geometry.dofs_per_cell; ++i)
                geometry.shape_gradients.push_back(
                  fe_values.shape_grad_component(i,
                                                 q,
                                                 geometry.components[i]));
            }
          geometry.material.push_back(&materials.at(cell->material_id()));
          geometry.damping_zeta.push_back(material.damping_zeta);
          ++geometry.n_cells;
        }

    // The direct addresses of the cell matrices' entries in the global
    // matrices. Adding a cell matrix through Epetra's SumIntoGlobalValues
    // searches every row for every column; with the addresses, it is a
    // plain loop (a sixth of the run time of the headline benchmark went
    // into those searches). The two matrices share their sparsity pattern
    // and so their storage layout, which is checked. In parallel runs the
    // rows of this process have addresses; the few rows of a cell that
    // another process owns (on the interface) still go through Epetra.
    // The vectors' entries of those rows are collected in a small ghost
    // vector and sent to their owners in one exchange whose pattern is set
    // up here once. All processes take the same decision, since setting up
    // that exchange is a collective operation.
    ghost_map.reset();
    ghost_import.reset();
    ghost_displacements.reset();
    ghost_forces.reset();
    bool usable = true;
    for (const auto &line : constraints.get_lines())
      usable = usable && line.entries.empty() && line.inhomogeneity == 0.;
    int    *row_offsets = nullptr, *columns = nullptr;
    double *values      = nullptr;
    const Epetra_CrsMatrix &matrix = system_matrix.trilinos_matrix();
    const bool serial = (Utilities::MPI::n_mpi_processes(mpi_communicator) == 1);
    usable =
      usable && matrix.ExtractCrsDataPointers(row_offsets, columns, values) == 0;
    if (usable && has_damping)
      {
        int    *damping_offsets = nullptr, *damping_columns = nullptr;
        double *damping_values  = nullptr;
        const Epetra_CrsMatrix &damping = damping_matrix.trilinos_matrix();
        usable = damping.ExtractCrsDataPointers(damping_offsets,
                                                damping_columns,
                                                damping_values) == 0 &&
                 damping.RowMap().SameAs(matrix.RowMap()) &&
                 damping.ColMap().SameAs(matrix.ColMap()) &&
                 damping.NumMyNonzeros() == matrix.NumMyNonzeros() &&
                 std::equal(columns,
                            columns + matrix.NumMyNonzeros(),
                            damping_columns) &&
                 std::equal(row_offsets,
                            row_offsets + matrix.NumMyRows() + 1,
                            damping_offsets);
      }
    if (Utilities::MPI::min(usable ? 1 : 0, mpi_communicator) == 0)
      return;
    const Epetra_BlockMap &vector_map = current.u.trilinos_vector().Map();
    const unsigned int n = geometry.dofs_per_cell;
    geometry.matrix_positions.resize(geometry.dof_indices.size() * n);
    geometry.diagonal_positions.resize(geometry.dof_indices.size());
    if (serial)
      geometry.vector_positions.resize(geometry.dof_indices.size());
    // the position of entry (row, column) in the value array
    const auto position = [&](const types::global_dof_index row,
                              const types::global_dof_index column) {
      const int local_row    = matrix.LRID(static_cast<int>(row));
      const int local_column = matrix.LCID(static_cast<int>(column));
      AssertThrow(local_row >= 0 && local_column >= 0, ExcInternalError());
      for (int k = row_offsets[local_row]; k < row_offsets[local_row + 1]; ++k)
        if (columns[k] == local_column)
          return k;
      AssertThrow(false, ExcMessage("A cell's entry is not in the matrix."));
      return -1;
    };
    for (unsigned int cell = 0; cell < geometry.n_cells; ++cell)
      {
        const types::global_dof_index *dofs =
          &geometry.dof_indices[cell * n];
        for (unsigned int i = 0; i < n; ++i)
          {
            const bool fixed = constraints.is_constrained(dofs[i]);
            if (serial)
              geometry.vector_positions[cell * n + i] =
                fixed ? -1 : vector_map.LID(static_cast<int>(dofs[i]));
            if (!locally_owned_dofs.is_element(dofs[i]))
              {
                geometry.diagonal_positions[cell * n + i] = -2;
                for (unsigned int j = 0; j < n; ++j)
                  geometry.matrix_positions[(cell * n + i) * n + j] = -2;
                continue;
              }
            geometry.diagonal_positions[cell * n + i] =
              fixed ? position(dofs[i], dofs[i]) : -1;
            for (unsigned int j = 0; j < n; ++j)
              geometry.matrix_positions[(cell * n + i) * n + j] =
                (fixed || constraints.is_constrained(dofs[j])) ?
                  -1 :
                  position(dofs[i], dofs[j]);
          }
      }
    if (serial)
      return;

    // The ghost vectors: the free dofs of this process's cells that another
    // process owns, in increasing order.
    std::vector<TrilinosWrappers::types::int_type> ghosts;
    for (const types::global_dof_index dof : geometry.dof_indices)
      if (!locally_owned_dofs.is_element(dof) && !constraints.is_constrained(dof))
        ghosts.push_back(static_cast<TrilinosWrappers::types::int_type>(dof));
    std::sort(ghosts.begin(), ghosts.end());
    ghosts.erase(std::unique(ghosts.begin(), ghosts.end()), ghosts.end());
    ghost_map = std::make_unique<Epetra_Map>(-1,
                                             static_cast<int>(ghosts.size()),
                                             ghosts.data(),
                                             0,
                                             vector_map.Comm());
    ghost_import        = std::make_unique<Epetra_Import>(*ghost_map, vector_map);
    ghost_displacements = std::make_unique<Epetra_Vector>(*ghost_map);
    ghost_forces        = std::make_unique<Epetra_Vector>(*ghost_map);
    geometry.distributed_vector_positions.resize(geometry.dof_indices.size());
    for (std::size_t k = 0; k < geometry.dof_indices.size(); ++k)
      {
        const types::global_dof_index dof = geometry.dof_indices[k];
        if (constraints.is_constrained(dof))
          geometry.distributed_vector_positions[k] = -1;
        else if (locally_owned_dofs.is_element(dof))
          geometry.distributed_vector_positions[k] =
            vector_map.LID(static_cast<TrilinosWrappers::types::int_type>(dof));
        else
          geometry.distributed_vector_positions[k] =
            -2 - static_cast<int>(
                   std::lower_bound(ghosts.begin(), ghosts.end(), dof) -
                   ghosts.begin());
      }
  }



  // @sect4{SoftRobotDynamics::setup_traction_faces}
  //
  // The data described at the declaration of TractionFaces, for the
  // locally owned cells' faces on the boundaries the parameter file names.
  template <int dim>
  void
  SoftRobotDynamics<dim>::setup_traction_faces()
  {
    traction_faces = TractionFaces();
    if (parameters.traction_boundary_ids.empty())
      return;
    const std::set<types::boundary_id> ids(
      parameters.traction_boundary_ids.begin(),
      parameters.traction_boundary_ids.end());
    FEFaceValues<dim>  fe_face_values(*mapping,
                                     *fe,
                                     *face_quadrature,
                                     update_values | update_quadrature_points |
                                       update_JxW_values);
    const unsigned int dofs_per_cell = fe->n_dofs_per_cell();
    std::vector<types::global_dof_index> dof_indices(dofs_per_cell);
    traction_faces.n_q_points = face_quadrature->size();
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const auto face : cell->face_indices())
          if (cell->face(face)->at_boundary() &&
              ids.count(cell->face(face)->boundary_id()) == 1)
            {
              fe_face_values.reinit(cell, face);
              cell->get_dof_indices(dof_indices);
              traction_faces.dof_indices.insert(
                traction_faces.dof_indices.end(),
                dof_indices.begin(),
                dof_indices.end());
              const double section = material_of(cell).section;
              for (const unsigned int q :
                   fe_face_values.quadrature_point_indices())
                {
                  traction_faces.points.push_back(
                    fe_face_values.quadrature_point(q));
                  for (const unsigned int i : fe_face_values.dof_indices())
                    traction_faces.weighted_shape_values.push_back(
                      fe_face_values.shape_value_component(
                        i, q, cell_geometry.components[i]) *
                      fe_face_values.JxW(q) * section);
                }
              ++traction_faces.n_faces;
            }
  }



  // @sect4{SoftRobotDynamics::assemble_mass_matrix}
  //
  // The consistent mass matrix $M_{ij} = \int\rho_0\,\mathbf N_i\cdot\mathbf
  // N_j\,dV$ (times the section factor) does not change during the run; it
  // is assembled once. The gravity load is assembled alongside, since it
  // is the mass matrix applied to the constant field $\mathbf g$.
  template <int dim>
  void
  SoftRobotDynamics<dim>::assemble_mass_matrix()
  {
    FEValues<dim>      fe_values(*mapping,
                            *fe,
                            *mass_quadrature,
                            update_values | update_JxW_values);
    const unsigned int dofs_per_cell = fe->n_dofs_per_cell();
    FullMatrix<double> cell_matrix(dofs_per_cell, dofs_per_cell);
    Vector<double>     cell_gravity(dofs_per_cell);
    std::vector<types::global_dof_index> dof_indices(dofs_per_cell);
    const FEValuesExtractors::Vector     displacements(0);

    gravity_force.reinit(locally_owned_dofs, mpi_communicator);
    mass = 0.;
    // The nodes of a cell are the support points of the scalar base
    // element; node n carries the dofs component_to_system_index(c, n).
    const unsigned int nodes_per_cell = fe->base_element(0).n_dofs_per_cell();
    const std::vector<Point<dim>> &unit_nodes =
      fe->base_element(0).get_unit_support_points();
    cell_nodal_mass.clear();
    cell_node_positions.clear();
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          cell_matrix  = 0.;
          cell_gravity = 0.;
          const double rho_A =
            densities.at(cell->material_id()) * material_of(cell).section;
          for (const unsigned int q : fe_values.quadrature_point_indices())
            for (const unsigned int i : fe_values.dof_indices())
              {
                const Tensor<1, dim> N_i = fe_values[displacements].value(i, q);
                cell_gravity(i) += rho_A * N_i * gravity * fe_values.JxW(q);
                for (const unsigned int j : fe_values.dof_indices())
                  cell_matrix(i, j) += rho_A * N_i *
                                       fe_values[displacements].value(j, q) *
                                       fe_values.JxW(q);
              }
          for (unsigned int n = 0; n < nodes_per_cell; ++n)
            {
              cell_node_positions.push_back(
                mapping->transform_unit_to_real_cell(cell, unit_nodes[n]));
              for (unsigned int k = 0; k < nodes_per_cell; ++k)
                cell_nodal_mass.push_back(
                  cell_matrix(fe->component_to_system_index(0, n),
                              fe->component_to_system_index(0, k)));
            }
          cell->get_dof_indices(dof_indices);
          constraints.distribute_local_to_global(
            cell_matrix, cell_gravity, dof_indices, mass, gravity_force);
        }
    mass.compress(VectorOperation::add);
    gravity_force.compress(VectorOperation::add);
  }



  template <int dim>
  const Parameters::Material &
  SoftRobotDynamics<dim>::material_of(
    const typename DoFHandler<dim>::active_cell_iterator &cell) const
  {
    return parameters.by_id.at(cell->material_id());
  }



  // @sect4{SoftRobotDynamics::run}
  //
  // The whole simulation. The output directory is created only after the
  // mesh has been read and checked, so a bad input leaves nothing behind.
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

    make_grid();
    setup_system();

    if (Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
      std::filesystem::create_directories(parameters.output_directory);
    open_trajectory_file();

    initialize_state();
    write_trajectory_line();
    unsigned int output_index = 0;
    double       next_output  = 0.;
    if (parameters.write_vtu)
      {
        output_results(output_index++);
        next_output += parameters.output_interval;
      }

    const double total_time = parameters.end_time;
    while (true)
      {
        bool advanced = false;
        try
          {
            advanced = advance_one_step();
          }
        catch (RunAborted &)
          {
            if (parameters.write_vtu)
              {
                output_results(output_index++);
                finish_output();
              }
            throw;
          }
        if (!advanced)
          break;
        write_trajectory_line();
        if (parameters.write_vtu &&
            current.time >= next_output - 1e-9 * parameters.time_step)
          {
            output_results(output_index++);
            next_output += parameters.output_interval;
          }
        if (parameters.progress_interval > 0 &&
            step_number % parameters.progress_interval == 0)
          {
            const double elapsed = wall_clock.wall_time();
            const double left =
              elapsed / current.time * (total_time - current.time);
            pcout << "step " << std::setw(5) << step_number
                  << "  t = " << std::fixed << std::setprecision(4)
                  << current.time << " s  dt = " << std::scientific
                  << std::setprecision(2) << time_step << "  Newton "
                  << last_newton_iterations << " (|r| = " << last_residual
                  << ")  elapsed " << std::fixed << std::setprecision(1)
                  << elapsed << " s  left ~" << left << " s"
                  << std::defaultfloat << std::setprecision(6) << std::endl;
          }
      }

    finish_output();
    const double wall_time = wall_clock.wall_time();
    pcout << "Finished " << step_number << " steps in " << wall_time
          << " s: " << total_newton_iterations << " Newton iterations, "
          << total_linear_iterations << " linear iterations, "
          << total_tangent_updates << " matrix factorizations or multigrid "
          << "set-ups, " << total_cutbacks << " time-step cutbacks."
          << std::endl;
    computing_timer.print_summary();
    write_run_statistics(wall_time);

    if (parameters.spectral_analysis)
      {
        trajectory.close();
        analyse_trajectory();
      }
  }



  // @sect4{SoftRobotDynamics::write_run_statistics}
  //
  // The cost of the run in a small machine-readable file,
  // `run_statistics.json` in the output directory, for benchmarks and
  // scripts: mesh size, counts of the solver's work, the wall time of each
  // timed section (the largest over the processes), and the peak resident
  // memory, summed over the processes.
  template <int dim>
  void
  SoftRobotDynamics<dim>::write_run_statistics(const double wall_time) const
  {
    Utilities::System::MemoryStats memory;
    Utilities::System::get_memory_stats(memory);
    const double peak_memory_mb =
      Utilities::MPI::sum(static_cast<double>(memory.VmHWM), mpi_communicator) /
      1024.;
    std::map<std::string, double> sections =
      computing_timer.get_summary_data(TimerOutput::total_wall_time);
    // (The same sections on every process: the maxima below are collective.)
    if (Utilities::MPI::max(background_output_seconds, mpi_communicator) > 0.)
      sections["Output (writing thread)"] = background_output_seconds;
    for (auto &[name, seconds] : sections)
      seconds = Utilities::MPI::max(seconds, mpi_communicator);
    if (Utilities::MPI::this_mpi_process(mpi_communicator) != 0)
      return;

    std::ofstream file(parameters.output_directory + "/run_statistics.json");
    file << std::setprecision(8) << "{\n"
         << "  \"dimension\": " << dim << ",\n"
         << "  \"cells\": " << triangulation.n_global_active_cells() << ",\n"
         << "  \"dofs\": " << dof_handler.n_dofs() << ",\n"
         << "  \"matrix_nonzeros\": " << system_matrix.n_nonzero_elements()
         << ",\n"
         << "  \"multigrid_operator_complexity\": " << amg_operator_complexity
         << ",\n"
         << "  \"degree\": " << parameters.degree << ",\n"
         << "  \"mpi_processes\": "
         << Utilities::MPI::n_mpi_processes(mpi_communicator) << ",\n"
         << "  \"threads_per_process\": " << MultithreadInfo::n_threads()
         << ",\n"
         << "  \"linear_solver\": \"" << Parameters::name_of(parameters.linear_solver)
         << "\",\n"
         << "  \"tangent_update\": \"" << Parameters::name_of(parameters.tangent_update) << "\",\n"
         << "  \"end_time\": " << current.time << ",\n"
         << "  \"steps\": " << step_number << ",\n"
         << "  \"newton_iterations\": " << total_newton_iterations << ",\n"
         << "  \"linear_iterations\": " << total_linear_iterations << ",\n"
         << "  \"factorizations_or_amg_setups\": " << total_tangent_updates
         << ",\n"
         << "  \"cutbacks\": " << total_cutbacks << ",\n"
         << "  \"wall_seconds\": " << wall_time << ",\n"
         << "  \"peak_memory_mb\": " << peak_memory_mb << ",\n"
         << "  \"sections\": {";
    bool first = true;
    for (const auto &[name, seconds] : sections)
      {
        file << (first ? "\n" : ",\n") << "    \"" << name
             << "\": " << seconds;
        first = false;
      }
    file << "\n  }\n}\n";
  }



  // The explicit instantiations of this file's member functions.
#define SOFT_ROBOT_INSTANTIATE(dim)                                         \
  template SoftRobotDynamics<dim>::SoftRobotDynamics(                       \
    const Parameters::AllParameters &, const MPI_Comm);                     \
  template SoftRobotDynamics<dim>::~SoftRobotDynamics();                    \
  template void SoftRobotDynamics<dim>::make_grid();                        \
  template void SoftRobotDynamics<dim>::setup_system();                     \
  template void SoftRobotDynamics<dim>::assemble_mass_matrix();             \
  template void SoftRobotDynamics<dim>::setup_cell_geometry();              \
  template void SoftRobotDynamics<dim>::setup_traction_faces();             \
  template void SoftRobotDynamics<dim>::write_run_statistics(const double)  \
    const;                                                                  \
  template const Parameters::Material &SoftRobotDynamics<dim>::material_of( \
    const typename DoFHandler<dim>::active_cell_iterator &) const;          \
  template void SoftRobotDynamics<dim>::run();                              \
  template void initialize_vector_function<dim>(FunctionParser<dim> &,      \
                                                const std::string &,        \
                                                const std::string &,        \
                                                const std::string &);

  SOFT_ROBOT_INSTANTIATE(1)
  SOFT_ROBOT_INSTANTIATE(2)
  SOFT_ROBOT_INSTANTIATE(3)
#undef SOFT_ROBOT_INSTANTIATE
} // namespace SoftRobot
