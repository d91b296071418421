// The FE experiments of fit (3) (experiments/sw_fe_fit/*.prm) drive the wire along the same
// paths as the macro-element's two-node driver in experiments/sw_fe_fit/macro_fit.toml: knot
// t = k / legs of an FE load path is waypoint k of the experiment's path, sub-knots lie on the
// legs, and with an end rotation the half model's top end turns by theta/2 and moves along the
// chord by a = ((L + u) sinc(theta/2) - L) / 2 (README.md there). Guards against editing one
// file and not the other.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "dtwire/calibrate/fit_file.hpp"
#include "dtwire/calibrate/law_replay.hpp"
#include "dtwire/calibrate/synthesize.hpp"

namespace dtwire::calibrate {
namespace {

const std::filesystem::path kFolder = std::filesystem::path(DTWIRE_SOURCE_DIR) / "experiments/sw_fe_fit";

// "set Key = value" entries of a ParameterHandler file (subsections ignored: keys are unique here).
std::map<std::string, std::string> prm_entries(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::map<std::string, std::string> out;
  std::string line;
  while (std::getline(in, line)) {
    const auto set = line.find("set ");
    const auto equals = line.find(" = ");
    if (line.rfind('#', 0) == 0 || set == std::string::npos || equals == std::string::npos) continue;
    out[line.substr(set + 4, equals - set - 4)] = line.substr(equals + 3);
  }
  return out;
}

std::vector<std::pair<double, double>> pairs(const std::string& text) {
  std::vector<std::pair<double, double>> out;
  std::istringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    const auto colon = item.find(':');
    out.emplace_back(std::stod(item.substr(0, colon)), std::stod(item.substr(colon + 1)));
  }
  return out;
}

double sinc(double x) { return x == 0.0 ? 1.0 : std::sin(x) / x; }

// Checks the experiments of `fit_file` whose target is an FE run of this folder (`prefix`: the
// folder of those runs under {targets}); returns how many.
std::size_t check_fe_knots(const std::filesystem::path& fit_file, const std::string& prefix) {
  FitReadOptions options;
  options.read_targets = false;
  const FitDefinition def = read_fit_file(fit_file, options);
  std::size_t checked = 0;
  for (std::size_t e = 0; e < def.experiments.size(); ++e) {
    const auto& name = def.experiment_target_names[e];
    if (name.filename() != "curve.csv") continue;  // not an FE run (the backbone)
    if (name.string().rfind(prefix, 0) != 0) continue;  // an FE run of another folder
    const auto prm = prm_entries(kFolder / (name.parent_path().filename().string() + ".prm"));
    SCOPED_TRACE(name.string());
    const auto* replay = dynamic_cast<const LawReplaySimulator*>(def.experiments[e].simulator.get());
    if (replay == nullptr) {
      ADD_FAILURE() << "not a law replay";
      continue;
    }
    const LoadPath& path = replay->path();
    const double multiplier = prm.at("Bottom end") == "symmetry" ? 2.0 : 1.0;
    const double length_mm = std::stod(prm.at("Length (mm)")) * multiplier;
    const auto load = pairs(prm.at("Load path (mm)"));
    const bool rotated = prm.count("Rotation path (deg)") > 0;
    const auto rotation = rotated ? pairs(prm.at("Rotation path (deg)")) : decltype(load){};
    if (rotated && rotation.size() != load.size()) {
      ADD_FAILURE() << rotation.size() << " rotation knots, " << load.size() << " load knots";
      continue;
    }
    const double legs = static_cast<double>(path.displacement_m.size() - 1);
    std::size_t waypoints = 0;
    for (std::size_t i = 0; i < load.size(); ++i) {
      const double t = load[i].first;
      const double s = t * legs;
      const std::size_t k = std::min<std::size_t>(static_cast<std::size_t>(std::floor(s + 1e-9)), path.displacement_m.size() - 2);
      const double f = s - static_cast<double>(k);
      waypoints += std::abs(f) < 1e-9 || std::abs(f - 1.0) < 1e-9;
      const double u_mm = 1e3 * (path.displacement_m[k] + f * (path.displacement_m[k + 1] - path.displacement_m[k]));
      const double theta = path.rotation_rad[k] + f * (path.rotation_rad[k + 1] - path.rotation_rad[k]);
      if (rotated) {
        EXPECT_NEAR(rotation[i].first, t, 1e-12);
        EXPECT_NEAR(rotation[i].second, 0.5 * theta * 180.0 / M_PI, 1e-8) << "t = " << t;
        EXPECT_NEAR(load[i].second, 0.5 * ((length_mm + u_mm) * sinc(0.5 * theta) - length_mm), 1e-8) << "t = " << t;
      } else {
        EXPECT_EQ(theta, 0.0);
        EXPECT_NEAR(load[i].second * multiplier, u_mm, 1e-9) << "t = " << t;
      }
    }
    EXPECT_EQ(waypoints, path.displacement_m.size()) << "every waypoint is a knot";
    ++checked;
  }
  return checked;
}

TEST(SwFeFitPaths, FeKnotsFollowTheDriverPaths) {
  EXPECT_EQ(check_fe_knots(kFolder / "macro_fit.toml", ""), 11u);
  // The segment fits replay the same FE runs ({targets}/sw_fe_fit/...), and the held-tension
  // bends (pull, then bend with the elongation held) only there.
  EXPECT_EQ(check_fe_knots(kFolder / "../segment/segment_fit.toml", "sw_fe_fit/"), 10u);
}

// Issue 20: the documented round trip `dtwire fit FILE --synthesize DIR` then `--targets DIR`
// stopped at a mapped column (axial_force) that no compared channel wrote.
TEST(ShippedFitFiles, SynthesizedTargetsReadBackThroughTheirMapping) {
  const std::filesystem::path targets = std::filesystem::temp_directory_path() / "dtwire_synthesized_round_trip";
  for (const auto& file : {kFolder / "macro_fit.toml"}) {  // the shipped file whose targets are {targets}/...
    std::filesystem::remove_all(targets);
    FitReadOptions synthesize;
    synthesize.read_targets = false;
    const FitDefinition def = read_fit_file(file, synthesize);
    EXPECT_EQ(write_synthetic_targets(def, targets, 0.0, 1, 81).size(), def.experiments.size()) << file;
    FitReadOptions read;
    read.targets_directory = targets;
    try {
      const FitDefinition back = read_fit_file(file, read);
      for (const Experiment& e : back.experiments) EXPECT_GE(e.target.size(), 3u) << file << ": " << e.name;
    } catch (const std::exception& error) {
      ADD_FAILURE() << file << ": " << error.what();
    }
  }
  std::filesystem::remove_all(targets);
}

}  // namespace
}  // namespace dtwire::calibrate
