// `dtwire gap` end to end through the command line: outputs written and parsed back, exit codes
// and messages for bad input.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <random>
#include <sstream>

#include <nlohmann/json.hpp>

#include "cli.hpp"
#include "dtwire/core/csv.hpp"
#include "dtwire/gap/effects.hpp"
#include "dtwire/gap/synthetic_curves.hpp"

namespace dtwire::gap {
namespace {

namespace fs = std::filesystem;

fs::path scratch() {
  const fs::path dir = fs::temp_directory_path() / "dtwire_gap_cli_test";
  fs::create_directories(dir);
  return dir;
}

void save(const ForceCurve& c, const fs::path& path) {
  Curve curve;
  std::vector<double> mm;
  for (double u : c.u) mm.push_back(u * 1e3);
  curve.add_channel("displacement", *find_unit("mm"), mm);
  curve.add_channel("force", *find_unit("N"), c.f);
  write_csv(curve, path);
}

struct CommandResult {
  int code;
  std::string err;
};

CommandResult run(const std::vector<std::string>& args) {
  std::ostringstream captured;
  auto* old = std::cerr.rdbuf(captured.rdbuf());
  const int code = app::run_command_line(args);
  std::cerr.rdbuf(old);
  return {code, captured.str()};
}

class GapCli : public ::testing::Test {
 protected:
  void SetUp() override {
    const ForceCurve sim = voce_tension_curve();
    const ForceCurve model =
        apply_effects(sim, {{&find_effect("gauge_length"), {1.2}}}, curve_scale(sim));
    std::mt19937 rng(9);
    LabSampling s;
    s.points = 600;
    s.noise_sigma_N = 8.0;
    save(sim, dir / "sim.csv");
    save(sample_lab_curve(model, s, rng), dir / "lab1.csv");
    save(sample_lab_curve(model, s, rng), dir / "lab2.csv");
  }
  fs::path dir = scratch();
};

TEST_F(GapCli, WritesJsonAndReportThatParseBack) {
  const fs::path json = dir / "out" / "gap.json", report = dir / "out" / "gap.md";
  fs::remove(json);
  const CommandResult r = run({"gap", "--lab", (dir / "lab1.csv").string(), "--lab", (dir / "lab2.csv").string(),
                     "--sim", (dir / "sim.csv").string(), "--json", json.string(), "--report",
                     report.string()});
  ASSERT_EQ(r.code, 0) << r.err;
  std::ifstream in(json);
  const auto j = nlohmann::json::parse(in);
  EXPECT_EQ(j.at("cause"), "gauge_length");
  EXPECT_TRUE(j.at("predictive_check").at("done").get<bool>());
  EXPECT_TRUE(fs::exists(report));
}

TEST_F(GapCli, EffectsOptionRestrictsTheCandidates) {
  const fs::path json = dir / "restricted.json";
  const CommandResult r = run({"gap", "--lab", (dir / "lab1.csv").string(), "--sim", (dir / "sim.csv").string(),
                     "--effects", "strain_rate,coating_slip", "--json", json.string()});
  ASSERT_EQ(r.code, 0) << r.err;
  std::ifstream in(json);
  const auto j = nlohmann::json::parse(in);
  ASSERT_EQ(j.at("ranking").size(), 1u);
  EXPECT_EQ(j.at("ranking")[0].at("effect"), "strain_rate");
  EXPECT_EQ(j.at("not_tested"), nlohmann::json::array({"coating_slip"}));
}

TEST_F(GapCli, BadInputExitsTwoNamingTheFileAndWritesNothing) {
  std::ofstream(dir / "deg.csv") << "displacement_deg,force_N\n0,0\n1,5\n2,10\n";
  const fs::path json = dir / "never.json";
  fs::remove(json);
  const CommandResult r = run({"gap", "--lab", (dir / "deg.csv").string(), "--sim", (dir / "sim.csv").string(),
                     "--json", json.string()});
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("deg.csv"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("length"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(json));
  const CommandResult unknown = run({"gap", "--lab", (dir / "lab1.csv").string(), "--sim",
                           (dir / "sim.csv").string(), "--effects", "gravity"});
  EXPECT_EQ(unknown.code, 2);
  EXPECT_NE(unknown.err.find("gravity"), std::string::npos) << unknown.err;
}

TEST_F(GapCli, LabSummaryWritesTheContractAndRejectsBadFigures) {
  const fs::path json = dir / "summary.json";
  fs::remove(json);
  const CommandResult r = run({"gap", "--lab-summary", "peak_force_N=900:50,residual_force_N=700:40",
                               "--sim", (dir / "sim.csv").string(), "--effects", "strain_rate,coating_slip",
                               "--json", json.string()});
  ASSERT_EQ(r.code, 0) << r.err;
  std::ifstream in(json);
  const auto j = nlohmann::json::parse(in);
  for (const char* key : {"metric", "noise_floor", "gap_before", "where", "ranking", "cause"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j.at("metric"), "summary_z_rms");
  EXPECT_EQ(j.at("not_tested_reason").at("coating_slip"), "needs --model");
  for (const std::vector<std::string>& bad :
       {std::vector<std::string>{"--lab-summary", "peak_force_N=900"},
        std::vector<std::string>{"--lab-summary", "peak_force=900:50"},
        std::vector<std::string>{"--lab-summary", "peak_force_N=900:50", "--lab", (dir / "lab1.csv").string()}}) {
    std::vector<std::string> args = {"gap", "--sim", (dir / "sim.csv").string()};
    args.insert(args.end(), bad.begin(), bad.end());
    const CommandResult e = run(args);
    EXPECT_EQ(e.code, 2) << bad[1];
    EXPECT_NE(e.err.find("--lab-summary"), std::string::npos) << e.err;
  }
}

TEST_F(GapCli, PlotIsRenderedWhenPythonWithMatplotlibIsThere) {
  if (std::system("/usr/bin/python3 -c 'import matplotlib' >/dev/null 2>&1") != 0)
    GTEST_SKIP() << "python3-matplotlib not installed";
  const fs::path png = dir / "gap.png";
  fs::remove(png);
  const CommandResult r = run({"gap", "--lab", (dir / "lab1.csv").string(), "--sim", (dir / "sim.csv").string(),
                     "--plot", png.string()});
  ASSERT_EQ(r.code, 0) << r.err;
  ASSERT_TRUE(fs::exists(png));
  EXPECT_GT(fs::file_size(png), 10000u);
}

}  // namespace
}  // namespace dtwire::gap
