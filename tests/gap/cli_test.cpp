// `dtwire gap` end to end through the command line: outputs written and parsed back, exit codes
// and messages for bad input.
#include <gtest/gtest.h>

#include <algorithm>
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

// Issue 37: a DEM punch against another DEM punch is not a wire test. A grip slip of metres
// was once named the cause; now only mesh effects apply, and they need the DEM model.
TEST_F(GapCli, APunchCurveGetsNoWireTestEffect) {
  const auto punch = [&](double stiffness, const fs::path& file) {
    Curve curve;
    std::vector<double> mm, force;
    for (int i = 0; i <= 200; ++i) {
      const double u = 3.0 * i;  // mm, to 0.6 m
      mm.push_back(u);
      force.push_back(u < 200.0 ? 0.0 : stiffness * (u - 200.0) * (u - 200.0));
    }
    curve.add_channel("tool_displacement", *find_unit("mm"), mm);
    curve.add_channel("tool_force", *find_unit("N"), force);
    curve.set_metadata("tool", "platter");
    write_csv(curve, file);
  };
  punch(0.3, dir / "punch_lab.csv");
  punch(0.6, dir / "punch_sim.csv");
  const fs::path json = dir / "punch_gap.json";
  const CommandResult r = run({"gap", "--lab", (dir / "punch_lab.csv").string(), "--sim", (dir / "punch_sim.csv").string(),
                               "--columns", "tool_displacement,tool_force", "--json", json.string()});
  ASSERT_EQ(r.code, 0) << r.err;
  std::ifstream in(json);
  const auto j = nlohmann::json::parse(in);
  EXPECT_EQ(j.at("cause"), "none");
  EXPECT_TRUE(j.at("ranking").empty());
  const auto& untested = j.at("not_tested");
  for (const char* name : {"grip_slip", "machine_compliance", "sw_softening"})
    EXPECT_NE(std::find(untested.begin(), untested.end(), name), untested.end()) << name;
}

// The same curve without its metadata reads as a tension test, but its 0.6 m of travel is no
// wire test's: the wire effects are still not tested.
TEST_F(GapCli, AWireEffectIsNotTestedFarOutsideAWireTestsDisplacements) {
  Curve lab, sim;
  std::vector<double> mm, f_lab, f_sim;
  for (int i = 0; i <= 200; ++i) {
    mm.push_back(3.0 * i);
    f_lab.push_back(20.0 * i);
    f_sim.push_back(30.0 * i);
  }
  lab.add_channel("displacement", *find_unit("mm"), mm);
  lab.add_channel("force", *find_unit("N"), f_lab);
  sim.add_channel("displacement", *find_unit("mm"), mm);
  sim.add_channel("force", *find_unit("N"), f_sim);
  write_csv(lab, dir / "long_lab.csv");
  write_csv(sim, dir / "long_sim.csv");
  const fs::path json = dir / "long_gap.json";
  const CommandResult r = run({"gap", "--lab", (dir / "long_lab.csv").string(), "--sim", (dir / "long_sim.csv").string(),
                               "--json", json.string()});
  ASSERT_EQ(r.code, 0) << r.err;
  std::ifstream in(json);
  const auto j = nlohmann::json::parse(in);
  EXPECT_EQ(j.at("cause"), "none");
  EXPECT_NE(j.at("not_tested_reason").at("grip_slip").get<std::string>().find("beyond a wire test"), std::string::npos);
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

// A compression curve of the same wire (signs turned), labelled by its CSV metadata.
void save_with_mode(const ForceCurve& c, const fs::path& path, const std::string& mode, double sign) {
  Curve curve;
  std::vector<double> mm, force;
  for (std::size_t i = 0; i < c.size(); ++i) {
    mm.push_back(sign * c.u[i] * 1e3);
    force.push_back(sign * c.f[i]);
  }
  curve.add_channel("displacement", *find_unit("mm"), mm);
  curve.add_channel("force", *find_unit("N"), force);
  if (!mode.empty()) curve.set_metadata("loading_mode", mode);
  write_csv(curve, path);
}

TEST_F(GapCli, SeveralLoadingModesGiveTheModesArrayAndCountsAreChecked) {
  const ForceCurve sim = voce_tension_curve();
  std::mt19937 rng(12);
  LabSampling s;
  s.points = 500;
  s.noise_sigma_N = 6.0;
  save_with_mode(sample_lab_curve(sim, s, rng), dir / "compression_lab.csv", "compression", -1.0);
  save_with_mode(sim, dir / "compression_sim.csv", "", -1.0);
  const fs::path json = dir / "modes.json";
  fs::remove(json);
  const std::string t1 = (dir / "lab1.csv").string(), t2 = (dir / "lab2.csv").string(),
                    c1 = (dir / "compression_lab.csv").string(), ts = (dir / "sim.csv").string(),
                    cs = (dir / "compression_sim.csv").string();
  const CommandResult r = run({"gap", "--lab", t1, "--lab", c1, "--lab", t2, "--sim", ts, "--sim", cs, "--sim", ts,
                               "--effects", "gauge_length,machine_compliance", "--json", json.string()});
  ASSERT_EQ(r.code, 0) << r.err;
  std::ifstream in(json);
  const auto j = nlohmann::json::parse(in);
  for (const char* key : {"metric", "noise_floor", "gap_before", "where", "ranking", "cause"})
    EXPECT_TRUE(j.contains(key)) << key;
  ASSERT_EQ(j.at("modes").size(), 2u);
  EXPECT_EQ(j.at("modes")[0].at("mode"), "tension");
  EXPECT_EQ(j.at("modes")[0].at("mode_basis"), "dominant force positive");
  EXPECT_EQ(j.at("modes")[0].at("curves"), nlohmann::json::array({t1, t2}));
  EXPECT_EQ(j.at("modes")[0].at("cause"), "gauge_length");
  EXPECT_EQ(j.at("modes")[1].at("mode"), "compression");
  EXPECT_EQ(j.at("modes")[1].at("mode_basis"), "metadata loading_mode");
  EXPECT_EQ(j.at("modes")[1].at("cause"), "none");
  EXPECT_EQ(j.at("modes")[1].at("not_tested_reason").at("gauge_length"), "does not apply to compression");
  EXPECT_EQ(j.at("cause"), "gauge_length");
  // --mode overrides the metadata: all three as tension share one simulation -> refused.
  const CommandResult overridden = run({"gap", "--lab", t1, "--lab", c1, "--sim", ts, "--sim", cs,
                                        "--mode", "tension,tension"});
  EXPECT_EQ(overridden.code, 2);
  EXPECT_NE(overridden.err.find("share one simulation"), std::string::npos) << overridden.err;

  // Mismatched counts and one simulation for two modes: exit 2 naming the option.
  const CommandResult two_for_three = run({"gap", "--lab", t1, "--lab", c1, "--lab", t2, "--sim", ts, "--sim", cs});
  EXPECT_EQ(two_for_three.code, 2);
  EXPECT_NE(two_for_three.err.find("--sim"), std::string::npos) << two_for_three.err;
  EXPECT_NE(two_for_three.err.find("2 simulations for 3 laboratory curves"), std::string::npos) << two_for_three.err;
  const CommandResult one_for_two_modes = run({"gap", "--lab", t1, "--lab", c1, "--sim", ts});
  EXPECT_EQ(one_for_two_modes.code, 2);
  EXPECT_NE(one_for_two_modes.err.find("2 loading modes (tension, compression)"), std::string::npos)
      << one_for_two_modes.err;
  const CommandResult bad_mode = run({"gap", "--lab", t1, "--sim", ts, "--mode", "twisting"});
  EXPECT_EQ(bad_mode.code, 2);
  EXPECT_NE(bad_mode.err.find("twisting"), std::string::npos) << bad_mode.err;
  const CommandResult modes_count = run({"gap", "--lab", t1, "--lab", c1, "--lab", t2, "--sim", ts, "--mode",
                                         "tension,compression"});
  EXPECT_EQ(modes_count.code, 2);
  EXPECT_NE(modes_count.err.find("--mode"), std::string::npos) << modes_count.err;
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
