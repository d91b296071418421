#include "dtwire/gap/selfcheck.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <map>
#include <random>
#include <sstream>
#include <stdexcept>

#include "dtwire/core/csv.hpp"
#include "dtwire/core/units.hpp"
#include "dtwire/gap/diagnosis.hpp"
#include "dtwire/gap/synthetic_curves.hpp"
#include "independent/independent_effects.hpp"

namespace dtwire::gap {

const std::vector<std::string>& selfcheck_effects() {
  static const std::vector<std::string> names = {"machine_compliance", "grip_slip", "initial_slack",
                                                 "gauge_length", "ductile_damage", "strain_rate"};
  return names;
}

namespace {

double uniform(std::mt19937& rng, double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(rng);
}

// A magnitude from `inner` (the smallest the trial should show above its noise) to `outer` (the
// plausible range's edge away from the neutral value, issue 51): uniform, with a fifth of the
// draws on the edge itself, so that a range too narrow for the diagnosis shows as missed trials.
double toward_edge(std::mt19937& rng, double inner, double outer) {
  return inner + (outer - inner) * std::min(1.0, uniform(rng, 0, 1) / 0.8);
}

// The plausible range of an effect's magnitude (the catalogue's).
ParameterSpec magnitude_range(const std::string& effect, const ForceCurve& sim) {
  const EffectSpec& e = find_effect(effect);
  return e.parameters(curve_scale(sim)).at(e.magnitude);
}

// Away from the neutral value on either side, out to the plausible range's edges.
double either_side(std::mt19937& rng, const ParameterSpec& range, double neutral, double margin) {
  return uniform(rng, 0, 1) < 0.5 ? toward_edge(rng, neutral + margin, range.plausible_upper)
                                  : toward_edge(rng, neutral - margin, range.plausible_lower);
}

struct Base {
  std::string name;
  ForceCurve curve;
  double min_end_fraction;
};

// Magnitudes for an injected effect over its whole plausible range (catalogue), relative to the
// visible part of the test where the range is.
std::vector<double> draw_params(const std::string& effect, const ForceCurve& sim, double end_m,
                                double visible_peak_N, std::mt19937& rng) {
  const ParameterSpec range = magnitude_range(effect, sim);
  if (effect == "machine_compliance") return {toward_edge(rng, 0.1, range.plausible_upper)};
  if (effect == "grip_slip") {
    const double step = uniform(rng, 0, 1) < 0.5 ? 0.0 : uniform(rng, 0.1, 0.5);
    return {uniform(rng, 0.3, 0.8) * visible_peak_N, toward_edge(rng, 1.0, range.plausible_upper), step};
  }
  if (effect == "initial_slack") {
    const ParameterSpec toe = find_effect(effect).parameters(curve_scale(sim)).at(1);
    const double toe_edge = toe.plausible_upper / curve_scale(sim).peak_force_N;
    return {toward_edge(rng, 0.2, range.plausible_upper), toward_edge(rng, 0.01, toe_edge) * visible_peak_N};
  }
  if (effect == "gauge_length") return {either_side(rng, range, 1.0, 0.05)};
  if (effect == "ductile_damage") {
    // The magnitude is the damage the test shows at its end (the law ends there, run_trial);
    // the growth exponent is drawn across its whole range (linear to strongly accelerating).
    const double onset = uniform(rng, 0.2, 0.6) * end_m;
    const ParameterSpec growth = find_effect(effect).parameters(curve_scale(sim)).at(2);
    return {onset * 1e3, toward_edge(rng, 0.05, range.plausible_upper),
            uniform(rng, growth.plausible_lower, growth.plausible_upper)};
  }
  if (effect == "strain_rate") {
    // Half the trials change the rate during the test (issue 51), at 20-60 % of what it shows.
    const double factor = either_side(rng, range, 1.0, 0.04);
    const double changed_at_mm = uniform(rng, 0, 1) < 0.5 ? 0.0 : uniform(rng, 0.2, 0.6) * end_m * 1e3;
    return {factor, 0.0, 0.0, changed_at_mm};
  }
  return {};
}

// A trial of `base` with `effects` injected: the truth is their sorted names joined by '+'.
SelfcheckTrial trial_of(const Base& base, const std::vector<std::string>& effects) {
  SelfcheckTrial t;
  t.base = base.name;
  std::vector<std::string> sorted = effects;
  std::sort(sorted.begin(), sorted.end());
  t.truth = "none";
  for (std::size_t i = 0; i < sorted.size(); ++i) t.truth = (i ? t.truth + "+" : "") + sorted[i];
  return t;
}

std::string injected_text(const std::vector<AppliedEffect>& injected, const CurveScale& scale) {
  std::ostringstream s;
  s.precision(4);
  for (std::size_t e = 0; e < injected.size(); ++e) {
    const auto specs = injected[e].effect->parameters(scale);
    s << (e ? "; " : "") << injected[e].effect->name << ":";
    for (std::size_t k = 0; k < specs.size() && k < injected[e].params.size(); ++k)
      s << (k ? ", " : " ") << specs[k].name << "=" << injected[e].params[k];
  }
  return s.str();
}

SelfcheckTrial run_trial(const Base& base, const std::vector<std::string>& effects,
                         std::mt19937& rng, unsigned seed, std::vector<ForceCurve>& labs_out) {
  const ForceCurve& sim = base.curve;
  CurveScale scale = curve_scale(sim);
  const double end_fraction = uniform(rng, base.min_end_fraction, 1.0);
  const double end_sim = end_fraction * sim.u.back();
  scale.test_end_m = end_sim;  // where an effect that grows along the test (damage) is judged
  double visible_peak = 0.0;
  std::size_t last = 0;
  for (std::size_t i = 0; i < sim.size() && sim.u[i] <= end_sim; ++i) {
    visible_peak = std::max(visible_peak, sim.f[i]);
    last = i;
  }
  std::vector<AppliedEffect> injected;
  for (const std::string& name : effects)
    injected.push_back({&find_effect(name), draw_params(name, sim, end_sim, visible_peak, rng)});
  const ForceCurve lab_model = apply_effects(sim, injected, scale);
  double end_lab = 0.0;
  for (std::size_t i = 0; i <= last; ++i) end_lab = std::max(end_lab, lab_model.u[i]);
  LabSampling sampling;
  sampling.points = static_cast<std::size_t>(uniform(rng, 400, 1500));
  sampling.end_m = end_lab;
  sampling.noise_sigma_N = uniform(rng, 0.002, 0.008) * visible_peak;
  sampling.noise_rho = uniform(rng, 0.0, 0.3);
  const ForceCurve lab = sample_lab_curve(lab_model, sampling, rng);

  DiagnosisOptions options;
  options.seed = seed;
  labs_out = {lab};
  const Diagnosis d = diagnose({lab}, sim, options);
  SelfcheckTrial t = trial_of(base, effects);
  t.injected = injected_text(injected, scale);
  t.predicted = d.cause;
  t.gap_before = d.gap_before;
  t.noise_floor = d.noise_floor;
  for (const RankedEffect& r : d.ranking)
    if (r.effect == d.cause) t.shrink = r.shrink;
  if (effects.size() == 1 && d.cause == effects.front()) {
    const EffectSpec& spec = find_effect(effects.front());
    const double truth = injected.front().params[spec.magnitude];
    for (const RankedEffect& r : d.ranking)
      if (r.effect == d.cause) {
        const double fitted = r.fitted.front().params[spec.magnitude];
        t.parameter_error = std::abs(fitted - truth) / std::abs(truth - spec.neutral);
      }
  }
  return t;
}

// Initial stiffness of the base model: steepest secant up to half its peak.
double initial_stiffness(const ForceCurve& sim) {
  const double peak = *std::max_element(sim.f.begin(), sim.f.end());
  double k = 0.0;
  for (std::size_t i = 1; i < sim.size() && sim.f[i] <= 0.5 * peak; ++i)
    if (sim.u[i] > sim.u.front()) k = std::max(k, (sim.f[i] - sim.f.front()) / (sim.u[i] - sim.u.front()));
  return k > 0 ? k : peak / sim.u.back();
}

// Independent family: each effect in one of its other physical forms, `repeats` specimens with
// scatter (base force and displacement each +- 1.5 % sd, effect magnitude +- 10 % sd), each
// record with irregular sampling, AR(1) load noise with rho 0.5-0.9, load-cell drift and the
// record ending where the specimen broke, with the fracture's drop. The diagnosis gets the bare
// base model.
SelfcheckTrial run_independent_trial(const Base& base, const std::vector<std::string>& effects,
                                     std::size_t repeats, std::mt19937& rng, unsigned seed,
                                     std::vector<ForceCurve>& labs_out) {
  const ForceCurve& sim = base.curve;
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<independent::Setting> settings(effects.size());
  for (std::size_t e = 0; e < effects.size(); ++e) {
    independent::Setting& s = settings[e];
    s.shape = static_cast<int>(uniform(rng, 0, independent::shape_count(effects[e]) - 1e-9));
    for (int k = 0; k < 4; ++k) s.draws.push_back(uniform(rng, 0, 1));
  }
  std::vector<ForceCurve> labs;
  for (std::size_t r = 0; r < std::max<std::size_t>(repeats, 1); ++r) {
    ForceCurve specimen = sim;
    const double force_scatter = 1.0 + 0.015 * normal(rng), length_scatter = 1.0 + 0.015 * normal(rng);
    for (std::size_t i = 0; i < specimen.size(); ++i) {
      specimen.u[i] *= length_scatter;
      specimen.f[i] *= force_scatter;
    }
    // Fracture: the record ends at 60-100 % (Voce) or 30-100 % (backbone) of the model travel.
    const double end = uniform(rng, base.min_end_fraction, 1.0) * specimen.u.back();
    double peak = 0.0;
    for (std::size_t i = 0; i < specimen.size() && specimen.u[i] <= end; ++i) peak = std::max(peak, specimen.f[i]);
    ForceCurve truth = specimen;
    for (std::size_t e = 0; e < effects.size(); ++e) {
      independent::Setting s = settings[e];
      s.scatter = 1.0 + 0.1 * normal(rng);
      s.end_m = e == 0 ? end : truth.u.back();
      s.visible_peak_N = peak;
      s.stiffness_N_per_m = initial_stiffness(specimen);
      truth = independent::apply(effects[e], e == 0 ? specimen : truth, s);
    }
    if (effects.empty()) truth = independent::visible(specimen, end);
    independent::Measurement m;
    m.points = static_cast<std::size_t>(uniform(rng, 300, 1500));
    m.end_m = *std::max_element(truth.u.begin(), truth.u.end());
    m.noise_sigma_N = uniform(rng, 0.002, 0.008) * peak;
    m.noise_rho = uniform(rng, 0.5, 0.9);
    m.drift_N = uniform(rng, -0.005, 0.005) * peak;
    m.jitter = uniform(rng, 0.0, 0.5);
    m.fracture = true;
    labs.push_back(independent::measure(truth, m, rng));
    labs.back().source = "specimen_" + std::to_string(r + 1);
  }
  DiagnosisOptions options;
  options.seed = seed;
  labs_out = labs;
  const Diagnosis d = diagnose(labs, sim, options);
  SelfcheckTrial t = trial_of(base, effects);
  for (std::size_t e = 0; e < effects.size(); ++e)
    t.shape += (e ? "+" : "") + independent::shape_name(effects[e], settings[e].shape);
  t.predicted = d.cause;
  t.gap_before = d.gap_before;
  t.noise_floor = d.noise_floor;
  for (const RankedEffect& r : d.ranking)
    if (r.effect == d.cause) t.shrink = r.shrink;
  return t;  // magnitudes are not comparable across shapes: no parameter error
}

Curve as_csv_curve(const ForceCurve& c, const SelfcheckTrial& t, const std::string& role) {
  Curve out;
  out.add_channel_si("displacement", Dimension::Length, c.u, *find_unit("m"));  // SI: the values read back exactly
  out.add_channel_si("force", Dimension::Force, c.f, *find_unit("N"));
  out.set_metadata("source", "gap selfcheck: " + role + (c.source.empty() ? "" : " (" + c.source + ")"));
  out.set_metadata("selfcheck_truth", t.truth);
  if (!t.shape.empty()) out.set_metadata("selfcheck_shape", t.shape);
  if (!t.injected.empty()) out.set_metadata("selfcheck_injected", t.injected);
  out.set_metadata("selfcheck_base", t.base);
  return out;
}

void write_trial_curves(const std::filesystem::path& dir, std::size_t index, const SelfcheckTrial& t, const Base& base,
                        const std::vector<ForceCurve>& labs) {
  std::ostringstream name;
  name << "trial_" << std::setw(3) << std::setfill('0') << index << "_" << t.truth;
  const std::filesystem::path trial = dir / name.str();
  std::filesystem::create_directories(trial);
  write_csv(as_csv_curve(base.curve, t, "simulation"), trial / "sim.csv");
  for (std::size_t i = 0; i < labs.size(); ++i)
    write_csv(as_csv_curve(labs[i], t, "laboratory"), trial / ("lab_" + std::to_string(i + 1) + ".csv"));
}

double fraction(std::size_t hit, std::size_t total) {
  return total ? static_cast<double>(hit) / static_cast<double>(total) : 0.0;
}

}  // namespace

SelfcheckResult run_selfcheck(const SelfcheckOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  std::vector<Base> bases = {{"voce", voce_tension_curve(), 0.6}};
  if (!options.backbone_csv.empty() && std::filesystem::exists(options.backbone_csv))
    bases.push_back({"backbone", backbone_tension_curve(options.backbone_csv), 0.3});
  std::mt19937 rng(options.seed);
  SelfcheckResult result;
  unsigned trial_seed = options.seed;
  std::size_t base_index = 0;
  auto next_base = [&]() -> const Base& { return bases[base_index++ % bases.size()]; };
  const bool independent_family = options.family == "independent";
  if (!independent_family && options.family != "fitted")
    throw std::invalid_argument("--family: expected fitted or independent, got " + options.family);
  const std::vector<std::string>& trialled = options.effects.empty() ? selfcheck_effects() : options.effects;
  for (const std::string& name : trialled)
    if (std::find(selfcheck_effects().begin(), selfcheck_effects().end(), name) == selfcheck_effects().end())
      throw std::invalid_argument("--effects: '" + name + "' is no curve-mode effect of the selfcheck");
  if (options.pair_trials > 0 && trialled.size() < 2)
    throw std::invalid_argument("--pair-trials: pairs need at least two --effects");
  const auto run_trial = [&](const Base& base, const std::vector<std::string>& effects, unsigned seed) {
    std::vector<ForceCurve> labs;
    SelfcheckTrial t = independent_family ? run_independent_trial(base, effects, options.repeats, rng, seed, labs)
                                          : dtwire::gap::run_trial(base, effects, rng, seed, labs);
    if (!options.curves_dir.empty()) write_trial_curves(options.curves_dir, result.trials.size() + 1, t, base, labs);
    return t;
  };
  for (std::size_t k = 0; k < options.trials; ++k)
    for (const std::string& effect : trialled)
      result.trials.push_back(run_trial(next_base(), {effect}, ++trial_seed));
  for (std::size_t k = 0; k < options.none_trials; ++k)
    result.trials.push_back(run_trial(next_base(), {}, ++trial_seed));
  for (std::size_t k = 0; k < options.pair_trials; ++k) {
    std::vector<std::string> names = trialled;
    std::shuffle(names.begin(), names.end(), rng);
    result.trials.push_back(run_trial(next_base(), {names[0], names[1]}, ++trial_seed));
  }

  score_trials(result);
  result.family = options.family;
  result.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

void score_trials(SelfcheckResult& result) {
  std::size_t spurious_pairs = 0;
  result.singles_below_floor = result.singles_below_floor_none = 0;
  std::size_t visible = 0, visible_hits = 0;
  std::size_t singles = 0, single_hits = 0, nones = 0, none_hits = 0, pairs = 0, pair_hits = 0,
              pair_partial = 0;
  double shrink_sum = 0.0;
  std::vector<double> errors;
  result.per_effect.clear();
  for (const SelfcheckTrial& t : result.trials) {
    if (t.truth == "none") {
      ++nones;
      none_hits += t.predicted == "none";
    } else if (t.truth.find('+') == std::string::npos) {
      ++singles;
      single_hits += t.predicted == t.truth;
      SelfcheckResult::EffectCounts& counts = result.per_effect[t.truth];
      if (t.gap_before > t.noise_floor) {
        ++visible;
        visible_hits += t.predicted == t.truth;
        ++counts.above_floor;
        counts.found += t.predicted == t.truth;
      } else {
        ++result.singles_below_floor;
        result.singles_below_floor_none += t.predicted == "none";
        ++counts.below_floor;
        counts.below_floor_none += t.predicted == "none";
      }
      spurious_pairs += t.predicted.find('+') != std::string::npos;
      shrink_sum += t.shrink;
      if (t.parameter_error >= 0) errors.push_back(t.parameter_error);
    } else {
      ++pairs;
      pair_hits += t.predicted == t.truth;
      const auto plus = t.truth.find('+');
      const std::string a = t.truth.substr(0, plus), b = t.truth.substr(plus + 1);
      auto has = [&](const std::string& name) {
        std::istringstream parts(t.predicted);
        std::string part;
        while (std::getline(parts, part, '+'))
          if (part == name) return true;
        return false;
      };
      pair_partial += has(a) || has(b);
    }
  }
  result.single_top1 = fraction(single_hits, singles);
  result.single_top1_visible = fraction(visible_hits, visible);
  result.single_mean_shrink = singles ? shrink_sum / static_cast<double>(singles) : 0.0;
  result.none_rate = fraction(none_hits, nones);
  result.spurious_pair_rate = fraction(spurious_pairs, singles);
  result.pair_exact = fraction(pair_hits, pairs);
  result.pair_partial = fraction(pair_partial, pairs);
  if (!errors.empty()) {
    double sum = 0.0;
    for (double e : errors) sum += e;
    result.mean_parameter_error = sum / static_cast<double>(errors.size());
    std::sort(errors.begin(), errors.end());
    result.median_parameter_error = errors[errors.size() / 2];
  }
  std::vector<std::string> labels = selfcheck_effects();
  labels.push_back("none");
  for (const SelfcheckTrial& t : result.trials)
    for (const std::string& name : {t.truth, t.predicted})
      if (std::find(labels.begin(), labels.end(), name) == labels.end()) labels.push_back(name);
  result.labels = labels;
  // The top-1 goal is judged on the trials whose effect is visible above the noise floor.
  result.goals_met = (visible == 0 || result.single_top1_visible >= kGoalTop1) &&
                     (singles == 0 || result.single_mean_shrink >= kGoalShrink) &&
                     (nones == 0 || result.none_rate >= kGoalNone) &&
                     (singles == 0 || result.spurious_pair_rate <= kGoalSpuriousPairs);
}

nlohmann::json selfcheck_json(const SelfcheckResult& r) {
  nlohmann::json trials = nlohmann::json::array();
  for (const SelfcheckTrial& t : r.trials) {
    nlohmann::json j = {{"base", t.base},           {"truth", t.truth},
                        {"predicted", t.predicted}, {"gap_before", t.gap_before},
                        {"noise_floor", t.noise_floor}, {"shrink", t.shrink}};
    if (t.parameter_error >= 0) j["parameter_error"] = t.parameter_error;
    if (!t.shape.empty()) j["shape"] = t.shape;
    if (!t.injected.empty()) j["injected"] = t.injected;
    trials.push_back(j);
  }
  std::map<std::string, std::map<std::string, int>> matrix;
  for (const SelfcheckTrial& t : r.trials) ++matrix[t.truth][t.predicted];
  nlohmann::json confusion = nlohmann::json::object();
  for (const auto& [truth, row] : matrix) confusion[truth] = row;
  nlohmann::json per_effect = nlohmann::json::object();
  for (const auto& [name, c] : r.per_effect)
    per_effect[name] = {{"above_floor", c.above_floor},
                        {"found", c.found},
                        {"below_floor", c.below_floor},
                        {"below_floor_read_none", c.below_floor_none}};
  return {{"single_top1", r.single_top1},
          {"single_top1_visible", r.single_top1_visible},
          {"singles_below_floor", r.singles_below_floor},
          {"singles_below_floor_read_none", r.singles_below_floor_none},
          {"single_mean_shrink", r.single_mean_shrink},
          {"none_rate", r.none_rate},
          {"spurious_pair_rate", r.spurious_pair_rate},
          {"family", r.family},
          {"pair_exact", r.pair_exact},
          {"pair_partial", r.pair_partial},
          {"mean_parameter_error", r.mean_parameter_error},
          {"median_parameter_error", r.median_parameter_error},
          {"goals", {{"single_top1", kGoalTop1}, {"single_mean_shrink", kGoalShrink}, {"none_rate", kGoalNone},
                     {"spurious_pair_rate_at_most", kGoalSpuriousPairs}}},
          {"goals_met", r.goals_met},
          {"seconds", r.seconds},
          {"labels", r.labels},
          {"confusion", confusion},
          {"per_effect", per_effect},
          {"goal_top1_per_effect", kGoalTop1PerEffect},
          {"trials", trials}};
}

std::string selfcheck_markdown(const SelfcheckResult& r) {
  std::map<std::string, std::map<std::string, int>> matrix;
  for (const SelfcheckTrial& t : r.trials) ++matrix[t.truth][t.predicted];
  std::vector<std::string> rows, columns;
  for (const std::string& label : r.labels) {
    bool as_truth = matrix.count(label) > 0, as_prediction = false;
    for (const auto& [truth, row] : matrix) as_prediction = as_prediction || row.count(label);
    if (as_truth) rows.push_back(label);
    if (as_prediction) columns.push_back(label);
  }
  // Sample sizes next to each figure; a figure with no trials behind it is n/a, not 0.
  std::size_t singles = 0, pairs = 0, nones = 0, magnitudes = 0;
  for (const SelfcheckTrial& t : r.trials) {
    if (t.truth == "none") ++nones;
    else if (t.truth.find('+') != std::string::npos) ++pairs;
    else ++singles;
    if (t.parameter_error >= 0.0) ++magnitudes;
  }
  const auto fixed2 = [](double value) {
    std::ostringstream c;
    c.setf(std::ios::fixed);
    c.precision(2);
    c << value;
    return c.str();
  };
  const auto cell = [&](double value, std::size_t n) {
    return n == 0 ? std::string("n/a") : fixed2(value) + " (n = " + std::to_string(n) + ")";
  };
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(2);
  std::map<std::string, std::size_t> per_base;
  for (const SelfcheckTrial& t : r.trials) ++per_base[t.base];
  std::string bases;
  for (const auto& [name, n] : per_base) bases += (bases.empty() ? "" : ", ") + name + " " + std::to_string(n);
  s << "### Gap diagnosis selfcheck (" << r.family << " family)\n\n"
    << r.trials.size() << " trials of synthetic laboratory curves (effect withheld from the simulation; base models: "
    << bases << "), " << r.seconds << " s.\n\n"
    << "| figure | value | goal |\n|---|---|---|\n"
    << "| top-1 cause correct, single effects whose gap stands above the noise floor | "
    << cell(r.single_top1_visible, singles - r.singles_below_floor) << " | >= " << kGoalTop1 << " |\n"
    << "| top-1 cause correct, every single effect | " << cell(r.single_top1, singles) << " | - |\n"
    << "| single effects below the noise floor (`none` is right there): read as `none` | "
    << r.singles_below_floor_none << " of " << r.singles_below_floor << " | - |\n"
    << "| mean gap shrink, single effects | " << cell(r.single_mean_shrink, singles) << " | >= " << kGoalShrink << " |\n"
    << "| `none` on effect-free curves | " << cell(r.none_rate, nones) << " | >= " << kGoalNone << " |\n"
    << "| pairs diagnosed on single-effect curves | " << cell(r.spurious_pair_rate, singles) << " | <= "
    << kGoalSpuriousPairs << " |\n"
    << "| pairs: both found | " << cell(r.pair_exact, pairs) << " | - |\n"
    << "| pairs: at least one found | " << cell(r.pair_partial, pairs) << " | - |\n"
    << "| magnitude recovery error (relative), mean / median | "
    << (magnitudes == 0 ? std::string("n/a (the family's shapes differ from the fitted forms)")
                        : fixed2(r.mean_parameter_error) + " / " + fixed2(r.median_parameter_error) +
                              " (n = " + std::to_string(magnitudes) + ")")
    << " | - |\n\n"
    << "Goals " << (r.goals_met ? "met" : "NOT met") << ".\n\n";
  if (!r.per_effect.empty()) {
    // Issue 51 asks for each effect at 0.95 or better; a handful of trials an effect cannot show
    // it, so this table is reported beside the goals, not counted in them.
    s << "Per effect (goal >= " << kGoalTop1PerEffect << " above the floor, each effect apart):\n\n"
      << "| injected | above the floor: found | below the floor: read `none` |\n|---|---|---|\n";
    for (const auto& [name, c] : r.per_effect)
      s << "| " << name << " | " << c.found << " of " << c.above_floor
        << (c.above_floor ? " (" + fixed2(fraction(c.found, c.above_floor)) + ")" : std::string()) << " | "
        << c.below_floor_none << " of " << c.below_floor << " |\n";
    s << "\n";
  }
  s << "Confusion matrix (rows: injected, columns: diagnosed):\n\n| injected |";
  for (const auto& c : columns) s << " " << c << " |";
  s << "\n|---|";
  for (std::size_t i = 0; i < columns.size(); ++i) s << "---|";
  s << "\n";
  for (const auto& row : rows) {
    s << "| " << row << " |";
    for (const auto& c : columns) {
      const auto it = matrix[row].find(c);
      s << " " << (it == matrix[row].end() ? 0 : it->second) << " |";
    }
    s << "\n";
  }
  return s.str();
}

}  // namespace dtwire::gap
