// The --model plug-in path: a ModelRunner standing in for the FE re-run makes the model-only
// effects candidates; without it they are listed as not tested.
#include <gtest/gtest.h>

#include <random>

#include "dtwire/gap/diagnosis.hpp"
#include "dtwire/gap/synthetic_curves.hpp"

namespace dtwire::gap {
namespace {

// Stand-in FE model: a wire whose diameter is scaled by `diameter_scale_1` carries d^2 times the
// force at the same displacement (cross-section scales with d^2).
ForceCurve fake_fe_run(const std::vector<AppliedEffect>& effects) {
  ForceCurve c = voce_tension_curve();
  for (const AppliedEffect& a : effects)
    if (a.effect->name == "geometry_imperfection")
      for (double& f : c.f) f *= a.params[0] * a.params[0];
  return c;
}

TEST(GapModelMode, ModelOnlyEffectIsFoundThroughTheRunner) {
  const ForceCurve sim = fake_fe_run({});
  const ForceCurve lab_model = fake_fe_run({{&find_effect("geometry_imperfection"), {1.03}}});
  std::mt19937 rng(8);
  LabSampling s;
  s.points = 600;
  s.noise_sigma_N = 6.0;
  ForceCurve lab = sample_lab_curve(lab_model, s, rng);
  lab.source = "lab";
  DiagnosisOptions options;
  options.effects = {"geometry_imperfection", "strain_rate", "machine_compliance"};
  options.model = fake_fe_run;
  const Diagnosis d = diagnose({lab}, sim, options);
  EXPECT_TRUE(d.not_tested.empty());
  ASSERT_EQ(d.cause, "geometry_imperfection") << d.reason;
  // d = 1.03 recovered within 0.003 (10 % of its distance from 1; 0.2 % load noise).
  EXPECT_NEAR(d.ranking.front().fitted.front().params[0], 1.03, 0.003);

  options.model = nullptr;
  const Diagnosis without = diagnose({lab}, sim, options);
  EXPECT_EQ(without.not_tested, std::vector<std::string>{"geometry_imperfection"});
  EXPECT_NE(without.cause, "geometry_imperfection");
}

}  // namespace
}  // namespace dtwire::gap
