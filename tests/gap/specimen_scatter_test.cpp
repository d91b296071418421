// Specimen scatter of repeated laboratory curves (issue 17): the scale fit, the bound on the
// mean specimen, and a small effect found under a scatter larger than its gap.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "dtwire/gap/diagnosis.hpp"
#include "dtwire/gap/effects.hpp"
#include "dtwire/gap/specimen_scatter.hpp"
#include "dtwire/gap/synthetic_curves.hpp"

namespace dtwire::gap {
namespace {

ForceCurve specimen(const ForceCurve& model, double force, double length, double sigma_N, unsigned seed) {
  std::mt19937 rng(seed);
  LabSampling sampling;
  sampling.points = 700;
  sampling.end_m = 0.8 * model.u.back() * (1.0 + length);
  sampling.noise_sigma_N = sigma_N;
  ForceCurve lab = sample_lab_curve(scaled(model, {force, length}), sampling, rng);
  lab.source = "specimen_" + std::to_string(seed);
  return lab;
}

TEST(GapSpecimenScatter, ScaleFitRecoversForceAndDisplacementScales) {
  const ForceCurve sim = voce_tension_curve();
  const Comparison lab = make_comparison(specimen(sim, 0.02, -0.015, 0.0, 1));
  const ScaleFit s = fit_specimen_scale(sim, lab);
  EXPECT_NEAR(s.force, 0.02, 0.002);
  EXPECT_NEAR(s.length, -0.015, 0.003);
}

TEST(GapSpecimenScatter, MeanSpecimenDeviationIsHeldWithinItsBound) {
  const ForceCurve sim = voce_tension_curve();
  // Both specimens 4 % stronger: per-specimen deviations are free, their mean only 1 %.
  const std::vector<Comparison> labs = {make_comparison(specimen(sim, 0.04, 0.0, 0.0, 1)),
                                        make_comparison(specimen(sim, 0.04, 0.0, 0.0, 2))};
  SpecimenScatter scatter{true, 0.01, 0.01};
  const auto forces = forces_with_scatter(sim, labs, scatter);
  const double peak = *std::max_element(sim.f.begin(), sim.f.end());
  const std::size_t i = labs[0].lab.size() / 2;
  EXPECT_NEAR(forces[0][i] / labs[0].lab.f[i], 1.01 / 1.04, 0.004);
  // Opposite deviations cancel in the mean: both are taken out.
  const std::vector<Comparison> apart = {make_comparison(specimen(sim, 0.03, 0.01, 0.0, 1)),
                                         make_comparison(specimen(sim, -0.03, -0.01, 0.0, 2))};
  const auto aligned = forces_with_scatter(sim, apart, scatter);
  for (std::size_t k = 0; k < 2; ++k)
    EXPECT_LT(normalised_area(aligned[k], apart[k]), 0.002 * peak / apart[k].f_scale);
  // Inactive: the plain model.
  EXPECT_EQ(forces_with_scatter(sim, labs, {}).front(), model_forces_at_lab(sim, labs[0]));
}

TEST(GapSpecimenScatter, ScatterBoundsFollowTheSpecimensWithAMinimum) {
  const ForceCurve sim = voce_tension_curve();
  const std::vector<ForceCurve> labs = {specimen(sim, 0.04, 0.0, 0.0, 1), specimen(sim, -0.04, 0.0, 0.0, 2)};
  const ScatterEstimate e = estimate_scatter(labs, {make_comparison(labs[0]), make_comparison(labs[1])});
  ASSERT_TRUE(e.scatter.active);
  // a_2 - a_1 = 0.96 / 1.04 - 1 = -0.077: sd 0.054, bound 3 sd / sqrt 2.
  EXPECT_NEAR(e.force_sd, 0.077 / std::sqrt(2.0), 0.005);
  EXPECT_NEAR(e.scatter.force_bound, kScatterAllowance * e.force_sd / std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(e.scatter.length_bound, kScatterAllowance * kMinimumSpecimenScatter / std::sqrt(2.0), 1e-12);
  EXPECT_LT(e.aligned_gap, 0.002);
}

// Two specimens 4 % apart in force, one with a small initial slack (0.25 mm): the raw scatter
// between them (about 0.03 of the normalised area) is larger than the slack's gap, which the
// mutual-gap floor called `none`; with the scatter profiled out the slack is the cause. Without
// the slack the same specimens give `none`.
TEST(GapSpecimenScatter, SmallEffectUnderLargerSpecimenScatterIsFound) {
  const ForceCurve sim = voce_tension_curve();
  const double peak = *std::max_element(sim.f.begin(), sim.f.end());
  const CurveScale scale = curve_scale(sim);
  const ForceCurve slack = apply_effects(sim, {{&find_effect("initial_slack"), {0.25, 0.03 * peak}}}, scale);
  DiagnosisOptions options;
  options.try_pairs = false;
  const Diagnosis d = diagnose({specimen(slack, 0.02, 0.005, 0.003 * peak, 1),
                                specimen(slack, -0.02, -0.005, 0.003 * peak, 2)}, sim, options);
  EXPECT_GT(d.scatter_gap, d.gap_before);
  EXPECT_LT(d.noise_floor, d.gap_before);
  EXPECT_EQ(d.cause, "initial_slack");
  const Diagnosis clean = diagnose({specimen(sim, 0.02, 0.005, 0.003 * peak, 1),
                                    specimen(sim, -0.02, -0.005, 0.003 * peak, 2)}, sim, options);
  EXPECT_EQ(clean.cause, "none");
}

}  // namespace
}  // namespace dtwire::gap
