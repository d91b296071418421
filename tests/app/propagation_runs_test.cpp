// `dem propagate`'s runs (app/commands/propagation_runs.hpp): a punch that does not load the net
// to failure within the travel is a set whose figures the test does not measure, as the campaign
// report judges it (report_recommendation.hpp). Checked on run folders written into the cache by
// hand (the runner reads a finished folder without running dtwire).
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "commands/propagation_runs.hpp"
#include "dtwire/core/csv.hpp"
#include "dtwire/core/units.hpp"

namespace dtwire::app {
namespace {

// A finished punch run in the runner's cache folder for `files`: its force rises linearly to
// `peak_N` at `peak_m`, then falls to half of it at the travel's end (0.75 m).
void write_punch_run(const PropagationRunner& runner, const std::filesystem::path& cache,
                     const std::map<std::string, std::string>& files, double peak_m, double peak_N) {
  const std::filesystem::path run = cache / runner.key(files);
  std::filesystem::create_directories(run / "out");
  std::vector<double> x, f;
  for (int k = 0; k <= 750; ++k) {
    x.push_back(k / 1000.0);
    f.push_back(x.back() <= peak_m ? peak_N * x.back() / peak_m
                                   : peak_N * (1.0 - 0.5 * (x.back() - peak_m) / (0.75 - peak_m)));
  }
  Curve curve;
  curve.add_channel("tool_displacement", *find_unit("m"), x);
  curve.add_channel("tool_force", *find_unit("N"), f);
  write_csv(curve, run / "out" / "curve.csv");
  std::ofstream(run / "out" / "summary.json") << "{\"status\": \"ok\", \"tool\": \"platter\", \"peak_force_N\": " << peak_N
                                              << ", \"displacement_at_peak_mm\": " << 1e3 * peak_m
                                              << ", \"onset_displacement_mm\": 100.0}\n";
  std::ofstream(run / "finished") << "test\n";
}

TEST(PropagationRuns, APunchWithoutAPeakWithinTheTravelIsNotBanded) {
  const auto cache = std::filesystem::temp_directory_path() / ("dtwire_propagation_runs_" + std::to_string(::getpid()));
  std::filesystem::remove_all(cache);
  PropagationRunner runner(cache, {"dem", "run", "punch.toml"}, "test", headline_figures("platter"));
  const std::map<std::string, std::string> failing = {{"sw", "a set whose net fails at 0.6 m"}};
  const std::map<std::string, std::string> rising = {{"sw", "a set still rising at the travel's end"}};
  write_punch_run(runner, cache, failing, 0.6, 56000.0);
  write_punch_run(runner, cache, rising, 0.75, 80000.0);

  const RunOutcome measured = runner.run(failing, "failing");
  EXPECT_TRUE(measured.cached);
  EXPECT_TRUE(measured.ok) << measured.status;
  ASSERT_EQ(measured.figures.size(), 3u);
  EXPECT_DOUBLE_EQ(measured.figures[0], 56.0);  // kN

  const RunOutcome unmeasured = runner.run(rising, "rising");
  EXPECT_FALSE(unmeasured.ok);
  EXPECT_EQ(unmeasured.status.rfind("not applicable: no peak within the travel", 0), 0u) << unmeasured.status;
  EXPECT_EQ(runner.runs_done(), 0);  // both from the cache: no dtwire run
  std::filesystem::remove_all(cache);
}

}  // namespace
}  // namespace dtwire::app
