// Issue 54: the campaign report shows the recommended set's mesh figures with their band
// (app/campaign/report_band.hpp), beside the standard's figures and the thesis sets' run, with
// the sensitivity rows that carry a share of the variance.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "campaign/report_band.hpp"
#include "campaign/report_mesh_scale.hpp"

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

  // The set's own runs: a figure no step bands is shown with its value and said to be unbanded
  // (the punch here, and the strip's stiffness); a banded one is not repeated.
  const json own_strip = {{"strength_per_width_kN_per_m", 43.6}, {"secant_EA_10_50_kN_per_m", 272.0}};
  const json own_punch = {{"peak_force_N", 90105.7}, {"displacement_at_peak_mm", 977.5}, {"onset_displacement_mm", 300.2}};
  const json thesis_punch = {{"peak_force_N", 66910.0}};
  const std::string unbanded =
      band_markdown("section + N-M fit", {{"dem_strip_nm_band", "section + N-M fit", "done", band_summary(false), {}}},
                    thesis_strip, thesis_punch, own_strip, own_punch);
  EXPECT_NE(unbanded.find("| punch peak force (kN) | 90.1 | not banded by this campaign |"), std::string::npos) << unbanded;
  EXPECT_NE(unbanded.find("| - | 66.9 |"), std::string::npos) << unbanded;
  EXPECT_NE(unbanded.find("| onset (1 kN) displacement (mm) | 300 | not banded"), std::string::npos) << unbanded;
  EXPECT_NE(unbanded.find("| secant EA per metre (10-50 % of the peak) (kN/m) | 272 | not banded"), std::string::npos) << unbanded;
  EXPECT_EQ(unbanded.find("| strength per metre (kN/m) | 43.6"), std::string::npos) << unbanded;

  // Another set's band, or none: no section.
  EXPECT_TRUE(band_markdown("straight-wire fit", {{"s", "section + N-M fit", "done", band_summary(true), {}}}, json(), json()).empty());
  // A band step that has not run is named.
  const std::string missing = band_markdown("section + N-M fit", {{"dem_strip_nm_band", "section + N-M fit", "blocked", json(), {}}}, json(), json());
  EXPECT_NE(missing.find("(no result: blocked)"), std::string::npos) << missing;
}

// A step that trained an emulator: its band is named beside the runs'; the mesh-scale band takes
// a converged runs' band first, then a converged emulated one, then the runs' band.
TEST(ReportBand, AnEmulatedBandIsShownAndTakenWhereItConvergedAndTheRunsDidNot) {
  json summary = band_summary(true);
  json& strength = summary["figures"][0];
  strength["converged"] = false;
  strength["emulated"] = {{"training_runs", 50}, {"loo_q_squared", 0.993}, {"band", {{"q05", 41.4}, {"q95", 61.7}}}};
  strength["emulator_converged"] = true;
  const std::vector<BandEvidence> bands = {{"dem_strip_nm_sampled", "section + N-M fit", "done", summary, {}}};
  const std::string md = band_markdown("section + N-M fit", bands, json(), json());
  EXPECT_NE(md.find("**not converged**; emulated 41.4 - 61.7 (Gaussian process on 50 runs, leave-one-out Q^2 0.99, converged)"),
            std::string::npos)
      << md;
  std::optional<FigureBand> band = figure_band(bands, "section + N-M fit", "strip_tension", "strength_per_width_kN_per_m");
  ASSERT_TRUE(band);
  EXPECT_TRUE(band->emulated);
  EXPECT_EQ(band->q05, 41.4);

  summary["figures"][0]["converged"] = true;  // the runs' own band converged: it is taken
  band = figure_band({{"dem_strip_nm_sampled", "section + N-M fit", "done", summary, {}}}, "section + N-M fit", "strip_tension",
                     "strength_per_width_kN_per_m");
  ASSERT_TRUE(band);
  EXPECT_TRUE(band->sampled);
  EXPECT_EQ(band->q05, 66.9);

  summary["figures"][0]["converged"] = false;  // neither converged: the runs' band
  summary["figures"][0]["emulator_converged"] = false;
  band = figure_band({{"dem_strip_nm_sampled", "section + N-M fit", "done", summary, {}}}, "section + N-M fit", "strip_tension",
                     "strength_per_width_kN_per_m");
  ASSERT_TRUE(band);
  EXPECT_TRUE(band->sampled);
}

// The mesh-scale table's punch cells of a set carry the band of its punch propagation (sampled
// before linearised), in the table's units (kN, m); a strip band's displacement_at_peak_mm (the
// same key) does not reach the punch's column, and another set's figures stay bare.
TEST(ReportBand, TheMeshScaleTableCarriesThePunchBand) {
  const json punch_summary = {{"label", "section + N-M fit"}, {"tool", "platter"}, {"onset_displacement_mm", 234.4},
                              {"peak_force_N", 56809.7}, {"displacement_at_peak_mm", 615.0}, {"sag_after_settling_mm", 96.6}};
  const json punch_band = {
      {"tool", "platter"},
      {"samples", {{"drawn", 40}}},
      {"figures",
       json::array({json{{"key", "peak_force_N"}, {"unit", "kN"}, {"fitted_set", 56.81},
                         {"linearised", {{"sd", 1.0}, {"q05", 55.2}, {"q95", 58.4}}},
                         {"sampled", {{"count", 38}, {"q05", 41.73}, {"q95", 60.21}}}},
                    json{{"key", "displacement_at_peak_mm"}, {"unit", "mm"}, {"fitted_set", 615.0},
                         {"linearised", {{"sd", 10.0}, {"q05", 598.6}, {"q95", 631.4}}}}})}};
  const json strip_band = {
      {"tool", "strip_tension"},
      {"figures", json::array({json{{"key", "displacement_at_peak_mm"}, {"unit", "mm"}, {"fitted_set", 50.0},
                                    {"linearised", {{"sd", 1.0}, {"q05", 48.4}, {"q95", 51.6}}}},
                               json{{"key", "strength_per_width_kN_per_m"}, {"unit", "kN/m"}, {"fitted_set", 71.4},
                                    {"linearised", {{"sd", 2.0}, {"q05", 68.1}, {"q95", 74.7}}}}})}};
  const std::vector<BandEvidence> bands = {{"dem_punch_nm_band", "section + N-M fit", "done", punch_band, {}},
                                           {"dem_strip_nm_band", "section + N-M fit", "done", strip_band, {}}};
  const std::vector<MeshScaleRun> runs = {{"section + N-M fit", "dem_punch_nm", "done", punch_summary},
                                          {"thesis published", "dem_punch_thesis", "done", punch_summary}};
  const std::string md = mesh_scale_table(runs, bands);
  EXPECT_NE(md.find("| section + N-M fit | 0.234 (+17 %) | 56.8 (+127 %) [5-95 %: 41.7 - 60.2] | "
                    "0.615 (+16 %) [5-95 %: 0.599 - 0.631, linearised] | 97 |"),
            std::string::npos) << md;
  EXPECT_NE(md.find("| thesis published | 0.234 (+17 %) | 56.8 (+127 %) | 0.615 (+16 %) | 97 |"), std::string::npos) << md;

  const auto peak = figure_band(bands, "section + N-M fit", "platter", "peak_force_N");
  ASSERT_TRUE(peak.has_value());
  EXPECT_TRUE(peak->sampled);
  EXPECT_EQ(peak->step, "dem_punch_nm_band");
  const auto elongation = figure_band(bands, "section + N-M fit", "strip_tension", "displacement_at_peak_mm");
  ASSERT_TRUE(elongation.has_value());
  EXPECT_DOUBLE_EQ(elongation->q05, 48.4);
  EXPECT_FALSE(figure_band(bands, "section + N-M fit", "platter", "onset_displacement_mm").has_value());
  // A step without a result bands nothing.
  EXPECT_FALSE(figure_band({{"dem_punch_nm_band", "section + N-M fit", "blocked", json(), {}}}, "section + N-M fit", "platter",
                           "peak_force_N").has_value());
}

// A linearised band that reaches 0 for a positive figure (the strip's secant of a set whose
// stiffness hangs on NOT IDENTIFIED parameters: 3258 kN/m, "-141 - 6657" before) is named not
// valid in both tables instead of printing a negative stiffness.
TEST(ReportBand, ALinearisedBandThatReachesZeroIsNamedNotValid) {
  const json strip_band = {
      {"tool", "strip_tension"},
      {"figures", json::array({json{{"key", "secant_EA_10_50_kN_per_m"}, {"unit", "kN/m"}, {"fitted_set", 3258.0},
                                    {"linearised", {{"sd", 2066.0}, {"q05", -141.0}, {"q95", 6657.0},
                                                    {"not_valid", "the first-order band reaches 0"}}}}})}};
  const std::vector<BandEvidence> bands = {{"dem_strip_nm_band", "section + N-M fit", "done", strip_band, {}}};
  const auto band = figure_band(bands, "section + N-M fit", "strip_tension", "secant_EA_10_50_kN_per_m");
  ASSERT_TRUE(band.has_value());
  EXPECT_FALSE(band->valid);
  const std::string md = band_markdown("section + N-M fit", bands, json(), json());
  EXPECT_EQ(md.find("-141 - 6657 | linearised"), std::string::npos) << md;
  EXPECT_NE(md.find("not valid (-141 - 6.66e+03) | linearised (J C J^T): the first-order band reaches 0"), std::string::npos) << md;
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
