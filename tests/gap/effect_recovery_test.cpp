// Each curve-mode effect, injected into a model curve with noise, is found again and its
// magnitude recovered; clean noisy curves give `none`.
#include <gtest/gtest.h>

#include <ostream>
#include <random>

#include "dtwire/gap/diagnosis.hpp"
#include "dtwire/gap/synthetic_curves.hpp"

namespace dtwire::gap {
namespace {

struct Case {
  std::string effect;
  std::vector<double> params;
};

// ctest shows the effect, not the bytes of the struct.
void PrintTo(const Case& c, std::ostream* out) { *out << c.effect; }

ForceCurve noisy_lab(const ForceCurve& model, unsigned seed, double sigma_N) {
  std::mt19937 rng(seed);
  LabSampling s;
  s.points = 700;
  s.noise_sigma_N = sigma_N;
  s.noise_rho = 0.2;
  ForceCurve lab = sample_lab_curve(model, s, rng);
  lab.source = "synthetic lab";
  return lab;
}

class GapEffectRecovery : public ::testing::TestWithParam<Case> {};

TEST_P(GapEffectRecovery, EffectIsTheCauseAndItsMagnitudeIsRecovered) {
  const Case& c = GetParam();
  const ForceCurve sim = voce_tension_curve();
  const CurveScale scale = curve_scale(sim);
  const EffectSpec& spec = find_effect(c.effect);
  const ForceCurve lab = noisy_lab(apply_effects(sim, {{&spec, c.params}}, scale), 11,
                                   0.004 * scale.peak_force_N);
  const Diagnosis d = diagnose({lab}, sim, {});
  ASSERT_EQ(d.cause, c.effect) << d.reason;
  const RankedEffect& top = d.ranking.front();
  ASSERT_EQ(top.effect, c.effect);
  // The gap closes to the noise: at least 70 % shrink (issue goal for the mean shrink).
  EXPECT_GT(top.shrink, 0.7);
  EXPECT_LE(top.gap_after, d.noise_floor);
  // Magnitude within 10 % of its distance from the neutral value (0.4 % load noise).
  const double truth = c.params[spec.magnitude];
  const double fitted = top.fitted.front().params[spec.magnitude];
  EXPECT_NEAR(fitted, truth, 0.10 * std::abs(truth - spec.neutral));
  // Stick-slip: the step is found on its search grid (0.3 mm, grid spacing 0.1 mm).
  if (c.effect == "grip_slip" && c.params[2] > 0) {
    EXPECT_NEAR(top.fitted.front().params[2], c.params[2], 0.1);
  }
}

INSTANTIATE_TEST_SUITE_P(
    CurveModeEffects, GapEffectRecovery,
    ::testing::Values(Case{"machine_compliance", {0.4}},
                      Case{"grip_slip", {1800.0, 3.0, 0.0}},
                      Case{"grip_slip", {1500.0, 4.0, 0.3}},  // stick-slip steps of 0.3 mm
                      Case{"initial_slack", {0.8, 60.0}},
                      Case{"gauge_length", {1.15}},
                      Case{"ductile_damage", {8.0, 0.3, 2.0}},
                      Case{"ductile_damage", {8.0, 0.3, 1.0}},   // Lemaitre's linear growth
                      Case{"ductile_damage", {8.0, 0.3, 3.5}},   // coalescence accelerating
                      Case{"strain_rate", {1.08}}),
    [](const ::testing::TestParamInfo<Case>& param_info) {
      return param_info.param.effect + "_" + std::to_string(param_info.index);
    });

TEST(GapNone, CleanCurvesWithNoiseGiveNone) {
  const ForceCurve sim = voce_tension_curve();
  const double peak = curve_scale(sim).peak_force_N;
  int none = 0;
  for (unsigned seed = 1; seed <= 5; ++seed) {
    const ForceCurve lab = noisy_lab(sim, seed, 0.005 * peak);
    const Diagnosis d = diagnose({lab}, sim, {});
    none += d.cause == "none";
    EXPECT_LE(d.gap_before, d.noise_floor * 1.5);
  }
  EXPECT_EQ(none, 5);
}

TEST(GapNone, RepeatedCurvesSetTheNoiseFloorFromTheirScatter) {
  const ForceCurve sim = voce_tension_curve();
  const double peak = curve_scale(sim).peak_force_N;
  const ForceCurve a = noisy_lab(sim, 21, 0.005 * peak);
  const ForceCurve b = noisy_lab(sim, 22, 0.005 * peak);
  const Diagnosis d = diagnose({a, b}, sim, {});
  EXPECT_EQ(d.cause, "none");
  ASSERT_GE(d.scatter_gap, 0.0);
  // The scatter once the curves are aligned by scale (docs/gap.md, "Specimen scatter").
  ASSERT_GE(d.aligned_scatter_gap, 0.0);
  EXPECT_LE(d.aligned_scatter_gap, d.scatter_gap);
  EXPECT_GE(d.noise_floor, d.aligned_scatter_gap);
}

}  // namespace
}  // namespace dtwire::gap

namespace dtwire::gap {
namespace {

// A loading-unloading-reloading test: the compliance of the machine also shows on the elastic
// unloading branch, which the comparison matches branch by branch.
TEST(GapUnloading, ComplianceFoundOnACycledCurveWithAnUnloadingRegion) {
  const ForceCurve mono = voce_tension_curve();
  ForceCurve sim;
  sim.source = "cycled model";
  const double k0 = curve_scale(mono).initial_stiffness_N_per_m;
  const double turn = 0.010;  // unload at 10 mm to zero force, reload to 20 mm
  std::size_t i = 0;
  for (; mono.u[i] <= turn; ++i) {
    sim.u.push_back(mono.u[i]);
    sim.f.push_back(mono.f[i]);
  }
  const double f_turn = sim.f.back(), u_turn = sim.u.back();
  for (int k = 1; k <= 40; ++k) {
    const double f = f_turn * (1.0 - k / 40.0);
    sim.u.push_back(u_turn - (f_turn - f) / k0);
    sim.f.push_back(f);
  }
  for (int k = 1; k < 40; ++k) {
    const double f = f_turn * (k / 40.0);
    sim.u.push_back(u_turn - (f_turn - f) / k0);
    sim.f.push_back(f);
  }
  for (; mono.u[i] <= 0.020; ++i) {
    sim.u.push_back(mono.u[i]);
    sim.f.push_back(mono.f[i]);
  }
  const ForceCurve lab_model =
      apply_effects(sim, {{&find_effect("machine_compliance"), {0.3}}}, curve_scale(sim));
  // Lab sampled densely along the model's own points plus noise (branches preserved).
  std::mt19937 rng(4);
  std::normal_distribution<double> noise(0.0, 5.0);
  ForceCurve lab = lab_model;
  lab.source = "cycled lab";
  for (double& f : lab.f) f += noise(rng);
  const Diagnosis d = diagnose({lab}, sim, {});
  EXPECT_EQ(d.cause, "machine_compliance") << d.reason;
  bool unloading = false;
  for (const GapSegment& g : d.where) unloading |= g.region == "unloading";
  EXPECT_TRUE(unloading);
  // 0.3 mm/kN recovered within 10 % (noise 5 N on a 2.6 kN curve).
  EXPECT_NEAR(d.ranking.front().fitted.front().params[0], 0.3, 0.03);
}

}  // namespace
}  // namespace dtwire::gap
