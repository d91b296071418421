// The verdict's three cases (issue 51): an effect closes the gap with a plausible magnitude (the
// cause); an effect closes it only with a magnitude beyond its plausible range (named, with its
// figures); no effect closes it. The laboratory curves are built here from the wire's
// mechanics (an extensometer over part of a necking wire), not from the fitted augmentation.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "dtwire/gap/diagnosis.hpp"
#include "dtwire/gap/gap_report.hpp"
#include "dtwire/gap/synthetic_curves.hpp"

namespace dtwire::gap {
namespace {

// The Voce wire of the selfcheck (250 mm between the grips) recorded by an extensometer over a
// fraction `share` of it: up to the peak force the strain is uniform, so the extensometer sees
// `share` of the elongation; past the peak the strain localises in the neck, which lies inside
// the extensometer, so it sees all of the further elongation (the rest of the wire unloads
// elastically by (F_p - F) / k over the length outside the extensometer).
ForceCurve extensometer_curve(const ForceCurve& wire, double share, double noise_fraction, unsigned seed) {
  const auto peak = static_cast<std::size_t>(std::max_element(wire.f.begin(), wire.f.end()) - wire.f.begin());
  const double u_peak = wire.u[peak], f_peak = wire.f[peak];
  const double k_outside = wire.f[1] / wire.u[1] / (1.0 - share);  // the length outside is stiffer
  ForceCurve lab = wire;
  for (std::size_t i = 0; i < wire.size(); ++i)
    lab.u[i] = i <= peak ? share * wire.u[i]
                         : share * u_peak + (wire.u[i] - u_peak) + (f_peak - wire.f[i]) / k_outside;
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, noise_fraction * f_peak);
  for (double& f : lab.f) f += noise(rng);
  lab.source = "extensometer over " + std::to_string(share) + " of the wire";
  return lab;
}

const RankedEffect& entry(const Diagnosis& d, const std::string& effect) {
  const auto found = std::find_if(d.ranking.begin(), d.ranking.end(), [&](const RankedEffect& r) { return r.effect == effect; });
  if (found == d.ranking.end()) throw std::runtime_error("no ranking entry " + effect);
  return *found;
}

// A reason that says no effect reduced the gap must be true.
void expect_reason_true(const Diagnosis& d) {
  if (d.reason.find("no effect reduces the gap") == std::string::npos) return;
  for (const RankedEffect& r : d.ranking) EXPECT_LE(r.shrink, 0.0) << r.effect << " reduced it: " << d.reason;
}

TEST(GapVerdict, ExtensometerOverPartOfTheWireIsTheGaugeLengthCause) {
  // 160 mm of the 250 mm: an extensometer over part of the wire, as in the Dundee SW tests.
  const ForceCurve sim = voce_tension_curve();
  const Diagnosis d = diagnose({extensometer_curve(sim, 0.64, 0.003, 3)}, sim, {});
  EXPECT_EQ(d.verdict, "cause") << d.reason;
  ASSERT_EQ(d.cause, "gauge_length") << d.reason;
  const RankedEffect& gauge = entry(d, "gauge_length");
  EXPECT_FALSE(gauge.implausible);
  EXPECT_GT(gauge.shrink, 0.7);
  // Fitted over the whole curve, the ratio lies between the uniform part's 0.64 and 1.
  EXPECT_GT(gauge.fitted.front().params[0], 0.6);
  EXPECT_LT(gauge.fitted.front().params[0], 0.8);
  expect_reason_true(d);
}

TEST(GapVerdict, AnEffectThatClosesTheGapOnlyBeyondItsRangeIsNamedWithItsFigures) {
  // The wire is 30 % stronger than the model (every flow-stress term of the Voce law x 1.3, same
  // E: a material the model was not calibrated on). Only a rate factor of about 1.3 closes that
  // gap, beyond what a rate reaches (0.85-1.15): the verdict names it with its figures instead
  // of calling it the cause, and instead of saying that nothing reduced the gap.
  const ForceCurve sim = voce_tension_curve();
  VoceWire stronger;
  stronger.yield_Pa *= 1.3;
  stronger.saturation_Pa *= 1.3;
  stronger.linear_Pa *= 1.3;
  ForceCurve lab = voce_tension_curve(stronger);
  std::mt19937 rng(4);
  const double peak = *std::max_element(lab.f.begin(), lab.f.end());
  std::normal_distribution<double> noise(0.0, 0.003 * peak);
  for (double& f : lab.f) f += noise(rng);
  lab.source = "wire 30 % stronger";
  const Diagnosis d = diagnose({lab}, sim, {});
  EXPECT_EQ(d.cause, "none") << d.reason;
  ASSERT_EQ(d.verdict, "beyond_plausible_range") << diagnosis_markdown(d);
  EXPECT_EQ(d.refused_effect, "strain_rate") << d.reason;
  const RankedEffect& refused = entry(d, d.refused_effect);
  EXPECT_TRUE(refused.implausible);
  EXPECT_TRUE(refused.qualifies_but_implausible);
  EXPECT_GT(refused.shrink, 0.8);
  ASSERT_EQ(refused.beyond_range.size(), 1u);
  EXPECT_EQ(refused.beyond_range.front().parameter, "stress_factor_1");
  EXPECT_NEAR(refused.beyond_range.front().value, 1.3, 0.05);
  // The sentence names the effect, its share of the gap, the magnitude and the range.
  EXPECT_NE(d.reason.find("strain_rate explains "), std::string::npos) << d.reason;
  EXPECT_NE(d.reason.find("% of the gap but needs a stress_factor_1 of 1."), std::string::npos) << d.reason;
  EXPECT_NE(d.reason.find("outside [0.85, 1.15]"), std::string::npos) << d.reason;
  const nlohmann::json j = diagnosis_json(d);
  EXPECT_EQ(j.at("verdict"), "beyond_plausible_range");
  EXPECT_EQ(j.at("refused_for_magnitude").at("effect"), "strain_rate");
  EXPECT_EQ(j.at("refused_for_magnitude").at("beyond_plausible_range")[0].at("parameter"), "stress_factor_1");
  EXPECT_EQ(j.at("refused_for_magnitude").at("beyond_plausible_range")[0].at("plausible")[1], 1.15);
  EXPECT_NE(diagnosis_markdown(d).find("strain_rate explains"), std::string::npos);
  expect_reason_true(d);
}

TEST(GapVerdict, NoEffectClosesARippleAndTheReasonSaysHowFarTheBestGot) {
  // A force ripple of 3 % over ten periods (a load cell picking up a resonance): no catalogue
  // effect has that shape.
  const ForceCurve sim = voce_tension_curve();
  ForceCurve lab = sim;
  const double peak = *std::max_element(sim.f.begin(), sim.f.end());
  std::mt19937 rng(5);
  std::normal_distribution<double> noise(0.0, 0.003 * peak);
  for (std::size_t i = 0; i < lab.size(); ++i)
    lab.f[i] += 0.03 * peak * std::sin(2.0 * M_PI * 10.0 * sim.u[i] / sim.u.back()) + noise(rng);
  DiagnosisOptions options;
  options.try_pairs = false;
  const Diagnosis d = diagnose({lab}, sim, options);
  EXPECT_EQ(d.cause, "none") << d.reason;
  EXPECT_EQ(d.verdict, "no_effect_closes") << d.reason;
  EXPECT_TRUE(d.refused_effect.empty());
  EXPECT_EQ(d.reason.find("explains"), std::string::npos) << d.reason;
  expect_reason_true(d);
}

}  // namespace
}  // namespace dtwire::gap

#include "dtwire/gap/force_curve.hpp"

namespace dtwire::gap {
namespace {

// An extensometer whose scale applies to the plastic part only, on the DEM backbone (a record of
// the independent selfcheck, `--effects gauge_length --seed 13`, trial 24; tests/gap/data/
// gauge_or_grip_slip). The curve hardens to its end, where the force is a function of the
// displacement, so a grip slip growing with the force stretches it as the gauge does: both close
// the gap to the noise floor (gap after 0.0018 and 0.0020, floor 0.0025) and the information
// criterion ranks the slip first. The verdict names the gauge beside it, never the slip alone.
TEST(GapVerdict, AnEffectThatAlsoClosesTheGapIsNamedBesideTheCause) {
  const std::string data = std::string(DTWIRE_SOURCE_DIR) + "/tests/gap/data/gauge_or_grip_slip/";
  const CurveConversion si;
  const std::vector<ForceCurve> labs = {load_force_curve(data + "lab_1.csv", si), load_force_curve(data + "lab_2.csv", si)};
  DiagnosisOptions options;
  options.try_pairs = false;
  const Diagnosis d = diagnose(labs, load_force_curve(data + "sim.csv", si), options);
  ASSERT_EQ(d.verdict, "cause") << d.reason;
  std::vector<std::string> named = d.also_closes;
  named.push_back(d.cause);
  EXPECT_NE(std::find(named.begin(), named.end(), "gauge_length"), named.end()) << d.reason;
  EXPECT_NE(std::find(named.begin(), named.end(), "grip_slip"), named.end()) << d.reason;
  for (const std::string& other : d.also_closes) {
    EXPECT_LE(entry(d, other).gap_after, d.noise_floor);
    EXPECT_NE(d.reason.find("so does " + d.also_closes.front()), std::string::npos) << d.reason;
  }
  EXPECT_EQ(diagnosis_json(d).at("also_closes").size(), d.also_closes.size());
}

}  // namespace
}  // namespace dtwire::gap

#include "../../gap/src/evidence.hpp"

namespace dtwire::gap {
namespace {

// The rule behind `also_closes`, as the summary-figure diagnosis applies it to its candidates:
// qualifying singles under the floor other than the cause; a pair, a candidate above the floor
// or one that does not qualify is not named.
TEST(GapVerdict, AlsoClosingNamesQualifyingSinglesUnderTheFloorOnly) {
  struct Candidate {
    std::string effect;
    bool qualifies;
    double gap_after, aic;
  };
  const std::vector<Candidate> ranking = {{"dt_weakening", true, 0.5, 2.0},   {"sw_softening", true, 0.8, 6.5},
                                          {"a+b", true, 0.3, 1.0},           {"mesh_distortion", true, 1.2, 9.0},
                                          {"edge_sliding", false, 0.4, 3.0}, {"slack_state", true, 0.9, 4.0}};
  std::vector<std::string> names;
  const std::string text = evidence::also_closing(ranking, ranking[0], 1.0, "AIC",
                                                  [](const Candidate& c) { return c.aic; }, &names);
  EXPECT_EQ(names, (std::vector<std::string>{"sw_softening", "slack_state"}));
  EXPECT_EQ(text, "; so does sw_softening (AIC +4.5), slack_state (AIC +2): the laboratory's scatter does not tell "
                  "them apart");
  names.clear();
  EXPECT_EQ(evidence::also_closing(ranking, ranking[0], 0.6, "AIC", [](const Candidate& c) { return c.aic; }, &names),
            "");
  EXPECT_TRUE(names.empty());
}

}  // namespace
}  // namespace dtwire::gap

#include "dtwire/gap/effect_fit.hpp"

namespace dtwire::gap {
namespace {

// The profile behind the edge rule: a parameter held at a value keeps it while the others are
// refitted. A damage (onset 8 mm, 0.3 at the test's end, grown as the square) and a frame
// compliance of 0.4 mm/kN, 0.4 % noise: with the damage's magnitude held at its truth the
// compliance and the onset are recovered; held at 0.15 the fit is worse and keeps 0.15.
TEST(GapVerdict, AHeldMagnitudeKeepsItsValueAndTheRestAreRefitted) {
  const ForceCurve sim = voce_tension_curve();
  FitProblem problem;
  problem.sim = sim;
  problem.scale = curve_scale(sim);
  problem.scale.test_end_m = sim.u.back();
  const EffectSpec& damage = find_effect("ductile_damage");
  const EffectSpec& compliance = find_effect("machine_compliance");
  const ForceCurve model = apply_effects(sim, {{&damage, {8.0, 0.3, 2.0}}, {&compliance, {0.4}}}, problem.scale);
  std::mt19937 noise_rng(21);
  LabSampling sampling;
  sampling.points = 700;
  sampling.noise_sigma_N = 0.004 * problem.scale.peak_force_N;
  problem.labs = {make_comparison(sample_lab_curve(model, sampling, noise_rng))};

  std::mt19937 rng(1);
  const EffectFit at_truth = fit_effects(problem, {&damage, &compliance}, {}, 2, rng, {{0, -1, damage.magnitude, 0.3}});
  EXPECT_EQ(at_truth.effects.at(0).params.at(damage.magnitude), 0.3);
  const auto parameters = damage.parameters(problem.scale).size() + compliance.parameters(problem.scale).size();
  EXPECT_EQ(at_truth.parameter_count, static_cast<int>(parameters) - 1);
  EXPECT_NEAR(at_truth.effects.at(1).params.at(0), 0.4, 0.04);
  EXPECT_NEAR(at_truth.effects.at(0).params.at(0), 8.0, 0.8);
  const EffectFit held_low = fit_effects(problem, {&damage, &compliance}, {}, 2, rng, {{0, -1, damage.magnitude, 0.15}});
  EXPECT_EQ(held_low.effects.at(0).params.at(damage.magnitude), 0.15);
  EXPECT_GT(held_low.weighted_sse, 2.0 * at_truth.weighted_sse);
}

// A selfcheck record of one laboratory curve (tests/gap/data/NAME: lab_1.csv, sim.csv) diagnosed
// over `effects`.
Diagnosis diagnose_record(const std::string& name, const std::vector<std::string>& effects) {
  const std::string data = std::string(DTWIRE_SOURCE_DIR) + "/tests/gap/data/" + name + "/";
  const CurveConversion si;
  DiagnosisOptions options;
  options.effects = effects;
  return diagnose({load_force_curve(data + "lab_1.csv", si)}, load_force_curve(data + "sim.csv", si), options);
}

// A pair the fitted selfcheck drew (`gap selfcheck --family fitted --seed 7`, trial 83; tests/
// gap/data/pair_at_edge, the injected parameters in the lab file's header): a damage of 0.5 at
// the test's end, the plausible range's edge, and a frame compliance of 0.227 mm/kN, 27 x the
// noise floor. The pair fits a damage of 0.512, just past the edge. Held at 0.5 with the
// compliance refitted it fits as well, so the pair is the cause; judged at 0.5 with the
// compliance left as fitted it was refused (over the whole catalogue the verdict read `none`,
// "needs a damage_at_test_end_1 of 0.512"; over these three effects, `ductile_damage` alone).
TEST(GapVerdict, AMagnitudeJustPastItsRangeIsTheEdgeWhenThePartnerTakesUpTheRest) {
  const Diagnosis d = diagnose_record("pair_at_edge", {"ductile_damage", "machine_compliance", "initial_slack"});
  ASSERT_EQ(d.cause, "ductile_damage+machine_compliance") << d.reason;
  EXPECT_EQ(d.verdict, "cause");
  const RankedEffect& pair = entry(d, d.cause);
  EXPECT_FALSE(pair.implausible);
  EXPECT_GT(pair.shrink, 0.9);
  const AppliedEffect& fitted_damage = pair.fitted.at(0).effect->name == "ductile_damage" ? pair.fitted.at(0) : pair.fitted.at(1);
  const ParameterSpec magnitude = fitted_damage.effect->parameters(curve_scale(d.sim)).at(fitted_damage.effect->magnitude);
  EXPECT_GT(fitted_damage.params.at(fitted_damage.effect->magnitude), magnitude.plausible_upper) << "the case is one beyond the edge";
  EXPECT_LT(fitted_damage.params.at(fitted_damage.effect->magnitude), 1.1 * magnitude.plausible_upper);
  // The verdict says so, in the text and the JSON.
  ASSERT_EQ(pair.at_range_edge.size(), 1u);
  EXPECT_EQ(pair.at_range_edge.front().parameter, "damage_at_test_end_1");
  EXPECT_NE(d.reason.find("its damage_at_test_end_1 of 0.51"), std::string::npos) << d.reason;
  EXPECT_NE(d.reason.find("is the edge of [0.02, 0.5] within what the data tell"), std::string::npos) << d.reason;
  const nlohmann::json j = diagnosis_json(d);
  bool listed = false;
  for (const auto& r : j.at("ranking"))
    if (r.at("effect") == d.cause) listed = r.at("at_plausible_edge")[0].at("parameter") == "damage_at_test_end_1";
  EXPECT_TRUE(listed);
}

// A single that closes the gap only beyond its range does not stand in for a plausible pair
// (`gap selfcheck --family fitted --seed 11 --pair-trials 16`, trial 7; tests/gap/data/
// slip_and_rate_pair, the injected parameters in the lab file's header): a grip slip of 10 mm/kN,
// its range's edge, with a rate factor of 0.853, 28 x the floor. The slip alone explains 96 % of
// the gap with 50 mm/kN; that single left the gap under 1.5 x the floor, so no pair was tried and
// the verdict read "no cause within the plausible ranges". Judged by the singles that can be the
// cause, the pairs are searched and the slip + rate pair is the cause.
TEST(GapVerdict, ASingleBeyondItsRangeDoesNotSpareThePairsTheirSearch) {
  const Diagnosis d = diagnose_record("slip_and_rate_pair", {"grip_slip", "strain_rate", "ductile_damage"});
  ASSERT_EQ(d.cause, "grip_slip+strain_rate") << d.reason;
  const RankedEffect& slip = entry(d, "grip_slip");
  EXPECT_TRUE(slip.implausible);
  EXPECT_LT(slip.gap_after, 1.5 * d.noise_floor) << "the case is one where the implausible single came close";
  const RankedEffect& pair = entry(d, d.cause);
  EXPECT_LE(pair.gap_after, d.noise_floor);
  for (const AppliedEffect& a : pair.fitted)
    if (a.effect->name == "strain_rate") EXPECT_NEAR(a.params.at(0), 0.853, 0.03);
}

// Both magnitudes of a pair on their edges (`gap selfcheck --family fitted --seed 11
// --pair-trials 16`, trial 9; tests/gap/data/pair_both_at_edges): a gauge scale of 1.5 and a grip
// slip of 10 mm/kN. The pair fits a slip of 10.1; held at 10, the refit pushes the gauge past
// 1.5, so the gauge is held at its edge too and the fit repeated: the pair is the cause. With
// the partner's new magnitude refused instead of held, the verdict read `none`.
TEST(GapVerdict, APartnerPushedPastItsEdgeIsHeldThereToo) {
  const Diagnosis d = diagnose_record("pair_both_at_edges", {"gauge_length", "grip_slip", "machine_compliance"});
  ASSERT_EQ(d.cause, "gauge_length+grip_slip") << d.reason;
  const RankedEffect& pair = entry(d, d.cause);
  EXPECT_FALSE(pair.implausible);
  EXPECT_LE(pair.gap_after, d.noise_floor);
  ASSERT_FALSE(pair.at_range_edge.empty());
  EXPECT_EQ(pair.at_range_edge.front().parameter, "slip_mm_per_kN");
}

}  // namespace
}  // namespace dtwire::gap
