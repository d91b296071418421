// The WirePM punch in our engine and in YADE (the script our exporter writes, run unchanged),
// with the platter as one sphere in YADE (both codes have the exact hemisphere): the peak force
// and its travel within 2 %, the force within 2 % of the peak at every travel up to the first of
// the two peaks (issue 55's goal) and on past it while no link has broken in either code, and the
// first broken link in the same output row or the next (the resolution of both curves). After
// that the links fail in cascades whose order differs between the codes (broken counts at the end
// are printed, not compared). The force on the platter is not reproducible to better than the
// chatter of the nodes riding on it: our own run with the platter's start 1 nm lower departs from
// the first by up to 3 % of the peak in the Bertrand case (peak 23 kN), so each case also runs
// that perturbed copy and the force bound is the larger of 2 % and that spread.
// experiments/dem/punch_yade_check.toml: a 1.6 x 1.6 m panel (not the 3 x 3 m of the thesis) so
// that both codes finish in minutes; punch_yade_distortion_check.toml: the same with the
// double twist's own curve and the Thoeni et al. 2013 random distortion, run here at
// lambda_u = 0, 0.04 and 0.08 with two seeds. The facet platter of the semi-spheroid departs
// from the exact one by up to 8 % near the peak while the nets agree link by link
// (docs/dem_engine.md, "The YADE export"); it is not what these tests compare.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <iostream>

#include "dtwire/core/csv.hpp"
#include "dtwire/dem/run.hpp"

namespace dtwire::dem {
namespace {

double interpolate(const std::vector<double>& x, const std::vector<double>& y, double at) {
  for (std::size_t i = 1; i < x.size(); ++i)
    if (x[i] >= at) return y[i - 1] + (y[i] - y[i - 1]) * (at - x[i - 1]) / (x[i] - x[i - 1]);
  return y.back();
}

std::size_t peak_index(const std::vector<double>& f) {
  std::size_t peak = 0;
  for (std::size_t i = 0; i < f.size(); ++i)
    if (f[i] > f[peak]) peak = i;
  return peak;
}

// Index of the first row with a broken link; the row count if none broke.
std::size_t first_failure(const std::vector<double>& broken) {
  for (std::size_t i = 0; i < broken.size(); ++i)
    if (broken[i] > 0.0) return i;
  return broken.size();
}

struct PunchCase {
  const char* name;
  const char* input;  // experiments/dem
  double lambda_u;    // distortion of both link types (distortion input only); 0: none
  int seed;
};

// Runs the case in both codes and compares the curves as above; returns YADE's log.
std::string expect_punch_agrees_with_yade(const PunchCase& c) {
  const std::filesystem::path input_file = std::string(DTWIRE_SOURCE_DIR) + "/experiments/dem/" + c.input;
  RunInput input = read_run_input(input_file);
  const bool distortion_input = std::string(c.input) == "punch_yade_distortion_check.toml";
  if (distortion_input)
    for (LinkTag tag : {LinkTag::SingleWire, LinkTag::DoubleTwist}) {
      Distortion& distortion = input.link_sets.at(tag).distortion;
      distortion = c.lambda_u > 0.0 ? Distortion{DistortionMode::Random, c.lambda_u, c.seed} : Distortion{};
    }
  const auto dir = std::filesystem::temp_directory_path() / (std::string("dtwire_punch_yade_") + c.name);
  std::filesystem::create_directories(dir);
  RunOptions options;
  options.out = dir / "ours";
  options.quiet = true;
  options.write_frames = false;
  options.threads = 2;
  const RunSummary ours = run_simulation(input, options);
  EXPECT_FALSE(ours.failed.has_value()) << (ours.failed ? ours.failed->message() : std::string());
  RunInput perturbed_input = input;
  perturbed_input.start_gap += 1e-9;
  RunOptions perturbed_options = options;
  perturbed_options.out = dir / "ours_perturbed";
  const RunSummary perturbed = run_simulation(perturbed_input, perturbed_options);

  const auto script = dir / "punch_yade.py";
  std::ofstream(script) << yade_run_script(input);  // a hemisphere: the sphere platter
  const auto yade_csv = dir / "yade.csv";
  const std::string command = "cd " + dir.string() + " && yade -j1 -n -x " + script.string() + " " + yade_csv.string() + " > yade.log 2>&1";
  EXPECT_EQ(std::system(command.c_str()), 0) << "see " << (dir / "yade.log").string();
  std::ifstream log_file(dir / "yade.log");
  const std::string log((std::istreambuf_iterator<char>(log_file)), std::istreambuf_iterator<char>());
  if (!std::filesystem::exists(yade_csv)) return log;
  const Curve yade = read_csv(yade_csv);

  const std::vector<double> d_ours = ours.history.channel("tool_displacement").values;
  const std::vector<double> f_ours = ours.history.channel("tool_force").values;
  const std::vector<double> b_ours = ours.history.channel("broken_links").values;
  const std::vector<double> d_yade = yade.channel("tool_displacement").values;
  const std::vector<double> f_yade = yade.channel("tool_force").values;
  const std::vector<double> b_yade = yade.channel("broken_links").values;
  const std::size_t p_ours = peak_index(f_ours), p_yade = peak_index(f_yade);
  const double peak = f_ours[p_ours];
  const std::vector<double> d_perturbed = perturbed.history.channel("tool_displacement").values;
  const std::vector<double> f_perturbed = perturbed.history.channel("tool_force").values;
  double spread = 0.0;  // ours against ours perturbed, up to our peak
  for (std::size_t i = 0; i <= p_ours; ++i)
    spread = std::max(spread, std::abs(interpolate(d_perturbed, f_perturbed, d_ours[i]) - f_ours[i]));
  const double bound = std::max(0.02 * peak, spread);
  const double first_peak = std::min(d_ours[p_ours], d_yade[p_yade]);
  const std::size_t failure_ours = first_failure(b_ours), failure_yade = first_failure(b_yade);
  // Past the peak: up to the last row before the first broken link in either code.
  const double intact = std::min(failure_ours > 0 ? d_ours[failure_ours - 1] : 0.0, failure_yade > 0 ? d_yade[failure_yade - 1] : 0.0);
  double worst_before = 0.0, worst_after = 0.0, at_before = 0.0;
  for (std::size_t i = 0; i < d_ours.size(); ++i) {
    const double difference = std::abs(interpolate(d_yade, f_yade, d_ours[i]) - f_ours[i]);
    if (d_ours[i] <= first_peak) {
      if (difference > worst_before) at_before = d_ours[i];
      worst_before = std::max(worst_before, difference);
    } else if (d_ours[i] <= intact) {
      worst_after = std::max(worst_after, difference);
    }
  }
  auto travel_of = [](const std::vector<double>& d, std::size_t row) { return row < d.size() ? d[row] : d.back(); };
  std::cout << c.name << ": peak ours " << peak << " N at " << d_ours[p_ours] << " mm; YADE " << f_yade[p_yade] << " N at "
            << d_yade[p_yade] << " mm; largest force difference up to the first peak " << worst_before / peak * 100.0
            << " % of the peak (at " << at_before << " mm), past it while intact " << worst_after / peak * 100.0
            << " %; first broken link at " << travel_of(d_ours, failure_ours) << " mm (ours), " << travel_of(d_yade, failure_yade)
            << " mm (YADE); broken at the end "
            << b_ours.back() << " (ours), " << b_yade.back() << " (YADE); sag ours " << 1000.0 * ours.sag << " mm, YADE "
            << yade.metadata("sag_after_settling_mm") << " mm; our own spread (start 1 nm lower) " << spread / peak * 100.0
            << " % of the peak, perturbed peak " << f_perturbed[peak_index(f_perturbed)] << " N\n";
  EXPECT_LE(std::abs(f_yade[p_yade] - peak), bound);
  EXPECT_NEAR(d_yade[p_yade] / d_ours[p_ours], 1.0, 0.02);
  EXPECT_LE(worst_before, bound);
  EXPECT_LE(worst_after, bound);
  EXPECT_LE(std::max(failure_ours, failure_yade) - std::min(failure_ours, failure_yade), 1u);
  return log;
}

class DemPunchYade : public ::testing::TestWithParam<PunchCase> {};

TEST_P(DemPunchYade, OurEngineAndYadeAgree) {
  if (std::system("command -v yade > /dev/null 2>&1") != 0) GTEST_SKIP() << "yade is not installed";
  const PunchCase& c = GetParam();
  const std::string log = expect_punch_agrees_with_yade(c);
  // With a distortion the script stops unless YADE gave every link the slack our engine drew.
  if (c.lambda_u > 0.0) {
    EXPECT_NE(log.find("slack of every link as dtwire drew it"), std::string::npos) << log;
  }
}

// The Bertrand double twist (YADE type 0), the double twist's own curve (type 1) and the
// distortion (type 2) at twice and four times Pol et al. 2017's quasi-static 1 %.
INSTANTIATE_TEST_SUITE_P(Cases, DemPunchYade,
                         ::testing::Values(PunchCase{"bertrand", "punch_yade_check.toml", 0.0, 0},
                                           PunchCase{"own_curve", "punch_yade_distortion_check.toml", 0.0, 0},
                                           PunchCase{"lambda_0_04_seed_2013", "punch_yade_distortion_check.toml", 0.04, 2013},
                                           PunchCase{"lambda_0_04_seed_55", "punch_yade_distortion_check.toml", 0.04, 55},
                                           PunchCase{"lambda_0_08_seed_2013", "punch_yade_distortion_check.toml", 0.08, 2013},
                                           PunchCase{"lambda_0_08_seed_55", "punch_yade_distortion_check.toml", 0.08, 55}),
                         [](const ::testing::TestParamInfo<PunchCase>& param_info) { return std::string(param_info.param.name); });

}  // namespace
}  // namespace dtwire::dem
