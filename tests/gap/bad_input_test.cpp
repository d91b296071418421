// Bad inputs get InputErrors that name the file and say what was expected.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "dtwire/core/error.hpp"
#include "dtwire/gap/diagnosis.hpp"
#include "dtwire/gap/force_curve.hpp"
#include "dtwire/gap/synthetic_curves.hpp"

namespace dtwire::gap {
namespace {

std::filesystem::path write_file(const std::string& name, const std::string& text) {
  const auto dir = std::filesystem::temp_directory_path() / "dtwire_gap_bad_input";
  std::filesystem::create_directories(dir);
  const auto path = dir / name;
  std::ofstream(path) << text;
  return path;
}

// Runs `f`, expects an InputError whose message contains every fragment.
template <class F>
void expect_input_error(F f, const std::vector<std::string>& fragments) {
  try {
    f();
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    for (const auto& fragment : fragments)
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos)
          << "'" << e.what() << "' lacks '" << fragment << "'";
  }
}

TEST(GapBadInput, DisplacementInDegreesIsRefused) {
  const auto path = write_file("deg.csv", "displacement_deg,force_N\n0,0\n1,10\n2,20\n");
  expect_input_error([&] { load_force_curve(path, {}); },
                     {"deg.csv", "displacement_deg", "length", "angle"});
}

TEST(GapBadInput, ForceInMillimetresIsRefused) {
  const auto path = write_file("force_mm.csv", "displacement_mm,force_mm\n0,0\n1,10\n2,20\n");
  expect_input_error([&] { load_force_curve(path, {}); }, {"force_mm.csv", "force_mm", "force"});
}

TEST(GapBadInput, MissingColumnsAreNamed) {
  const auto path = write_file("cols.csv", "time_s,moment_Nm\n0,0\n1,10\n2,20\n");
  expect_input_error([&] { load_force_curve(path, {}); }, {"cols.csv", "displacement", "time_s"});
}

TEST(GapBadInput, StrainStressNeedsGaugeAndArea) {
  const auto path = write_file("ss.csv", "strain_1,stress_Pa\n0,0\n0.01,1e8\n0.02,2e8\n");
  expect_input_error([&] { load_force_curve(path, {}); }, {"ss.csv", "--gauge-mm", "--area-mm2"});
}

TEST(GapBadInput, SinglePointIsRefused) {
  const auto path = write_file("one.csv", "displacement_mm,force_N\n0,0\n");
  expect_input_error([&] { load_force_curve(path, {}); }, {"one.csv"});
  ForceCurve two{{0.0, 1e-3}, {0.0, 5.0}, "two points"};
  expect_input_error([&] { validate_force_curve(two); }, {"two points", "at least 3"});
}

TEST(GapBadInput, CurvesThatDoNotOverlapAreRefused) {
  ForceCurve lab = voce_tension_curve();
  lab.source = "lab.csv";
  ForceCurve sim = lab;
  sim.source = "sim.csv";
  for (double& u : sim.u) u += 1.0;  // 1 m further on: no common displacement
  expect_input_error([&] { diagnose({lab}, sim, {}); }, {"lab.csv", "sim.csv", "overlap"});
}

TEST(GapBadInput, ZeroForceIsRefused) {
  ForceCurve lab{{0.0, 1e-3, 2e-3}, {0.0, 0.0, 0.0}, "flat.csv"};
  ForceCurve sim = voce_tension_curve();
  expect_input_error([&] { diagnose({lab}, sim, {}); }, {"flat.csv", "zero"});
}

TEST(GapBadInput, UnknownEffectIsNamed) {
  EXPECT_THROW(find_effect("gravity"), std::invalid_argument);
  EXPECT_NO_THROW(find_effect("grip_slip"));
}

}  // namespace
}  // namespace dtwire::gap
