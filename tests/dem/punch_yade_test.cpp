// The WirePM punch in our engine and in YADE (the script our exporter writes, run unchanged),
// with the platter as one sphere in YADE (both codes have the exact hemisphere). Issue 55's goal:
// the force within 2 % of the peak at every travel up to the first of the two peaks and on past
// it while no link has broken, the peak force and its travel within 2 %, and the first broken
// link in the same output row or the next (the resolution of both curves). After that the links
// fail in cascades whose order differs between the codes (broken counts at the end are printed,
// not compared).
// The force on the platter is chaotic in both codes (the chatter of the nodes riding on it): a
// run whose platter starts 1-10 nm lower departs from the first by up to 4.6 % of the peak in
// ours and alike in YADE (docs/validation.md, issue 55), so one run of each code cannot tell a
// 2 % difference of the codes from that spread. The test is therefore sequential: each case runs
// once in each code; if that pair already agrees within 2 % the case passes; otherwise both codes
// run an ensemble of kMembers runs whose platter starts 0, 1, ..., kMembers - 1 nm lower (the
// pair is its first member) and the ensemble means are compared: a case fails when the 95 %
// confidence interval of the mean difference lies wholly outside +-2 % of the peak, that is when
// |mean YADE - mean ours| > 2 % of the peak + t SE, SE = sqrt((s_ours^2 + s_yade^2) / n) and t the
// 0.975 quantile of Student's t with 2n - 2 degrees of freedom (the two-sample t interval of a
// difference of means with equal sizes, NIST/SEMATECH e-Handbook of Statistical Methods, 7.3.1;
// the pooled degrees of freedom assume equal spreads, which the ensembles do not contradict), at
// every compared travel, for the peak force, its travel (margin 2 % of it) and the first broken
// link's row (margin one row). Three members are the fewest whose t has more than 2 degrees of
// freedom; with ensembles only where the pair does not decide, and each travel ending about
// 30 mm past the peak, the six cases cost about 11 CPU minutes (docs/validation.md, issue 55).
// DTWIRE_PUNCH_YADE_MEMBERS=N (N >= 2) runs N members of each code in every case, with no early
// stop, and judges the ensembles alike (t with 2N - 2 degrees of freedom): the by-hand study that
// narrows the means beyond what the test's three members can.
// experiments/dem/punch_yade_check.toml: a 1.6 x 1.6 m panel (not the 3 x 3 m of the thesis) so
// that both codes finish in minutes; punch_yade_distortion_check.toml: the same with the
// double twist's own curve and the Thoeni et al. 2013 random distortion, run here at
// lambda_u = 0, 0.04 and 0.08 with two seeds. The facet platter of the semi-spheroid departs
// from the exact one by up to 8 % near the peak while the nets agree link by link
// (docs/dem_engine.md, "The YADE export"); it is not what these tests compare.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <stdexcept>
#include <string>

#include <boost/math/distributions/students_t.hpp>

#include "dtwire/core/csv.hpp"
#include "dtwire/dem/run.hpp"

namespace dtwire::dem {
namespace {

constexpr int kMembers = 3;         // runs per code in an ensemble
constexpr double kStartStep = 1e-9;  // platter start of member k: k nm lower [m]
constexpr double kGoal = 0.02;       // issue 55: 2 % of the peak, 2 % of the peak's travel

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

struct PunchCase {
  const char* name;
  const char* input;  // experiments/dem
  double lambda_u;    // distortion of both link types (distortion input only); 0: none
  int seed;
  double travel_m;    // about 30 mm past both codes' peak (measured), the rest is cascade
};

// One run's curve and the figures compared.
struct PunchRun {
  std::vector<double> d, f, broken;  // travel [mm], platter force [N], broken links
  double peak_force() const { return f[peak_index(f)]; }
  double peak_travel() const { return d[peak_index(f)]; }
  // Row of the first broken link (both codes write a row every output interval from the same
  // start, so rows, not travels, line up), and the travel of the last row before it.
  double first_failure() const {
    for (std::size_t i = 0; i < broken.size(); ++i)
      if (broken[i] > 0.0) return static_cast<double>(i);
    return static_cast<double>(broken.size());
  }
  double last_intact() const {
    for (std::size_t i = 0; i < broken.size(); ++i)
      if (broken[i] > 0.0) return i > 0 ? d[i - 1] : 0.0;
    return d.back();
  }
};

PunchRun from_curve(const Curve& curve) {
  return {curve.channel("tool_displacement").values, curve.channel("tool_force").values, curve.channel("broken_links").values};
}

RunInput case_input(const PunchCase& c, int member) {
  RunInput input = read_run_input(std::string(DTWIRE_SOURCE_DIR) + "/experiments/dem/" + c.input);
  if (std::string(c.input) == "punch_yade_distortion_check.toml")
    for (LinkTag tag : {LinkTag::SingleWire, LinkTag::DoubleTwist}) {
      Distortion& distortion = input.link_sets.at(tag).distortion;
      distortion = c.lambda_u > 0.0 ? Distortion{DistortionMode::Random, c.lambda_u, c.seed} : Distortion{};
    }
  input.travel = c.travel_m;
  input.start_gap += member * kStartStep;
  return input;
}

PunchRun run_ours(const RunInput& input, const std::filesystem::path& dir) {
  RunOptions options;
  options.out = dir;
  options.quiet = true;
  options.write_frames = false;
  options.threads = 1;  // ctest -j2 fills the two cores
  const RunSummary summary = run_simulation(input, options);
  EXPECT_FALSE(summary.failed.has_value()) << (summary.failed ? summary.failed->message() : std::string());
  return {summary.history.channel("tool_displacement").values, summary.history.channel("tool_force").values,
          summary.history.channel("broken_links").values};
}

// YADE on the script our exporter writes; with a distortion the script stops unless YADE gave
// every link the slack our engine drew.
PunchRun run_yade(const RunInput& input, const std::filesystem::path& dir, bool distortion) {
  std::filesystem::create_directories(dir);
  const auto script = dir / "punch_yade.py";
  std::ofstream(script) << yade_run_script(input);  // a hemisphere: the sphere platter
  const auto csv = dir / "yade.csv";
  const std::string command = "cd " + dir.string() + " && yade -j1 -n -x " + script.string() + " " + csv.string() + " > yade.log 2>&1";
  EXPECT_EQ(std::system(command.c_str()), 0) << "see " << (dir / "yade.log").string();
  std::ifstream log_file(dir / "yade.log");
  const std::string log((std::istreambuf_iterator<char>(log_file)), std::istreambuf_iterator<char>());
  if (distortion) {
    EXPECT_NE(log.find("slack of every link as dtwire drew it"), std::string::npos) << log;
  }
  if (!std::filesystem::exists(csv)) return {};
  return from_curve(read_csv(csv));
}

// Mean and sample variance of the members' values.
struct Sample {
  double mean = 0.0, variance = 0.0;
};
Sample sample(const std::vector<double>& values) {
  Sample s;
  for (double v : values) s.mean += v / values.size();
  if (values.size() > 1)
    for (double v : values) s.variance += (v - s.mean) * (v - s.mean) / (values.size() - 1);
  return s;
}

// The difference YADE - ours of one figure and its allowance: the goal (margin) alone for a
// single pair, the goal plus t SE for ensembles.
struct Figure {
  double difference = 0.0, allowed = 0.0, at_mm = 0.0;
  bool within() const { return std::abs(difference) <= allowed; }
};

// The rows of a stretch of the curve: the largest difference (the figure) and whether
// every row is within its own allowance (the allowance varies with the members' spread).
struct Rows {
  Figure largest;
  int rows = 0, outside = 0;
  void add(const Figure& row) {
    if (rows++ == 0 || std::abs(row.difference) > std::abs(largest.difference)) largest = row;
    if (!row.within()) ++outside;
  }
  bool within() const { return outside == 0; }
};

// t(0.975) with 2 n - 2 degrees of freedom (2.776 for the test's three members).
double student_t(std::size_t members) {
  const boost::math::students_t t(2.0 * static_cast<double>(members) - 2.0);
  return boost::math::quantile(t, 0.975);
}

Figure compare(const std::vector<double>& ours, const std::vector<double>& yade, double margin) {
  const Sample o = sample(ours), y = sample(yade);
  const double se = std::sqrt((o.variance + y.variance) / ours.size());
  return {y.mean - o.mean, margin + (ours.size() > 1 ? student_t(ours.size()) * se : 0.0), 0.0};
}

// The members per code: the test's sequential three, or DTWIRE_PUNCH_YADE_MEMBERS of them, all run.
struct Members {
  int count = kMembers;
  bool all = false;  // no early stop on an agreeing pair
};
Members members_to_run() {
  const char* value = std::getenv("DTWIRE_PUNCH_YADE_MEMBERS");
  if (value == nullptr || *value == '\0') return {};
  char* end = nullptr;
  const long count = std::strtol(value, &end, 10);
  if (*end != '\0' || count < 2 || count > 50)
    throw std::invalid_argument(std::string("DTWIRE_PUNCH_YADE_MEMBERS = '") + value + "': expected an integer from 2 to 50");
  return {static_cast<int>(count), true};
}

struct Comparison {
  Figure peak_force, peak_travel, failure;
  Rows before_peak, past_peak;
  double peak_ours = 0.0, peak_yade = 0.0, travel_ours = 0.0, travel_yade = 0.0;
  bool within() const {
    return peak_force.within() && peak_travel.within() && failure.within() && before_peak.within() && past_peak.within();
  }
};

// Both codes' members (one each: a single pair) on our first member's travels: the worst row up
// to the first of the two mean curves' peaks and past it while no member has a broken link.
Comparison compare_members(const std::vector<PunchRun>& ours, const std::vector<PunchRun>& yade) {
  auto figures = [](const std::vector<PunchRun>& runs, double (PunchRun::*of)() const) {
    std::vector<double> values;
    for (const PunchRun& run : runs) values.push_back((run.*of)());
    return values;
  };
  Comparison c;
  const std::vector<double> peaks_ours = figures(ours, &PunchRun::peak_force);
  c.peak_ours = sample(peaks_ours).mean;
  c.peak_yade = sample(figures(yade, &PunchRun::peak_force)).mean;
  c.travel_ours = sample(figures(ours, &PunchRun::peak_travel)).mean;
  c.travel_yade = sample(figures(yade, &PunchRun::peak_travel)).mean;
  const double goal = kGoal * c.peak_ours;
  c.peak_force = compare(peaks_ours, figures(yade, &PunchRun::peak_force), goal);
  c.peak_travel = compare(figures(ours, &PunchRun::peak_travel), figures(yade, &PunchRun::peak_travel), kGoal * c.travel_ours);
  const std::vector<double>& grid = ours.front().d;
  c.failure = compare(figures(ours, &PunchRun::first_failure), figures(yade, &PunchRun::first_failure), 1.0);

  std::vector<std::vector<double>> rows_ours(grid.size()), rows_yade(grid.size());
  std::vector<double> mean_ours(grid.size()), mean_yade(grid.size());
  for (std::size_t i = 0; i < grid.size(); ++i) {
    for (const PunchRun& run : ours) rows_ours[i].push_back(interpolate(run.d, run.f, grid[i]));
    for (const PunchRun& run : yade) rows_yade[i].push_back(interpolate(run.d, run.f, grid[i]));
    mean_ours[i] = sample(rows_ours[i]).mean;
    mean_yade[i] = sample(rows_yade[i]).mean;
  }
  const double first_peak = std::min(grid[peak_index(mean_ours)], grid[peak_index(mean_yade)]);
  double intact = grid.back();
  for (const std::vector<PunchRun>* runs : {&ours, &yade})
    for (const PunchRun& run : *runs) intact = std::min(intact, run.last_intact());
  for (std::size_t i = 0; i < grid.size(); ++i) {
    Figure row = compare(rows_ours[i], rows_yade[i], goal);
    row.at_mm = grid[i];
    if (grid[i] <= first_peak)
      c.before_peak.add(row);
    else if (grid[i] <= intact)
      c.past_peak.add(row);
  }
  return c;
}

std::string percent(double part, double whole) { return std::to_string(100.0 * part / whole) + " %"; }

std::string describe(const Rows& rows, double peak) {
  if (rows.rows == 0) return "no row";
  return percent(rows.largest.difference, peak) + " at " + std::to_string(rows.largest.at_mm) + " mm (allowed there " +
         percent(rows.largest.allowed, peak) + "), " + std::to_string(rows.outside) + " of " + std::to_string(rows.rows) +
         " rows outside their allowance";
}

void print(const char* name, const char* kind, const Comparison& c) {
  std::cout << name << ", " << kind << ": peak ours " << c.peak_ours << " N at " << c.travel_ours << " mm; YADE " << c.peak_yade
            << " N at " << c.travel_yade << " mm; peak force " << percent(c.peak_force.difference, c.peak_ours) << " (allowed "
            << percent(c.peak_force.allowed, c.peak_ours) << "), its travel " << percent(c.peak_travel.difference, c.travel_ours)
            << " (allowed " << percent(c.peak_travel.allowed, c.travel_ours) << "); force up to the first peak: largest "
            << describe(c.before_peak, c.peak_ours) << "; past it while no link is broken: " << describe(c.past_peak, c.peak_ours)
            << "; first broken link YADE - ours " << c.failure.difference << " rows (allowed " << c.failure.allowed << ")\n";
}

class DemPunchYade : public ::testing::TestWithParam<PunchCase> {};

TEST_P(DemPunchYade, OurEngineAndYadeAgree) {
  if (std::system("command -v yade > /dev/null 2>&1") != 0) GTEST_SKIP() << "yade is not installed";
  const PunchCase& c = GetParam();
  const auto dir = std::filesystem::temp_directory_path() / (std::string("dtwire_punch_yade_") + c.name);
  const Members members = members_to_run();
  std::vector<PunchRun> ours, yade;
  for (int member = 0; member < members.count; ++member) {
    const RunInput input = case_input(c, member);
    const std::string suffix = std::to_string(member);
    ours.push_back(run_ours(input, dir / ("ours_" + suffix)));
    yade.push_back(run_yade(input, dir / ("yade_" + suffix), c.lambda_u > 0.0));
    ASSERT_FALSE(yade.back().f.empty()) << "YADE wrote no curve";
    const Comparison comparison = compare_members(ours, yade);
    print(c.name, member == 0 ? "one run each" : ("ensembles of " + std::to_string(member + 1)).c_str(), comparison);
    if (member == 0 && comparison.within() && !members.all) return;  // the pair agrees within 2 %
    if (member + 1 < members.count) continue;
    std::cout << c.name << ": broken at the end, ours / YADE:";
    for (int k = 0; k < members.count; ++k) std::cout << " " << ours[k].broken.back() << " / " << yade[k].broken.back();
    std::cout << "\n";
    EXPECT_TRUE(comparison.peak_force.within());
    EXPECT_TRUE(comparison.peak_travel.within());
    EXPECT_TRUE(comparison.before_peak.within());
    EXPECT_TRUE(comparison.past_peak.within());
    EXPECT_TRUE(comparison.failure.within());
  }
}

// The Bertrand double twist (YADE type 0), the double twist's own curve (type 1) and the
// distortion (type 2) at twice and four times Pol et al. 2017's quasi-static 1 %. Travels:
// peaks at 250 mm (Bertrand), 395 mm (own curve), 435 mm (lambda_u 0.04), 470 mm (0.08).
INSTANTIATE_TEST_SUITE_P(Cases, DemPunchYade,
                         ::testing::Values(PunchCase{"bertrand", "punch_yade_check.toml", 0.0, 0, 0.28},
                                           PunchCase{"own_curve", "punch_yade_distortion_check.toml", 0.0, 0, 0.425},
                                           PunchCase{"lambda_0_04_seed_2013", "punch_yade_distortion_check.toml", 0.04, 2013, 0.465},
                                           PunchCase{"lambda_0_04_seed_55", "punch_yade_distortion_check.toml", 0.04, 55, 0.465},
                                           PunchCase{"lambda_0_08_seed_2013", "punch_yade_distortion_check.toml", 0.08, 2013, 0.5},
                                           PunchCase{"lambda_0_08_seed_55", "punch_yade_distortion_check.toml", 0.08, 55, 0.5}),
                         [](const ::testing::TestParamInfo<PunchCase>& param_info) { return std::string(param_info.param.name); });

}  // namespace
}  // namespace dtwire::dem
