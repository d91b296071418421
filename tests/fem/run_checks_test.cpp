// The FE run's self-checks (issue 37) on step records whose energies are known: a balanced
// elastic-plastic account passes, a missing term or a deep penetration stops the run at the step
// where it leaves its bound, naming the check, the step and the bound.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "run_checks.hpp"

namespace dtwire::fem {
namespace {

// A bar pulled to force f = k u (elastic) then f = f_y (plastic): external work by the
// trapezoidal rule equals elastic + plastic energy exactly for this bilinear law when the yield
// point is a step boundary, so any imbalance comes from what a test removes.
std::vector<StepRecord> bilinear_pull(unsigned steps, double k = 1e6, double f_y = 2e3, double du = 1e-3) {
  std::vector<StepRecord> records;
  double work = 0.0, previous_force = 0.0;
  const double u_y = f_y / k;
  for (unsigned i = 0; i <= steps; ++i) {
    StepRecord r;
    r.step = i;
    r.displacement = i * du;
    r.force = std::min(k * r.displacement, f_y);
    r.end_force = {0.0, 0.0, r.force};
    r.end_translation = {0.0, 0.0, r.displacement};
    if (i > 0) work += 0.5 * (r.force + previous_force) * du;
    previous_force = r.force;
    r.external_work = work;
    r.elastic_energy = 0.5 * r.force * r.force / k;
    r.plastic_dissipation = r.displacement > u_y ? f_y * (r.displacement - u_y) : 0.0;
    records.push_back(r);
  }
  return records;
}

TEST(RunChecks, BalancedBilinearPullPasses) {
  RunGuard guard(RunChecks{}, 2.7e-3);
  for (const StepRecord& r : bilinear_pull(20)) EXPECT_FALSE(guard.check(r)) << "step " << r.step;
  EXPECT_LT(guard.largest_balance_error(), 1e-12);
  EXPECT_EQ(guard.largest_penetration(), 0.0);
}

TEST(RunChecks, MissingPlasticWorkFailsWhereItLeavesTheBound) {
  // Without the plastic term the imbalance at step i (> 2, work W_i = 2 + 2 (i - 2) J) is the
  // plastic work 2 (i - 2) J, less the trapezoid's allowance of the two elastic steps
  // (1/2 x 1 kN x 1 mm each = 1 J): 1 J of 4 J at step 3.
  RunChecks bounds;
  bounds.max_balance_error = 0.05;
  RunGuard guard(bounds, 2.7e-3);
  std::optional<FailedCheck> failed;
  for (StepRecord r : bilinear_pull(20)) {
    r.plastic_dissipation = 0.0;
    if ((failed = guard.check(r))) break;
  }
  ASSERT_TRUE(failed);
  EXPECT_EQ(failed->check, "energy_balance");
  EXPECT_EQ(failed->step, 3u);
  EXPECT_NEAR(failed->value, 0.25, 1e-12);
  EXPECT_EQ(failed->entry, "Max energy balance error (%)");
  const std::string message = failed->message();
  EXPECT_NE(message.find("check 'energy_balance' failed at step 3 (pseudo-time 0, displacement 3 mm)"), std::string::npos) << message;
  EXPECT_NE(message.find("against the bound 5 % (Checks/Max energy balance error (%))"), std::string::npos) << message;
}

// One coarse step from rest to 3 mm, through yield at 2 mm: the trapezoid books 3 J, the wire
// stores 2 J elastic and dissipates 2 J plastic. The 1 J (33 %) is the quadrature's, within its
// bound 1/2 x 2 kN x 3 mm = 3 J: no failure.
TEST(RunChecks, CoarseStepThroughYieldIsNotAnImbalance) {
  const double k = 1e6, f_y = 2e3;
  StepRecord rest, coarse;
  coarse.step = 1;
  coarse.displacement = 3e-3;
  coarse.force = f_y;
  coarse.end_force = {0.0, 0.0, f_y};
  coarse.end_translation = {0.0, 0.0, 3e-3};
  coarse.external_work = 0.5 * f_y * 3e-3;
  coarse.elastic_energy = 0.5 * f_y * f_y / k;
  coarse.plastic_dissipation = f_y * (3e-3 - f_y / k);
  RunGuard guard(RunChecks{}, 2.7e-3);
  EXPECT_FALSE(guard.check(rest));
  EXPECT_FALSE(guard.check(coarse));
  EXPECT_EQ(guard.largest_balance_error(), 0.0);
}

TEST(RunChecks, BelowTheEnergyFloorTheBalanceIsNotJudged) {
  RunChecks bounds;
  bounds.energy_floor = 1e3;  // J: more than the pull's 40 J
  RunGuard guard(bounds, 2.7e-3);
  for (StepRecord r : bilinear_pull(20)) {
    r.plastic_dissipation = 0.0;
    EXPECT_FALSE(guard.check(r)) << "step " << r.step;
  }
}

TEST(RunChecks, AsMadeStartingEnergyIsNotAnImbalance) {
  RunGuard guard(RunChecks{}, 2.7e-3);
  for (StepRecord r : bilinear_pull(20)) {
    r.elastic_energy += 7.0;  // left by the forming, before the load path
    EXPECT_FALSE(guard.check(r)) << "step " << r.step;
  }
}

TEST(RunChecks, DeepPenetrationFails) {
  RunChecks bounds;
  bounds.max_penetration = 0.1;
  RunGuard guard(bounds, 2.0e-3);
  std::vector<StepRecord> records = bilinear_pull(4);
  records[3].wire_contact.max_penetration = 0.19e-3;  // 9.5 % of the diameter
  records[4].contact.max_penetration = 0.21e-3;       // 10.5 %
  for (std::size_t i = 0; i < 4; ++i) EXPECT_FALSE(guard.check(records[i])) << i;
  const auto failed = guard.check(records[4]);
  ASSERT_TRUE(failed);
  EXPECT_EQ(failed->check, "penetration");
  EXPECT_NEAR(failed->value, 0.105, 1e-12);
  EXPECT_NEAR(guard.largest_penetration(), 0.105, 1e-12);
}

TEST(RunChecks, NonFiniteStateFails) {
  RunGuard guard(RunChecks{}, 2.7e-3);
  std::vector<StepRecord> records = bilinear_pull(3);
  records[2].force = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(guard.check(records[0]));
  EXPECT_FALSE(guard.check(records[1]));
  const auto failed = guard.check(records[2]);
  ASSERT_TRUE(failed);
  EXPECT_EQ(failed->check, "finite_state");
  EXPECT_NE(failed->message().find("not finite"), std::string::npos);
}

}  // namespace
}  // namespace dtwire::fem
