// The shipped DT link fit (experiments/dt_fe_fit/dt_link_fit.toml) reads against FE-like targets
// with the link columns its README documents, follows each target's rows and evaluates at the
// thesis DT set, so a renamed column or a broken path_from_target shows here and not only in a
// campaign run.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "dtwire/calibrate/fit_file.hpp"

namespace dtwire::calibrate {
namespace {

const std::filesystem::path kFolder = std::filesystem::path(DTWIRE_SOURCE_DIR) / "experiments/dt_fe_fit";

// A short pull-and-bend history under the FE run's column names (both bending axes present).
void write_fe_like_curve(const std::filesystem::path& file) {
  std::filesystem::create_directories(file.parent_path());
  std::ofstream out(file);
  out << "displacement_mm,force_N,extensometer_elongation_mm,link_rotation_x_rad,link_rotation_y_rad,"
         "link_axial_force_N,link_moment_x_Nm,link_moment_y_Nm\n";
  for (int k = 0; k <= 6; ++k)
    out << 0.5 * k << "," << 400.0 * k << "," << 0.05 * k << "," << 0.01 * k << "," << 0.02 * k << "," << 400.0 * k
        << "," << 0.05 * k << "," << 0.08 * k << "\n";
}

TEST(ShippedDtLinkFit, ReadsFollowsTheTargetsAndEvaluates) {
  const std::filesystem::path targets = std::filesystem::temp_directory_path() / "dtwire_dt_link_fit_targets";
  std::filesystem::remove_all(targets);
  for (const char* name : {"tension", "compression", "cycles", "bending_in_plane", "bending_out_of_plane",
                           "pull_spin_ratio_0.2", "pull_spin_ratio_0.5", "pull_spin_ratio_2", "pull_angle_25deg",
                           "pull_angle_47deg", "pull_angle_78deg"}) {
    ASSERT_TRUE(std::filesystem::is_regular_file(kFolder / (std::string(name) + ".prm"))) << name;
    write_fe_like_curve(targets / name / "curve.csv");
  }
  FitReadOptions read;
  read.targets_directory = targets;
  const FitDefinition def = read_fit_file(kFolder / "dt_link_fit.toml", read);
  EXPECT_EQ(def.experiments.size(), 11u);
  ParameterValues reference;
  for (const auto& p : def.parameters) reference[p.name] = p.reference.value();
  for (const Experiment& e : def.experiments) {
    EXPECT_EQ(e.target.si("time"), (std::vector<double>{0, 1, 2, 3, 4, 5, 6})) << e.name;  // one waypoint per row
    const Curve simulated = e.simulator->simulate(reference);
    EXPECT_NEAR(simulated.si("time").back(), 6.0, 1e-12) << e.name;
    EXPECT_NEAR(simulated.si("displacement").back(), 0.3e-3, 1e-12) << e.name;  // the extensometer column
    for (double f : simulated.si("force")) EXPECT_TRUE(std::isfinite(f)) << e.name;
  }
  std::filesystem::remove_all(targets);
}

}  // namespace
}  // namespace dtwire::calibrate
