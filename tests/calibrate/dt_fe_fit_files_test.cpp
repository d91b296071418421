// The shipped DT link fits (experiments/dt_fe_fit/dt_link_fit.toml, thesis law, and
// dt_link_fit_macro3d.toml) read against FE-like targets with the link columns the README
// documents, follow each target's rows and evaluate at their reference sets, so a renamed column
// or a broken path_from_target shows here and not only in a campaign run. At its reference
// (coupling 0, r_M = Nult/N0, the thesis DT set in radians) macro3d gives the thesis law's forces.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <vector>

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
  std::vector<std::vector<double>> forces[2];
  const char* files[2] = {"dt_link_fit.toml", "dt_link_fit_macro3d.toml"};
  for (int f = 0; f < 2; ++f) {
    SCOPED_TRACE(files[f]);
    const FitDefinition def = read_fit_file(kFolder / files[f], read);
    EXPECT_EQ(def.experiments.size(), 11u);
    ParameterValues reference;
    for (const auto& p : def.parameters) reference[p.name] = p.reference.value();
    for (const Experiment& e : def.experiments) {
      EXPECT_EQ(e.target.si("time"), (std::vector<double>{0, 1, 2, 3, 4, 5, 6})) << e.name;  // one waypoint per row
      const Curve simulated = e.simulator->simulate(reference);
      EXPECT_NEAR(simulated.si("time").back(), 6.0, 1e-12) << e.name;
      EXPECT_NEAR(simulated.si("displacement").back(), 0.3e-3, 1e-12) << e.name;  // the extensometer column
      for (double force : simulated.si("force")) EXPECT_TRUE(std::isfinite(force)) << e.name;
      forces[f].push_back(simulated.si("force"));
    }
  }
  // Same element at the reference: forces within 1 % of N0 (implicit return vs RK2(3)).
  ASSERT_EQ(forces[0].size(), forces[1].size());
  for (std::size_t e = 0; e < forces[0].size(); ++e)
    for (std::size_t k = 0; k < forces[0][e].size(); ++k) EXPECT_NEAR(forces[1][e][k], forces[0][e][k], 28.0) << e;
  std::filesystem::remove_all(targets);
}

}  // namespace
}  // namespace dtwire::calibrate
