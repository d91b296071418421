// Cross-checks with Debian's YADE (slow): our WirePM against Law2_ScGeom_WirePhys_WirePM on the
// two-node pull-unload-reload-break path, and the script `dtwire export` writes against
// `dtwire dem driver`. Tolerance 0.5 % of the peak force at every sample, and 0.5 % relative
// wherever the force exceeds 1 % of the peak.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>

#include "dtwire/core/csv.hpp"
#include "dtwire/dem/driver.hpp"
#include "dtwire/dem/export.hpp"

namespace dtwire::dem {
namespace {

const std::string kBackbone = std::string(DTWIRE_SOURCE_DIR) + "/experiments/data/sw_2.7mm_dem_backbone.csv";

bool have_yade() { return std::system("command -v yade > /dev/null 2>&1") == 0; }

std::filesystem::path scratch(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("dtwire_dem_yade_" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

// Runs `command` in `dir`; returns its exit status and prints the wall time.
int run_timed(const std::string& what, const std::filesystem::path& dir, const std::string& command) {
  const auto start = std::chrono::steady_clock::now();
  const int status = std::system(("cd '" + dir.string() + "' && " + command + " > run.log 2>&1").c_str());
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::cout << "[ timing ] " << what << ": " << seconds << " s\n";
  return status;
}

void expect_same_force_history(const std::vector<double>& reference, const std::vector<double>& ours,
                               const std::string& label) {
  ASSERT_EQ(reference.size(), ours.size()) << label;
  double peak = 0.0;
  for (double f : reference) peak = std::max(peak, std::abs(f));
  ASSERT_GT(peak, 0.0) << label;
  double worst = 0.0;
  for (std::size_t i = 0; i < ours.size(); ++i) {
    const double error = std::abs(ours[i] - reference[i]);
    worst = std::max(worst, error / peak);
    ASSERT_LE(error, 5e-3 * peak) << label << " sample " << i;  // 0.5 % of the peak force
    if (std::abs(reference[i]) > 1e-2 * peak) {
      ASSERT_LE(error, 5e-3 * std::abs(reference[i])) << label << " sample " << i;  // 0.5 % relative
    }
  }
  EXPECT_EQ(ours.back(), 0.0) << label << ": the path ends past the break";
  EXPECT_EQ(reference.back(), 0.0) << label;
  std::cout << "[ result ] " << label << ": max |F_dtwire - F_yade| / F_peak = " << worst << "\n";
}

ParameterSet base_set() {
  ParameterSet set{"sw", "wirepm", {}};
  set.set("reference_length_m", 0.06);
  set.set("diameter_m", 0.0027);
  add_backbone(set, read_backbone_csv(kBackbone));
  return set;
}

struct YadeCase {
  std::string name;
  std::vector<std::pair<std::string, double>> changes;
};

class WirePmAgainstYade : public ::testing::TestWithParam<YadeCase> {};

TEST_P(WirePmAgainstYade, ForceHistoryMatchesOnPullUnloadReloadBreak) {
  if (!have_yade()) GTEST_SKIP() << "yade is not installed (scripts/setup installs it)";
  ParameterSet set = base_set();
  for (const auto& [name, value] : GetParam().changes) set.set(name, value);
  const ParameterMap parameters = set.map();
  PathOptions options = default_path_options("wirepm", parameters);  // pulls past the break
  options.steps = 1500;

  const auto dir = scratch(GetParam().name);
  write_yade_script(parameters, options, dir / "wirepm.py");
  ASSERT_EQ(run_timed("yade " + GetParam().name, dir, "yade -n -x wirepm.py yade.csv"), 0)
      << "see " << (dir / "run.log").string();
  const Curve yade = read_csv(dir / "yade.csv");

  const auto law = make_contact_law("wirepm", parameters);
  const Curve ours = replay_path(*law, yade_script_path(options));
  const auto u_yade = yade.si("axial_displacement"), u_ours = ours.si("axial_displacement");
  ASSERT_EQ(u_yade.size(), u_ours.size());
  for (std::size_t i = 0; i < u_ours.size(); ++i) ASSERT_NEAR(u_yade[i], u_ours[i], 1e-12);  // same samples [m]
  expect_same_force_history(yade.si("axial_force"), ours.si("axial_force"), GetParam().name);
}

INSTANTIATE_TEST_SUITE_P(
    Cases, WirePmAgainstYade,
    ::testing::Values(
        YadeCase{"single_wire", {}},
        YadeCase{"bertrand_double_twist",
                 {{"reference_length_m", 0.04}, {"double_twist", 1}, {"lambda_k", 0.66}, {"lambda_eps", 0.4},
                  {"poisson_1", 0.3}}},
        YadeCase{"thoeni_distortion", {{"lambda_u", 0.2}, {"lambda_F", 0.5}, {"seed", 2013}}},
        YadeCase{"own_double_twist_curve_shifted",
                 {{"reference_length_m", 0.04}, {"double_twist", 1}, {"double_twist_model", 1}, {"lambda_u", 0.2},
                  {"lambda_F", 0.0}, {"seed", -1}}}),
    [](const ::testing::TestParamInfo<YadeCase>& param_info) { return param_info.param.name; });

TEST(ExportedYadeScript, ReproducesTheDriverCurve) {
  if (!have_yade()) GTEST_SKIP() << "yade is not installed (scripts/setup installs it)";
  const auto dir = scratch("exported");
  {
    std::ofstream(dir / "params.json")
        << R"({"law": "wirepm", "wire_type": "sw_2_7mm", "parameters": {"reference_length_m": 0.06,
              "diameter_m": 0.0027, "lambda_u": 0.2, "lambda_F": 0.7, "seed": 99}})";
  }
  const std::string dtwire = DTWIRE_EXECUTABLE;
  const std::string common = " --params params.json --backbone '" + kBackbone + "' --steps 1200";
  ASSERT_EQ(run_timed("dtwire export", dir, "'" + dtwire + "' export" + common + " --out export"), 0);
  ASSERT_EQ(run_timed("dtwire dem driver", dir,
                      "'" + dtwire + "' dem driver --law wirepm --path cycles" + common + " --out driver"),
            0);
  ASSERT_EQ(run_timed("yade (exported script)", dir / "export", "yade -n -x sw_2_7mm_wirepm_yade.py"), 0);
  const Curve yade = read_csv(dir / "export" / "sw_2_7mm_wirepm_yade_force.csv");
  const Curve driver = read_csv(dir / "driver" / "cycles.csv");
  expect_same_force_history(yade.si("axial_force"), driver.si("axial_force"), "exported script vs driver");
}

}  // namespace
}  // namespace dtwire::dem
