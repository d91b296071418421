// Parsimony of pairs (issue 17): the information criterion with the effective sample size of
// autocorrelated residuals, the held-out blocks, and pairs that only fit noise.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "../../gap/src/parsimony.hpp"
#include "dtwire/gap/curve_metrics.hpp"
#include "dtwire/gap/diagnosis.hpp"
#include "dtwire/gap/effects.hpp"
#include "dtwire/gap/synthetic_curves.hpp"

namespace dtwire::gap {
namespace {

std::vector<double> ar1(std::size_t n, double rho, double sigma, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<double> e(n);
  double x = 0.0;
  for (std::size_t i = 0; i < n; ++i) e[i] = sigma * (x = i == 0 ? normal(rng) : rho * x + std::sqrt(1 - rho * rho) * normal(rng));
  return e;
}

TEST(GapParsimony, BicChargesEachParameterTheLogOfTheEffectiveSampleSize) {
  // Schwarz 1978: n ln(mse) + k ln(n); exact to rounding (1e-12).
  EXPECT_NEAR(parsimony::bic(std::exp(-2.0), 100.0, 2), -200.0 + 2.0 * std::log(100.0), 1e-12);
  EXPECT_NEAR(parsimony::bic(std::exp(-2.0), 100.0, 3) - parsimony::bic(std::exp(-2.0), 100.0, 2), std::log(100.0), 1e-12);
}

TEST(GapParsimony, HeldOutBlocksAlternateAndCarryNoWeightInTheTrainingFit) {
  ForceCurve lab;
  for (int i = 0; i < 100; ++i) {
    lab.u.push_back(i * 1e-4);
    lab.f.push_back(100.0 + i);
  }
  FitProblem problem;
  problem.labs = {make_comparison(lab), make_comparison(lab)};
  std::vector<bool> held_out;
  const FitProblem training = parsimony::training_problem(problem, 10, &held_out);
  ASSERT_EQ(held_out.size(), 200u);
  int count = 0;
  for (std::size_t k = 0; k < held_out.size(); ++k) {
    const std::size_t i = k % 100;
    EXPECT_EQ(held_out[k], (i / 10) % 2 == 1) << k;
    EXPECT_EQ(training.labs[k / 100].weight[i] == 0.0, held_out[k]) << k;
    count += held_out[k];
  }
  EXPECT_EQ(count, 100);
  EXPECT_NEAR(parsimony::held_out_error({1.0, 2.0, 3.0}, {false, true, true}), 13.0, 1e-12);
}

// A pair 10 % better in SSE on strongly autocorrelated residuals (rho 0.95, 1000 points, n_eff
// about 26) gains less than its extra parameter costs: it is "also possible", not the cause.
TEST(GapParsimony, PairThatOnlyAbsorbsCorrelatedMisfitIsNotReported) {
  const std::vector<double> residual = ar1(1000, 0.95, 0.01, 3);
  double sse = 0.0;
  for (double r : residual) sse += r * r;
  std::vector<RankedEffect> ranking(2);
  ranking[0].effect = "machine_compliance";
  ranking[0].parameters = 1;
  ranking[1].effect = "machine_compliance+strain_rate";
  ranking[1].parameters = 2;
  for (RankedEffect& r : ranking) {
    r.qualifies = true;
    r.score = 1.0;
  }
  std::vector<EffectFit> fits(2);
  fits[0].weighted_sse = sse;
  fits[0].residual = residual;
  fits[1].weighted_sse = 0.9 * sse;
  fits[1].residual = residual;
  ForceCurve lab;
  for (int i = 0; i < 1000; ++i) {
    lab.u.push_back(i * 1e-5);
    lab.f.push_back(1.0 + i);
  }
  FitProblem problem;
  problem.labs = {make_comparison(lab)};
  std::mt19937 rng(1);
  parsimony::apply(ranking, fits, 1, problem, rng);
  const PairEvidence& e = ranking[1].against_single;
  EXPECT_TRUE(e.done);
  EXPECT_EQ(e.single, "machine_compliance");
  EXPECT_GT(e.lag1, 0.85);
  EXPECT_LT(e.n_eff, 60.0);  // 1000 x 0.05 / 1.95 = 26 for rho 0.95; sample rho scatters
  EXPECT_FALSE(e.information_ok);
  EXPECT_FALSE(ranking[1].qualifies);
  EXPECT_TRUE(ranking[1].also_possible);
  EXPECT_NEAR(ranking[1].score, 0.1, 1e-12);
  EXPECT_TRUE(ranking[0].qualifies);
}

ForceCurve lab_from(const ForceCurve& sim, const std::vector<AppliedEffect>& effects, double rho, double sigma_share,
                    unsigned seed) {
  const ForceCurve model = apply_effects(sim, effects, curve_scale(sim));
  LabSampling sampling;
  sampling.points = 800;
  sampling.noise_rho = rho;
  sampling.noise_sigma_N = sigma_share * *std::max_element(sim.f.begin(), sim.f.end());
  std::mt19937 rng(seed);
  return sample_lab_curve(model, sampling, rng);
}

// End to end: one effect plus strongly correlated load noise (rho 0.97, 1 % of the peak): the
// pairs that absorb the noise's slow wander are not the cause (inverse crime for the effect
// itself: the data are made by the fitted formula; the noise is what is tested here).
TEST(GapParsimony, CorrelatedNoiseDoesNotMakeAPair) {
  const ForceCurve sim = voce_tension_curve();
  for (unsigned seed : {1u}) {
    const ForceCurve lab = lab_from(sim, {{&find_effect("machine_compliance"), {0.6}}}, 0.97, 0.01, seed);
    DiagnosisOptions options;
    options.seed = seed;
    const Diagnosis d = diagnose({lab}, sim, options);
    EXPECT_EQ(d.cause, "machine_compliance") << "seed " << seed;
  }
}

// A real pair (compliance 0.6 mm/kN and 20 % damage) with light white noise passes both rules
// and the evidence is filled in.
TEST(GapParsimony, RealPairPassesBothRulesWithItsEvidence) {
  const ForceCurve sim = voce_tension_curve();
  const double end_mm = sim.u.back() * 1e3;
  const ForceCurve lab = lab_from(sim, {{&find_effect("ductile_damage"), {0.4 * end_mm, 0.2}},
                                        {&find_effect("machine_compliance"), {0.6}}}, 0.0, 0.003, 5);
  DiagnosisOptions options;
  const Diagnosis d = diagnose({lab}, sim, options);
  ASSERT_EQ(d.cause, "ductile_damage+machine_compliance");
  const RankedEffect& pair = d.ranking.front();
  ASSERT_EQ(pair.effect, d.cause);
  EXPECT_TRUE(pair.against_single.done);
  EXPECT_TRUE(pair.against_single.information_ok);
  EXPECT_LT(pair.against_single.bic_pair, pair.against_single.bic_single - kPairBicMargin);
  EXPECT_TRUE(pair.against_single.heldout_done);
  EXPECT_LT(pair.against_single.heldout_error_pair, kPairHeldOutRatio * pair.against_single.heldout_error_single);
  EXPECT_FALSE(pair.also_possible);
}

}  // namespace
}  // namespace dtwire::gap
