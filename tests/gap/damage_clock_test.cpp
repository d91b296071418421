// The damage clock (issue 51): a damage law runs on each fractured record's own clock to that
// record's end; a record without a terminal drop keeps the law's own clock.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "dtwire/gap/diagnosis.hpp"
#include "dtwire/gap/fracture.hpp"
#include "dtwire/gap/synthetic_curves.hpp"
#include "../../gap/src/parsimony.hpp"

namespace dtwire::gap {
namespace {

// The test's damage law, written out here (not the catalogue's apply): D reaches the critical
// damage D_c at the record's end e_k (Lemaitre 1985), growing from the onset theta e_k as the
// square of the travel past it: D = D_c ((u/e_k - theta) / (1 - theta))^2.
constexpr double kCritical = 0.3, kOnsetShare = 0.4;

double law(double u, double end) {
  const double x = std::max(0.0, (u / end - kOnsetShare) / (1.0 - kOnsetShare));
  return kCritical * x * x;
}

// A record of the damaged wire to `end` (the simulation's force at `points` evenly spaced
// displacements, times 1 - D, 0.2 % load noise), with the fracture's drop (two samples at a
// fifth of the load noise) when `broke`.
ForceCurve record(const ForceCurve& sim, double end, std::size_t points, bool broke, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, 0.002 * *std::max_element(sim.f.begin(), sim.f.end()));
  ForceCurve lab;
  lab.source = "specimen " + std::to_string(seed);
  for (std::size_t i = 0; i < points; ++i) {
    const double u = end * static_cast<double>(i) / static_cast<double>(points - 1);
    lab.u.push_back(u);
    lab.f.push_back(interpolate_clamped(sim.u, sim.f, u) * (1.0 - law(u, end)) + noise(rng));
  }
  if (broke)
    for (int k = 1; k <= 2; ++k) {
      lab.u.push_back(end * (1.0 + 0.001 * k));
      lab.f.push_back(0.2 * noise(rng));
    }
  return lab;
}

TEST(GapDamageClock, RecordsBrokenApartRecoverOneLaw) {
  const ForceCurve sim = voce_tension_curve();
  const double travel = sim.u.back();
  const double short_end = 0.6 * travel, long_end = 0.9 * travel;
  const std::vector<ForceCurve> labs = {record(sim, short_end, 600, true, 1), record(sim, long_end, 800, true, 2)};
  DiagnosisOptions options;
  options.seed = 3;
  const Diagnosis d = diagnose(labs, sim, options);
  ASSERT_EQ(d.fracture_m.size(), 2u);
  EXPECT_NEAR(d.fracture_m[0], short_end, 1e-12);
  EXPECT_NEAR(d.fracture_m[1], long_end, 1e-12);
  EXPECT_EQ(d.cause, "ductile_damage") << d.reason;
  const RankedEffect* damage = nullptr;
  for (const RankedEffect& r : d.ranking)
    if (r.effect == "ductile_damage") damage = &r;
  ASSERT_NE(damage, nullptr);
  // On the law's own clock, that of the record that broke last: the onset at theta e_ref and the
  // critical damage at the test's end.
  const std::vector<double>& p = damage->fitted.front().params;
  EXPECT_NEAR(p[0], kOnsetShare * long_end * 1e3, 0.05 * kOnsetShare * long_end * 1e3);
  EXPECT_NEAR(p[1], kCritical, 0.05 * kCritical);
}

TEST(GapDamageClock, OnlyARecordThatBrokeHasAClockOfItsOwn) {
  const ForceCurve sim = voce_tension_curve();
  const double travel = sim.u.back();
  const ForceCurve broke = record(sim, 0.6 * travel, 600, true, 1);
  const ForceCurve cut = record(sim, 0.5 * travel, 500, false, 2);
  const ForceCurve last = record(sim, 0.9 * travel, 800, true, 3);

  const RecordEnd end = record_end(broke);
  EXPECT_TRUE(end.fracture);
  EXPECT_EQ(end.intact_points, 600u);
  EXPECT_DOUBLE_EQ(end.end_m, 0.6 * travel);
  EXPECT_EQ(intact_part(broke, end).size(), 600u);
  EXPECT_FALSE(record_end(cut).fracture);
  EXPECT_EQ(record_end(cut).intact_points, cut.size());
  // The model's own neck falls to 0.4 of the peak over the neck's length: no fracture's drop.
  EXPECT_FALSE(record_end(sim).fracture);
  // Unloading to zero force at the end: the displacement goes back, no fracture.
  ForceCurve unloaded = cut;
  const double k = 0.5 * *std::max_element(sim.f.begin(), sim.f.end()) / (0.002 * travel);
  const double f_end = unloaded.f.back(), u_end = unloaded.u.back();
  for (int i = 1; i <= 5; ++i) {
    unloaded.f.push_back(f_end * (1.0 - 0.2 * i));
    unloaded.u.push_back(u_end - f_end * 0.2 * i / k);
  }
  EXPECT_FALSE(record_end(unloaded).fracture);

  // The clocks: the last fracture is the reference; the cut record keeps the law's own clock.
  std::vector<Comparison> labs;
  for (const ForceCurve& c : {broke, cut, last}) {
    const RecordEnd re = record_end(c);
    labs.push_back(make_comparison(intact_part(c, re)));
    labs.back().fracture_m = re.fracture ? re.end_m : 0.0;
  }
  set_damage_clocks(labs);
  EXPECT_NEAR(labs[0].damage_clock, 1.5, 1e-12);
  EXPECT_DOUBLE_EQ(labs[1].damage_clock, 1.0);
  EXPECT_DOUBLE_EQ(labs[2].damage_clock, 1.0);

  // A held-out block is no fracture: the training problem, its last block held out, keeps the
  // records' clocks.
  FitProblem problem;
  problem.sim = sim;
  problem.scale = curve_scale(sim);
  problem.labs = labs;
  std::vector<bool> held_out;
  const FitProblem training = parsimony::training_problem(problem, kHeldOutBlocks, &held_out);
  for (std::size_t i = 0; i < labs.size(); ++i) EXPECT_DOUBLE_EQ(training.labs[i].damage_clock, labs[i].damage_clock);
  // The damage curve of the broken record runs 1.5 times as fast as the cut one's.
  const std::vector<AppliedEffect> damage = {{&find_effect("ductile_damage"), {5.0, 0.3}}};
  const auto models = record_models(problem, damage);
  ASSERT_EQ(models.size(), 3u);
  EXPECT_EQ(models[1].f, models[2].f);
  CurveScale fast = problem.scale;
  fast.damage_clock = labs[0].damage_clock;
  EXPECT_EQ(models[0].f, apply_effects(sim, damage, fast).f);
  EXPECT_NE(models[0].f, models[1].f);

  // The diagnosis: the record without its drop gets no fracture.
  DiagnosisOptions options;
  options.effects = {"ductile_damage"};
  options.try_pairs = false;
  const Diagnosis d = diagnose({cut, last}, sim, options);
  ASSERT_EQ(d.fracture_m.size(), 2u);
  EXPECT_EQ(d.fracture_m[0], 0.0);
  EXPECT_NEAR(d.fracture_m[1], 0.9 * travel, 1e-12);
}

}  // namespace
}  // namespace dtwire::gap
