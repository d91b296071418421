// Output of a finished fit: parameters.json in the format `dtwire export` reads, the HDF5
// results store with sigma, the curve CSVs and the report.
#include <gtest/gtest.h>

#include <filesystem>
#include <algorithm>
#include <fstream>
#include <iterator>

#include <nlohmann/json.hpp>

#include "dtwire/calibrate/fit_file.hpp"
#include "dtwire/calibrate/fit_output.hpp"
#include "dtwire/calibrate/voce_bar.hpp"
#include "dtwire/core/csv.hpp"
#include "dtwire/core/results_store.hpp"

namespace dtwire::calibrate {
namespace {

TEST(FitOutput, JsonAndHdf5HoldValuesUnitsSigmaCovarianceQuality) {
  const auto dir = std::filesystem::temp_directory_path() / "dtwire_fit_output_test";
  std::filesystem::remove_all(dir);
  FitDefinition def;
  def.file = dir / "fit.toml";
  def.law = "voce_bar";
  def.wire_type = "single_wire";
  def.fixed = {{"W1_J", 9.21}};
  def.parameters = {{"E_Pa", "Pa", 150e9, 50e9, 400e9, 0.0, 200e9},
                    {"sigma_y0_Pa", "Pa", 250e6, 50e6, 800e6, 0.0, std::nullopt},
                    {"Q_Pa", "Pa", 100e6, 0.0, 500e6, 0.0, std::nullopt},
                    {"b_1", "1", 10.0, 0.5, 200.0, 0.0, std::nullopt}};
  auto simulator = std::make_shared<VoceBarSimulator>(std::vector<double>{0.0, 0.02, 0.01, 0.04}, 40);
  Experiment e;
  e.name = "cyclic";
  e.simulator = simulator;
  // Noise-free target made by the same model: small (rounded) residuals, finite covariance.
  const Curve clean = simulator->simulate({{"E_Pa", 200e9}, {"sigma_y0_Pa", 300e6}, {"Q_Pa", 150e6}, {"b_1", 20.0}});
  std::vector<double> stress = clean.channel("stress").values;
  for (std::size_t i = 0; i < stress.size(); ++i) stress[i] += (i % 2 ? 1e6 : -1e6);
  e.target.add_channel("strain", *find_unit("1"), clean.channel("strain").values);
  e.target.add_channel("stress", *find_unit("Pa"), stress);
  e.abscissa = "strain";
  e.channels = {{"stress", 1.0, 0.0}};
  e.peaks = {{"stress", 1.0, 0.0}};
  def.experiments = {e};
  ProblemEvaluator evaluator(def.experiments, def.parameters, EvaluationOptions{});
  FitOptions options;
  options.polish_relative_step = 1e-2;
  const FitResult result = run_fit(evaluator, options);
  write_fit_outputs(def, result, make_provenance("test"), dir);

  std::ifstream in(dir / "parameters.json");
  const auto json = nlohmann::json::parse(in);
  EXPECT_EQ(json["law"], "voce_bar");
  EXPECT_EQ(json["wire_type"], "single_wire");
  ASSERT_EQ(json["parameters"].size(), 5u);  // 4 fitted + 1 fixed
  EXPECT_EQ(json["parameters"][0]["name"], "E_Pa");
  EXPECT_EQ(json["parameters"][0]["unit"], "Pa");
  EXPECT_EQ(json["parameters"][0]["value"].get<double>(), result.values[0]);
  EXPECT_EQ(json["parameters"][0]["sigma"].get<double>(), result.sigma[0]);
  EXPECT_EQ(json["parameters"][0]["lower"].get<double>(), 50e9);
  EXPECT_EQ(json["parameters"][0]["reference"].get<double>(), 200e9);
  EXPECT_EQ(json["parameters"][4]["name"], "W1_J");
  EXPECT_EQ(json["parameters"][4]["unit"], "J");
  EXPECT_TRUE(json["parameters"][4]["sigma"].is_null());
  EXPECT_EQ(json["covariance"].size(), 4u);
  EXPECT_EQ(json["correlation"][0][0].get<double>(), 1.0);
  ASSERT_EQ(json["fit_quality"].size(), 1u);
  EXPECT_TRUE(std::filesystem::exists(dir / json["fit_quality"][0]["fitted_csv"].get<std::string>()));
  EXPECT_TRUE(json["provenance"].contains("git_hash"));
  ASSERT_EQ(json["fit_peaks"].size(), 1u);
  EXPECT_EQ(json["fit_peaks"][0]["quantity"], "stress");
  EXPECT_NEAR(json["fit_peaks"][0]["target"].get<double>(), *std::max_element(stress.begin(), stress.end()), 1.0);
  EXPECT_NEAR(json["fit_peaks"][0]["fitted"].get<double>(), json["fit_peaks"][0]["target"].get<double>(), 5e6)
      << "the fit meets the peak within the target's +-1 MPa noise and its own misfit";

  const Results stored = read_results(dir / "parameters.h5");
  ASSERT_EQ(stored.parameters.size(), 5u);
  EXPECT_EQ(stored.parameters[0].name, "E_Pa");
  EXPECT_EQ(stored.parameters[0].value, result.values[0]);
  ASSERT_TRUE(stored.parameters[0].sigma.has_value());
  EXPECT_EQ(*stored.parameters[0].sigma, result.sigma[0]);
  EXPECT_EQ(stored.curves.size(), 2u);  // target and fitted
  std::ifstream report_in(dir / "fit_report.md");
  const std::string report((std::istreambuf_iterator<char>(report_in)), std::istreambuf_iterator<char>());
  EXPECT_NE(report.find("| cyclic | stress |"), std::string::npos) << report;
  EXPECT_NE(report.find("Peaks (the target's value"), std::string::npos) << report;
  // The polish, whether taken or not, with its costs (FitOptions::polish_relative_step).
  ASSERT_TRUE(json.contains("polish"));
  EXPECT_EQ(json["polish"]["relative_step"].get<double>(), 1e-2);
  EXPECT_EQ(json["polish"]["cost_before"].get<double>(), result.polish.cost_before);
  EXPECT_EQ(json["polish"]["taken"].get<bool>(), result.polish.taken);
  EXPECT_LE(result.cost, result.polish.cost_before);
  EXPECT_NE(report.find("Polish (finite-difference step"), std::string::npos) << report;
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace dtwire::calibrate
