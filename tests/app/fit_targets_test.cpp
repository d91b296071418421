// dtwire fit --targets DIR and --synthesize with target_columns: synthetic FE-like targets
// (an FE half model's column names and half rotation) are written below a targets directory,
// read back through the same mapping and fitted; bad uses exit with code 2 and say why.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "run_dtwire.hpp"

namespace {

using dtwire::test::run;

class FitTargets : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("dtwire_fit_targets_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  std::string write_definition(const std::string& bend_target) {
    const auto thesis = std::filesystem::path(DTWIRE_SOURCE_DIR) / "experiments/data/macroelement_thesis_params.json";
    std::ofstream(dir_ / "fit.toml")
        << "wire_type = \"single_wire\"\n"
           "[simulator]\n"
           "kind = \"law_replay\"\n"
           "law = \"thesis\"\n"
           "fixed_parameters_file = \"" << thesis.string() << "\"\n"
           "fixed_parameters_section = \"single_wire\"\n"
           "[[parameter]]\n"
           "name = \"EI_Nm2_per_deg_convention\"\n"
           "initial = 0.09\nlower = 0.01\nupper = 1\nreference = 0.122\n"
           "[[parameter]]\n"
           "name = \"N0_N\"\n"
           "initial = 2400\nlower = 500\nupper = 3100\nreference = 2750\n"
           "[[experiment]]\n"
           "name = \"pull\"\n"
           "target = \"{targets}/pull/curve.csv\"\n"  // line 21
           "channels = [\"force\"]\n"
           "path_displacement_mm = [0, 1]\n"
           "[[experiment]]\n"
           "name = \"bend\"\n"
           "target = \"" << bend_target << "\"\n"
           "target_columns = {force = \"axial_force\", rotation = {column = \"rotation\", factor = 2}}\n"
           "abscissa = \"rotation\"\n"
           "channels = [\"moment\", \"force\"]\n"
           "path_displacement_mm = [0, 0.2]\n"
           "path_rotation_deg = [0, 10]\n";
    return (dir_ / "fit.toml").string();
  }

  std::filesystem::path dir_;
};

std::string header_of(const std::filesystem::path& csv) {
  std::ifstream in(csv);
  std::string line;
  while (std::getline(in, line))
    if (!line.empty() && line[0] != '#') return line;
  return "";
}

TEST_F(FitTargets, SynthesizedTargetsReadBackThroughTheMapping) {
  const std::string toml = write_definition("{targets}/bend/curve.csv");
  const auto targets = dir_ / "targets";
  auto r = run("fit " + toml + " --synthesize " + targets.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  // Written as the FE half model writes them: axial_force_N, half rotation.
  EXPECT_EQ(header_of(targets / "bend/curve.csv"), "rotation_rad,displacement_mm,moment_Nm,axial_force_N");
  EXPECT_EQ(header_of(targets / "pull/curve.csv"), "displacement_mm,rotation_rad,force_N");

  const auto out = dir_ / "out";
  r = run("fit " + toml + " --targets " + targets.string() + " --out " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::ifstream in(out / "parameters.json");
  const auto result = nlohmann::json::parse(in);
  // Noise-free targets at the reference values: recovered (relative 1e-4).
  for (const auto& p : result["parameters"]) {
    if (!p["fitted"].get<bool>()) continue;
    EXPECT_NEAR(p["value"].get<double>(), p["reference"].get<double>(), 1e-4 * p["reference"].get<double>())
        << p["name"];
  }
  EXPECT_NE(result["provenance"]["command"].get<std::string>().find("--targets"), std::string::npos);
  EXPECT_EQ(result["provenance"]["inputs"].count((targets / "bend/curve.csv").string()), 1u);
}

TEST_F(FitTargets, InitialStartsFromAnEarlierFitAndRefusesValuesOutsideTheBounds) {
  const std::string toml = write_definition("{targets}/bend/curve.csv");
  const auto targets = dir_ / "targets";
  ASSERT_EQ(run("fit " + toml + " --synthesize " + targets.string()).exit_code, 0);
  const auto first = dir_ / "first";
  ASSERT_EQ(run("fit " + toml + " --targets " + targets.string() + " --out " + first.string()).exit_code, 0);
  const auto second = dir_ / "second";
  auto r = run("fit " + toml + " --targets " + targets.string() + " --initial " + (first / "parameters.json").string() +
               " --out " + second.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("initial values of 2 of 2 parameters"), std::string::npos) << r.output;
  std::ifstream in_first(first / "parameters.json"), in_second(second / "parameters.json");
  const auto a = nlohmann::json::parse(in_first), b = nlohmann::json::parse(in_second);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(b["parameters"][i]["name"], a["parameters"][i]["name"]);
    EXPECT_DOUBLE_EQ(b["parameters"][i]["initial"].get<double>(), a["parameters"][i]["value"].get<double>());
  }
  EXPECT_NE(b["provenance"]["command"].get<std::string>().find("--initial"), std::string::npos);
  std::ofstream(dir_ / "outside.json") << R"({"parameters": [{"name": "N0_N", "value": 9000}]})";
  r = run("fit " + toml + " --targets " + targets.string() + " --initial " + (dir_ / "outside.json").string() +
          " --out " + (dir_ / "third").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("outside.json"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("N0_N"), std::string::npos) << r.output;
}

TEST_F(FitTargets, PlaceholderWithoutTargetsExitsTwoNamingTheLine) {
  const std::string toml = write_definition("{targets}/bend/curve.csv");
  const auto r = run("fit " + toml + " --out " + (dir_ / "out").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("fit.toml:21"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("--targets DIR"), std::string::npos) << r.output;
}

TEST_F(FitTargets, MissingTargetsDirectoryExitsTwo) {
  const std::string toml = write_definition("{targets}/bend/curve.csv");
  const auto r = run("fit " + toml + " --targets " + (dir_ / "absent").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--targets"), std::string::npos) << r.output;
}

TEST_F(FitTargets, SynthesizeRefusesTwoExperimentsWritingOneFile) {
  const std::string toml = write_definition("{targets}/pull/curve.csv");
  const auto r = run("fit " + toml + " --synthesize " + (dir_ / "targets").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("same target name pull/curve.csv"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir_ / "targets"));
}

}  // namespace
