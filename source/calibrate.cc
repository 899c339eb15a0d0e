// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Calibration commands}
//
// Three commands that produce the numbers of the bellows models which are
// not measured directly, so that every such number in a scene file or in
// the validation's discussion can be reproduced:
//
// <code>calibrate reduced-models</code> computes the geometry of the
// reduced models from static solves of the 3D actuator. The 1D column is
// given the cross-section area, and the 2D strip the width and thickness,
// with which their axial stiffness (and, in 2D, the lateral stiffness of
// the tip) equal those of the 3D body. The stiffnesses are tangent
// stiffnesses at the hanging equilibrium under gravity, the state about
// which the tip oscillates: the response to small tip loads added to the
// weight. Because the bellows (a structure of bending walls) and the
// neo-Hookean bar or strip stiffen differently under the weight, the
// reduced geometry depends on the silicone and the parameter set; each
// reduced scene holds its own. Nothing is fitted to a measured frequency.
// The 3D scenes' discretisation can be changed with `--set` options (for
// both), so that the reduced models can follow the converged 3D model.
//
// <code>calibrate shear-modulus</code> finds the shear modulus with which
// the experiment-1 scene (vertical oscillation) rings at the measured
// frequency of its silicone. The frequency is computed as the study
// computed the measured one: the peak of the Fourier transform of the
// tip's vertical displacement, over the record after the scene's
// `Spectral analysis skip`. The damping coefficient is not fitted:
// zeta = 2 xi / omega with the measured xi and omega (see
// parameters/silicones.prm).
//
// <code>calibrate dead-volume</code> is the alternative for a scene whose
// cavity holds a sealed gas (`Pneumatics/Pressure model = gas`): with the
// shear modulus of the scene unchanged, it finds the volume of gas outside
// the actuator (tubing, valves, a reservoir) with which the scene rings at
// the measured frequency. A smaller volume makes the gas a stiffer spring
// on the end cap. It is the second calibrated model of the validation's
// model-form study (doc/validation_discussion.md): a modulus from the
// material's data and the air in the inlet instead of a fitted modulus.

#include <algorithm>
#include <analysis/spectral_analysis.h>
#include <cmath>
#include <core/mpi_session.h>
#include <core/parameters.h>
#include <core/simulator_access.h>
#include <core/soft_robot_dynamics.h>
#include <deal.II/base/mpi.h>
#include <deal.II/fe/fe_values.h>
#include <filesystem>
#include <functional>
#include <iomanip>
#include <iostream>
#include <solvers/blas_kernels.h>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

namespace
{
  using namespace SoftRobot;
  using namespace dealii;

  // The total force of the small tip loads, mN (kg mm/s^2). At the hanging
  // equilibrium 10 mN, 0.5 % of the weight of actuator and block: it moves
  // the tip by at most about a millimetre (laterally, Ecoflex), small
  // against the motion and far above the solver's tolerance. The unloaded
  // body is much softer laterally (it lacks the pendulum stiffness of its
  // weight), and its stiffness is proportional to the shear modulus: there
  // the load is 1e-3 mN per kPa of shear modulus, which moves the tip by
  // about 0.1 mm laterally for every silicone. The load is applied with
  // both signs and the stiffness taken from the difference, which removes
  // the quadratic part of the response.
  double
  probe_force(const Parameters::AllParameters &parameters)
  {
    const bool unloaded = parameters.gravity[0] == 0. &&
                          parameters.gravity[1] == 0. &&
                          parameters.gravity[2] == 0.;
    return unloaded ? 1e-3 * parameters.by_id.at(1).shear_modulus : 10.;
  }

  // The root of value(x) = target for a positive x and a value that grows
  // with x like a power: a secant iteration on the logarithms, started from
  // x0 with the exponent `slope`, to a relative tolerance. The exponent of
  // each secant is kept in [min_slope, max_slope] so that a noisy value
  // cannot throw the iteration far off.
  double
  solve_power_law(const std::function<double(const double)> &value,
                  const double                               target,
                  double                                     x,
                  double                                     slope,
                  const double                               min_slope,
                  const double                               max_slope,
                  const double                               tolerance)
  {
    double y = value(x);
    for (unsigned int iteration = 0;
         iteration < 20 && std::abs(y / target - 1.) > tolerance;
         ++iteration)
      {
        const double next_x = x * std::exp(std::log(target / y) / slope);
        const double next_y = value(next_x);
        if (std::abs(next_y - y) > 1e-12 * std::abs(y))
          slope = std::clamp(std::log(next_y / y) / std::log(next_x / x),
                             min_slope,
                             max_slope);
        x = next_x;
        y = next_y;
      }
    AssertThrow(std::abs(y / target - 1.) <= tolerance,
                ExcMessage("The calibration did not converge: reached " +
                           std::to_string(y) + " for the target " +
                           std::to_string(target) + "."));
    return x;
  }



  // A scene at its hanging equilibrium with a tip load added to gravity:
  // the traction expression replaces the scene's loads; on the bottom face
  // of the tip block (x = 99.25, boundary 5) in 3D, on the tip's end
  // (boundary 1) in the reduced models. The static solve applies gravity
  // first, then the tip load.
  Parameters::AllParameters
  tip_load_problem(Parameters::AllParameters parameters,
                   const std::string        &traction)
  {
    parameters.constants             = "";
    parameters.traction_expression   = traction;
    parameters.traction_boundary_ids = {parameters.dimension == 3 ? 5u : 1u};
    parameters.initial_state =
      Parameters::InitialConditions::InitialState::static_equilibrium;
    parameters.load_steps              = 1;
    parameters.displacement_expression = "";
    parameters.velocity_expression     = "";
    parameters.tip_region_type   = Parameters::Output::TipRegionType::material;
    parameters.tip_region_id     = 2;
    parameters.progress_interval = 0;
    return parameters;
  }

  // The same body unloaded: without gravity.
  Parameters::AllParameters
  without_gravity(Parameters::AllParameters parameters)
  {
    parameters.gravity = {0., 0., 0.};
    return parameters;
  }

  // The displacement of the tip (mean over the block) under the load.
  template <int dim>
  Tensor<1, dim>
  tip_displacement(const Parameters::AllParameters &parameters)
  {
    SoftRobotDynamics<dim> model(parameters, MPI_COMM_WORLD);
    SimulatorAccess<dim>   access(model);
    access.make_grid();
    access.setup_system();
    access.initialize_state();
    return access.tip_motion().first;
  }

  // The stiffness of the tip in direction `component`: force over
  // displacement, from the loads +F and -F. `traction_of` gives the
  // traction expression for a signed force.
  template <int dim>
  double
  tip_stiffness(const Parameters::AllParameters                &parameters,
                const unsigned int                              component,
                const std::function<std::string(const double)> &traction_of)
  {
    const double force = probe_force(parameters);
    const double plus  = tip_displacement<dim>(
      tip_load_problem(parameters, traction_of(force)))[component];
    const double minus = tip_displacement<dim>(
      tip_load_problem(parameters, traction_of(-force)))[component];
    return 2. * force / (plus - minus);
  }

  std::string
  number(const double value, const int digits = 8)
  {
    std::ostringstream text;
    text << std::setprecision(digits) << value;
    return text.str();
  }

  // A traction expression with one non-zero component on the faces with
  // x above `x_min`, as the parameter file writes it.
  std::string
  traction_expression(const unsigned int dim,
                      const unsigned int component,
                      const double       value,
                      const double       x_min)
  {
    std::string text;
    for (unsigned int d = 0; d < dim; ++d)
      {
        if (d > 0)
          text += "; ";
        text += (d == component)
                  ? "x > " + number(x_min) + " ? " + number(value, 17) + " : 0"
                  : "0";
      }
    return text;
  }

  Parameters::AllParameters
  read(const std::string              &filename,
       const std::vector<std::string> &overrides = {})
  {
    Parameters::AllParameters parameters;
    parameters.read_file(filename, overrides);
    return parameters;
  }

  // The geometry of the reduced models, as the scene files state it.
  struct ReducedGeometry
  {
    double column_section;  // mm^2
    double strip_width;     // mm
    double strip_thickness; // mm
  };

  // The 2D strip's mesh: the cells along x of the scene file, four cells
  // across the width w, centred on the axis.
  //
  // deal.II checks (in its Debug build) that the steps add up to the extent
  // to 1e-12; with 17 digits (the default) the numbers are those of the
  // computation exactly, w/4 and w/2 being exact binary fractions of w. A
  // width rounded to micrometres is written exactly with 10.
  std::string
  strip_generator_arguments(const std::string &x_steps,
                            const double       width,
                            const int          digits = 17)
  {
    const std::string quarter = number(width / 4., digits);
    return x_steps + "; " + quarter + "," + quarter + "," + quarter + "," +
           quarter + ": -15.25, " + number(-width / 2., digits) + ": 99.25, " +
           number(width / 2., digits) + ": true";
  }

  // The strip's width w from the arguments: the second coordinate of the
  // first corner is -w/2.
  double
  width_of(const std::string &generator_arguments)
  {
    const auto corners = Utilities::split_string_list(generator_arguments, ':');
    return -2. * Utilities::string_to_double(
                   Utilities::split_string_list(corners.at(1), ',').at(1));
  }

  // The width as the scene file writes it, to a micrometre.
  double
  rounded_width(const double width)
  {
    return std::round(width * 1e3) / 1e3;
  }

  // The step sizes along x of a 2D scene's 'subdivided_hyper_rectangle'
  // arguments (everything before the first ';').
  std::string
  x_steps_of(const std::string &generator_arguments)
  {
    return Utilities::trim(
      generator_arguments.substr(0, generator_arguments.find(';')));
  }



  // The area of the tip block's loaded face (the faces of boundary 5 whose
  // centre lies beyond x = x_min, i.e. below it, x pointing down) of the
  // whole body, integrated with the scene's mapping: 841 mm^2 for the box
  // of the tetrahedral meshes, 880.0 mm^2 for the cylinder of the
  // hexahedral mesh (880.69 mm^2 exactly; its rim interpolated
  // quadratically in eight arcs encloses 880.005 mm^2). A model of a
  // fraction of the body holds that fraction of the face.
  double
  loaded_face_area(const Parameters::AllParameters &parameters,
                   const double                     x_min)
  {
    SoftRobotDynamics<3> model(parameters, MPI_COMM_WORLD);
    SimulatorAccess<3>   access(model);
    access.make_grid();
    access.setup_system();
    const DoFHandler<3> &dof_handler = access.get_dof_handler();
    const Quadrature<2>  quadrature =
      dof_handler.get_fe()
        .reference_cell()
        .face_reference_cell(0)
        .get_gauss_type_quadrature<2>(dof_handler.get_fe().degree + 1);
    FEFaceValues<3> face_values(access.get_mapping(),
                                dof_handler.get_fe(),
                                quadrature,
                                update_JxW_values);
    double          area = 0.;
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const auto &face : cell->face_iterators())
          if (face->at_boundary() && face->boundary_id() == 5 &&
              face->center()[0] > x_min)
            {
              face_values.reinit(cell, face);
              for (unsigned int q = 0; q < quadrature.size(); ++q)
                area += face_values.JxW(q);
            }
    return Utilities::MPI::sum(area, MPI_COMM_WORLD) /
           parameters.model_fraction;
  }



  // @sect4{The reduced models from static 3D solves}
  ReducedGeometry
  calibrate_reduced_models(const std::string              &quarter_scene,
                           const std::string              &half_scene,
                           const std::string              &column_scene,
                           const std::string              &strip_scene,
                           const std::vector<std::string> &overrides)
  {
    const double x_bottom = 99.2; // faces below this are not loaded

    // The 3D targets: axial stiffness from the quarter model, lateral
    // (y) stiffness from the half model; the overrides change both.
    const Parameters::AllParameters quarter = read(quarter_scene, overrides);
    const Parameters::AllParameters half    = read(half_scene, overrides);
    const double block_face = loaded_face_area(quarter, x_bottom);
    std::cout << "Loaded face of the tip block: " << number(block_face, 6)
              << " mm^2" << std::endl;
    const auto face_traction = [&](const unsigned int component) {
      return [=](const double force) {
        return traction_expression(3, component, force / block_face, x_bottom);
      };
    };
    const double axial_3d   = tip_stiffness<3>(quarter, 0, face_traction(0));
    const double lateral_3d = tip_stiffness<3>(half, 1, face_traction(1));
    std::cout << "3D actuator at its hanging equilibrium ("
              << quarter.by_id.at(1).silicone << ", "
              << Parameters::name_of(quarter.parameter_set)
              << ", mu = " << quarter.by_id.at(1).shear_modulus << " kPa; "
              << quarter.mesh_file << ", " << half.mesh_file << ", degree "
              << quarter.degree
              << "):\n  axial stiffness   = " << number(axial_3d, 6)
              << " mN/mm\n  lateral stiffness = " << number(lateral_3d, 6)
              << " mN/mm" << std::endl;

    ReducedGeometry geometry;

    // The 1D column: the traction on its end point times the block's
    // section is the force. The stiffness grows with the section somewhat
    // faster than linearly (a thicker bar is stretched less by the weight
    // and so stiffer); a secant iteration on the logarithms finds the
    // section.
    Parameters::AllParameters column           = read(column_scene);
    const auto                column_stiffness = [&](const double section) {
      column.by_id.at(1).section = section;
      column.by_id.at(2).section = section;
      const double stiffness =
        tip_stiffness<1>(column, 0, [&](const double force) {
          return traction_expression(1, 0, force / section, x_bottom);
        });
      std::cout << "  1D column, section " << number(section, 6)
                << " mm^2: axial stiffness = " << number(stiffness, 6)
                << " mN/mm" << std::endl;
      return stiffness;
    };
    geometry.column_section = solve_power_law(column_stiffness,
                                              axial_3d,
                                              column.by_id.at(1).section,
                                              1.,
                                              0.5,
                                              3.,
                                              1e-4);

    // The 2D strip of width w and thickness t. The width sets the ratio of
    // the strip's bending to its axial stiffness, a property of the shape:
    // it is found from the unloaded bodies (without gravity, where both
    // stiffnesses are proportional to the shear modulus, so that the width
    // is the same for every silicone), together with a provisional
    // thickness. The thickness then gives the strip the axial tangent
    // stiffness of the 3D body at the hanging equilibrium. The lateral
    // stiffness at the hanging equilibrium is then compared, not matched:
    // it is mostly that of a pendulum (weight over length), which the width
    // hardly changes, and for the softest silicone the hanging 3D bellows is
    // laterally softer than any strip of its axial stiffness.
    Parameters::AllParameters strip   = read(strip_scene);
    const std::string         x_steps = x_steps_of(strip.generator_arguments);
    geometry.strip_width              = width_of(strip.generator_arguments);
    geometry.strip_thickness          = strip.by_id.at(1).section;
    const auto strip_stiffness = [&](const Parameters::AllParameters &base,
                                     const double                     width,
                                     const double                     thickness,
                                     const unsigned int component) {
      Parameters::AllParameters model = base;
      model.generator_arguments = strip_generator_arguments(x_steps, width);
      model.by_id.at(1).section = thickness;
      model.by_id.at(2).section = thickness;
      const double area         = width * thickness;
      const double stiffness =
        tip_stiffness<2>(model, component, [&](const double force) {
          return traction_expression(2, component, force / area, x_bottom);
        });
      std::cout << "  2D strip" << (base.gravity[0] == 0. ? " (unloaded)" : "")
                << ", width " << number(width, 6) << " mm, thickness "
                << number(thickness, 6)
                << " mm: " << (component == 0 ? "axial" : "lateral")
                << " stiffness " << number(stiffness, 6) << " mN/mm"
                << std::endl;
      return stiffness;
    };
    {
      const Parameters::AllParameters unloaded = without_gravity(strip);
      const double                    axial_0 =
        tip_stiffness<3>(without_gravity(quarter), 0, face_traction(0));
      const double lateral_0 =
        tip_stiffness<3>(without_gravity(half), 1, face_traction(1));
      std::cout << "3D actuator unloaded: axial stiffness "
                << number(axial_0, 6) << " mN/mm, lateral stiffness "
                << number(lateral_0, 6) << " mN/mm" << std::endl;
      // For a slender strip the axial stiffness goes as t w and the
      // lateral one as t w^3; these corrections are exact for such a strip
      // and converge in a few iterations for the real, stubby one.
      for (unsigned int iteration = 0; iteration < 20; ++iteration)
        {
          const double axial_ratio =
            axial_0 / strip_stiffness(unloaded,
                                      geometry.strip_width,
                                      geometry.strip_thickness,
                                      0);
          const double lateral_ratio =
            lateral_0 / strip_stiffness(unloaded,
                                        geometry.strip_width,
                                        geometry.strip_thickness,
                                        1);
          if (std::abs(axial_ratio - 1.) < 1e-4 &&
              std::abs(lateral_ratio - 1.) < 1e-4)
            break;
          const double width_factor = std::sqrt(lateral_ratio / axial_ratio);
          geometry.strip_width *= width_factor;
          geometry.strip_thickness *= axial_ratio / width_factor;
        }
      geometry.strip_width = rounded_width(geometry.strip_width);
    }
    geometry.strip_thickness = solve_power_law(
      [&](const double t) {
        return strip_stiffness(strip, geometry.strip_width, t, 0);
      },
      axial_3d,
      geometry.strip_thickness,
      1.,
      0.5,
      3.,
      1e-4);
    const double lateral_2d =
      strip_stiffness(strip, geometry.strip_width, geometry.strip_thickness, 1);
    std::cout << "  lateral stiffness at the hanging equilibrium: 2D "
              << number(lateral_2d, 6) << " mN/mm, 3D " << number(lateral_3d, 6)
              << " mN/mm (" << std::showpos
              << number(100. * (lateral_2d / lateral_3d - 1.), 3)
              << std::noshowpos << " %)" << std::endl;

    std::cout << "\nFor " << column_scene << ":\n"
              << "  set Section = " << number(geometry.column_section, 5)
              << "   (Material 1 and 2)\nFor " << strip_scene << ":\n"
              << "  set Generator arguments = "
              << strip_generator_arguments(x_steps, geometry.strip_width, 10)
              << "\n  set Section = " << number(geometry.strip_thickness, 5)
              << "   (Material 1 and 2)\n  set Function constants = "
                 "force=958.4, end_area="
              << number(geometry.strip_width * geometry.strip_thickness, 5)
              << std::endl;
    return geometry;
  }



  // The value of one of the 'Function constants' ('name=value, ...'), or
  // zero if it is not there.
  double
  constant(const std::string &constants, const std::string &name)
  {
    for (const std::string &entry : Utilities::split_string_list(constants))
      {
        const auto pair = Utilities::split_string_list(entry, '=');
        if (pair.size() == 2 && pair[0] == name)
          return Utilities::string_to_double(pair[1]);
      }
    return 0.;
  }

  // Whether the scene files hold the computed geometry (to 0.5 %).
  bool
  scenes_match(const ReducedGeometry &geometry,
               const std::string     &column_scene,
               const std::string     &strip_scene)
  {
    const Parameters::AllParameters column = read(column_scene);
    const Parameters::AllParameters strip  = read(strip_scene);
    const double                    width = width_of(strip.generator_arguments);
    const auto                      close = [](const double a, const double b) {
      return std::abs(a - b) <= 5e-3 * std::abs(b);
    };
    bool       match = true;
    const auto check = [&](const std::string &what,
                           const double       in_file,
                           const double       computed) {
      if (!close(in_file, computed))
        {
          std::cout << "MISMATCH: " << what << " is " << in_file
                    << " in the scene file, computed " << computed << std::endl;
          match = false;
        }
    };
    check(column_scene + ": Material 1/Section",
          column.by_id.at(1).section,
          geometry.column_section);
    check(strip_scene + ": strip width", width, geometry.strip_width);
    check(strip_scene + ": Material 1/Section",
          strip.by_id.at(1).section,
          geometry.strip_thickness);
    check(column_scene + ": Function constants section",
          constant(column.constants, "section"),
          geometry.column_section);
    check(strip_scene + ": Function constants end_area",
          constant(strip.constants, "end_area"),
          geometry.strip_width * geometry.strip_thickness);
    return match;
  }



  // @sect4{The shear modulus from the experiment-1 frequency}
  //
  // The vertical frequency of the scene: the scene is run (without VTU
  // output, into a scratch directory) and its tip trajectory analysed.
  double
  vertical_frequency(Parameters::AllParameters parameters,
                     const std::string        &directory)
  {
    parameters.output_directory  = directory;
    parameters.trajectory_file   = "tip_trajectory.csv";
    parameters.write_vtu         = false;
    parameters.spectral_analysis = false;
    parameters.progress_interval = 0;
    // The directory holds the previous trial's run.
    parameters.existing_output = Parameters::Output::ExistingOutput::replace;
    {
      SoftRobotDynamics<3> model(parameters, MPI_COMM_WORLD);
      model.run();
    }
    const Analysis::TrajectoryAnalysis analysis =
      Analysis::analyse_trajectory(Analysis::read_tip_trajectory(
                                     directory + "/tip_trajectory.csv"),
                                   Analysis::SpectralOptions(),
                                   parameters.spectral_skip);
    const Analysis::SpectralResult &vertical = analysis.directions.at(0).result;
    AssertThrow(vertical.has_peak,
                ExcMessage("The vertical motion has no spectral peak: " +
                           vertical.no_peak_reason));
    return vertical.dominant_peak.frequency;
  }

  // The scene with the shear modulus mu and the scene's ratio of bulk to
  // shear modulus.
  Parameters::AllParameters
  with_shear_modulus(Parameters::AllParameters parameters,
                     const double              shear_modulus)
  {
    Parameters::Material &silicone = parameters.by_id.at(1);
    const double ratio     = silicone.bulk_modulus / silicone.shear_modulus;
    silicone.shear_modulus = shear_modulus;
    silicone.bulk_modulus  = ratio * shear_modulus;
    return parameters;
  }

  // The silicone of an experiment-1 scene's Material 1, whose measured
  // frequency the calibrations aim at.
  const Parameters::Silicone &
  silicone_of(const Parameters::AllParameters &parameters,
              const std::string               &scene)
  {
    const Parameters::Material &material = parameters.by_id.at(1);
    AssertThrow(!material.silicone.empty(),
                ExcMessage(scene + ": Material 1 must name a Silicone of the "
                                   "library."));
    return parameters.silicones.at(material.silicone);
  }

  // A scratch directory for the trial runs of one calibration.
  std::string
  scratch_directory()
  {
    return (std::filesystem::temp_directory_path() /
            ("soft-robot-calibrate-" + std::to_string(::getpid())))
      .string();
  }

  double
  calibrate_shear_modulus(const std::string              &scene,
                          const std::vector<std::string> &overrides)
  {
    const Parameters::AllParameters parameters = read(scene, overrides);
    const Parameters::Silicone     &silicone   = silicone_of(parameters, scene);
    const double                    target     = silicone.frequency;
    const std::string               directory  = scratch_directory();

    // Started from the baseline (C1) with the exponent 1/2 of a linear
    // spring, to 0.1 % (the measured frequencies are given to three digits).
    const double mu = solve_power_law(
      [&](const double shear_modulus) {
        const double frequency =
          vertical_frequency(with_shear_modulus(parameters, shear_modulus),
                             directory);
        std::cout << "  mu = " << number(shear_modulus, 6)
                  << " kPa: f = " << number(frequency, 6) << " Hz" << std::endl;
        return frequency;
      },
      target,
      silicone.c1,
      0.5,
      0.2,
      1.,
      1e-3);
    std::filesystem::remove_all(directory);
    std::cout << silicone.name << ": target " << target
              << " Hz (experiment 1)\n  set Calibrated shear modulus = "
              << number(mu, 4) << "   (C1 = " << silicone.c1 << ", ratio "
              << number(mu / silicone.c1, 4) << ")" << std::endl;
    return mu;
  }

  // @sect4{The dead volume of a sealed gas from the experiment-1 frequency}
  //
  // The gas's stiffness on the end cap is about gamma P A^2 / V for the
  // gas volume V = V_c + V_d, the cavity's (about 32,000 mm^3 for the
  // whole hanging bellows) and the dead volume: the frequency grows with
  // 1/V_d, at most like the power 1/2 (the gas alone), less as V_c
  // matters and the silicone carries part of the stiffness. The same
  // secant iteration as for the modulus, on 1/V_d, started from the
  // scene's dead volume with the exponent 1/4; each secant's exponent is
  // kept in [0.01, 0.5].
  double
  calibrate_dead_volume(const std::string              &scene,
                        const std::vector<std::string> &overrides)
  {
    const Parameters::AllParameters parameters = read(scene, overrides);
    const Parameters::Silicone     &silicone   = silicone_of(parameters, scene);
    AssertThrow(parameters.pressure_model ==
                  Parameters::Pneumatics::PressureModel::gas,
                ExcMessage(scene +
                           ": Pneumatics/Pressure model is 'prescribed'; "
                           "calibrate dead-volume needs 'gas' (a sealed "
                           "cavity, with Pressure boundary ids)."));
    AssertThrow(parameters.dead_volume > 0.,
                ExcMessage(scene + ": Pneumatics/Dead volume = " +
                           number(parameters.dead_volume) +
                           " mm^3; the calibration starts from it and needs "
                           "a value > 0."));
    const double      target    = silicone.frequency;
    const std::string directory = scratch_directory();

    const double inverse_volume = solve_power_law(
      [&](const double x) {
        Parameters::AllParameters trial = parameters;
        trial.dead_volume               = 1. / x;
        const double frequency          = vertical_frequency(trial, directory);
        std::cout << "  dead volume = " << number(1. / x, 6)
                  << " mm^3: f = " << number(frequency, 6) << " Hz"
                  << std::endl;
        return frequency;
      },
      target,
      1. / parameters.dead_volume,
      0.25,
      0.01,
      0.5,
      1e-3);
    std::filesystem::remove_all(directory);
    std::cout << silicone.name << ": target " << target
              << " Hz (experiment 1), shear modulus "
              << parameters.by_id.at(1).shear_modulus
              << " kPa, gas law exponent " << parameters.gas_exponent
              << "\n  set Dead volume = " << number(1. / inverse_volume, 4)
              << "   (mm^3)" << std::endl;
    return 1. / inverse_volume;
  }

  void
  print_usage()
  {
    std::cerr
      << "Usage:\n"
         "  calibrate reduced-models <quarter 3D scene> <half 3D scene> "
         "<1D scene> <2D scene> [--check]\n"
         "                           [--set 'Subsection/Entry=value']...\n"
         "      section of the 1D column, width and thickness of the 2D "
         "strip from static\n"
         "      solves of the 3D actuator; --check: exit with 1 unless "
         "the 1D and 2D\n"
         "      scene files hold these numbers (to 0.5 %); each --set "
         "changes one entry of\n"
         "      both 3D scenes\n"
         "  calibrate shear-modulus <experiment-1 scene> "
         "[--set 'Subsection/Entry=value']...\n"
         "      the shear modulus with which the scene rings at its "
         "silicone's measured\n"
         "      experiment-1 frequency; each --set changes one entry of the "
         "scene, as for\n"
         "      soft-robot (another mesh, element or time step)\n"
         "  calibrate dead-volume <experiment-1 scene> "
         "[--set 'Subsection/Entry=value']...\n"
         "      for a scene whose cavity holds a sealed gas: the dead volume "
         "with which it\n"
         "      rings at the measured experiment-1 frequency, the shear "
         "modulus unchanged;\n"
         "      started from the scene's Dead volume\n";
  }
} // namespace



int
main(int argc, char *argv[])
{
  // OpenBLAS's kernels for this processor (solvers/blas_kernels.h).
  SoftRobot::BlasKernels::select();
  // Open MPI's settings for a run without mpirun (core/mpi_session.h).
  const SoftRobot::SerialMpiSession mpi_session;
  // Threads for the assembly: the cores divided among the MPI processes.
  Utilities::MPI::MPI_InitFinalize mpi(argc,
                                       argv,
                                       numbers::invalid_unsigned_int);
  const std::vector<std::string>   arguments(argv + 1, argv + argc);
  try
    {
      // The options after the positional arguments: --set 'S/E=v' (any
      // number) and, for reduced-models, --check.
      const auto options = [&](const unsigned int        first,
                               std::vector<std::string> &overrides,
                               bool                     *check) {
        for (unsigned int i = first; i < arguments.size(); ++i)
          if (arguments[i] == "--set" && i + 1 < arguments.size())
            overrides.push_back(arguments[++i]);
          else if (arguments[i] == "--check" && check != nullptr)
            *check = true;
          else
            return false;
        return true;
      };
      std::vector<std::string> overrides;
      bool                     check = false;
      if (arguments.size() >= 5 && arguments[0] == "reduced-models")
        {
          if (!options(5, overrides, &check))
            {
              print_usage();
              return 1;
            }
          const ReducedGeometry geometry = calibrate_reduced_models(
            arguments[1], arguments[2], arguments[3], arguments[4], overrides);
          if (check && !scenes_match(geometry, arguments[3], arguments[4]))
            return 1;
          return 0;
        }
      if (arguments.size() >= 2 && arguments[0] == "shear-modulus")
        {
          if (!options(2, overrides, nullptr))
            {
              print_usage();
              return 1;
            }
          calibrate_shear_modulus(arguments[1], overrides);
          return 0;
        }
      if (arguments.size() >= 2 && arguments[0] == "dead-volume")
        {
          if (!options(2, overrides, nullptr))
            {
              print_usage();
              return 1;
            }
          calibrate_dead_volume(arguments[1], overrides);
          return 0;
        }
      print_usage();
      return 1;
    }
  catch (ExceptionBase &error)
    {
      std::cerr << "\nError:\n";
      error.print_info(std::cerr);
      return 1;
    }
  catch (std::exception &error)
    {
      std::cerr << "\nError: " << error.what() << std::endl;
      return 1;
    }
}
