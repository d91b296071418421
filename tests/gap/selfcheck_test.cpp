// A small selfcheck on a fixed seed meets the goals.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "dtwire/gap/selfcheck.hpp"

namespace dtwire::gap {
namespace {

TEST(GapSelfcheck, SmallRunMeetsTheAccuracyGoals) {
  SelfcheckOptions options;
  options.trials = 3;
  options.pair_trials = 0;
  options.none_trials = 6;
  options.seed = 2024;
  options.backbone_csv = std::string(DTWIRE_SOURCE_DIR) + "/experiments/data/sw_2.7mm_dem_backbone.csv";
  const SelfcheckResult r = run_selfcheck(options);
  ASSERT_EQ(r.trials.size(), 3u * 6u + 6u);
  // Goals of issue #8.
  EXPECT_GE(r.single_top1, kGoalTop1);
  EXPECT_GE(r.single_mean_shrink, kGoalShrink);
  EXPECT_GE(r.none_rate, kGoalNone);
  EXPECT_TRUE(r.goals_met);
  const auto j = selfcheck_json(r);
  EXPECT_EQ(j.at("trials").size(), r.trials.size());
}

}  // namespace
}  // namespace dtwire::gap

namespace dtwire::gap {
namespace {

// Independent family (issue 17), two effect-free trials on the Voce base: the family runs and
// reports itself. No goal is asserted on two trials (docs/gap.md, "Independent family", has the
// measured figures).
TEST(GapSelfcheck, IndependentFamilyRunsOnRepeatedSpecimens) {
  SelfcheckOptions options;
  options.family = "independent";
  options.trials = 0;
  options.pair_trials = 0;
  options.none_trials = 2;
  options.seed = 1;
  const SelfcheckResult r = run_selfcheck(options);
  ASSERT_EQ(r.trials.size(), 2u);
  for (const SelfcheckTrial& t : r.trials) {
    EXPECT_EQ(t.truth, "none");
    EXPECT_TRUE(std::isfinite(t.gap_before) && t.gap_before > 0);
    EXPECT_GT(t.noise_floor, 0.0);
  }
  EXPECT_EQ(selfcheck_json(r).at("family"), "independent");
  options.family = "other";
  EXPECT_THROW(run_selfcheck(options), std::invalid_argument);
}

// --effects: the trials are of the chosen effects only; a name that is no effect, or pairs drawn
// from one effect, are refused.
TEST(GapSelfcheck, OnlyTheChosenEffectsAreTrialled) {
  SelfcheckOptions options;
  options.family = "independent";
  options.trials = 1;
  options.pair_trials = 0;
  options.none_trials = 0;
  options.seed = 5;
  options.effects = {"gauge_length"};
  const SelfcheckResult r = run_selfcheck(options);
  ASSERT_EQ(r.trials.size(), 1u);
  for (const SelfcheckTrial& t : r.trials) EXPECT_EQ(t.truth, "gauge_length");
  options.pair_trials = 1;
  EXPECT_THROW(run_selfcheck(options), std::invalid_argument);
  options.pair_trials = 0;
  options.effects = {"gauge_length", "wire_friction"};
  EXPECT_THROW(run_selfcheck(options), std::invalid_argument);
}

}  // namespace
}  // namespace dtwire::gap

namespace dtwire::gap {
namespace {

// Issue 51: an effect whose gap lies below the noise floor cannot be told from the scatter; its
// trial is reported apart (read as `none` is right there) and the top-1 goal is judged on the
// trials whose gap stands above the floor.
TEST(GapSelfcheck, TrialsBelowTheNoiseFloorAreScoredApart) {
  SelfcheckResult r;
  const auto trial = [](const std::string& truth, const std::string& predicted, double gap) {
    SelfcheckTrial t;
    t.base = "voce";
    t.truth = truth;
    t.predicted = predicted;
    t.gap_before = gap;
    t.noise_floor = 0.01;
    t.shrink = predicted == truth ? 0.8 : 0.0;
    return t;
  };
  for (int i = 0; i < 9; ++i) r.trials.push_back(trial("grip_slip", "grip_slip", 0.05));
  r.trials.push_back(trial("grip_slip", "gauge_length", 0.05));  // a visible miss
  r.trials.push_back(trial("strain_rate", "none", 0.008));       // below the floor: none is right
  r.trials.push_back(trial("strain_rate", "ductile_damage", 0.009));
  r.trials.push_back(trial("none", "none", 0.004));
  score_trials(r);
  EXPECT_DOUBLE_EQ(r.single_top1, 9.0 / 12.0);
  EXPECT_DOUBLE_EQ(r.single_top1_visible, 9.0 / 10.0);
  EXPECT_EQ(r.singles_below_floor, 2u);
  EXPECT_EQ(r.singles_below_floor_none, 1u);
  EXPECT_DOUBLE_EQ(r.none_rate, 1.0);
  // 0.9 top-1 on the visible trials meets its goal; the shrink (0.6 mean over all 12) does not.
  EXPECT_FALSE(r.goals_met);
  const std::string text = selfcheck_markdown(r);
  EXPECT_NE(text.find("above the noise floor | 0.90 (n = 10)"), std::string::npos) << text;
  EXPECT_NE(text.find("1 of 2"), std::string::npos) << text;
  EXPECT_EQ(selfcheck_json(r).at("singles_below_floor").get<std::size_t>(), 2u);
  // Issue 51's goal is per effect: grip_slip 9 of 10 above the floor, strain_rate none above it.
  ASSERT_EQ(r.per_effect.size(), 2u);
  EXPECT_EQ(r.per_effect.at("grip_slip").above_floor, 10u);
  EXPECT_EQ(r.per_effect.at("grip_slip").found, 9u);
  EXPECT_EQ(r.per_effect.at("strain_rate").below_floor, 2u);
  EXPECT_EQ(r.per_effect.at("strain_rate").below_floor_none, 1u);
  EXPECT_NE(text.find("| grip_slip | 9 of 10 (0.90) | 0 of 0 |"), std::string::npos) << text;
  EXPECT_EQ(selfcheck_json(r).at("per_effect").at("strain_rate").at("below_floor_read_none").get<int>(), 1);
}

}  // namespace
}  // namespace dtwire::gap

#include <filesystem>

#include "dtwire/core/csv.hpp"
#include "dtwire/gap/diagnosis.hpp"
#include "dtwire/gap/force_curve.hpp"
#include "dtwire/gap/synthetic_curves.hpp"

namespace dtwire::gap {
namespace {

// --write-curves: a trial's curves as written are the ones it diagnosed: diagnosed again from the
// files, the gap is the one the selfcheck recorded.
TEST(GapSelfcheck, WrittenCurvesReproduceTheTrial) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "dtwire_selfcheck_curves_test";
  std::filesystem::remove_all(dir);
  SelfcheckOptions options;
  options.family = "independent";
  options.trials = 0;
  options.pair_trials = 0;
  options.none_trials = 1;
  options.seed = 3;
  options.curves_dir = dir;
  const SelfcheckResult r = run_selfcheck(options);
  ASSERT_EQ(r.trials.size(), 1u);
  const std::filesystem::path trial = dir / "trial_001_none";
  ASSERT_TRUE(std::filesystem::exists(trial / "sim.csv"));
  EXPECT_EQ(read_csv(trial / "lab_1.csv").metadata("selfcheck_truth"), "none");
  const CurveConversion si;
  std::vector<ForceCurve> labs;
  for (const char* name : {"lab_1.csv", "lab_2.csv"}) labs.push_back(load_force_curve(trial / name, si));
  DiagnosisOptions again;
  again.seed = options.seed + 1;  // the first trial's seed
  const Diagnosis d = diagnose(labs, load_force_curve(trial / "sim.csv", si), again);
  EXPECT_NEAR(d.gap_before, r.trials[0].gap_before, 1e-12 * r.trials[0].gap_before);
  EXPECT_EQ(d.cause, r.trials[0].predicted);
  std::filesystem::remove_all(dir);
}

// The fitted family's files name what was put in, so a miss can be judged against its truth.
TEST(GapSelfcheck, WrittenCurvesOfTheFittedFamilyNameTheInjectedParameters) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "dtwire_selfcheck_injected_test";
  std::filesystem::remove_all(dir);
  SelfcheckOptions options;
  options.trials = 1;
  options.pair_trials = 0;
  options.none_trials = 0;
  options.effects = {"machine_compliance"};
  options.curves_dir = dir;
  const SelfcheckResult r = run_selfcheck(options);
  ASSERT_EQ(r.trials.size(), 1u);
  const std::string injected = read_csv(dir / "trial_001_machine_compliance" / "lab_1.csv").metadata("selfcheck_injected");
  EXPECT_EQ(injected, r.trials[0].injected);
  const std::string prefix = "machine_compliance: compliance_mm_per_kN=";
  ASSERT_EQ(injected.rfind(prefix, 0), 0u) << injected;
  const double value = std::stod(injected.substr(prefix.size()));
  const ParameterSpec range = find_effect("machine_compliance").parameters(curve_scale(voce_tension_curve())).at(0);
  EXPECT_GE(value, range.plausible_lower);
  EXPECT_LE(value, range.plausible_upper);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace dtwire::gap
