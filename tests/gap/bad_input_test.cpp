// Bad inputs get InputErrors that name the file and say what was expected.
#include <gtest/gtest.h>

#include <filesystem>
#include <algorithm>
#include <cmath>
#include <fstream>
#include <random>

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

// Issue 20: a laboratory CSV with shuffled rows used to be read as dozens of load cycles.
TEST(GapRowOrder, ShuffledOrSortedRowsAreFlaggedRealTestsAreNot) {
  std::mt19937 random(7);
  std::normal_distribution<double> noise(0.0, 1e-6);
  ForceCurve monotone, cyclic, coarse_cyclic;
  monotone.source = "monotone.csv";
  for (int i = 0; i < 200; ++i) {
    const double u = 0.03 * i / 199.0;  // a tension test with a softening end
    monotone.u.push_back(u + noise(random));
    monotone.f.push_back(3000.0 * std::sin(3.0 * u / 0.03));
  }
  for (int i = 0; i < 2000; ++i) {  // 20 cycles of 100 rows, with a noisy displacement
    cyclic.u.push_back(0.005 * (1.0 - std::cos(2.0 * M_PI * i / 100.0)) + noise(random));
    cyclic.f.push_back(1000.0 * cyclic.u.back() / 0.01);
  }
  for (int i = 0; i < 60; ++i) {  // 5 cycles sampled at 12 rows each
    coarse_cyclic.u.push_back(0.005 * (1.0 - std::cos(2.0 * M_PI * i / 12.0)));
    coarse_cyclic.f.push_back(coarse_cyclic.u.back() * 1e5);
  }
  EXPECT_EQ(row_order_warning(monotone), "");
  EXPECT_EQ(row_order_warning(cyclic), "");
  EXPECT_EQ(row_order_warning(coarse_cyclic), "");

  ForceCurve shuffled = monotone;
  std::vector<std::size_t> order(shuffled.u.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::shuffle(order.begin(), order.end(), random);
  for (std::size_t i = 0; i < order.size(); ++i) {
    shuffled.u[i] = monotone.u[order[i]];
    shuffled.f[i] = monotone.f[order[i]];
  }
  const std::string warning = row_order_warning(shuffled);
  EXPECT_NE(warning.find("monotone.csv"), std::string::npos) << warning;
  EXPECT_NE(warning.find("order of the test"), std::string::npos) << warning;

  ForceCurve by_force = monotone;  // sorted by force: the softening branch interleaves
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return monotone.f[a] < monotone.f[b]; });
  for (std::size_t i = 0; i < order.size(); ++i) {
    by_force.u[i] = monotone.u[order[i]];
    by_force.f[i] = monotone.f[order[i]];
  }
  EXPECT_NE(row_order_warning(by_force), "");
}

}  // namespace
}  // namespace dtwire::gap
