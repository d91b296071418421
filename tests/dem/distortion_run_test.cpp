// `dtwire dem run` with the Thoeni et al. 2013 distortion (links.<type>.distortion): bad input
// exits 2 naming file:line and the field with nothing written; build_net gives link k the slack
// lambda_u l0 r_k (r_k YADE's k-th draw for the seed, 1 in constant mode), WirePM through its
// own shift (YADE's type 2), the other laws through DistortedLaw; the YADE script carries it.
#include <gtest/gtest.h>

#include "run_cli.hpp"

#include <cstdio>
#include <fstream>
#include <unistd.h>

#include "dtwire/core/error.hpp"
#include "dtwire/dem/run.hpp"
#include "dtwire/dem/wirepm.hpp"

namespace dtwire::dem {
namespace {

const std::string kData = std::string(DTWIRE_SOURCE_DIR) + "/experiments/data/";

std::string small_punch(const std::string& sw_extra, const std::string& dt_extra = "",
                        const std::string& dt_params = "wirepm_dt_2.7mm.json") {
  return "title = \"small distorted punch\"\n"
         "[mesh]\npattern = \"8x10_2.7mm\"\nwidth_m = 0.6\nheight_m = 0.6\n"
         "[links.sw]\nparams = \"" + kData + "wirepm_sw_2.7mm.json\"\nbackbone = \"" + kData + "sw_2.7mm_dem_backbone.csv\"\n" +
         sw_extra +
         "[links.dt]\nparams = \"" + kData + dt_params + "\"\nbackbone = \"" + kData + "sw_2.7mm_dem_backbone.csv\"\n" +
         dt_extra +
         "[tool]\nkind = \"platter\"\nbase_radius_m = 0.12\nheight_m = 0.05\ngap_m = 0.002\nspeed_m_per_s = 0.5\ntravel_m = 0.2\n";
}

std::filesystem::path scratch() {
  const auto dir = std::filesystem::temp_directory_path() / ("dtwire_dem_distortion_test_" + std::to_string(getpid()));
  std::filesystem::create_directories(dir);
  return dir;
}

std::filesystem::path write_input(const std::string& name, const std::string& text) {
  const auto path = scratch() / name;
  std::ofstream(path) << text;
  return path;
}

// The line (1-based) of the first occurrence of `key` in `text`.
int line_of(const std::string& text, const std::string& key) {
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(text.find(key)), '\n'));
}

void expect_bad_input(const std::string& name, const std::string& text, const std::string& field, const std::string& key) {
  const auto path = write_input(name, text);
  const auto out = scratch() / ("out_" + name);
  const auto [code, output] = test::run_dtwire("dem run " + path.string() + " -q -o " + out.string());
  EXPECT_EQ(code, 2) << output;
  EXPECT_NE(output.find(field), std::string::npos) << output;
  EXPECT_NE(output.find(name + ":" + std::to_string(line_of(text, key)) + ":"), std::string::npos) << output;
  EXPECT_FALSE(std::filesystem::exists(out)) << "nothing is written for a bad input";
}

TEST(DemRunDistortion, BadInputsExitTwoNamingFileLineAndField) {
  expect_bad_input("mode.toml", small_punch("distortion = \"wavy\"\ndistortion_lambda_u = 0.1\n"), "links.sw.distortion",
                   "distortion = ");
  expect_bad_input("one.toml", small_punch("distortion = \"constant\"\ndistortion_lambda_u = 1.0\n"),
                   "links.sw.distortion_lambda_u", "distortion_lambda_u");
  expect_bad_input("negative.toml", small_punch("", "distortion = \"constant\"\ndistortion_lambda_u = -0.1\n"),
                   "links.dt.distortion_lambda_u", "distortion_lambda_u");
  expect_bad_input("fraction.toml", small_punch("distortion = \"random\"\ndistortion_lambda_u = 0.1\ndistortion_seed = 3.5\n"),
                   "links.sw.distortion_seed", "distortion_seed");
  expect_bad_input("text.toml", small_punch("distortion = \"random\"\ndistortion_lambda_u = 0.1\ndistortion_seed = \"7\"\n"),
                   "links.sw.distortion_seed", "distortion_seed");
  expect_bad_input("zero.toml", small_punch("distortion = \"random\"\ndistortion_lambda_u = 0.1\ndistortion_seed = 0\n"),
                   "links.sw.distortion_seed", "distortion_seed");
  expect_bad_input("noeffect.toml", small_punch("distortion_lambda_u = 0.1\n"), "links.sw.distortion_lambda_u",
                   "distortion_lambda_u");
  expect_bad_input("seedconst.toml", small_punch("distortion = \"constant\"\ndistortion_lambda_u = 0.1\ndistortion_seed = 5\n"),
                   "links.sw.distortion_seed", "distortion_seed");
}

TEST(DemRunDistortion, EveryLinkGetsItsSlackFromTheSeedAsYadeDrawsIt) {
  const std::string random = "distortion = \"random\"\ndistortion_lambda_u = 0.2\ndistortion_seed = 2013\n";
  const RunInput input = read_run_input(write_input("random.toml", small_punch(random, random)));
  const BuiltNet built = build_net(input);
  const BuiltNet again = build_net(input);
  ASSERT_GT(built.links.size(), 50U);
  double smallest = 1.0, largest = 0.0;
  for (std::size_t k = 0; k < built.links.size(); ++k) {
    const auto& law = dynamic_cast<const WirePmLaw&>(*built.links[k].law);
    const NetLink& link = built.mesh.net.links[k];
    const double length = (built.mesh.net.nodes[link.b].position - built.mesh.net.nodes[link.a].position).norm();
    const double expected = 0.2 * length * yade_triangular_variate(2013, k);
    ASSERT_NEAR(law.backbone().shift, expected, 1e-15 * length) << "link " << k;  // tol: product order
    ASSERT_EQ(law.backbone().shift, dynamic_cast<const WirePmLaw&>(*again.links[k].law).backbone().shift);
    smallest = std::min(smallest, law.backbone().shift / length);
    largest = std::max(largest, law.backbone().shift / length);
    // lambda_F = 1 (YADE's default): the first segment runs from the origin to the shifted first point.
    ASSERT_EQ(law.backbone().points.size(), 8U) << "origin + the 7 backbone points, no soft point";
  }
  EXPECT_GE(smallest, 0.0);
  EXPECT_LE(largest, 0.2);
  EXPECT_LT(smallest, 0.05);  // the draws spread over [0, lambda_u]
  EXPECT_GT(largest, 0.15);
}

TEST(DemRunDistortion, ConstantModeShiftsEveryLinkByLambdaUTimesItsLength) {
  const std::string constant = "distortion = \"constant\"\ndistortion_lambda_u = 0.05\n";
  const BuiltNet built = build_net(read_run_input(write_input("constant.toml", small_punch(constant))));
  for (std::size_t k = 0; k < built.links.size(); ++k) {
    const NetLink& link = built.mesh.net.links[k];
    const double length = (built.mesh.net.nodes[link.b].position - built.mesh.net.nodes[link.a].position).norm();
    const double shift = dynamic_cast<const WirePmLaw&>(*built.links[k].law).backbone().shift;
    if (link.tag == LinkTag::SingleWire)
      ASSERT_NEAR(shift, 0.05 * length, 1e-15 * length) << "link " << k;
    else
      ASSERT_EQ(shift, 0.0) << "the dt set has no distortion";
  }
}

TEST(DemRunDistortion, MacroElementLinksAreWrappedWithTheSameSlack) {
  std::string text = small_punch("law = \"thesis\"\nwire_type = \"single_wire\"\ndistortion = \"random\"\n"
                                 "distortion_lambda_u = 0.1\ndistortion_seed = 7\n");
  const std::string sw_params = kData + "wirepm_sw_2.7mm.json";
  text.replace(text.find(sw_params), sw_params.size(), kData + "macroelement_thesis_params.json");
  const std::string backbone = "backbone = \"" + kData + "sw_2.7mm_dem_backbone.csv\"\n";
  text.erase(text.find(backbone), backbone.size());
  const auto path = write_input("thesis.toml", text);
  const BuiltNet built = build_net(read_run_input(path));
  std::size_t wrapped = 0;
  for (std::size_t k = 0; k < built.links.size(); ++k) {
    const NetLink& link = built.mesh.net.links[k];
    if (link.tag != LinkTag::SingleWire) continue;
    const auto* law = dynamic_cast<const DistortedLaw*>(built.links[k].law.get());
    ASSERT_NE(law, nullptr) << "link " << k;
    const double length = (built.mesh.net.nodes[link.b].position - built.mesh.net.nodes[link.a].position).norm();
    ASSERT_NEAR(law->slack(), 0.1 * length * yade_triangular_variate(7, k), 1e-15 * length);
    EXPECT_EQ(law->name(), "thesis");
    ++wrapped;
  }
  EXPECT_GT(wrapped, 20U);
  // Three nodes per wire: both halves of wire w take the wire's draw, each half its share of
  // the wire's slack (0.1 x half the length x r_w), so the wire's slack is the two-node mesh's.
  // (The dt links too take the thesis set: WirePM links cannot be split.)
  const std::string dt_params = kData + "wirepm_dt_2.7mm.json";
  text.replace(text.find(dt_params), dt_params.size(), kData + "macroelement_thesis_params.json");
  text.erase(text.find(backbone), backbone.size());
  text.insert(text.find("[links.dt]\n") + 11, "law = \"thesis\"\nwire_type = \"double_twist\"\n");
  const BuiltNet split = build_net(read_run_input(write_input("thesis_split.toml", text), {"mesh.nodes_per_wire=3"}));
  std::size_t halves = 0;
  for (std::size_t k = 0; k < split.links.size(); ++k) {
    const NetLink& link = split.mesh.net.links[k];
    if (link.tag != LinkTag::SingleWire) continue;
    const auto* law = dynamic_cast<const DistortedLaw*>(split.links[k].law.get());
    ASSERT_NE(law, nullptr) << "link " << k;
    ASSERT_EQ(link.parts, 2);
    const NetLink& whole = built.mesh.net.links[static_cast<std::size_t>(link.wire)];
    const double length = (built.mesh.net.nodes[whole.b].position - built.mesh.net.nodes[whole.a].position).norm();
    ASSERT_NEAR(law->slack(), 0.5 * 0.1 * length * yade_triangular_variate(7, static_cast<std::size_t>(link.wire)), 1e-15 * length);
    ++halves;
  }
  EXPECT_EQ(halves, 2 * wrapped);
}

TEST(DemRunDistortion, YadeScriptCarriesTypeTwoLambdauSeedAndOurSlacks) {
  const std::string random = "distortion = \"random\"\ndistortion_lambda_u = 0.04\ndistortion_seed = 2013\n";
  const RunInput input = read_run_input(write_input("yade.toml", small_punch(random, random, "wirepm_dt_2.7mm_own_curve.json")));
  const std::string script = yade_run_script(input);
  for (const char* piece : {"type=2", "strainStressValuesDT=strain_stress_dt", "lambdau=0.04, seed=2013, lambdaF=1",
                            "createInteraction(a, b)", "expected_slack = [", "raise SystemExit('YADE drew other slacks"})
    EXPECT_NE(script.find(piece), std::string::npos) << piece;
  const std::string constant = "distortion = \"constant\"\ndistortion_lambda_u = 0.04\n";
  const std::string constant_script =
      yade_run_script(read_run_input(write_input("yade_c.toml", small_punch(constant, constant, "wirepm_dt_2.7mm_own_curve.json"))));
  EXPECT_NE(constant_script.find("lambdau=0.04, seed=-1"), std::string::npos);
  // YADE cannot: a Bertrand double twist with a shift, or one distortion per link type.
  EXPECT_THROW(yade_run_script(read_run_input(write_input("bertrand.toml", small_punch(random, random)))), InputError);
  const std::string other_seed = "distortion = \"random\"\ndistortion_lambda_u = 0.04\ndistortion_seed = 2014\n";
  EXPECT_THROW(yade_run_script(read_run_input(
                   write_input("seeds.toml", small_punch(random, other_seed, "wirepm_dt_2.7mm_own_curve.json")))),
               InputError);
}

}  // namespace
}  // namespace dtwire::dem
