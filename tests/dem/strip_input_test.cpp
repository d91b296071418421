// `dtwire dem run` with `[tool] kind = "strip_tension"`: bad strip inputs exit 2 naming
// file:line and the field, and write nothing.
#include <gtest/gtest.h>

#include "run_cli.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>

namespace {

const std::string kData = std::string(DTWIRE_SOURCE_DIR) + "/experiments/data/";

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  if (at == std::string::npos) throw std::logic_error("test text has no " + from);
  return text.replace(at, from.size(), to);
}

std::string strip(const std::string& replace_from = "", const std::string& replace_to = "") {
  std::string text = "[mesh]\npattern = \"8x10_2.7mm\"\nwidth_m = 1.0\nheight_m = 1.0\n"
                     "[links.sw]\nparams = \"" + kData + "wirepm_sw_2.7mm.json\"\nbackbone = \"" + kData + "sw_2.7mm_dem_backbone.csv\"\n"
                     "[links.dt]\nparams = \"" + kData + "wirepm_dt_2.7mm.json\"\nbackbone = \"" + kData + "sw_2.7mm_dem_backbone.csv\"\n"
                     "[dynamics]\ngravity_m_per_s2 = 0.0\nlocal_damping = 0.5\nmass_scale = 100\n"
                     "[tool]\nkind = \"strip_tension\"\ndirection = \"along_twists\"\nclamp_depth_m = 0.1\n"
                     "speed_m_per_s = 0.5\ntravel_m = 0.01\n";
  return replace_from.empty() ? text : replaced(text, replace_from, replace_to);
}

struct Outcome {
  int code;
  std::string output;
};

// Runs the input; the output folder must stay absent.
Outcome run_strip(const std::string& name, const std::string& text) {
  const auto dir = std::filesystem::temp_directory_path() / "dtwire_strip_input_test";
  std::filesystem::create_directories(dir);
  const auto path = dir / name;
  std::ofstream(path) << text;
  const auto out = dir / ("out_" + name);
  std::filesystem::remove_all(out);
  const dtwire::dem::test::CliOutcome outcome = dtwire::dem::test::run_dtwire("dem run " + path.string() + " -q -o " + out.string());
  EXPECT_FALSE(std::filesystem::exists(out)) << name << ": wrote " << out;
  return {outcome.code, outcome.output};
}

void expect_bad_strip(const std::string& name, const std::string& text, const std::string& where) {
  const Outcome o = run_strip(name, text);
  EXPECT_EQ(o.code, 2) << o.output;
  EXPECT_NE(o.output.find(where), std::string::npos) << "expected '" << where << "' in: " << o.output;
}

TEST(DemStripInput, BadStripInputsExitTwoNamingTheLineAndField) {
  // Clamps deeper than half the strip (1.0 m along the pull); line 18, column 17 of the input.
  expect_bad_strip("deep.toml", strip("clamp_depth_m = 0.1", "clamp_depth_m = 0.5"), "deep.toml:18:17: tool.clamp_depth_m");
  // Across the twists the strip is 1.0 m long along x (mesh.width_m).
  expect_bad_strip("deep_across.toml",
                   strip("direction = \"along_twists\"\nclamp_depth_m = 0.1", "direction = \"across_twists\"\nclamp_depth_m = 0.6"),
                   "tool.clamp_depth_m");
  // Narrower than one opening across the pull: D = 80 mm along the twists, H = 100 mm across.
  expect_bad_strip("narrow.toml", strip("width_m = 1.0", "width_m = 0.06"), "mesh.width_m");
  expect_bad_strip("narrow_across.toml",
                   replaced(strip("height_m = 1.0", "height_m = 0.09"), "along_twists", "across_twists"),
                   "mesh.height_m");
  expect_bad_strip("direction.toml", strip("along_twists", "diagonal"), "tool.direction");
  expect_bad_strip("travel.toml", strip("travel_m = 0.01\n", ""), "tool.travel_m");
  expect_bad_strip("depth.toml", strip("clamp_depth_m = 0.1\n", ""), "tool.clamp_depth_m");
  expect_bad_strip("negative.toml", strip("clamp_depth_m = 0.1", "clamp_depth_m = -0.1"), "tool.clamp_depth_m");
  // The clamps are the boundary; the edges along the pull are free.
  expect_bad_strip("pinned.toml", strip("[tool]", "[boundary]\npinned = [\"left\"]\n[tool]"), "boundary.pinned");
  expect_bad_strip("pretension.toml", strip("[tool]", "[boundary]\npretension_strain = 1e-4\n[tool]"),
                   "boundary.pretension_strain");
  // Platter keys do not apply to the strip; strip keys do not apply to the platter.
  expect_bad_strip("platter_key.toml", strip("travel_m = 0.01", "travel_m = 0.01\nbase_radius_m = 0.5"), "tool.base_radius_m");
  expect_bad_strip("punch_key.toml", strip("kind = \"strip_tension\"", "kind = \"platter\""), "tool.direction");
  // The nominal 0.9 m panel ends its nodes at 0.88 m: 2 x 0.445 m clamps leave nothing free.
  expect_bad_strip("no_free.toml", replaced(strip("height_m = 1.0", "height_m = 0.9"), "clamp_depth_m = 0.1", "clamp_depth_m = 0.445"),
                   "tool.clamp_depth_m");
}

}  // namespace
