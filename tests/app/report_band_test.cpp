// Issue 54: the campaign report shows the recommended set's mesh figures with their band
// (app/campaign/report_band.hpp), beside the standard's figures and the thesis sets' run, with
// the sensitivity rows that carry a share of the variance.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "campaign/report_band.hpp"

namespace dtwire::app {
namespace {

using nlohmann::json;

json band_summary(bool sampled) {
  json strength = {{"key", "strength_per_width_kN_per_m"}, {"label", "strength per metre"}, {"unit", "kN/m"},
                   {"fitted_set", 71.4}, {"linearised", {{"sd", 2.0}, {"q05", 68.1}, {"q95", 74.7}}}};
  if (sampled) {
    strength["sampled"] = {{"count", 60}, {"mean", 71.0}, {"sd", 2.5}, {"q05", 66.9}, {"q95", 75.2}};
    strength["converged"] = true;
  }
  return {{"tool", "strip_tension"}, {"samples", {{"drawn", 60}}}, {"figures", json::array({strength})}};
}

std::vector<std::vector<std::string>> sensitivity_rows() {
  return {{"figure", "figure_unit", "parameter", "parameter_unit", "identified", "sampled_as", "coordinate",
           "derivative_figure_unit_per_parameter_unit", "linearised_share_1", "first_order_index_1", "first_order_index_floor_1"},
          {"strength_per_width_kN_per_m", "kN/m", "dt.Nult_N", "N", "yes", "normal", "linear", "0.012", "0.91", "0.88", "0.1"},
          {"strength_per_width_kN_per_m", "kN/m", "sw.k_M", "1/deg", "no", "uniform", "log", "0", "0.001", "0.11", "0.1"}};
}

TEST(ReportBand, TheRecommendedSetsFiguresWithTheirBandAndReferences) {
  const json thesis_strip = {{"strength_per_width_kN_per_m", 58.8}};
  const std::string linearised =
      band_markdown("section + N-M fit", {{"dem_strip_nm_band", "section + N-M fit", "done", band_summary(false), sensitivity_rows()}},
                    thesis_strip, json());
  EXPECT_NE(linearised.find("| strength per metre (kN/m) | 71.4 | 68.1 - 74.7 | linearised"), std::string::npos) << linearised;
  EXPECT_NE(linearised.find("| 50 kN/m | 58.8 |"), std::string::npos) << linearised;
  // The parameter that carries the variance is listed, the one at its index's floor is not.
  EXPECT_NE(linearised.find("dt.Nult_N (yes)"), std::string::npos) << linearised;
  EXPECT_EQ(linearised.find("sw.k_M"), std::string::npos) << linearised;

  const std::string sampled =
      band_markdown("section + N-M fit", {{"dem_strip_nm_sampled", "section + N-M fit", "done", band_summary(true), {}}},
                    thesis_strip, json());
  EXPECT_NE(sampled.find("66.9 - 75.2 | sampled, 60 runs of 60 drawn, converged; linearised 68.1 - 74.7"), std::string::npos)
      << sampled;

  // Another set's band, or none: no section.
  EXPECT_TRUE(band_markdown("straight-wire fit", {{"s", "section + N-M fit", "done", band_summary(true), {}}}, json(), json()).empty());
  // A band step that has not run is named.
  const std::string missing = band_markdown("section + N-M fit", {{"dem_strip_nm_band", "section + N-M fit", "blocked", json(), {}}}, json(), json());
  EXPECT_NE(missing.find("(no result: blocked)"), std::string::npos) << missing;
}

TEST(ReportBand, ReadsTheSensitivityCsv) {
  const auto file = std::filesystem::temp_directory_path() / ("dtwire_sensitivity_" + std::to_string(::getpid()) + ".csv");
  std::ofstream(file) << "figure,parameter,first_order_index_1\nstrength,dt.N0_N,\n";
  const auto rows = read_sensitivity_rows(file.string());
  ASSERT_EQ(rows.size(), 2u);
  ASSERT_EQ(rows[1].size(), 3u);  // the empty last cell is kept
  EXPECT_EQ(rows[1][1], "dt.N0_N");
  EXPECT_TRUE(read_sensitivity_rows("/nonexistent/sensitivity.csv").empty());
  std::filesystem::remove(file);
}

}  // namespace
}  // namespace dtwire::app
