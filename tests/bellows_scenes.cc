// SPDX-License-Identifier: LGPL-2.1-or-later

// Checks the bellows scenes of parameters/bellows/ as the program reads
// them (fast: no simulation; the scenes are run for a few steps by the
// ctest entries scene.<name> of tests/CMakeLists.txt):
//  - every one of the thirty scenes (three experiments in 3D, two reduced,
//    three silicones, two parameter sets) parses;
//  - its silicone's shear modulus, bulk modulus and damping coefficient are
//    those of the Silicone library for its parameter set, and the damping
//    coefficient is zeta = 2 xi / omega of the measured experiment-1 values
//    of the study (FACTS.md), written here independently;
//  - the masses are the measured ones, the duration and time step the
//    study's, and the reduced scenes have a section;
// and that the Silicone library rejects a name it does not have, with a
// message naming the entry and the names it has.

// Not typed on the dimension: parameter files are read, nothing is run.

#include <cmath>
#include <core/parameters.h>
#include <cstdlib>
#include <deal.II/base/numbers.h>
#include <gtest/gtest.h>
#include <map>
#include <string>

namespace
{
  using namespace SoftRobot;

  std::string
  scene_file(const std::string &name)
  {
    const char *source = std::getenv("SOFT_ROBOT_SOURCE_DIR");
    return std::string(source ? source : "..") + "/parameters/bellows/" + name +
           ".prm";
  }

  // The study's numbers (FACTS.md): C1 in kPa, experiment-1 frequency in Hz
  // and damping ratio.
  struct Measured
  {
    std::string name;
    double      c1, frequency, damping_ratio;
  };
  const std::map<std::string, Measured> silicones = {
    {"ef50", {"Ecoflex 00-50", 22.4, 2.05, 0.041}},
    {"ds20", {"Dragon Skin 20", 116., 4.20, 0.021}},
    {"ds30", {"Dragon Skin 30", 191.6, 5.57, 0.035}}};

  const std::vector<std::string> experiments = {"vertical_%_3d",
                                                "planar_%_3d",
                                                "spherical_%_3d",
                                                "column_%_1d",
                                                "planar_%_2d"};

  std::string
  scene_name(const std::string &pattern,
             const std::string &key,
             const bool         calibrated)
  {
    std::string name = pattern;
    name.replace(name.find('%'), 1, key);
    return name + (calibrated ? "_calibrated" : "");
  }
} // namespace



TEST(BellowsScenes, EveryScenePairsItsSiliconeWithTheLibraryData)
{
  for (const auto &[key, measured] : silicones)
    for (const bool calibrated : {false, true})
      for (const std::string &pattern : experiments)
        {
          const std::string name = scene_name(pattern, key, calibrated);
          SCOPED_TRACE(name);
          Parameters::AllParameters parameters;
          ASSERT_NO_THROW(parameters.read_file(scene_file(name)));

          EXPECT_EQ(parameters.parameter_set,
                    calibrated ? Parameters::Silicone::ParameterSet::calibrated
                               : Parameters::Silicone::ParameterSet::baseline);
          const Parameters::Material &silicone = parameters.by_id.at(1);
          EXPECT_EQ(silicone.silicone, measured.name);
          if (calibrated)
            EXPECT_GT(silicone.shear_modulus, measured.c1);
          else
            EXPECT_DOUBLE_EQ(silicone.shear_modulus, measured.c1);
          EXPECT_DOUBLE_EQ(silicone.bulk_modulus,
                           100. * silicone.shear_modulus);
          EXPECT_NEAR(silicone.damping_zeta,
                      2. * measured.damping_ratio /
                        (2. * dealii::numbers::PI * measured.frequency),
                      1e-12);
          EXPECT_DOUBLE_EQ(silicone.mass, 0.0766);
          EXPECT_DOUBLE_EQ(parameters.by_id.at(2).mass, 0.1188);

          const bool vertical = name.find("vertical") != std::string::npos ||
                                name.find("column") != std::string::npos;
          EXPECT_DOUBLE_EQ(parameters.end_time, vertical ? 5.25 : 6.);
          // The swing of the 3D scenes is resolved at 0.01 s (see
          // protocol_planar_3d.prm); the rest keeps 0.005 s.
          const bool swing_3d = parameters.dimension == 3 && !vertical;
          EXPECT_DOUBLE_EQ(parameters.time_step, swing_3d ? 0.01 : 0.005);
          EXPECT_EQ(parameters.output_directory, "output/" + name);
          if (parameters.dimension < 3)
            {
              EXPECT_NE(silicone.section, 1.);
              EXPECT_DOUBLE_EQ(parameters.by_id.at(2).section,
                               silicone.section);
            }
        }
}



TEST(BellowsScenes, CalibratedShearModulusIsSharedByTheThreeExperiments)
{
  for (const auto &[key, measured] : silicones)
    {
      Parameters::AllParameters vertical, spherical;
      vertical.read_file(scene_file(scene_name("vertical_%_3d", key, true)));
      spherical.read_file(scene_file(scene_name("spherical_%_3d", key, true)));
      EXPECT_DOUBLE_EQ(vertical.by_id.at(1).shear_modulus,
                       spherical.by_id.at(1).shear_modulus);
    }
}



TEST(BellowsScenes, UnknownSiliconeIsAClearError)
{
  Parameters::AllParameters parameters;
  try
    {
      parameters.read_file(scene_file("vertical_ds20_3d"),
                           {"Material 1/Silicone=Dragon Skin 10"});
      FAIL() << "no error for an unknown silicone";
    }
  catch (dealii::ExceptionBase &error)
    {
      std::ostringstream message;
      error.print_info(message);
      EXPECT_NE(message.str().find("Material 1/Silicone names 'Dragon Skin "
                                   "10'"),
                std::string::npos)
        << message.str();
      EXPECT_NE(message.str().find("'Ecoflex 00-50'"), std::string::npos)
        << message.str();
    }
}



TEST(BellowsScenes, OverridesAreCheckedLikeTheFile)
{
  Parameters::AllParameters parameters;
  parameters.read_file(scene_file("vertical_ds20_3d"),
                       {"Time integration/End time=0.5",
                        "Silicone library/Parameter set=calibrated"});
  EXPECT_DOUBLE_EQ(parameters.end_time, 0.5);
  EXPECT_GT(parameters.by_id.at(1).shear_modulus, 116.);

  for (const std::string &bad : {std::string("Time integration/End time=-1"),
                                 std::string("Time integration/Endtime=1"),
                                 std::string("no equals sign")})
    {
      SCOPED_TRACE(bad);
      try
        {
          parameters.read_file(scene_file("vertical_ds20_3d"), {bad});
          FAIL() << "no error for a bad override";
        }
      catch (dealii::ExceptionBase &error)
        {
          std::ostringstream message;
          error.print_info(message);
          EXPECT_NE(message.str().find("--set '" + bad + "'"),
                    std::string::npos)
            << message.str();
        }
    }
}
