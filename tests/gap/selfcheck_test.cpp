// A small selfcheck on a fixed seed meets the goals.
#include <gtest/gtest.h>

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
