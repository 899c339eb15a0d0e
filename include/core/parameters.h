// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Run-time parameters}
//
// Everything a user chooses is read from a `.prm` file through deal.II's
// ParameterHandler. As in the deal.II tutorials there is one structure per
// subsection of the file, each with a function that declares its entries
// (with a pattern that checks the allowed range and a documentation
// string) and one that reads them. The file `parameters/default.prm` is
// generated from these declarations by `soft-robot --print-parameters`,
// so the documentation of every entry lives here and only here.
//
// Vector-valued functions of space and time (initial fields, tractions)
// are given as muparser expressions with one component per space
// dimension, separated by semicolons, in the variables `x`, `y`, `z`
// (as many as the dimension) and `t`. An empty expression means zero.

#ifndef soft_robot_core_parameters_h
#define soft_robot_core_parameters_h

#include <deal.II/base/parameter_handler.h>
#include <map>
#include <string>
#include <vector>

namespace SoftRobot
{
  using namespace dealii;

  namespace Parameters
  {
    // @sect4{Problem}
    struct Problem
    {
      unsigned int dimension;
      std::string  output_directory;
      // The scales beyond which the tip is said to run away (see
      // core/plausibility_guard.h); 0 chooses them from the body.
      double runaway_displacement;
      double runaway_speed;

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);
    };

    // @sect4{Geometry}
    //
    // The mesh comes either from one of deal.II's generators, named with
    // its arguments as in GridGenerator::generate_from_name_and_arguments(),
    // from a gmsh file whose physical volume tags become material ids
    // and whose physical surface tags become boundary ids, or from the
    // hexahedral generator of the bellows actuator (core/bellows_mesh.h),
    // which reads the design of the body from its gmsh geometry file.
    struct Geometry
    {
      enum class MeshSource
      {
        generator,
        file,
        bellows
      };
      MeshSource   mesh_source;
      std::string  generator_name;
      std::string  generator_arguments;
      std::string  mesh_file;
      unsigned int global_refinements;
      bool         convert_to_simplices;
      double       distortion;
      std::string  material_id_function;
      double       model_fraction;
      // The bellows generator's resolution (subsection Geometry/Bellows).
      unsigned int bellows_cells_through_wall;
      unsigned int bellows_cells_along_flank;
      unsigned int bellows_cells_per_chord;
      unsigned int bellows_cells_per_quarter_turn;

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);
    };

    // @sect4{Finite element}
    struct FiniteElement
    {
      unsigned int degree;
      unsigned int quadrature_points;
      // How the volumetric energy enters (see the declaration).
      enum class VolumetricFormulation
      {
        displacement,
        mean_dilatation,
        linear_dilatation
      };
      VolumetricFormulation volumetric_formulation;
      // Whether the global addition uses DirectAddressAssembler.
      bool direct_addresses;

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);
    };

    // @sect4{Materials}
    //
    // One subsection `Material <id>` per material id of the mesh. The
    // silicone body and the stiff tip block of the actuator are two
    // materials of one mesh. In the reduced models (dim = 1 and 2) the
    // `Section` entry is the cross-section area (dim = 1) or the thickness
    // (dim = 2) that turns integrals over the model into integrals over
    // the body it stands for; in 3D it is one.
    struct Material
    {
      std::string name;
      double      shear_modulus;
      double      bulk_modulus;
      double      density;
      double      mass;
      double      damping_zeta;
      double      mass_damping;
      double      section;
      std::string silicone;
    };

    // The silicones are described once, in a library of their measured and
    // fitted data (parameters/silicones.prm, included by every scene), and
    // a material takes its shear modulus, bulk modulus and damping from the
    // library entry it names. The library holds two parameter sets per
    // silicone: 'baseline' (the shear modulus is the study's neo-Hookean
    // C1, as the reference used it) and 'calibrated' (fitted to the
    // experiment-1 frequency). In both, kappa = (bulk-to-shear ratio) mu
    // and zeta = 2 xi / omega from the experiment-1 frequency f and damping
    // ratio xi: zeta = xi / (pi f).
    struct Silicone
    {
      std::string name;
      double      c1;
      double      calibrated_shear_modulus;
      double      bulk_to_shear_ratio;
      double      frequency;
      double      damping_ratio;

      enum class ParameterSet
      {
        baseline,
        calibrated
      };
      double
      shear_modulus(const ParameterSet parameter_set) const;
      double
      damping_coefficient() const;
    };

    struct Materials
    {
      static constexpr unsigned int max_material_id = 9;
      static constexpr unsigned int max_silicones   = 8;

      Silicone::ParameterSet          parameter_set;
      std::map<std::string, Silicone> silicones;
      // Only the subsections whose `Name` is not empty.
      std::map<unsigned int, Material> by_id;

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);
    };

    // @sect4{Damping}
    //
    // The form of the stiffness-proportional damping (each material's
    // `Damping coefficient`) and the damping by the surrounding air. See
    // KelvinVoigtDamping and AerodynamicDrag.
    struct Damping
    {
      enum class StiffnessDamping
      {
        kelvin_voigt,
        lagged_matrix
      };
      StiffnessDamping          stiffness_damping;
      std::vector<unsigned int> drag_boundary_ids;
      double                    drag_coefficient;
      double                    air_density;

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);
    };

    // @sect4{Loads and constraints}
    struct Loads
    {
      std::vector<double> gravity;
      // Boundary id to the components fixed there ("xyz", "y", ...).
      std::map<unsigned int, std::string> fixed_components;
      std::vector<unsigned int>           traction_boundary_ids;
      std::string                         traction_expression;
      std::string                         constants;

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);
    };

    // @sect4{Pneumatics}
    //
    // A pressure on the cavity of a pneumatic actuator: prescribed as a
    // function of time (an expression or a table of measured pressures), or
    // that of a gas enclosed in the cavity. See PneumaticLoad,
    // FollowerPressure, GasCavity and PressureHistory.
    struct Pneumatics
    {
      enum class PressureModel
      {
        prescribed,
        gas
      };
      std::vector<unsigned int> pressure_boundary_ids;
      PressureModel             pressure_model;
      std::string               pressure_expression;
      std::string               pressure_table;
      double                    equivalent_area;
      double                    initial_gas_pressure;
      double                    ambient_pressure;
      double                    gas_exponent;
      double                    dead_volume;
      std::string               inflow_expression;
      double                    gas_temperature;
      bool                      rank_one_tangent;

      // Whether a pressure acts (any boundary named).
      bool
      has_pressure() const
      {
        return !pressure_boundary_ids.empty();
      }

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);
    };

    // @sect4{Initial conditions}
    struct InitialConditions
    {
      enum class InitialState
      {
        expressions,
        static_equilibrium
      };
      // Where the Velocity expression is evaluated: at the reference
      // position of each node, or at its position in the initial state
      // (reference plus initial displacement).
      enum class VelocityCoordinates
      {
        reference,
        initial_state
      };
      InitialState        initial_state;
      std::string         displacement_expression;
      std::string         velocity_expression;
      VelocityCoordinates velocity_coordinates;
      unsigned int        load_steps;
      double              load_step_tolerance;
      double              equilibrium_tolerance;

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);
    };

    // @sect4{Time integration}
    struct TimeIntegration
    {
      double       end_time;
      double       time_step;
      double       minimum_time_step;
      double       alpha;
      double       beta;
      double       gamma;
      unsigned int regrowth_steps;
      unsigned int max_cutbacks;

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);
    };

    // @sect4{Newton's method}
    struct NonlinearSolver
    {
      // 'every step' is the modified Newton method, 'every iteration'
      // Newton's method proper, 'when needed' the modified Newton method
      // with a matrix kept across steps (see the declaration).
      enum class TangentUpdate
      {
        every_step,
        every_iteration,
        when_needed
      };
      unsigned int  newton_max_iterations;
      double        newton_absolute_tolerance;
      double        newton_relative_tolerance;
      TangentUpdate tangent_update;
      double        rebuild_threshold;
      unsigned int  acceleration_depth;
      bool          tangent_extrapolation;
      bool          rotated_tangent;
      bool          line_search;
      unsigned int  max_line_search_steps;
      bool          verbose;

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);
    };

    // @sect4{Linear solver}
    struct LinearSolver
    {
      enum class LinearSolverType
      {
        cg,
        gmres,
        direct
      };
      enum class DirectSolverType
      {
        automatic,
        klu,
        mumps
      };
      LinearSolverType linear_solver;
      DirectSolverType direct_solver;
      bool             symmetric_factorization = false;
      bool             single_precision_factor = false;
      double           linear_relative_tolerance;
      unsigned int     linear_max_iterations;
      unsigned int     smoother_sweeps;
      double           aggregation_threshold;

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);
    };

    // @sect4{Output}
    struct Output
    {
      bool write_vtu;
      bool write_hdf5;
      // What a run does with the files of an earlier run in its output
      // directory (see output/output_directory.h).
      enum class ExistingOutput
      {
        refuse,
        replace
      };
      ExistingOutput existing_output;
      double         output_interval;
      enum class TipRegionType
      {
        boundary,
        material
      };
      TipRegionType tip_region_type;
      unsigned int  tip_region_id;
      std::string   trajectory_file;
      unsigned int  progress_interval;
      unsigned int  checkpoint_interval;
      bool          spectral_analysis;
      double        spectral_skip;

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);
    };

    // @sect4{All parameters}
    //
    // The sum of the above, read from a file (the usual case) or from a
    // string (tests). The name of the file is kept for error messages
    // about entries that are valid one by one but not together.
    struct AllParameters : public Problem,
                           public Geometry,
                           public FiniteElement,
                           public Materials,
                           public Damping,
                           public Loads,
                           public Pneumatics,
                           public InitialConditions,
                           public TimeIntegration,
                           public NonlinearSolver,
                           public LinearSolver,
                           public Output
    {
      AllParameters() = default;

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);

      // Reads and checks a parameter file; throws with a message that names
      // the file, the entry and the allowed values.
      //
      // The overrides, each 'Subsection/.../Entry=value', replace entries of
      // the file after it is read (the command line's --set).
      void
      read_file(const std::string              &filename,
                const std::vector<std::string> &overrides = {});
      void
      read_string(const std::string &text);

      std::string source_name = "(string)";

      // Every entry of the file, one 'Subsection/Entry = value' per line,
      // except those a restart may change (End time, Checkpoint interval,
      // Progress interval): what a checkpoint records of its parameters,
      // so that a restart with other physics or numerics is refused.
      std::string fingerprint;

      // Not an entry of the file: the checkpoint directory a run continues
      // from (the command line's --restart), empty for a new run.
      std::string restart_directory;

      // "In the parameter file '<name>': ", the start of the messages about
      // the input.
      std::string
      where() const;

    private:
      void
      check_consistency() const;
      void
      check_pneumatics() const;
    };

    // The words of the parameter file for the options that other output
    // (messages, run statistics) repeats.
    std::string
    name_of(const LinearSolver::LinearSolverType type);
    std::string
    name_of(const NonlinearSolver::TangentUpdate update);
    std::string
    name_of(const Output::TipRegionType type);
    std::string
    name_of(const Silicone::ParameterSet parameter_set);
  } // namespace Parameters
} // namespace SoftRobot

#endif
