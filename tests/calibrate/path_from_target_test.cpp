// path_from_target: a law replayed along a target's own measured kinematics (the DT link's
// elongation and rotation read off an FE run, experiments/dt_fe_fit/). The path and its pseudo-
// time column against the rows; a fit file that uses it reads, refuses misuse at file:line, and
// recovers the law's parameters from a target the law made on an irregular path (an inverse
// crime: it checks the machinery, not the element's fit to the FE).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>

#include "dtwire/calibrate/fit_file.hpp"
#include "dtwire/calibrate/fitter.hpp"
#include "dtwire/calibrate/law_replay.hpp"
#include "dtwire/core/csv.hpp"
#include "dtwire/core/error.hpp"

namespace dtwire::calibrate {
namespace {

Curve kinematics(std::vector<double> u_m, std::vector<double> theta_rad) {
  Curve c;
  c.add_channel_si("displacement", Dimension::Length, u_m, *find_unit("mm"));
  c.add_channel_si("rotation", Dimension::Angle, theta_rad, *find_unit("rad"));
  return c;
}

TEST(PathFromTarget, WaypointsAreTheRowsAndTimeCountsThem) {
  Curve from_origin = kinematics({0.0, 1e-3, 0.5e-3}, {0.0, 0.01, 0.02});
  const LoadPath a = path_from_target(from_origin, 7);
  EXPECT_EQ(a.displacement_m, (std::vector<double>{0.0, 1e-3, 0.5e-3}));
  EXPECT_EQ(a.rotation_rad, (std::vector<double>{0.0, 0.01, 0.02}));
  EXPECT_EQ(a.increments_per_leg, 7);
  EXPECT_EQ(from_origin.si("time"), (std::vector<double>{0.0, 1.0, 2.0}));

  Curve off_origin = kinematics({0.2e-3, 1e-3}, {0.0, 0.0});  // a laboratory curve's first row
  const LoadPath b = path_from_target(off_origin, 3);
  EXPECT_EQ(b.displacement_m, (std::vector<double>{0.0, 0.2e-3, 1e-3}));
  EXPECT_EQ(off_origin.si("time"), (std::vector<double>{1.0, 2.0}));

  Curve force_only;
  force_only.add_channel_si("force", Dimension::Force, {0.0, 1.0}, *find_unit("N"));
  EXPECT_THROW(path_from_target(force_only, 1), std::invalid_argument);
  Curve timed = kinematics({0.0, 1e-3}, {0.0, 0.0});
  timed.add_channel_si("time", Dimension::Time, {0.0, 1.0}, *find_unit("s"));
  EXPECT_THROW(path_from_target(timed, 1), std::invalid_argument);
}

class PathFromTargetFit : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("dtwire_path_from_target_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  // Four starts: from a single start (N0 2000 N, EI 0.4) the fit stalls in a local minimum of
  // the elastoplastic objective (N0 0.86 of the truth on this path).
  // An FE-like target: the thesis law (the published DT set, fitted N0 = 2800 N and EI = 0.25 N m^2 per deg) replayed
  // on an irregular pull-and-bend path, written under FE link column names.
  void write_target(double noise) {
    std::mt19937_64 generator(5);
    std::normal_distribution<double> gauss(0.0, 1.0);
    std::vector<double> u{0.0}, theta{0.0};
    for (int k = 1; k <= 40; ++k) {
      u.push_back(u.back() + 0.06e-3 * (1.0 + 0.6 * std::sin(0.7 * k)));
      theta.push_back(theta.back() + 0.006 * std::cos(0.3 * k));
    }
    LoadPath path{u, theta, 20};
    const LawReplaySimulator law("thesis", fixed(), path);
    const Curve replayed = law.simulate({{"N0_N", 2800.0}, {"EI_Nm2_per_deg_convention", 0.25}});
    // The replay has 20 increments per leg: row k of the target is increment 20 k.
    const std::vector<double> f = replayed.si("force"), m = replayed.si("moment");
    double f_range = 0, m_range = 0;
    for (std::size_t k = 0; k < u.size(); ++k) {
      f_range = std::max(f_range, std::abs(f[20 * k]));
      m_range = std::max(m_range, std::abs(m[20 * k]));
    }
    std::ofstream out(dir_ / "link.csv");
    out.precision(17);
    out << "link_elongation_mm,link_rotation_y_rad,link_axial_force_N,link_moment_y_Nm\n";
    for (std::size_t k = 0; k < u.size(); ++k)
      out << u[k] * 1e3 << "," << theta[k] << "," << f[20 * k] + (k ? noise * f_range * gauss(generator) : 0.0) << ","
          << m[20 * k] + (k ? noise * m_range * gauss(generator) : 0.0) << "\n";
  }
  // The published DT set (experiments/data/macroelement_thesis_params.json).
  static dem::ParameterMap fixed() {
    return {{"reference_length_m", 0.04}, {"D_m", 0.0027}, {"EA_N", 1.71e6}, {"EI_Nm2_per_deg_convention", 0.257},
            {"N0_N", 2800},  {"Nult_N", 5000}, {"Nc_N", 1650},   {"m_f", 0.0354},  {"beta_f", 0.0642},
            {"k_F", 4080},   {"k_M", 0.112},   {"m_g", 0.000632}, {"alpha_g", 0.5}, {"beta_g", 3.24},
            {"W1_J", 10.5},  {"W2_J", 202.278}, {"alpha_d", 2.75}, {"slide_a", 0.0}, {"slide_b", 0.0015}};
  }
  std::filesystem::path write_fit(const std::string& experiment_extra) {
    {
      std::ofstream json(dir_ / "fixed.json");
      json << "{\"double_twist\": {";
      bool first = true;
      for (const auto& [key, value] : fixed()) {
        json << (first ? "" : ", ") << "\"" << key << "\": " << value;
        first = false;
      }
      json << "}}";
    }
    const auto path = dir_ / "fit.toml";
    std::ofstream(path) << "title = \"link\"\n"
                           "[simulator]\nkind = \"law_replay\"\nlaw = \"thesis\"\n"
                           "fixed_parameters_file = \"fixed.json\"\nfixed_parameters_section = \"double_twist\"\n"
                           "[fit]\nloss = \"squared\"\nstarts = 4\nseed = 3\n"
                           "[[parameter]]\nname = \"N0_N\"\nunit = \"N\"\ninitial = 2000\nlower = 500\nupper = 6000\n"
                           "[[parameter]]\nname = \"EI_Nm2_per_deg_convention\"\nunit = \"N m^2/deg\"\ninitial = 0.4\n"
                           "lower = 0.01\nupper = 2\n"
                           "[[experiment]]\nname = \"link\"\ntarget = \"link.csv\"\nabscissa = \"time\"\n"
                           "channels = [\"force\", \"moment\"]\nincrements_per_leg = 20\n"
                           "target_columns = {displacement = \"link_elongation\", rotation = \"link_rotation_y\", "
                           "force = \"link_axial_force\", moment = \"link_moment_y\"}\n" +
                               experiment_extra;
    return path;
  }
  std::filesystem::path dir_;
};

TEST_F(PathFromTargetFit, RecoversTheParametersOfTheLawThatMadeTheTarget) {
  for (const double noise : {0.0, 0.01}) {
    write_target(noise);
    FitDefinition def = read_fit_file(write_fit("path_from_target = true\n"));
    ProblemEvaluator evaluator(def.experiments, def.parameters, def.evaluation);
    const FitResult result = run_fit(evaluator, def.fit);
    ASSERT_TRUE(result.completed);
    const double tolerance = noise == 0.0 ? 1e-6 : 0.0;
    for (std::size_t i = 0; i < result.values.size(); ++i) {
      const double truth = result.parameters[i].name == "N0_N" ? 2800.0 : 0.25;
      if (noise == 0.0) {
        EXPECT_NEAR(result.values[i] / truth, 1.0, tolerance) << result.parameters[i].name;
      } else {  // within 2 sigma of the reported covariance
        ASSERT_FALSE(result.sigma.empty());
        EXPECT_LT(std::abs(result.values[i] - truth), 2.0 * result.sigma[i])
            << result.parameters[i].name << " = " << result.values[i] << " +- " << result.sigma[i];
      }
    }
  }
}

TEST_F(PathFromTargetFit, MisuseIsRefusedAtItsLine) {
  write_target(0.0);
  try {
    read_fit_file(write_fit("path_from_target = true\npath_displacement_mm = [0, 1]\n"));
    FAIL() << "waypoints and path_from_target together were accepted";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("path_displacement_mm"), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("not both"), std::string::npos) << error.what();
  }
  FitReadOptions no_targets;
  no_targets.read_targets = false;
  try {
    read_fit_file(write_fit("path_from_target = true\n"), no_targets);
    FAIL() << "path_from_target without a target was accepted";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("needs the target curve"), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find(":30:"), std::string::npos) << error.what();  // its line
  }
}

}  // namespace
}  // namespace dtwire::calibrate
