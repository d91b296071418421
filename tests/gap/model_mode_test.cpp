// The --model plug-in path: a ModelRunner standing in for the FE re-run makes the model-only
// effects candidates; without it they are listed as not tested.
#include <gtest/gtest.h>

#include <random>

#include "dtwire/gap/diagnosis.hpp"
#include "dtwire/gap/synthetic_curves.hpp"

namespace dtwire::gap {
namespace {

// Stand-in FE model: scaling the imperfection amplitude by s lowers the force by a factor
// 1 / (1 + 0.05 (s - 1)) (a crooked member carries less at the same shortening).
ForceCurve fake_fe_run(const std::vector<AppliedEffect>& effects) {
  ForceCurve c = voce_tension_curve();
  for (const AppliedEffect& a : effects)
    if (a.effect->name == "geometry_imperfection")
      for (double& f : c.f) f /= 1.0 + 0.05 * (a.params[0] - 1.0);
  return c;
}

TEST(GapModelMode, ModelOnlyEffectIsFoundThroughTheRunner) {
  const ForceCurve sim = fake_fe_run({});
  const ForceCurve lab_model = fake_fe_run({{&find_effect("geometry_imperfection"), {2.5}}});
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
  // s = 2.5 recovered within 0.15 (10 % of its distance from 1; 0.2 % load noise).
  EXPECT_NEAR(d.ranking.front().fitted.front().params[0], 2.5, 0.15);

  options.model = nullptr;
  const Diagnosis without = diagnose({lab}, sim, options);
  EXPECT_EQ(without.not_tested, std::vector<std::string>{"geometry_imperfection"});
  EXPECT_NE(without.cause, "geometry_imperfection");
}

}  // namespace
}  // namespace dtwire::gap
