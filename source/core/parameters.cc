// SPDX-License-Identifier: LGPL-2.1-or-later

#include <core/parameter_file.h>
#include <core/parameters.h>
#include <deal.II/base/exceptions.h>
#include <deal.II/base/numbers.h>
#include <deal.II/base/utilities.h>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

// @sect3{Run-time parameters: declarations and parsing}
//
// Each structure of include/core/parameters.h declares its subsection's
// entries -- with the pattern that checks the allowed values and the
// documentation that parameters/default.prm shows -- and parses them into
// its fields, options into enum values, once.

namespace SoftRobot
{
  namespace Parameters
  {
    // @sect4{Problem}
    void
    Problem::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Problem");
      prm.declare_entry("Dimension",
                        "3",
                        Patterns::Integer(1, 3),
                        "Space dimension of the model: 1 for the column "
                        "(axial motion only), 2 for the planar model, 3 for "
                        "the full body.");
      prm.declare_entry("Output directory",
                        "output",
                        Patterns::Anything(),
                        "Directory for the VTU files, the PVD record and the "
                        "tip trajectory. It is created if it does not exist.");
      // A tip that moves farther than the body is large, or faster than
      // waves run through its softest material, has left every motion a
      // soft robot makes: what the run computes beyond that point is the
      // answer to a load or a time step no experiment has, and it stops
      // (see core/plausibility_guard.h).
      prm.declare_entry("Run-away displacement",
                        "0",
                        Patterns::Double(0),
                        "The run stops (exit code 2, the output so far is "
                        "kept) when the tip displacement exceeds this, mm. "
                        "0: ten times the diagonal of the bounding box of "
                        "the mesh.");
      prm.declare_entry("Run-away speed",
                        "0",
                        Patterns::Double(0),
                        "The run stops (exit code 2, the output so far is "
                        "kept) when the tip speed exceeds this, mm/s. 0: ten "
                        "times the shear wave speed sqrt(mu / rho) of the "
                        "softest material.");
      prm.leave_subsection();
    }

    void
    Problem::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Problem");
      dimension            = prm.get_integer("Dimension");
      output_directory     = prm.get("Output directory");
      runaway_displacement = prm.get_double("Run-away displacement");
      runaway_speed        = prm.get_double("Run-away speed");
      prm.leave_subsection();
    }



    // @sect4{Geometry}
    void
    Geometry::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Geometry");
      prm.declare_entry("Mesh source",
                        "generator",
                        Patterns::Selection("generator|file|bellows"),
                        "Where the mesh comes from: one of deal.II's "
                        "GridGenerator functions, a gmsh file, or the "
                        "hexahedral mesh of the bellows actuator (3D only), "
                        "made from the design in the gmsh geometry that "
                        "Mesh file names (subsection Bellows).");
      prm.declare_entry("Generator",
                        "hyper_cube",
                        Patterns::Anything(),
                        "Name of a GridGenerator function, as accepted by "
                        "GridGenerator::generate_from_name_and_arguments().");
      prm.declare_entry("Generator arguments",
                        "0: 1: true",
                        Patterns::Anything(),
                        "Arguments of that function, separated by colons; "
                        "points and vectors as comma-separated coordinates. "
                        "For subdivided_hyper_rectangle: repetitions: lower "
                        "corner: upper corner: colorize, e.g. "
                        "'4, 1, 1: 0, 0, 0: 4, 1, 1: true' in 3D.");
      prm.declare_entry("Mesh file",
                        "",
                        Patterns::Anything(),
                        "A gmsh .msh file (format 2.2 or 4.1), relative to "
                        "the directory of the parameter file. Physical volume "
                        "tags become material ids, physical surface tags "
                        "boundary ids. A format 2.2 file of second-order "
                        "triangles or tetrahedra (gmsh -order 2) gives "
                        "curved cells: their mid-edge nodes shape the "
                        "geometry, whatever the Polynomial degree. With Mesh "
                        "source = bellows: the gmsh geometry (.geo) whose "
                        "design numbers (lines 'Name = number;') the "
                        "generator reads.");
      prm.declare_entry("Global refinements",
                        "0",
                        Patterns::Integer(0, 10),
                        "Uniform refinements of the mesh after it is made.");
      prm.declare_entry("Convert to simplices",
                        "false",
                        Patterns::Bool(),
                        "Split every quadrilateral or hexahedron of a "
                        "generated mesh into triangles or tetrahedra.");
      prm.declare_entry("Random distortion",
                        "0",
                        Patterns::Double(0, 0.4),
                        "Move interior vertices randomly by up to this "
                        "fraction of the adjacent edge lengths (tests of "
                        "distorted meshes).");
      prm.declare_entry("Material id function",
                        "",
                        Patterns::Anything(),
                        "If not empty: an expression in x, y, z whose value "
                        "at a cell's centre, rounded to an integer, becomes "
                        "the cell's material id, e.g. 'x > 89.25 ? 2 : 1'. "
                        "Empty: keep the ids of a mesh file; a generated "
                        "mesh is then of material 1.");
      prm.declare_entry("Model fraction",
                        "1",
                        Patterns::Double(0, 1),
                        "Fraction of the physical body the mesh represents: "
                        "0.25 for a quarter model with two symmetry planes, "
                        "0.5 for a half model. Only used to convert the "
                        "'Mass' of a material into a density, and by Mesh "
                        "source = bellows for the part of the body it "
                        "meshes (0.25, 0.5 or 1).");
      prm.enter_subsection("Bellows");
      prm.declare_entry("Cells through the wall",
                        "1",
                        Patterns::Integer(1, 16),
                        "Hexahedra across the 3 mm wall (and the rows of "
                        "the base ring, the cap and the block scale with "
                        "it).");
      prm.declare_entry("Cells along a flank",
                        "3",
                        Patterns::Integer(1, 64),
                        "Hexahedra along each straight flank of a "
                        "convolution.");
      prm.declare_entry("Cells per chord",
                        "1",
                        Patterns::Integer(1, 16),
                        "Hexahedra along each chord of the section "
                        "polygon's folds.");
      prm.declare_entry("Cells per quarter turn",
                        "2",
                        Patterns::Integer(2, 64),
                        "Hexahedra per 90 degrees about the axis; an even "
                        "number (the O-grid about the axis has half as "
                        "many along each side of its square core).");
      prm.leave_subsection();
      prm.leave_subsection();
    }

    void
    Geometry::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Geometry");
      const std::string source = prm.get("Mesh source");
      mesh_source              = (source == "file")      ? MeshSource::file
                                 : (source == "bellows") ? MeshSource::bellows
                                                         : MeshSource::generator;
      generator_name           = prm.get("Generator");
      generator_arguments      = prm.get("Generator arguments");
      mesh_file                = prm.get("Mesh file");
      global_refinements       = prm.get_integer("Global refinements");
      convert_to_simplices     = prm.get_bool("Convert to simplices");
      distortion               = prm.get_double("Random distortion");
      material_id_function     = prm.get("Material id function");
      model_fraction           = prm.get_double("Model fraction");
      prm.enter_subsection("Bellows");
      bellows_cells_through_wall = prm.get_integer("Cells through the wall");
      bellows_cells_along_flank  = prm.get_integer("Cells along a flank");
      bellows_cells_per_chord    = prm.get_integer("Cells per chord");
      bellows_cells_per_quarter_turn =
        prm.get_integer("Cells per quarter turn");
      prm.leave_subsection();
      prm.leave_subsection();
    }



    // @sect4{Finite element}
    void
    FiniteElement::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Finite element");
      prm.declare_entry("Polynomial degree",
                        "2",
                        Patterns::Integer(1, 2),
                        "Degree p of the Lagrange elements of the "
                        "displacement (FE_Q on quadrilaterals and "
                        "hexahedra, FE_SimplexP on triangles and "
                        "tetrahedra).");
      prm.declare_entry("Quadrature points",
                        "0",
                        Patterns::Integer(0, 5),
                        "Gauss points per direction of the quadrature of "
                        "the internal forces (for simplices the argument of "
                        "QGaussSimplex). 0 chooses the cheapest exact one "
                        "for a linear problem: p + 1 on hypercubes, p on "
                        "simplices (one point for linear tetrahedra). The "
                        "mass matrix always uses p + 1.");
      prm.declare_entry(
        "Volumetric formulation",
        "displacement",
        Patterns::Selection("displacement|mean dilatation|linear dilatation"),
        "How the volumetric energy U(J) of the 3D material enters. "
        "'displacement': at every quadrature point, the pure displacement "
        "formulation; it locks when the bulk modulus is large against the "
        "shear modulus, most of all with linear tetrahedra. 'mean "
        "dilatation': the three-field formulation with pressure and "
        "dilatation constant in each cell, condensed cell by cell, so that "
        "U acts on the cell's mean volume ratio; with quadratic elements it "
        "does not lock, with linear tetrahedra it is the same as "
        "'displacement'. 'linear dilatation': the same with pressure and "
        "dilatation linear in each cell (discontinuous, step-44's Q2-DGP1), "
        "four constraints per cell instead of one. The reduced 1D and 2D "
        "models are incompressible by construction and allow 'displacement' "
        "only.");
      prm.declare_entry(
        "Direct addresses",
        "true",
        Patterns::Bool(),
        "How the cell matrices and vectors are added into the global ones: "
        "true, at addresses in Trilinos' value arrays computed once (the "
        "fast path, used where all constraints are homogeneous); false, "
        "through AffineConstraints::distribute_local_to_global() (the "
        "reference, slower; tests/system_assembler.cc checks that both give "
        "the same system to round-off).");
      prm.leave_subsection();
    }

    void
    FiniteElement::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Finite element");
      degree                        = prm.get_integer("Polynomial degree");
      quadrature_points             = prm.get_integer("Quadrature points");
      const std::string formulation = prm.get("Volumetric formulation");
      volumetric_formulation        = (formulation == "mean dilatation")
                                        ? VolumetricFormulation::mean_dilatation
                                      : (formulation == "linear dilatation")
                                        ? VolumetricFormulation::linear_dilatation
                                        : VolumetricFormulation::displacement;
      direct_addresses              = prm.get_bool("Direct addresses");
      prm.leave_subsection();
    }



    // @sect4{Materials}
    void
    Materials::declare_parameters(ParameterHandler &prm)
    {
      for (unsigned int id = 0; id <= max_material_id; ++id)
        {
          prm.enter_subsection("Material " + std::to_string(id));
          prm.declare_entry("Name",
                            "",
                            Patterns::Anything(),
                            "Name of the material of the cells with this "
                            "material id. A material with an empty name is "
                            "not defined; a mesh that uses its id is an "
                            "error.");
          prm.declare_entry("Shear modulus",
                            "100",
                            Patterns::Double(1e-12),
                            "Initial shear modulus mu of the neo-Hookean "
                            "energy, kPa (= kg/(mm s^2)).");
          prm.declare_entry("Bulk modulus",
                            "10000",
                            Patterns::Double(1e-12),
                            "Bulk modulus kappa, kPa. Used in 3D only; the "
                            "reduced 1D and 2D models are incompressible.");
          prm.declare_entry("Density",
                            "1.1e-6",
                            Patterns::Double(0),
                            "Mass density in the reference configuration, "
                            "kg/mm^3. Ignored if 'Mass' is positive.");
          prm.declare_entry("Mass",
                            "0",
                            Patterns::Double(0),
                            "If positive: the mass of this material in the "
                            "whole physical body, kg. The density is then "
                            "set so that the meshed region (times its "
                            "section, divided by the model fraction) weighs "
                            "this much.");
          prm.declare_entry("Damping coefficient",
                            "0",
                            Patterns::Double(0, 10),
                            "zeta of the stiffness-proportional Rayleigh "
                            "damping C = zeta K, s. A mode of circular "
                            "frequency omega gets the damping ratio "
                            "xi = zeta omega / 2. Its form is that of "
                            "Damping/Stiffness-proportional damping.");
          prm.declare_entry(
            "Mass damping coefficient",
            "0",
            Patterns::Double(0, 1e4),
            "alpha of the mass-proportional Rayleigh damping force alpha M v, "
            "1/s: a mode of circular frequency omega gets the damping ratio "
            "alpha / (2 omega). It is not objective: it also brakes rigid "
            "translations and rotations of the body (a swinging pendulum "
            "loses its swing to it), which is why it is off by default; it "
            "stands for a drag of the surroundings proportional to the "
            "velocity.");
          prm.declare_entry("Section",
                            "1",
                            Patterns::Double(1e-12),
                            "dim = 1: cross-section area of the column, "
                            "mm^2; dim = 2: out-of-plane thickness, mm; "
                            "dim = 3: must be 1.");
          prm.declare_entry("Silicone",
                            "",
                            Patterns::Anything(),
                            "If not empty: the Name of an entry of the "
                            "Silicone library, which then gives this "
                            "material's shear modulus, bulk modulus and "
                            "damping coefficient (the three entries above "
                            "are ignored).");
          prm.leave_subsection();
        }

      prm.enter_subsection("Silicone library");
      prm.declare_entry("Parameter set",
                        "baseline",
                        Patterns::Selection("baseline|calibrated"),
                        "Which shear modulus the library gives: "
                        "'baseline', the neo-Hookean C1 of the material "
                        "database as the reference study used it, or "
                        "'calibrated', fitted to the experiment-1 "
                        "frequency.");
      for (unsigned int i = 1; i <= max_silicones; ++i)
        {
          prm.enter_subsection("Silicone " + std::to_string(i));
          prm.declare_entry("Name",
                            "",
                            Patterns::Anything(),
                            "Name by which a material refers to this entry; "
                            "empty: the entry is not used.");
          prm.declare_entry("Neo-Hookean C1",
                            "100",
                            Patterns::Double(1e-12),
                            "C1 of the material database's neo-Hookean "
                            "fit, kPa: the baseline shear modulus.");
          prm.declare_entry("Calibrated shear modulus",
                            "0",
                            Patterns::Double(0),
                            "Shear modulus fitted to the experiment-1 "
                            "frequency, kPa (0: not calibrated).");
          prm.declare_entry("Bulk-to-shear ratio",
                            "100",
                            Patterns::Double(1),
                            "kappa / mu in both parameter sets.");
          prm.declare_entry("Experiment-1 frequency",
                            "1",
                            Patterns::Double(1e-6),
                            "Measured frequency of the vertical "
                            "oscillation, Hz.");
          prm.declare_entry("Experiment-1 damping ratio",
                            "0",
                            Patterns::Double(0, 1),
                            "Measured damping ratio of the vertical "
                            "oscillation; zeta = xi / (pi f).");
          prm.leave_subsection();
        }
      prm.leave_subsection();
    }



    double
    Silicone::shear_modulus(const ParameterSet parameter_set) const
    {
      return (parameter_set == ParameterSet::calibrated)
               ? calibrated_shear_modulus
               : c1;
    }

    double
    Silicone::damping_coefficient() const
    {
      return damping_ratio / (numbers::PI * frequency);
    }

    void
    Materials::parse_parameters(ParameterHandler &prm)
    {
      silicones.clear();
      prm.enter_subsection("Silicone library");
      parameter_set = (prm.get("Parameter set") == "calibrated")
                        ? Silicone::ParameterSet::calibrated
                        : Silicone::ParameterSet::baseline;
      for (unsigned int i = 1; i <= max_silicones; ++i)
        {
          prm.enter_subsection("Silicone " + std::to_string(i));
          Silicone silicone;
          silicone.name = prm.get("Name");
          if (!silicone.name.empty())
            {
              silicone.c1 = prm.get_double("Neo-Hookean C1");
              silicone.calibrated_shear_modulus =
                prm.get_double("Calibrated shear modulus");
              silicone.bulk_to_shear_ratio =
                prm.get_double("Bulk-to-shear ratio");
              silicone.frequency = prm.get_double("Experiment-1 frequency");
              silicone.damping_ratio =
                prm.get_double("Experiment-1 damping ratio");
              silicones[silicone.name] = silicone;
            }
          prm.leave_subsection();
        }
      prm.leave_subsection();

      by_id.clear();
      for (unsigned int id = 0; id <= max_material_id; ++id)
        {
          prm.enter_subsection("Material " + std::to_string(id));
          Material material;
          material.name = prm.get("Name");
          if (!material.name.empty())
            {
              material.shear_modulus = prm.get_double("Shear modulus");
              material.bulk_modulus  = prm.get_double("Bulk modulus");
              material.density       = prm.get_double("Density");
              material.mass          = prm.get_double("Mass");
              material.damping_zeta  = prm.get_double("Damping coefficient");
              material.mass_damping =
                prm.get_double("Mass damping coefficient");
              material.section  = prm.get_double("Section");
              material.silicone = prm.get("Silicone");
              if (!material.silicone.empty())
                {
                  const auto  entry = silicones.find(material.silicone);
                  std::string known;
                  for (const auto &[name, silicone] : silicones)
                    known += " '" + name + "'";
                  AssertThrow(entry != silicones.end(),
                              ExcMessage("Material " + std::to_string(id) +
                                         "/Silicone names '" +
                                         material.silicone +
                                         "', which the Silicone library "
                                         "does not have (it has:" +
                                         known + ")."));
                  const Silicone &silicone = entry->second;
                  AssertThrow(silicone.shear_modulus(parameter_set) > 0,
                              ExcMessage("Silicone library: '" + silicone.name +
                                         "' has no Calibrated shear modulus "
                                         "(it is 0), but the Parameter set "
                                         "is 'calibrated'."));
                  material.shear_modulus =
                    silicone.shear_modulus(parameter_set);
                  material.bulk_modulus =
                    silicone.bulk_to_shear_ratio * material.shear_modulus;
                  material.damping_zeta = silicone.damping_coefficient();
                }
              by_id[id] = material;
            }
          prm.leave_subsection();
        }
    }



    // @sect4{Damping}
    void
    Damping::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Damping");
      prm.declare_entry(
        "Stiffness-proportional damping",
        "Kelvin-Voigt",
        Patterns::Selection("Kelvin-Voigt|lagged matrix"),
        "The form of the damping of each material's Damping coefficient "
        "zeta. 'Kelvin-Voigt': a viscous stress zeta C+ : dE/dt driven by the "
        "rate of the Green-Lagrange strain, with C+ the positive part of the "
        "material tangent at the state each time step starts from; it "
        "vanishes for every rigid motion, translations and finite rotations "
        "alike, and for small motions about an equilibrium it is C = zeta K. "
        "'lagged matrix': the damping matrix zeta K+ of the state a step "
        "starts from applied to the velocity at its end; it damps rigid "
        "rotations by an amount that grows with (Omega dt)^2 (a body that "
        "swings or spins loses energy it should keep, and the damping "
        "depends on the time step). Kept to compare with earlier results.");
      prm.declare_entry(
        "Drag boundary ids",
        "",
        Patterns::List(Patterns::Integer(0)),
        "Boundaries on which the surrounding air exerts the quadratic drag "
        "-1/2 rho_air C_d |v.n| (v.n) n per unit deformed area (n the "
        "current outer normal, v the velocity); empty: none.");
      prm.declare_entry("Drag coefficient",
                        "1",
                        Patterns::Double(0, 100),
                        "C_d of the drag on the Drag boundary ids.");
      prm.declare_entry("Air density",
                        "1.2e-9",
                        Patterns::Double(0, 1),
                        "rho_air of the drag, kg/mm^3 (air at 20 C: "
                        "1.2e-9).");
      prm.leave_subsection();
    }

    void
    Damping::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Damping");
      stiffness_damping =
        (prm.get("Stiffness-proportional damping") == "lagged matrix")
          ? StiffnessDamping::lagged_matrix
          : StiffnessDamping::kelvin_voigt;
      drag_boundary_ids.clear();
      for (const int id : Utilities::string_to_int(
             Utilities::split_string_list(prm.get("Drag boundary ids"))))
        drag_boundary_ids.push_back(id);
      drag_coefficient = prm.get_double("Drag coefficient");
      air_density      = prm.get_double("Air density");
      prm.leave_subsection();
    }



    // @sect4{Loads and constraints}
    void
    Loads::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Loads and constraints");
      prm.declare_entry("Gravity",
                        "0, 0, 0",
                        Patterns::List(Patterns::Double(), 3, 3),
                        "Gravitational acceleration, mm/s^2, three "
                        "components of which the first dim are used. The "
                        "actuator's axis is x, pointing down: 9810, 0, 0.");
      prm.declare_entry("Fixed components",
                        "",
                        Patterns::Map(Patterns::Integer(0),
                                      Patterns::Anything()),
                        "Homogeneous Dirichlet conditions: boundary id, "
                        "colon, the fixed displacement components as letters "
                        "from 'xyz'; e.g. '1: xyz, 3: y, 4: z' clamps "
                        "boundary 1 and makes 3 and 4 symmetry planes "
                        "with normals y and z.");
      prm.declare_entry("Traction boundary ids",
                        "",
                        Patterns::List(Patterns::Integer(0)),
                        "Boundary ids on which the traction below acts.");
      prm.declare_entry("Traction",
                        "",
                        Patterns::Anything(),
                        "Nominal traction (force per reference area, kPa) "
                        "as dim expressions of x, y, z, t separated by "
                        "semicolons; it is a dead load. Empty: zero.");
      prm.declare_entry("Function constants",
                        "",
                        Patterns::Anything(),
                        "Constants for all expressions of this file, e.g. "
                        "'F0=1.5, L=10'.");
      prm.leave_subsection();
    }

    void
    Loads::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Loads and constraints");
      gravity = Utilities::string_to_double(
        Utilities::split_string_list(prm.get("Gravity")));
      fixed_components.clear();
      for (const auto &entry :
           Utilities::split_string_list(prm.get("Fixed components"), ','))
        {
          const auto pair = Utilities::split_string_list(entry, ':');
          fixed_components[Utilities::string_to_int(pair[0])] = pair[1];
        }
      traction_boundary_ids.clear();
      for (const int id : Utilities::string_to_int(
             Utilities::split_string_list(prm.get("Traction boundary ids"))))
        traction_boundary_ids.push_back(id);
      traction_expression = prm.get("Traction");
      constants           = prm.get("Function constants");
      prm.leave_subsection();
    }



    // @sect4{Pneumatics}
    void
    Pneumatics::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Pneumatics");
      prm.declare_entry(
        "Pressure boundary ids",
        "",
        Patterns::List(Patterns::Integer(0)),
        "Boundaries on which the pressure acts; empty: none. In 3D the "
        "cavity surface (boundary 2 of the bellows meshes), loaded by the "
        "pressure p on its deformed area (a follower load, -p n da with n "
        "the body's outer normal). In the reduced 1D and 2D models, with an "
        "Equivalent area, the end face that stands for the bellows' end cap; "
        "without one, any boundary, loaded by p on its deformed area.");
      prm.declare_entry(
        "Pressure model",
        "prescribed",
        Patterns::Selection("prescribed|gas"),
        "'prescribed': p is the function of time of Pressure or Pressure "
        "table. 'gas': the cavity holds a gas sealed at t = 0 with the "
        "Initial pressure, p_abs = p_abs0 (rho / rho0)^gamma with the gas "
        "density rho = m(t) / V from the cavity volume V (closed by the "
        "symmetry planes, divided by the Model fraction, plus the Dead "
        "volume) and the gas mass m(t) (Mass inflow rate).");
      prm.declare_entry(
        "Pressure",
        "",
        Patterns::Anything(),
        "Prescribed gauge pressure (above ambient), kPa, an expression of t "
        "(steps, ramps, sinusoids; the Function constants of Loads and "
        "constraints apply), e.g. 't < 0.1 ? 10*t/0.1 : 10'. Negative: a "
        "vacuum. Empty: zero, or the Pressure table.");
      prm.declare_entry(
        "Pressure table",
        "",
        Patterns::Anything(),
        "A CSV file of measured pressures, relative to the directory of the "
        "parameter file: lines 'time, gauge pressure' (s, kPa) with "
        "increasing times; lines starting with '#' and a first line of "
        "column names are skipped. The pressure is interpolated linearly, "
        "and held at the first and last value outside the table. Only one "
        "of Pressure and Pressure table may be given.");
      prm.declare_entry(
        "Equivalent area",
        "0",
        Patterns::Double(0),
        "Reduced 1D and 2D models of the bellows only: the cavity's pressure "
        "acts as the end force p A on the Pressure boundary ids, spread "
        "evenly over them along their reference outer normal, and the cavity "
        "volume changes by A times their mean normal displacement; A in "
        "mm^2, the force-equivalent area of the 3D actuator (the end force "
        "that elongates it as far as the pressure does, per unit pressure; "
        "see doc/pneumatics.md). 0: the "
        "pressure acts on the deformed boundary itself (any dimension).");
      prm.declare_entry("Initial pressure",
                        "0",
                        Patterns::Double(),
                        "Gas model: the gauge pressure of the gas at t = 0, "
                        "kPa, with which the initial static equilibrium is "
                        "computed and the cavity is sealed.");
      prm.declare_entry("Ambient pressure",
                        "101.325",
                        Patterns::Double(1e-6),
                        "Gas model: the absolute pressure of the "
                        "surroundings, kPa; the load is the gauge pressure, "
                        "the absolute one less this.");
      prm.declare_entry("Gas law exponent",
                        "1",
                        Patterns::Double(1, 2),
                        "Gas model: gamma of p_abs V^gamma = const for a "
                        "fixed gas mass; 1 for an isothermal gas (slow "
                        "motions, a cavity that exchanges heat with its "
                        "walls), 1.4 for air compressed adiabatically.");
      prm.declare_entry("Dead volume",
                        "0",
                        Patterns::Double(0),
                        "Gas model: the volume the gas occupies outside the "
                        "meshed cavity (tubing, valves), mm^3, for the "
                        "whole physical body; in the reduced models with "
                        "an Equivalent area, the whole cavity volume at "
                        "zero displacement.");
      prm.declare_entry("Mass inflow rate",
                        "",
                        Patterns::Anything(),
                        "Gas model: the mass of gas flowing into the "
                        "cavity per unit time, kg/s, an expression of t "
                        "(negative: outflow); empty: a closed cavity. "
                        "Integrated in time on a fixed grid of 1e-4 s, "
                        "independent of the time step.");
      prm.declare_entry("Gas temperature",
                        "293.15",
                        Patterns::Double(1),
                        "Gas model: the temperature of the gas at t = 0, K, "
                        "which with the specific gas constant of air (287.05 "
                        "J/(kg K)) gives its initial density and so the "
                        "effect of a Mass inflow rate.");
      prm.declare_entry("Rank-one tangent",
                        "true",
                        Patterns::Bool(),
                        "Gas model: keep the gas's stiffness, the rank-one "
                        "term -(dp/dV) g g^T of the tangent (g = dV/du), in "
                        "the Newton matrix, solved by the Sherman-Morrison "
                        "formula on top of the sparse matrix's "
                        "factorization or multigrid. false leaves it out, "
                        "for comparison: the iterations then converge "
                        "linearly, to the same answer.");
      prm.leave_subsection();
    }

    void
    Pneumatics::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Pneumatics");
      pressure_boundary_ids.clear();
      for (const int id : Utilities::string_to_int(
             Utilities::split_string_list(prm.get("Pressure boundary ids"))))
        pressure_boundary_ids.push_back(id);
      pressure_model       = (prm.get("Pressure model") == "gas")
                               ? PressureModel::gas
                               : PressureModel::prescribed;
      pressure_expression  = prm.get("Pressure");
      pressure_table       = prm.get("Pressure table");
      equivalent_area      = prm.get_double("Equivalent area");
      initial_gas_pressure = prm.get_double("Initial pressure");
      ambient_pressure     = prm.get_double("Ambient pressure");
      gas_exponent         = prm.get_double("Gas law exponent");
      dead_volume          = prm.get_double("Dead volume");
      inflow_expression    = prm.get("Mass inflow rate");
      gas_temperature      = prm.get_double("Gas temperature");
      rank_one_tangent     = prm.get_bool("Rank-one tangent");
      prm.leave_subsection();
    }



    // @sect4{Initial conditions}
    void
    InitialConditions::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Initial conditions");
      prm.declare_entry("Type",
                        "expressions",
                        Patterns::Selection("expressions|static equilibrium"),
                        "'expressions': the initial displacement and "
                        "velocity below. 'static equilibrium': the initial "
                        "displacement is the equilibrium under the loads at "
                        "t = 0 (gravity and tractions, with the expression "
                        "below as the starting guess), and the velocity is "
                        "the expression below.");
      prm.declare_entry("Displacement",
                        "",
                        Patterns::Anything(),
                        "Initial displacement, mm: dim expressions of x, y, "
                        "z separated by semicolons. Empty: zero.");
      prm.declare_entry("Velocity",
                        "",
                        Patterns::Anything(),
                        "Initial velocity, mm/s, likewise.");
      prm.declare_entry(
        "Velocity coordinates",
        "reference",
        Patterns::Selection("reference|initial state"),
        "Where x, y, z of the Velocity expression are taken: 'reference', "
        "the position of each node in the mesh; 'initial state', its "
        "position in the initial state (the mesh plus the initial "
        "displacement, after the static equilibrium if there is one). A "
        "rigid rotation of a deformed body, which neither strains it nor "
        "loads its damping, is written with the latter, e.g. '-w*(z - "
        "z0); 0; w*(x - x0)'.");
      prm.declare_entry("Load steps",
                        "4",
                        Patterns::Integer(1, 1000),
                        "Number of equal increments in which the loads are "
                        "applied for the static equilibrium.");
      prm.declare_entry(
        "Load step tolerance",
        "0.1",
        Patterns::Double(0., 1.),
        "Relative tolerance of Newton's method in the load steps of the "
        "static equilibrium before the last one (times the same force "
        "scale as Nonlinear solver/Relative tolerance, and never below it; "
        "0 converges every step to that tolerance). These steps only lead "
        "to the equilibrium: the last one converges to the Nonlinear "
        "solver's tolerances from wherever they end.");
      prm.declare_entry(
        "Equilibrium tolerance",
        "0",
        Patterns::Double(0., 1.),
        "Relative tolerance of Newton's method in the last load step of the "
        "static equilibrium, the state the motion starts from (times the "
        "same force scale as Nonlinear solver/Relative tolerance, and never "
        "above it; 0: that tolerance). The residual this state keeps is the "
        "initial acceleration times the masses: with the start at 1e-5 the "
        "planar pendulum's first step was cut back, with it at 1e-6 not "
        "(doc/performance_discussion.md, item 41).");
      prm.leave_subsection();
    }

    void
    InitialConditions::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Initial conditions");
      initial_state           = (prm.get("Type") == "static equilibrium")
                                  ? InitialState::static_equilibrium
                                  : InitialState::expressions;
      displacement_expression = prm.get("Displacement");
      velocity_expression     = prm.get("Velocity");
      velocity_coordinates =
        (prm.get("Velocity coordinates") == "initial state")
          ? VelocityCoordinates::initial_state
          : VelocityCoordinates::reference;
      load_steps            = prm.get_integer("Load steps");
      load_step_tolerance   = prm.get_double("Load step tolerance");
      equilibrium_tolerance = prm.get_double("Equilibrium tolerance");
      prm.leave_subsection();
    }



    // @sect4{Time integration}
    void
    TimeIntegration::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Time integration");
      prm.declare_entry("End time",
                        "1",
                        Patterns::Double(0, 1e6),
                        "Duration of the simulation, s.");
      prm.declare_entry("Time step",
                        "0.01",
                        Patterns::Double(1e-12, 1e3),
                        "Nominal time step, s. It is halved when Newton's "
                        "method fails and grows back afterwards.");
      prm.declare_entry("Minimum time step",
                        "1e-6",
                        Patterns::Double(1e-15, 1e3),
                        "The run stops with an error (keeping the output "
                        "written so far) when a step would need to be "
                        "smaller than this, s.");
      prm.declare_entry("Alpha",
                        "-0.25",
                        Patterns::Double(-1. / 3., 0),
                        "HHT parameter alpha in [-1/3, 0]; 0 is the "
                        "trapezoidal rule, more negative values damp high "
                        "frequencies more.");
      prm.declare_entry("Beta",
                        "-1",
                        Patterns::Double(-1, 1),
                        "Newmark beta; a negative value selects the "
                        "standard (1 - alpha)^2 / 4. The reference study "
                        "used 0.4.");
      prm.declare_entry("Gamma",
                        "-1",
                        Patterns::Double(-1, 1.5),
                        "Newmark gamma; a negative value selects the "
                        "standard 1/2 - alpha. The reference study used "
                        "0.75.");
      prm.declare_entry("Max cutbacks",
                        "1000",
                        Patterns::Integer(1, 1000000000),
                        "The run stops with an error (keeping the output "
                        "written so far) after this many time-step cut "
                        "backs in total. A motion that the mesh and the "
                        "step cannot follow otherwise ends in thousands of "
                        "tiny steps that never grow back, which looks like "
                        "a hang.");
      prm.declare_entry("Regrowth steps",
                        "4",
                        Patterns::Integer(1, 1000),
                        "After a cut back, the time step is doubled again "
                        "after this many successful steps (never beyond "
                        "the nominal step).");
      prm.leave_subsection();
    }

    void
    TimeIntegration::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Time integration");
      end_time          = prm.get_double("End time");
      time_step         = prm.get_double("Time step");
      minimum_time_step = prm.get_double("Minimum time step");
      alpha             = prm.get_double("Alpha");
      beta              = prm.get_double("Beta");
      gamma             = prm.get_double("Gamma");
      regrowth_steps    = prm.get_integer("Regrowth steps");
      max_cutbacks      = prm.get_integer("Max cutbacks");
      prm.leave_subsection();
    }



    // @sect4{Newton's method}
    void
    NonlinearSolver::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Nonlinear solver");
      prm.declare_entry("Max iterations",
                        "12",
                        Patterns::Integer(1, 200),
                        "Newton iterations per step before the step is "
                        "declared failed and cut back.");
      prm.declare_entry("Absolute tolerance",
                        "1e-8",
                        Patterns::Double(0),
                        "Converged when the l2 norm of the residual (mN) "
                        "is below this ...");
      prm.declare_entry("Relative tolerance",
                        "1e-9",
                        Patterns::Double(0, 1),
                        "... or below this fraction of a force scale: the "
                        "largest of the norms of the external forces, the "
                        "internal and inertial forces, and the step's first "
                        "residual.");
      prm.declare_entry(
        "Tangent update",
        "every step",
        Patterns::Selection("every step|every iteration|when needed"),
        "When the time steps' Newton method rebuilds its matrix. 'every "
        "iteration': Newton's method proper, a new tangent and a new "
        "factorization (or multigrid hierarchy) in every iteration. 'every "
        "step': the tangent of the last converged state, built and "
        "factorized once per step, for all iterations of the step (modified "
        "Newton); it is rebuilt at the current iterate when an iteration "
        "reduces the residual too little (see Rebuild threshold). 'when "
        "needed': as 'every step', but the matrix and its factorization are kept "
        "from step to step as long as the iterations converge with them; "
        "it is rebuilt at the current iterate by the same rule, and after a "
        "failed step or a change of the step size. All three converge to "
        "the same tolerance; 'every step' is several times cheaper than "
        "'every iteration' for smooth motions, and 'when needed' saves the "
        "matrices and factorizations of the steps that converge with the "
        "old one. The static equilibrium always uses 'every iteration'.");
      prm.declare_entry(
        "Rebuild threshold",
        "0.5",
        Patterns::Double(0.01, 1),
        "With 'Tangent update = every step' or 'when needed': the matrix is "
        "rebuilt at the current iterate when an iteration with the old one "
        "leaves more than this fraction of the residual (0.5: when it "
        "reduces the residual by less than a factor of two). A rebuild "
        "costs an assembly of the tangent and a factorization, often as "
        "much as several iterations with the old matrix; where the old "
        "matrix still converges steadily, a larger value trades rebuilds "
        "for iterations. The converged answer is the same to the "
        "tolerance.");
      prm.declare_entry(
        "Acceleration depth",
        "2",
        Patterns::Integer(0, 10),
        "With 'Tangent update = every step' or 'when needed': the number of previous "
        "iterations whose iterates and updates Anderson acceleration "
        "combines into the next step (zero turns it off). The accelerated "
        "step is taken only if it lowers the residual; the converged answer "
        "is the same to the tolerance, reached in fewer iterations.");
      prm.declare_entry(
        "Tangent extrapolation",
        "true",
        Patterns::Bool(),
        "With 'Tangent update = every step': build the step's matrix from "
        "the stiffness extrapolated linearly in time from the last two "
        "converged states, K_n + (K_n - K_n-1) dt_n+1/dt_n, instead of K_n "
        "alone. It is closer to the stiffness at the end of the step, and "
        "the iterations converge faster; the converged answer is the same "
        "to the tolerance.");
      prm.declare_entry(
        "Rotated tangent",
        "false",
        Patterns::Bool(),
        "With 'Tangent update = every step' or 'when needed' (serial runs, "
        "dim > 1): solve with the old matrix rotated with the body, node by "
        "node, by the rotation from the state the matrix was built at to "
        "the current iterate (see include/solvers/rotated_tangent.h). A "
        "nearly incompressible body that turns converges with the old "
        "matrix for longer; the converged answer is the same to the "
        "tolerance.");
      prm.declare_entry("Line search",
                        "true",
                        Patterns::Bool(),
                        "Backtrack along the Newton direction until the "
                        "residual decreases.");
      prm.declare_entry("Max line search steps",
                        "5",
                        Patterns::Integer(0, 30),
                        "Halvings of the Newton step before the step fails.");
      prm.declare_entry("Verbose",
                        "false",
                        Patterns::Bool(),
                        "Print the residual, the linear iterations and the "
                        "step length of every Newton iteration.");
      prm.leave_subsection();
    }

    void
    NonlinearSolver::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Nonlinear solver");
      newton_max_iterations     = prm.get_integer("Max iterations");
      newton_absolute_tolerance = prm.get_double("Absolute tolerance");
      newton_relative_tolerance = prm.get_double("Relative tolerance");
      // The entry is one of the names of name_of() (the pattern checks it).
      const std::string update = prm.get("Tangent update");
      tangent_update           = TangentUpdate::every_step;
      for (const TangentUpdate value : {TangentUpdate::every_step,
                                        TangentUpdate::every_iteration,
                                        TangentUpdate::when_needed})
        if (update == name_of(value))
          tangent_update = value;
      rebuild_threshold     = prm.get_double("Rebuild threshold");
      acceleration_depth    = prm.get_integer("Acceleration depth");
      tangent_extrapolation = prm.get_bool("Tangent extrapolation");
      rotated_tangent       = prm.get_bool("Rotated tangent");
      line_search           = prm.get_bool("Line search");
      max_line_search_steps = prm.get_integer("Max line search steps");
      verbose               = prm.get_bool("Verbose");
      prm.leave_subsection();
    }



    // @sect4{Linear solver}
    void
    LinearSolver::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Linear solver");
      prm.declare_entry("Solver",
                        "CG",
                        Patterns::Selection("CG|GMRES|Direct"),
                        "CG or GMRES preconditioned by algebraic multigrid "
                        "(Trilinos ML), or a sparse direct solver (Amesos, "
                        "see Direct solver) for small problems.");
      prm.declare_entry("Direct solver",
                        "automatic",
                        Patterns::Selection("automatic|KLU|MUMPS"),
                        "The sparse direct solver of `Solver = Direct`, "
                        "through Trilinos Amesos: KLU (left-looking, the "
                        "faster one on the bellows meshes below some 10,000 "
                        "unknowns) or MUMPS (multifrontal, on an optimized "
                        "BLAS such as OpenBLAS up to twice as fast as KLU "
                        "from there on, with less memory). 'automatic' "
                        "takes KLU below 10,000 unknowns and MUMPS from "
                        "there on. Both give the same answer to round-off.");
      prm.declare_entry(
        "Symmetric factorization",
        "false",
        Patterns::Bool(),
        "Where MUMPS is the direct solver and the run has one process: "
        "factorize the matrix as L D L^T from its lower triangle (MUMPS "
        "called directly, not through Amesos): about half the arithmetic "
        "of the general factorization, a fifth to a third less time on "
        "the bellows meshes. The tangent is then assembled "
        "symmetric: the non-symmetric parts of the damping's tangent are "
        "left out, as for CG. The answer is the same to the Newton "
        "tolerance; the iterations may be more.");
      prm.declare_entry(
        "Factorization precision",
        "double",
        Patterns::Selection("double|single"),
        "The arithmetic of the symmetric factorization's factor (with "
        "'Symmetric factorization'; ignored otherwise). 'single' keeps "
        "the factor in single precision: half the factor's bytes, and "
        "faster factorizations and back substitutions (measured in "
        "doc/performance_discussion.md, item 47). A back substitution then solves to single "
        "precision only; the Newton iterations on the double-precision "
        "residual correct that as they correct an old matrix, so the "
        "answer is the same to the Newton tolerance. The time steps only: "
        "the static equilibrium, whose tangent lacks their mass term, is "
        "factorized in double precision.");
      // The linear solves are the inner iteration of Newton's method, whose
      // own test on the true residual decides when a step has converged: a
      // linear solve only has to give a direction that is good enough.
      // Newton's method with linear solves to a relative residual eta (an
      // "inexact Newton method", Dembo, Eisenstat and Steihaug, SIAM J.
      // Numer. Anal. 19, 1982) converges as long as eta < 1, with eta added
      // to the rate at which the residual falls; the modified Newton
      // iterations of the time steps reduce it by a factor of 5 to 10 per
      // iteration anyway. On the quarter model's meshes, eta = 1e-2 takes
      // 3 to 8 percent more Newton iterations than 1e-8 and about a quarter
      // of the CG iterations, with the same motion to ten digits; with 1e-1
      // the Newton iterations rise by half.
      prm.declare_entry("Relative tolerance",
                        "1e-2",
                        Patterns::Double(1e-16, 0.5),
                        "Iterative solvers stop when the residual has "
                        "dropped by this factor. It is the forcing term of "
                        "an inexact Newton method: Newton's own test on "
                        "the residual decides the accuracy of the answer, "
                        "and a solve only has to give a good direction. "
                        "Smaller values cost more CG iterations per Newton "
                        "iteration without changing the converged states.");
      prm.declare_entry("Max iterations",
                        "1000",
                        Patterns::Integer(1),
                        "Iterative solvers fail (and the step is cut back) "
                        "after this many iterations.");
      prm.declare_entry("AMG smoother sweeps",
                        "2",
                        Patterns::Integer(1, 10),
                        "Chebyshev smoother sweeps on each AMG level.");
      prm.declare_entry("AMG aggregation threshold",
                        "1e-4",
                        Patterns::Double(0, 1),
                        "Drop tolerance of ML's aggregation.");
      prm.leave_subsection();
    }

    void
    LinearSolver::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Linear solver");
      const std::string solver = prm.get("Solver");
      linear_solver            = (solver == "Direct") ? LinearSolverType::direct
                                 : (solver == "GMRES") ? LinearSolverType::gmres
                                                       : LinearSolverType::cg;
      symmetric_factorization  = prm.get_bool("Symmetric factorization");
      single_precision_factor =
        (prm.get("Factorization precision") == "single");
      direct_solver =
        (prm.get("Direct solver") == "MUMPS") ? DirectSolverType::mumps
        : (prm.get("Direct solver") == "KLU") ? DirectSolverType::klu
                                              : DirectSolverType::automatic;
      linear_relative_tolerance = prm.get_double("Relative tolerance");
      linear_max_iterations     = prm.get_integer("Max iterations");
      smoother_sweeps           = prm.get_integer("AMG smoother sweeps");
      aggregation_threshold     = prm.get_double("AMG aggregation threshold");
      prm.leave_subsection();
    }



    // @sect4{Output}
    void
    Output::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Output");
      prm.declare_entry("Write VTU",
                        "true",
                        Patterns::Bool(),
                        "Write the fields for ParaView (VTU files and a PVD "
                        "record with the physical times).");
      prm.declare_entry("Write HDF5",
                        "false",
                        Patterns::Bool(),
                        "Write the fields as HDF5 files, one per output "
                        "time for all MPI processes together, with the mesh "
                        "in a file of its own written once, and an XDMF "
                        "record (solution.xdmf) that ParaView and VisIt "
                        "open. Can be combined with Write VTU.");
      prm.declare_entry("Existing output",
                        "refuse",
                        Patterns::Selection("refuse|replace"),
                        "What a run does when its output directory holds "
                        "the output of an earlier run (a trajectory, field "
                        "output, statistics, spectra or checkpoints). "
                        "'refuse': stop before anything is written, with a "
                        "message (exit code 1). 'replace': remove the "
                        "earlier run's field output, statistics, spectra and "
                        "checkpoints, and write the trajectory anew. Other "
                        "files are never touched.");
      prm.declare_entry("Output interval",
                        "0.05",
                        Patterns::Double(0),
                        "Time between two VTU outputs, s; 0 writes every "
                        "step.");
      prm.declare_entry("Tip region",
                        "boundary 5",
                        Patterns::Anything(),
                        "Where the tip trajectory is measured: 'boundary "
                        "<id>' (mean displacement and velocity of that "
                        "surface) or 'material <id>' (centre of mass of "
                        "that region).");
      prm.declare_entry("Trajectory file",
                        "tip_trajectory.csv",
                        Patterns::Anything(),
                        "CSV file in the output directory with one row per "
                        "time step: time, time step, tip displacement and "
                        "velocity, energies, Newton iterations.");
      prm.declare_entry(
        "Spectral analysis",
        "false",
        Patterns::Bool(),
        "At the end of the run, analyse the tip trajectory "
        "as tip-spectrum does (peak frequency, half-power "
        "damping ratio, damped-mode fit, logarithmic "
        "decrement, per direction), print a summary and "
        "write tip_spectrum.csv and tip_spectrum_magnitudes.csv "
        "to the output directory.");
      prm.declare_entry(
        "Spectral analysis skip",
        "1",
        Patterns::Double(0),
        "Seconds at the start of the trajectory that the spectral analysis "
        "leaves out, as tip-spectrum --skip does: the start-up transient of a "
        "release, in which the damping takes the energy that the release put "
        "into stiff modes (in the bellows scenes most of it in the first 0.3 s, "
        "see doc/damping.md). Records too short for it are not analysed.");
      prm.declare_entry("Progress interval",
                        "10",
                        Patterns::Integer(0),
                        "Print a progress line every this many steps (0: "
                        "never).");
      prm.declare_entry("Checkpoint interval",
                        "0",
                        Patterns::Integer(0),
                        "Write a checkpoint every this many steps (0: only "
                        "when the run is interrupted by SIGINT or SIGTERM) "
                        "into the directory 'checkpoint' of the output "
                        "directory; soft-robot --restart continues the run "
                        "from it (see output/checkpoint.h).");
      prm.leave_subsection();
    }

    void
    Output::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Output");
      write_vtu           = prm.get_bool("Write VTU");
      write_hdf5          = prm.get_bool("Write HDF5");
      existing_output     = (prm.get("Existing output") == "replace")
                              ? ExistingOutput::replace
                              : ExistingOutput::refuse;
      output_interval     = prm.get_double("Output interval");
      trajectory_file     = prm.get("Trajectory file");
      progress_interval   = prm.get_integer("Progress interval");
      checkpoint_interval = prm.get_integer("Checkpoint interval");
      spectral_analysis   = prm.get_bool("Spectral analysis");
      spectral_skip       = prm.get_double("Spectral analysis skip");
      const auto words =
        Utilities::split_string_list(prm.get("Tip region"), ' ');
      AssertThrow(words.size() == 2 &&
                    (words[0] == "boundary" || words[0] == "material"),
                  ExcMessage("Output/Tip region must be 'boundary <id>' or "
                             "'material <id>', not '" +
                             prm.get("Tip region") + "'."));
      tip_region_type = (words[0] == "boundary") ? TipRegionType::boundary
                                                 : TipRegionType::material;
      const int id    = Utilities::string_to_int(words[1]);
      AssertThrow(id >= 0 && id < 256,
                  ExcMessage("Output/Tip region: the id in '" +
                             prm.get("Tip region") + "' must be in [0, 255]."));
      tip_region_id = id;
      prm.leave_subsection();
    }



    // @sect4{AllParameters}
    void
    AllParameters::declare_parameters(ParameterHandler &prm)
    {
      Problem::declare_parameters(prm);
      Geometry::declare_parameters(prm);
      FiniteElement::declare_parameters(prm);
      Materials::declare_parameters(prm);
      Damping::declare_parameters(prm);
      Loads::declare_parameters(prm);
      Pneumatics::declare_parameters(prm);
      InitialConditions::declare_parameters(prm);
      TimeIntegration::declare_parameters(prm);
      NonlinearSolver::declare_parameters(prm);
      LinearSolver::declare_parameters(prm);
      Output::declare_parameters(prm);
    }

    void
    AllParameters::parse_parameters(ParameterHandler &prm)
    {
      Problem::parse_parameters(prm);
      Geometry::parse_parameters(prm);
      FiniteElement::parse_parameters(prm);
      Materials::parse_parameters(prm);
      Damping::parse_parameters(prm);
      Loads::parse_parameters(prm);
      Pneumatics::parse_parameters(prm);
      InitialConditions::parse_parameters(prm);
      TimeIntegration::parse_parameters(prm);
      NonlinearSolver::parse_parameters(prm);
      LinearSolver::parse_parameters(prm);
      Output::parse_parameters(prm);
    }



    // An override 'Subsection/.../Entry=value' from the command line. The
    // value is checked against the entry's pattern as if it stood in the
    // file; a mistake names the override and the file.
    namespace
    {
      void
      apply_override(ParameterHandler  &prm,
                     const std::string &assignment,
                     const std::string &filename)
      {
        const std::string where =
          "In the override --set '" + assignment + "' of '" + filename + "': ";
        const auto equals = assignment.find('=');
        AssertThrow(equals != std::string::npos && equals > 0,
                    ExcMessage(where + "expected 'Subsection/Entry=value'."));
        const std::vector<std::string> path =
          Utilities::split_string_list(assignment.substr(0, equals), '/');
        const std::string value =
          Utilities::trim(assignment.substr(equals + 1));
        for (unsigned int i = 0; i + 1 < path.size(); ++i)
          prm.enter_subsection(path[i]);
        try
          {
            prm.set(path.back(), value);
          }
        catch (ExceptionBase &error)
          {
            std::ostringstream reason;
            error.print_info(reason);
            for (unsigned int i = 0; i + 1 < path.size(); ++i)
              prm.leave_subsection();
            AssertThrow(false, ExcMessage(where + one_line(reason.str())));
          }
        for (unsigned int i = 0; i + 1 < path.size(); ++i)
          prm.leave_subsection();
      }
    } // namespace



    // The fingerprint of the parameters (AllParameters::fingerprint): the
    // short listing of ParameterHandler, one line per entry with its path.
    namespace
    {
      std::string
      fingerprint_of(const ParameterHandler &prm)
      {
        std::ostringstream listing;
        prm.print_parameters(listing, ParameterHandler::ShortPRM);
        std::istringstream       lines(listing.str());
        std::vector<std::string> path;
        std::string              line, result;
        while (std::getline(lines, line))
          {
            line = Utilities::trim(line);
            if (line.rfind("subsection ", 0) == 0)
              path.push_back(Utilities::trim(line.substr(11)));
            else if (line == "end" && !path.empty())
              path.pop_back();
            else if (line.rfind("set ", 0) == 0)
              {
                const auto  equals = line.find('=');
                std::string entry;
                for (const std::string &subsection : path)
                  entry += subsection + "/";
                entry += Utilities::trim(line.substr(4, equals - 4));
                if (entry != "Time integration/End time" &&
                    entry != "Output/Checkpoint interval" &&
                    entry != "Output/Progress interval")
                  result += entry + " = " +
                            Utilities::trim(line.substr(equals + 1)) + "\n";
              }
          }
        return result;
      }
    } // namespace



    // The file is read by ParameterFileText, which expands its includes
    // (relative to the file that holds them) and turns ParameterHandler's
    // messages into one line that names the file, line, subsection, entry,
    // value and pattern. We add the file name to the messages about
    // combinations of entries that ParameterHandler cannot check.
    void
    AllParameters::read_file(const std::string              &filename,
                             const std::vector<std::string> &overrides)
    {
      const ParameterFileText file(filename);
      source_name = filename;

      ParameterHandler prm;
      declare_parameters(prm);
      try
        {
          std::istringstream text(file.text());
          prm.parse_input(text, filename);
        }
      catch (ExceptionBase &error)
        {
          std::ostringstream reason;
          error.print_info(reason);
          AssertThrow(false, ExcMessage(file.locate(reason.str())));
        }
      for (const std::string &assignment : overrides)
        apply_override(prm, assignment, filename);
      try
        {
          parse_parameters(prm);
        }
      catch (ExceptionBase &error)
        {
          std::ostringstream reason;
          error.print_info(reason);
          const std::string message = one_line(reason.str());
          AssertThrow(false,
                      ExcMessage(message.rfind("In ", 0) == 0
                                   ? message
                                   : where() + message));
        }
      // File names in the parameter file (the mesh) are relative to the
      // directory of the parameter file, so that a scene runs from
      // anywhere.
      const std::filesystem::path directory =
        std::filesystem::path(filename).parent_path();
      if (!mesh_file.empty() && std::filesystem::path(mesh_file).is_relative())
        mesh_file = (directory / mesh_file).string();
      if (!pressure_table.empty() &&
          std::filesystem::path(pressure_table).is_relative())
        pressure_table = (directory / pressure_table).string();
      fingerprint = fingerprint_of(prm);
      check_consistency();
    }

    void
    AllParameters::read_string(const std::string &text)
    {
      ParameterHandler prm;
      declare_parameters(prm);
      prm.parse_input_from_string(text);
      parse_parameters(prm);
      fingerprint = fingerprint_of(prm);
      check_consistency();
    }



    std::string
    AllParameters::where() const
    {
      return "In the parameter file '" + source_name + "': ";
    }



    void
    AllParameters::check_consistency() const
    {
      const std::string where = this->where();
      AssertThrow(model_fraction > 0,
                  ExcMessage(where + "Geometry/Model fraction = 0 is not "
                                     "allowed: it must be in (0, 1], the "
                                     "fraction of the body the mesh "
                                     "represents (1 for the whole body)."));
      AssertThrow(!write_hdf5 || dimension > 1,
                  ExcMessage(where + "Output/Write HDF5 = true is not "
                                     "available in 1D (deal.II's HDF5 writer "
                                     "needs 2 or 3 space dimensions); use "
                                     "Write VTU."));
      AssertThrow(!output_directory.empty(),
                  ExcMessage(where + "Problem/Output directory is empty; "
                                     "name a directory, e.g. 'output'."));
      AssertThrow(time_step >= minimum_time_step,
                  ExcMessage(where + "Time integration/Time step (" +
                             std::to_string(time_step) +
                             ") must not be smaller than Minimum time step (" +
                             std::to_string(minimum_time_step) + ")."));
      AssertThrow((beta < 0) == (gamma < 0),
                  ExcMessage(where +
                             "Time integration/Beta and Gamma must "
                             "be given both (values in (0, 1] and [0, 1.5]) "
                             "or neither (negative values)."));
      AssertThrow(!by_id.empty(),
                  ExcMessage(where +
                             "no material is defined: give at least "
                             "one subsection 'Material <id>' (id 0 to " +
                             std::to_string(max_material_id) +
                             ") with a non-empty Name."));
      for (const auto &[id, material] : by_id)
        AssertThrow(dimension != 3 || material.section == 1.,
                    ExcMessage(where + "Material " + std::to_string(id) +
                               "/Section must be 1 in 3D (it is the area or "
                               "thickness of the reduced 1D and 2D models)."));
      AssertThrow(dimension == 3 || volumetric_formulation ==
                                      VolumetricFormulation::displacement,
                  ExcMessage(where +
                             "Finite element/Volumetric formulation must be "
                             "'displacement' in " +
                             std::to_string(dimension) +
                             "D ('mean dilatation' and 'linear dilatation' "
                             "are for the compressible 3D material only)."));
      for (const auto &[id, letters] : fixed_components)
        {
          AssertThrow(!letters.empty() &&
                        letters.find_first_not_of(
                          std::string("xyz").substr(0, dimension)) ==
                          std::string::npos,
                      ExcMessage(where +
                                 "Loads and constraints/Fixed "
                                 "components: boundary " +
                                 std::to_string(id) + " has '" + letters +
                                 "', but only the letters '" +
                                 std::string("xyz").substr(0, dimension) +
                                 "' are allowed in " +
                                 std::to_string(dimension) + "D."));
        }
      check_pneumatics();
      AssertThrow(mesh_source == MeshSource::generator || !mesh_file.empty(),
                  ExcMessage(where + "Geometry/Mesh file must name a gmsh "
                                     "file when Mesh source = file or "
                                     "bellows."));
      AssertThrow(mesh_source == MeshSource::generator ||
                    std::ifstream(mesh_file),
                  ExcMessage(where + "Geometry/Mesh file: cannot open '" +
                             mesh_file + "'."));
      if (mesh_source == MeshSource::bellows)
        {
          AssertThrow(dimension == 3,
                      ExcMessage(where +
                                 "Geometry/Mesh source = bellows "
                                 "makes a 3D mesh; Problem/Dimension "
                                 "is " +
                                 std::to_string(dimension) + "."));
          AssertThrow(model_fraction == 0.25 || model_fraction == 0.5 ||
                        model_fraction == 1.,
                      ExcMessage(where + "Geometry/Model fraction = " +
                                 std::to_string(model_fraction) +
                                 ": with Mesh source = bellows it must be "
                                 "0.25 (quarter), 0.5 (half) or 1 (full "
                                 "body)."));
          AssertThrow(bellows_cells_per_quarter_turn % 2 == 0,
                      ExcMessage(
                        where +
                        "Geometry/Bellows/Cells per quarter "
                        "turn = " +
                        std::to_string(bellows_cells_per_quarter_turn) +
                        ": it must be even (2 to 64)."));
        }
    }



    // The entries of Pneumatics that are valid one by one but not together.
    void
    AllParameters::check_pneumatics() const
    {
      const std::string where = this->where() + "Pneumatics/";
      const bool        gas   = (pressure_model == PressureModel::gas);
      AssertThrow(pressure_expression.empty() || pressure_table.empty(),
                  ExcMessage(where + "Pressure = '" + pressure_expression +
                             "' and Pressure table = '" + pressure_table +
                             "' are both given; give one of them."));
      AssertThrow(!gas ||
                    (pressure_expression.empty() && pressure_table.empty()),
                  ExcMessage(where + "Pressure model = gas takes its "
                                     "pressure from the gas law: Pressure "
                                     "and Pressure table must be empty "
                                     "(the gas starts at Initial "
                                     "pressure)."));
      AssertThrow(!gas || has_pressure(),
                  ExcMessage(where + "Pressure model = gas needs the "
                                     "cavity surface in Pressure boundary "
                                     "ids."));
      AssertThrow(gas || inflow_expression.empty(),
                  ExcMessage(where + "Mass inflow rate = '" +
                             inflow_expression +
                             "' is given, but the Pressure model is "
                             "'prescribed': a gas flows only into a cavity "
                             "of the 'gas' model."));
      AssertThrow(dimension < 3 || equivalent_area == 0.,
                  ExcMessage(where + "Equivalent area = " +
                             std::to_string(equivalent_area) +
                             " is for the reduced 1D and 2D models; in 3D "
                             "the pressure acts on the cavity surface "
                             "itself (set it to 0)."));
      AssertThrow(!gas || dimension == 3 || equivalent_area > 0.,
                  ExcMessage(where + "Pressure model = gas in " +
                             std::to_string(dimension) +
                             "D needs an Equivalent area: the reduced "
                             "models have no cavity whose volume the gas "
                             "could fill."));
      AssertThrow(!gas || ambient_pressure + initial_gas_pressure > 0.,
                  ExcMessage(
                    where + "Initial pressure = " +
                    std::to_string(initial_gas_pressure) +
                    " kPa is an absolute pressure of " +
                    std::to_string(ambient_pressure + initial_gas_pressure) +
                    " kPa with the Ambient pressure: it must be "
                    "positive (a gauge pressure above -" +
                    std::to_string(ambient_pressure) + " kPa)."));
      AssertThrow(pressure_table.empty() || std::ifstream(pressure_table),
                  ExcMessage(where + "Pressure table: cannot open '" +
                             pressure_table + "'."));
    }



    std::string
    name_of(const LinearSolver::LinearSolverType type)
    {
      switch (type)
        {
          case LinearSolver::LinearSolverType::cg:
            return "CG";
          case LinearSolver::LinearSolverType::gmres:
            return "GMRES";
          case LinearSolver::LinearSolverType::direct:
            return "Direct";
        }
      Assert(false, ExcInternalError());
      return "";
    }

    std::string
    name_of(const NonlinearSolver::TangentUpdate update)
    {
      switch (update)
        {
          case NonlinearSolver::TangentUpdate::every_step:
            return "every step";
          case NonlinearSolver::TangentUpdate::when_needed:
            return "when needed";
          default:
            return "every iteration";
        }
    }

    std::string
    name_of(const Output::TipRegionType type)
    {
      return (type == Output::TipRegionType::boundary) ? "boundary"
                                                       : "material";
    }

    std::string
    name_of(const Silicone::ParameterSet parameter_set)
    {
      return (parameter_set == Silicone::ParameterSet::calibrated)
               ? "calibrated"
               : "baseline";
    }
  } // namespace Parameters
} // namespace SoftRobot
