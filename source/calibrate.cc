// @sect3{Calibration commands}
//
// Two commands that produce the numbers of the bellows scenes which are not
// measured directly, so that every such number in a scene file can be
// reproduced:
//
// <code>calibrate reduced-models</code> computes the geometry of the
// reduced models from static solves of the 3D actuator. The 1D column is
// given the cross-section area, and the 2D strip the width and thickness,
// with which their axial stiffness (and, in 2D, the lateral stiffness of
// the tip) equal those of the 3D body. The stiffnesses are those of small
// tip loads about the unloaded state, without gravity: they are then
// proportional to the shear modulus in every model (the bulk-to-shear
// ratio being fixed), so the same reduced geometry serves every silicone
// and both parameter sets. Nothing is fitted to a measured frequency.
//
// <code>calibrate shear-modulus</code> finds the shear modulus with which
// the experiment-1 scene (vertical oscillation) rings at the measured
// frequency of its silicone. The frequency is computed as the study
// computed the measured one: the peak of the Fourier transform of the
// tip's vertical displacement over the whole record. The damping
// coefficient is not fitted: zeta = 2 xi / omega with the measured xi and
// omega (see parameters/silicones.prm).

#include <analysis/spectral_analysis.h>
#include <core/parameters.h>
#include <core/soft_robot_dynamics.h>
#include <deal.II/base/mpi.h>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

namespace
{
  using namespace SoftRobot;
  using namespace dealii;

  // The total force of the small tip loads, mN (kg mm/s^2). It moves the tip
  // of the stiffest silicone by a few hundredths of a millimetre: small
  // enough for the response to be linear, large enough to be far above the
  // solver's tolerance. The load is applied with both signs and the
  // stiffness taken from the difference, which removes the quadratic part
  // of the response.
  constexpr double probe_force = 10.;

  // The 3D model with only a tip load: the given total force (of the whole
  // body, in the direction `component`) spread uniformly over the bottom
  // face of the tip block (x = 99.25, 29 x 29 mm in the full body; the
  // model's share of it in the quarter and half models, so the traction is
  // the same).
  Parameters::AllParameters
  tip_load_problem(Parameters::AllParameters parameters,
                   const std::string        &traction)
  {
    parameters.gravity                 = {0., 0., 0.};
    parameters.constants               = "";
    parameters.traction_expression     = traction;
    parameters.traction_boundary_ids   = {parameters.dimension == 3 ? 5u : 1u};
    parameters.InitialConditions::type = "static equilibrium";
    parameters.load_steps              = 1;
    parameters.displacement_expression = "";
    parameters.velocity_expression     = "";
    parameters.tip_region_type         = "material";
    parameters.tip_region_id           = 2;
    parameters.progress_interval       = 0;
    return parameters;
  }

  // The displacement of the tip (mean over the block) under the load.
  template <int dim>
  Tensor<1, dim>
  tip_displacement(const Parameters::AllParameters &parameters)
  {
    SoftRobotDynamics<dim> model(parameters, MPI_COMM_WORLD);
    model.make_grid();
    model.setup_system();
    model.initialize_state();
    return model.tip_motion().first;
  }

  // The stiffness of the tip in direction `component`: force over
  // displacement, from the loads +F and -F. `traction_of` gives the
  // traction expression for a signed force.
  template <int dim>
  double
  tip_stiffness(const Parameters::AllParameters                 &parameters,
                const unsigned int                               component,
                const std::function<std::string(const double)> &traction_of)
  {
    const double plus =
      tip_displacement<dim>(
        tip_load_problem(parameters, traction_of(probe_force)))[component];
    const double minus =
      tip_displacement<dim>(
        tip_load_problem(parameters, traction_of(-probe_force)))[component];
    return 2. * probe_force / (plus - minus);
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
        text += (d == component) ?
                  "x > " + number(x_min) + " ? " + number(value, 17) + " : 0" :
                  "0";
      }
    return text;
  }

  Parameters::AllParameters
  read(const std::string &filename)
  {
    Parameters::AllParameters parameters;
    parameters.read_file(filename);
    return parameters;
  }

  // The geometry of the reduced models, as the scene files state it.
  struct ReducedGeometry
  {
    double column_section; // mm^2
    double strip_width;    // mm
    double strip_thickness; // mm
  };

  // The 2D strip's mesh: the cells along x of the scene file, four cells
  // across the width w, centred on the axis.
  std::string
  strip_generator_arguments(const std::string &x_steps, const double width)
  {
    const std::string quarter = number(width / 4., 10);
    return x_steps + "; " + quarter + "," + quarter + "," + quarter + "," +
           quarter + ": -15.25, " + number(-width / 2., 10) + ": 99.25, " +
           number(width / 2., 10) + ": true";
  }

  // The step sizes along x of a 2D scene's 'subdivided_hyper_rectangle'
  // arguments (everything before the first ';').
  std::string
  x_steps_of(const std::string &generator_arguments)
  {
    return Utilities::trim(
      generator_arguments.substr(0, generator_arguments.find(';')));
  }



  // @sect4{The reduced models from static 3D solves}
  ReducedGeometry
  calibrate_reduced_models(const std::string &quarter_scene,
                           const std::string &half_scene,
                           const std::string &column_scene,
                           const std::string &strip_scene)
  {
    const double block_face = 29. * 29.; // the block's bottom face, mm^2
    const double x_bottom   = 99.2;      // faces below this are not loaded

    // The 3D targets: axial stiffness from the quarter model, lateral
    // (y) stiffness from the half model, both per kPa of shear modulus.
    const Parameters::AllParameters quarter = read(quarter_scene);
    const Parameters::AllParameters half    = read(half_scene);
    const double                    mu_3d   = quarter.by_id.at(1).shear_modulus;
    const auto face_traction = [&](const unsigned int component) {
      return [=](const double force) {
        return traction_expression(3, component, force / block_face, x_bottom);
      };
    };
    const double axial_3d =
      tip_stiffness<3>(quarter, 0, face_traction(0)) / mu_3d;
    const double lateral_3d =
      tip_stiffness<3>(half, 1, face_traction(1)) /
      half.by_id.at(1).shear_modulus;
    std::cout << "3D actuator (" << quarter.mesh_file << ", "
              << half.mesh_file << ", degree " << quarter.degree
              << "):\n  axial stiffness / mu   = " << number(axial_3d, 6)
              << " mm\n  lateral stiffness / mu = " << number(lateral_3d, 6)
              << " mm" << std::endl;

    ReducedGeometry geometry;

    // The 1D column: the traction on its end point times the block's
    // section is the force. The axial stiffness is proportional to the
    // section; one correction is exact, a second one confirms it.
    Parameters::AllParameters column = read(column_scene);
    geometry.column_section          = column.by_id.at(1).section;
    for (unsigned int iteration = 0; iteration < 2; ++iteration)
      {
        column.by_id.at(1).section = geometry.column_section;
        column.by_id.at(2).section = geometry.column_section;
        const double stiffness =
          tip_stiffness<1>(column, 0, [&](const double force) {
            return traction_expression(1,
                                       0,
                                       force / geometry.column_section,
                                       x_bottom);
          }) /
          column.by_id.at(1).shear_modulus;
        std::cout << "  1D column, section " << number(geometry.column_section, 6)
                  << " mm^2: axial stiffness / mu = " << number(stiffness, 6)
                  << " mm" << std::endl;
        geometry.column_section *= axial_3d / stiffness;
      }

    // The 2D strip of width w and thickness t. For a slender strip the
    // axial stiffness goes as t w and the lateral one as t w^3; the
    // corrections below are exact for these laws and converge in a few
    // iterations for the real, stubby strip.
    Parameters::AllParameters strip   = read(strip_scene);
    const std::string         x_steps = x_steps_of(strip.generator_arguments);
    geometry.strip_thickness          = strip.by_id.at(1).section;
    {
      const auto words = Utilities::split_string_list(
        strip.generator_arguments.substr(strip.generator_arguments.find(':') +
                                         1),
        ',');
      geometry.strip_width = -2. * Utilities::string_to_double(
                                     Utilities::split_string_list(
                                       words.at(1), ':')[0]);
    }
    for (unsigned int iteration = 0; iteration < 12; ++iteration)
      {
        strip.generator_arguments =
          strip_generator_arguments(x_steps, geometry.strip_width);
        strip.by_id.at(1).section = geometry.strip_thickness;
        strip.by_id.at(2).section = geometry.strip_thickness;
        const double area = geometry.strip_width * geometry.strip_thickness;
        const auto   end_traction = [&](const unsigned int component) {
          return [=](const double force) {
            return traction_expression(2, component, force / area, x_bottom);
          };
        };
        const double mu = strip.by_id.at(1).shear_modulus;
        const double axial =
          tip_stiffness<2>(strip, 0, end_traction(0)) / mu;
        const double lateral =
          tip_stiffness<2>(strip, 1, end_traction(1)) / mu;
        std::cout << "  2D strip, width " << number(geometry.strip_width, 6)
                  << " mm, thickness " << number(geometry.strip_thickness, 6)
                  << " mm: axial / mu = " << number(axial, 6)
                  << " mm, lateral / mu = " << number(lateral, 6) << " mm"
                  << std::endl;
        const double axial_ratio   = axial_3d / axial;
        const double lateral_ratio = lateral_3d / lateral;
        if (std::abs(axial_ratio - 1.) < 1e-4 &&
            std::abs(lateral_ratio - 1.) < 1e-4)
          break;
        const double width_factor = std::sqrt(lateral_ratio / axial_ratio);
        geometry.strip_width *= width_factor;
        geometry.strip_thickness *= axial_ratio / width_factor;
      }

    std::cout << "\nFor the 1D scenes (Material 1 and 2):\n"
              << "  set Section = " << number(geometry.column_section, 5)
              << "\nFor the 2D scenes (Geometry; Material 1 and 2):\n"
              << "  set Generator arguments = "
              << strip_generator_arguments(x_steps,
                                           std::round(geometry.strip_width *
                                                      1e3) /
                                             1e3)
              << "\n  set Section = " << number(geometry.strip_thickness, 5)
              << "\n  set Function constants = force=958.4, end_area="
              << number(geometry.strip_width * geometry.strip_thickness, 5)
              << std::endl;
    return geometry;
  }

  // Whether the scene files hold the computed geometry (to 0.5 %).
  bool
  scenes_match(const ReducedGeometry &geometry,
               const std::string     &column_scene,
               const std::string     &strip_scene)
  {
    const Parameters::AllParameters column = read(column_scene);
    const Parameters::AllParameters strip  = read(strip_scene);
    const auto                      words  = Utilities::split_string_list(
      strip.generator_arguments.substr(strip.generator_arguments.find(':') + 1),
      ',');
    const double width =
      -2. *
      Utilities::string_to_double(Utilities::split_string_list(words.at(1),
                                                               ':')[0]);
    const auto close = [](const double a, const double b) {
      return std::abs(a - b) <= 5e-3 * std::abs(b);
    };
    bool match = true;
    const auto check = [&](const std::string &what,
                           const double       in_file,
                           const double       computed) {
      if (!close(in_file, computed))
        {
          std::cout << "MISMATCH: " << what << " is " << in_file
                    << " in the scene file, computed " << computed
                    << std::endl;
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
    const auto area = strip.constants.find("end_area=");
    check(strip_scene + ": Function constants end_area",
          area == std::string::npos ?
            0. :
            Utilities::string_to_double(Utilities::split_string_list(
              strip.constants.substr(area + 9), ',')[0]),
          geometry.strip_width * geometry.strip_thickness);
    return match;
  }



  // @sect4{The shear modulus from the experiment-1 frequency}
  //
  // The vertical frequency of the scene with shear modulus mu: the scene is
  // run (without VTU output, into a scratch directory) and its tip
  // trajectory analysed.
  double
  vertical_frequency(Parameters::AllParameters parameters,
                     const double              shear_modulus,
                     const std::string        &directory)
  {
    Parameters::Material &silicone = parameters.by_id.at(1);
    const double ratio = silicone.bulk_modulus / silicone.shear_modulus;
    silicone.shear_modulus     = shear_modulus;
    silicone.bulk_modulus      = ratio * shear_modulus;
    parameters.output_directory = directory;
    parameters.trajectory_file  = "tip_trajectory.csv";
    parameters.write_vtu         = false;
    parameters.spectral_analysis = false;
    parameters.progress_interval = 0;
    {
      SoftRobotDynamics<3> model(parameters, MPI_COMM_WORLD);
      model.run();
    }
    const Analysis::TrajectoryAnalysis analysis = Analysis::analyse_trajectory(
      Analysis::read_tip_trajectory(directory + "/tip_trajectory.csv"),
      Analysis::SpectralOptions(),
      parameters.spectral_skip);
    const Analysis::SpectralResult &vertical = analysis.directions.at(0).result;
    AssertThrow(vertical.has_peak,
                ExcMessage("The vertical motion has no spectral peak: " +
                           vertical.no_peak_reason));
    return vertical.dominant_peak.frequency;
  }

  double
  calibrate_shear_modulus(const std::string &scene)
  {
    const Parameters::AllParameters parameters = read(scene);
    const Parameters::Material     &material   = parameters.by_id.at(1);
    AssertThrow(!material.silicone.empty(),
                ExcMessage(scene + ": Material 1 must name a Silicone of the "
                                   "library."));
    const Parameters::Silicone &silicone =
      parameters.silicones.at(material.silicone);
    const double target = silicone.frequency;
    const std::string directory =
      (std::filesystem::temp_directory_path() /
       ("soft-robot-calibrate-" + std::to_string(::getpid())))
        .string();

    // Secant iteration on log(f) against log(mu), started from the
    // baseline (C1) with the exponent 1/2 of a linear spring.
    double mu        = silicone.c1;
    double frequency = vertical_frequency(parameters, mu, directory);
    double slope     = 0.5;
    std::cout << "  mu = " << number(mu, 6)
              << " kPa: f = " << number(frequency, 6) << " Hz" << std::endl;
    for (unsigned int iteration = 0;
         iteration < 8 && std::abs(frequency / target - 1.) > 5e-4;
         ++iteration)
      {
        const double next_mu =
          mu * std::exp(std::log(target / frequency) / slope);
        const double next_frequency =
          vertical_frequency(parameters, next_mu, directory);
        std::cout << "  mu = " << number(next_mu, 6)
                  << " kPa: f = " << number(next_frequency, 6) << " Hz"
                  << std::endl;
        if (std::abs(next_frequency - frequency) > 1e-9)
          slope = std::log(next_frequency / frequency) / std::log(next_mu / mu);
        slope     = std::clamp(slope, 0.2, 1.);
        mu        = next_mu;
        frequency = next_frequency;
      }
    std::filesystem::remove_all(directory);
    std::cout << silicone.name << ": target " << target
              << " Hz (experiment 1), reached " << number(frequency, 6)
              << " Hz\n  set Calibrated shear modulus = " << number(mu, 4)
              << "   (C1 = " << silicone.c1 << ", ratio "
              << number(mu / silicone.c1, 4) << ")" << std::endl;
    return mu;
  }

  void
  print_usage()
  {
    std::cerr
      << "Usage:\n"
         "  calibrate reduced-models <quarter 3D scene> <half 3D scene> "
         "<1D scene> <2D scene> [--check]\n"
         "      section of the 1D column, width and thickness of the 2D "
         "strip from static\n"
         "      solves of the 3D actuator; --check: exit with 1 unless "
         "the 1D and 2D\n"
         "      scene files hold these numbers (to 0.5 %)\n"
         "  calibrate shear-modulus <experiment-1 scene>\n"
         "      the shear modulus with which the scene rings at its "
         "silicone's measured\n"
         "      experiment-1 frequency\n";
  }
} // namespace



int
main(int argc, char *argv[])
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const std::vector<std::string>   arguments(argv + 1, argv + argc);
  try
    {
      if (arguments.size() >= 5 && arguments[0] == "reduced-models")
        {
          const bool check = arguments.size() == 6 && arguments[5] == "--check";
          if (arguments.size() == 6 && !check)
            {
              print_usage();
              return 1;
            }
          const ReducedGeometry geometry = calibrate_reduced_models(
            arguments[1], arguments[2], arguments[3], arguments[4]);
          if (check && !scenes_match(geometry, arguments[3], arguments[4]))
            return 1;
          return 0;
        }
      if (arguments.size() == 2 && arguments[0] == "shear-modulus")
        {
          calibrate_shear_modulus(arguments[1]);
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
