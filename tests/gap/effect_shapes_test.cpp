// Shape parameters of the fitted effects (issue 17): each reduces to the earlier form at its
// neutral value, follows its physical form elsewhere, and the diagnosis recovers it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "dtwire/gap/diagnosis.hpp"
#include "dtwire/gap/effects.hpp"
#include "dtwire/gap/force_curve.hpp"
#include "dtwire/gap/synthetic_curves.hpp"
#include "../../gap/src/independent/independent_effects.hpp"

namespace dtwire::gap {
namespace {

ForceCurve with(const ForceCurve& sim, const std::string& effect, const std::vector<double>& p) {
  return apply_effects(sim, {{&find_effect(effect), p}}, curve_scale(sim));
}

// A laboratory curve of 700 points with 0.3 % load noise (seed 5) of the effect put into sim.
ForceCurve noisy_lab(const ForceCurve& sim, const std::string& effect, const std::vector<double>& p) {
  std::mt19937 rng(5);
  LabSampling sampling;
  sampling.points = 700;
  sampling.noise_sigma_N = 0.003 * curve_scale(sim).peak_force_N;
  return sample_lab_curve(with(sim, effect, p), sampling, rng);
}

TEST(GapEffectShapes, NeutralShapeGivesTheEarlierForm) {
  const ForceCurve sim = voce_tension_curve();
  const CurveScale s = curve_scale(sim);
  const ForceCurve linear = with(sim, "machine_compliance", {0.5, 1.0});
  const ForceCurve scaled_u = with(sim, "gauge_length", {1.2, 0.0});
  const ForceCurve constant = with(sim, "strain_rate", {1.1, 0.0, 0.0});
  for (std::size_t i = 0; i < sim.size(); ++i) {
    EXPECT_DOUBLE_EQ(linear.u[i], sim.u[i] + 0.5e-6 * sim.f[i]);
    EXPECT_DOUBLE_EQ(scaled_u.u[i], 1.2 * sim.u[i]);
    EXPECT_NEAR(constant.f[i], 1.1 * sim.f[i], 1e-9 * s.peak_force_N);
    EXPECT_NEAR(constant.u[i], sim.u[i] + 0.1 * sim.f[i] / s.initial_stiffness_N_per_m, 1e-15);
  }
  // A parameter list without the shape (earlier callers) is the neutral shape.
  EXPECT_EQ(with(sim, "machine_compliance", {0.5}).u, linear.u);
  EXPECT_EQ(with(sim, "gauge_length", {1.2}).u, scaled_u.u);
  EXPECT_EQ(with(sim, "strain_rate", {1.1}).f, constant.f);
  EXPECT_EQ(with(sim, "strain_rate", {1.1, 0.0}).f, constant.f);
}

TEST(GapEffectShapes, ShapesFollowTheirPhysicalForms) {
  const ForceCurve sim = voce_tension_curve();
  const CurveScale s = curve_scale(sim);
  const ForceCurve hertz = with(sim, "machine_compliance", {0.5, 2.0 / 3.0});
  const ForceCurve plastic = with(sim, "gauge_length", {1.2, 1.0});
  const ForceCurve fading = with(sim, "strain_rate", {1.1, 1.0});
  for (std::size_t i = 0; i < sim.size(); ++i) {
    const double f = sim.f[i], u = sim.u[i];
    // Hertzian contacts: approach ~ load^(2/3), secant compliance C at the peak force.
    EXPECT_NEAR(hertz.u[i], u + 0.5e-6 * s.peak_force_N * std::pow(f / s.peak_force_N, 2.0 / 3.0), 1e-12);
    // Only the plastic part u - f/k0 is scaled.
    const double elastic = std::min(u, f / s.initial_stiffness_N_per_m);
    EXPECT_NEAR(plastic.u[i], elastic + 1.2 * (u - elastic), 1e-12);
    // The whole gain lost at the end of the test, none at its start.
    EXPECT_NEAR(fading.f[i], (1.0 + 0.1 * (1.0 - u / s.max_displacement_m)) * f, 1e-9 * s.peak_force_N);
  }
  EXPECT_NEAR(fading.f.back(), sim.f.back(), 1e-9 * s.peak_force_N);
}

// The rate gain growing over the test (g < 0) and in the neck (h, past the simulated peak force;
// issue 37), and the bounds that keep the factor on the side of 1 its start is on.
TEST(GapEffectShapes, RateGainGrowsOverTheTestAndInTheNeck) {
  const ForceCurve sim = voce_tension_curve();
  const CurveScale s = curve_scale(sim);
  ASSERT_GT(s.peak_displacement_m, 0.5 * s.max_displacement_m);  // the Voce wire necks
  ASSERT_LT(s.peak_displacement_m, s.max_displacement_m);
  const ForceCurve growing = with(sim, "strain_rate", {1.1, -1.0, 0.0});
  const ForceCurve necking = with(sim, "strain_rate", {1.1, 0.0, 1.0});
  const ForceCurve slower = with(sim, "strain_rate", {0.9, 0.0, 1.0});
  for (std::size_t i = 0; i < sim.size(); ++i) {
    const double f = sim.f[i], u = sim.u[i];
    // Doubled by the end of the test.
    EXPECT_NEAR(growing.f[i], (1.0 + 0.1 * (1.0 + u / s.max_displacement_m)) * f, 1e-9 * s.peak_force_N);
    // Constant up to the peak, then y (2 - y) of the gain added: doubled at the end; a deficit
    // (s0 < 1) shrinks instead, to none at the end.
    const double y = std::max(0.0, (u - s.peak_displacement_m) / (s.max_displacement_m - s.peak_displacement_m));
    EXPECT_NEAR(necking.f[i], (1.0 + 0.1 * (1.0 + y * (2.0 - y))) * f, 1e-9 * s.peak_force_N);
    EXPECT_NEAR(slower.f[i], (1.0 - 0.1 * (1.0 - y * (2.0 - y))) * f, 1e-9 * s.peak_force_N);
  }
  // Over the whole bounds, s stays >= 1 for s0 >= 1 and <= 1 for s0 <= 1: neither a fading nor
  // a growing gain can turn into a softening (damage) or a hardening of the other sign.
  for (double s0 : {0.6, 0.95, 1.0, 1.05, 1.6})
    for (double g : {-1.0, -0.5, 0.0, 0.5, 1.0})
      for (double h : {0.0, 0.5, 1.0}) {
        const ForceCurve r = with(sim, "strain_rate", {s0, g, h});
        for (std::size_t i = 1; i < sim.size(); ++i) {
          const double factor = r.f[i] / sim.f[i];
          if (s0 >= 1.0) {
            EXPECT_GE(factor, 1.0 - 1e-12) << s0 << " " << g << " " << h;
          }
          if (s0 <= 1.0) {
            EXPECT_LE(factor, 1.0 + 1e-12) << s0 << " " << g << " " << h;
          }
          EXPECT_LE(std::abs(factor - 1.0), 4.0 * std::abs(s0 - 1.0) + 1e-12);
        }
      }
  // A curve that runs beyond the simulated test (a --model run) keeps the bounds: the travel is
  // clamped to the test.
  ForceCurve longer = sim;
  for (double& u : longer.u) u *= 1.5;
  for (double s0 : {0.9, 1.1}) {
    const ForceCurve faded = apply_effects(longer, {{&find_effect("strain_rate"), {s0, 1.0, 0.0}}}, s);
    for (std::size_t i = 1; i < sim.size(); ++i)
      EXPECT_GE((faded.f[i] / longer.f[i] - 1.0) * (s0 - 1.0), -1e-15) << "u " << longer.u[i];
  }
  // A curve whose force rises to its end has no neck: the neck parameter does nothing there.
  ForceCurve rising;
  for (int k = 0; k <= 100; ++k) {
    rising.u.push_back(1e-4 * k);
    rising.f.push_back(1000.0 * std::sqrt(k / 100.0));
  }
  EXPECT_EQ(with(rising, "strain_rate", {1.1, 0.3, 1.0}).f, with(rising, "strain_rate", {1.1, 0.3, 0.0}).f);
}

// Hertzian compliance (m = 2/3) with 0.3 % load noise: the linear spring alone leaves a toe-like
// misfit that initial slack took; with the exponent, compliance is the cause and m is recovered.
TEST(GapEffectShapes, HertzianComplianceIsFoundWithItsExponent) {
  const ForceCurve sim = voce_tension_curve();
  const ForceCurve lab = noisy_lab(sim, "machine_compliance", {0.6, 2.0 / 3.0});
  DiagnosisOptions options;
  options.effects = {"machine_compliance", "initial_slack", "grip_slip"};
  options.try_pairs = false;
  const Diagnosis d = diagnose({lab}, sim, options);
  ASSERT_EQ(d.cause, "machine_compliance") << d.reason;
  const RankedEffect& top = d.ranking.front();
  ASSERT_EQ(top.effect, "machine_compliance");
  EXPECT_NEAR(top.fitted[0].params[0], 0.6, 0.06);
  EXPECT_NEAR(top.fitted[0].params[1], 2.0 / 3.0, 0.05);
  EXPECT_LE(top.gap_after, d.noise_floor);
}

// The grip slip's onset spread over the jaw (issue 51): slip = c E[(F_max - F_s,i)+] with the
// onset forces F_s,i ~ N(F_s, w^2), counted from the unloaded grip. Checked against the expectation
// integrated numerically (midpoint rule over +- 8 w), not against the closed form the effect uses.
TEST(GapEffectShapes, GripSlipOnsetSpreadIsTheMeanSlipOverTheJaw) {
  const ForceCurve sim = voce_tension_curve();
  const double onset = 1500.0, rate = 4.0e-6, w = 400.0;  // N, m/N, N
  const ForceCurve sharp = with(sim, "grip_slip", {onset, 4.0, 0.0});
  EXPECT_EQ(with(sim, "grip_slip", {onset, 4.0, 0.0, 0.0}).u, sharp.u);  // w = 0: the earlier form
  const ForceCurve spread = with(sim, "grip_slip", {onset, 4.0, 0.0, w});
  const auto mean_excess = [&](double f) {
    const int n = 4000;
    double sum = 0.0;
    for (int k = 0; k < n; ++k) {
      const double x = onset - 8.0 * w + 16.0 * w * (k + 0.5) / n;
      const double density = std::exp(-0.5 * std::pow((x - onset) / w, 2)) / (w * std::sqrt(2.0 * M_PI));
      sum += std::max(0.0, f - x) * density * 16.0 * w / n;
    }
    return sum;
  };
  double fmax = 0.0;
  for (std::size_t i = 0; i < sim.size(); ++i) {
    fmax = std::max(fmax, sim.f[i]);
    if (i % 25 == 0) {
      EXPECT_NEAR(spread.u[i] - sim.u[i], rate * (mean_excess(fmax) - mean_excess(0.0)), 1e-7) << "at F_max " << fmax;
    }
  }
  EXPECT_DOUBLE_EQ(spread.u.front(), sim.u.front());  // nothing slips at rest
}

// A smoothly setting-in slip (onset 1500 N spread by 400 N, 4 mm/kN) with 0.3 % load noise on the
// Voce wire: the fit from its own starts (the catalogue's) is the cause and recovers the rate and
// the spread within 5 %.
TEST(GapEffectShapes, GripSlipWithASpreadOnsetIsRecovered) {
  const ForceCurve sim = voce_tension_curve();
  const ForceCurve lab = noisy_lab(sim, "grip_slip", {1500.0, 4.0, 0.0, 400.0});
  DiagnosisOptions options;
  options.try_pairs = false;
  const Diagnosis d = diagnose({lab}, sim, options);
  ASSERT_EQ(d.cause, "grip_slip") << d.reason;
  const RankedEffect& top = d.ranking.front();
  ASSERT_EQ(top.effect, "grip_slip");
  EXPECT_NEAR(top.fitted[0].params[1], 4.0, 0.05 * 4.0);
  EXPECT_NEAR(top.fitted[0].params[3], 400.0, 0.05 * 400.0);
  EXPECT_LE(top.gap_after, d.noise_floor);
}

// The independent family's magnitudes stay within the plausible ranges they are drawn over
// (issue 51): the wedge seating's secant compliance at the visible peak (its log part included)
// and the drifting extensometer's gauge factor over the whole test, at the edge draws.
TEST(GapEffectShapes, IndependentSeatingAndDriftStayWithinTheirRanges) {
  const ForceCurve sim = voce_tension_curve();
  const CurveScale s = curve_scale(sim);
  independent::Setting edge;
  edge.draws = {0.95, 0.0, 0.0, 1.0};  // on the edge; F_b 5 % of the peak; drift 6 % down
  edge.scatter = 1.3;                   // a specimen beyond the edge, held on it
  edge.end_m = sim.u.back();
  edge.visible_peak_N = s.peak_force_N;
  edge.stiffness_N_per_m = s.initial_stiffness_N_per_m;
  edge.shape = 0;
  const ForceCurve seated = independent::machine_compliance(sim, edge);
  const auto peak_at = std::max_element(sim.f.begin(), sim.f.end()) - sim.f.begin();
  const double secant_mm_per_kN = (seated.u[peak_at] - sim.u[peak_at]) / sim.f[peak_at] * 1e6;
  EXPECT_NEAR(secant_mm_per_kN, find_effect("machine_compliance").parameters(s)[0].plausible_upper, 1e-9);
  for (const double side : {0.0, 1.0}) {  // draws[1] < 0.5: the factor above 1, else below
    for (const double down : {0.0, 1.0}) {  // draws[2] < 0.5: drifting down, else up
      edge.draws = {0.95, side, down, 1.0};
      const ForceCurve drifting = independent::gauge_length(sim, edge);
      for (std::size_t i = 1; i < sim.size(); ++i) {
        const double factor = drifting.u[i] / sim.u[i];
        EXPECT_GE(factor, 0.5 - 1e-12);
        EXPECT_LE(factor, 1.5 + 1e-12);
      }
    }
  }
}

}  // namespace
}  // namespace dtwire::gap

namespace dtwire::gap {
namespace {

// Knife edges creeping on the wire: two specimens whose extensometer's gauge factor drifts over
// the test (a record of the independent selfcheck's `drifting_knife_edge`, the fitted form being a
// uniform scale; tests/gap/data/drifting_knife_edge). Scaling the displacement of a curve with a
// peak has a basin per way the peaks line up: from the centre and random starts alone the fit
// ended at a scale of 1.08 for these four seeds (of 12 tried, 4), and the diagnosis read
// `grip_slip`; with starts across the range it finds the scale of 1.43 and the gauge.
TEST(GapEffectShapes, ADriftingGaugeIsFoundWhateverTheSeed) {
  const std::string data = std::string(DTWIRE_SOURCE_DIR) + "/tests/gap/data/drifting_knife_edge/";
  const CurveConversion si;
  const std::vector<ForceCurve> labs = {load_force_curve(data + "lab_1.csv", si), load_force_curve(data + "lab_2.csv", si)};
  const ForceCurve sim = load_force_curve(data + "sim.csv", si);
  for (unsigned seed : {23u, 25u, 28u, 29u}) {
    DiagnosisOptions options;
    options.seed = seed;
    options.try_pairs = false;
    const Diagnosis d = diagnose(labs, sim, options);
    EXPECT_EQ(d.cause, "gauge_length") << "seed " << seed;
    const auto gauge = std::find_if(d.ranking.begin(), d.ranking.end(),
                                    [](const RankedEffect& r) { return r.effect == "gauge_length"; });
    ASSERT_NE(gauge, d.ranking.end());
    EXPECT_NEAR(gauge->fitted.at(0).params.at(0), 1.43, 0.02) << "seed " << seed;
  }
}

// A rate jump at 6.4 mm of the backbone's 87.5 mm (two specimens; a record of the independent
// selfcheck, `--trials 20 --seed 17`, trial 24; tests/gap/data/rate_jump_between_starts). The
// fit of where the rate changes has a basin about one transient (5 % of the travel) wide around
// each place: from starts every 20 % of the travel it ended at 12.8 mm, gap 0.024 against the floor
// 0.0081, and a pair with a neutral partner (compliance 0) found the jump, so the diagnosis read
// the pair. From starts every 10 % the single finds it and closes the gap.
TEST(GapEffectShapes, ARateJumpBetweenTwoStartsIsFound) {
  const std::string data = std::string(DTWIRE_SOURCE_DIR) + "/tests/gap/data/rate_jump_between_starts/";
  const CurveConversion si;
  const std::vector<ForceCurve> labs = {load_force_curve(data + "lab_1.csv", si), load_force_curve(data + "lab_2.csv", si)};
  const Diagnosis d = diagnose(labs, load_force_curve(data + "sim.csv", si), {});
  EXPECT_EQ(d.cause, "strain_rate") << d.reason;
  const auto rate = std::find_if(d.ranking.begin(), d.ranking.end(),
                                 [](const RankedEffect& r) { return r.effect == "strain_rate"; });
  ASSERT_NE(rate, d.ranking.end());
  EXPECT_LE(rate->gap_after, d.noise_floor);
  EXPECT_NEAR(rate->fitted.at(0).params.at(3), 6.4, 0.5);
}

// A late exponential damage, D proportional to exp(4x) - 1 after its onset, on the Voce wire (two
// specimens broken apart; a record of the independent selfcheck, `--trials 20 --seed 17`,
// trial 47; tests/gap/data/late_damage). While the law ended at the simulation's end with its
// damage there bounded at 0.95, and grew as the square, it could not reach the test's end
// steeply enough (0.95 at the bound, onset 0): a gauge scale of 0.78 took the rest and the
// diagnosis read the pair `ductile_damage+gauge_length`. With the law ending at the test's end and
// its growth exponent the single closes the gap, its damage within the plausible range.
TEST(GapEffectShapes, ALateDamageIsOneEffectNotAPair) {
  const std::string data = std::string(DTWIRE_SOURCE_DIR) + "/tests/gap/data/late_damage/";
  const CurveConversion si;
  const std::vector<ForceCurve> labs = {load_force_curve(data + "lab_1.csv", si), load_force_curve(data + "lab_2.csv", si)};
  DiagnosisOptions options;
  options.effects = {"ductile_damage", "gauge_length"};  // the pair it was read as
  const Diagnosis d = diagnose(labs, load_force_curve(data + "sim.csv", si), options);
  EXPECT_EQ(d.cause, "ductile_damage") << d.reason;
  const auto damage = std::find_if(d.ranking.begin(), d.ranking.end(),
                                   [](const RankedEffect& r) { return r.effect == "ductile_damage"; });
  ASSERT_NE(damage, d.ranking.end());
  EXPECT_LE(damage->gap_after, d.noise_floor);
  const ParameterSpec magnitude = find_effect("ductile_damage").parameters(curve_scale(d.sim)).at(1);
  EXPECT_GE(damage->fitted.at(0).params.at(1), magnitude.plausible_lower);
  EXPECT_LE(damage->fitted.at(0).params.at(1), magnitude.plausible_upper);
  EXPECT_GT(damage->fitted.at(0).params.at(2), 2.0) << "a late damage grows faster than the square";
}

// An adiabatic softening of the flow stress (two specimens; a record of the independent
// selfcheck, `--effects strain_rate --trials 60 --seed 13`, trial 36; tests/gap/data/
// rate_not_a_pair). The single rate fit stopped in a local minimum (factor 0.95, gap twice the
// floor) while the pair with the damage found the rate's better fit (factor 0.86) with the
// damage at 0, switched off: the pair was read as the cause. A pair with one member at its
// neutral value is the other effect alone: the single is refitted from the pair's values.
TEST(GapEffectShapes, APairWithOneMemberSwitchedOffIsTheOtherAlone) {
  const std::string data = std::string(DTWIRE_SOURCE_DIR) + "/tests/gap/data/rate_not_a_pair/";
  const CurveConversion si;
  const std::vector<ForceCurve> labs = {load_force_curve(data + "lab_1.csv", si), load_force_curve(data + "lab_2.csv", si)};
  DiagnosisOptions options;
  options.effects = {"strain_rate", "ductile_damage", "gauge_length"};
  const Diagnosis d = diagnose(labs, load_force_curve(data + "sim.csv", si), options);
  EXPECT_EQ(d.cause, "strain_rate") << d.reason;
  const auto rate = std::find_if(d.ranking.begin(), d.ranking.end(), [](const RankedEffect& r) { return r.effect == "strain_rate"; });
  ASSERT_NE(rate, d.ranking.end());
  EXPECT_LE(rate->gap_after, d.noise_floor);
}

// The same record with the selfcheck's own seed for the trial (13 + 36): there the pairs found the
// rate's better fit with a gauge of 0.889 beside it, not switched off, and the trial read
// `gauge_length+strain_rate`; the single rate fit, started only at the factor 1 where the misfit
// is flat in the shape parameters, stopped at 0.95 (gap 0.0082, twice the floor). Starts at the
// factor range's edges reach the adiabatic basin (0.86, the gain lost to the end) alone.
TEST(GapEffectShapes, AFadingRateGainIsFoundByTheSingleFitFromTheFactorsEdges) {
  const std::string data = std::string(DTWIRE_SOURCE_DIR) + "/tests/gap/data/rate_not_a_pair/";
  const CurveConversion si;
  const std::vector<ForceCurve> labs = {load_force_curve(data + "lab_1.csv", si), load_force_curve(data + "lab_2.csv", si)};
  DiagnosisOptions options;
  options.seed = 49;
  const Diagnosis d = diagnose(labs, load_force_curve(data + "sim.csv", si), options);
  EXPECT_EQ(d.cause, "strain_rate") << d.reason;
  const auto rate = std::find_if(d.ranking.begin(), d.ranking.end(), [](const RankedEffect& r) { return r.effect == "strain_rate"; });
  ASSERT_NE(rate, d.ranking.end());
  EXPECT_LE(rate->gap_after, d.noise_floor);
  EXPECT_NEAR(rate->fitted.at(0).params.at(0), 0.86, 0.02);  // the stress factor at the start
  EXPECT_GT(rate->fitted.at(0).params.at(1), 0.8);           // the gain lost by the end
}

}  // namespace
}  // namespace dtwire::gap
