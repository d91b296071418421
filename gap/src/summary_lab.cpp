#include "dtwire/gap/summary_lab.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <map>
#include <optional>
#include <random>
#include <sstream>
#include <thread>

#include "dtwire/core/error.hpp"
#include "dtwire/gap/diagnosis.hpp"
#include "dtwire/gap/gap_report.hpp"
#include "dtwire/gap/model_search.hpp"
#include "dtwire/lsq/least_squares.hpp"
#include "evidence.hpp"

namespace dtwire::gap {
namespace {

std::vector<double> features_of(const ForceCurve& c, const std::vector<SummaryFeature>& lab) {
  std::vector<double> out;
  for (const SummaryFeature& f : lab) out.push_back(curve_feature(c, f.name));
  return out;
}

// Curve-mode effect: bounded least squares on the feature z-scores (the lsq engine, central
// differences), from the plausible centre, the neutral value and two random starts; the
// answer only if it beats the neutral value. `held_magnitude`: the magnitude kept at this value
// (the edge rule), the other parameters fitted.
std::vector<double> fit_curve_effect(const ForceCurve& sim, const CurveScale& scale,
                                     const EffectSpec& effect, const std::vector<SummaryFeature>& lab,
                                     std::mt19937& rng, std::optional<double> held_magnitude = std::nullopt) {
  // Shape parameters cannot be told apart by a few features: held at the basic form.
  auto specs = effect.parameters(scale);
  std::vector<std::size_t> free;
  const auto hold = [](ParameterSpec& s, double value) {
    s.lower = s.upper = s.plausible_lower = s.plausible_upper = value;
  };
  for (std::size_t j = 0; j < specs.size(); ++j) {
    if (specs[j].shape_neutral)
      hold(specs[j], *specs[j].shape_neutral);
    else if (held_magnitude && j == effect.magnitude)
      hold(specs[j], *held_magnitude);
    else
      free.push_back(j);
  }
  std::vector<std::vector<double>> starts;
  std::vector<double> centre;
  for (const auto& s : specs) centre.push_back(s.grid.empty() ? 0.5 * (s.plausible_lower + s.plausible_upper) : 0.0);
  starts.push_back(centre);
  std::vector<double> neutral = centre;
  if (!held_magnitude) neutral[effect.magnitude] = effect.neutral;
  starts.push_back(neutral);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int k = 0; k < 2; ++k) {
    std::vector<double> p;
    for (const auto& s : specs) p.push_back(s.grid.empty() ? s.plausible_lower + unit(rng) * s.width() : 0.0);
    starts.push_back(p);
  }
  const auto value_of = [&specs, &free](const std::vector<double>& x) {
    std::vector<double> p;
    for (const ParameterSpec& s : specs) p.push_back(s.from_scaled(0.0));
    for (std::size_t k = 0; k < free.size(); ++k) p[free[k]] = specs[free[k]].from_scaled(x[k]);
    return p;
  };
  if (free.empty()) return value_of({});
  lsq::Problem problem;
  problem.parameter_count = free.size();
  problem.residual_count = lab.size();
  problem.difference_step = 1e-4;
  for (std::size_t j : free) {
    problem.lower.push_back(specs[j].to_scaled(specs[j].lower));
    problem.upper.push_back(specs[j].to_scaled(specs[j].upper));
  }
  problem.residuals = [&](const std::vector<double>& x, std::vector<double>& r) {
    const auto f = features_of(apply_effects(sim, {{&effect, value_of(x)}}, scale), lab);
    r.resize(f.size());
    for (std::size_t i = 0; i < f.size(); ++i) r[i] = (f[i] - lab[i].mean) / lab[i].sd;
  };
  std::vector<std::vector<double>> points;
  for (const auto& start : starts) {
    std::vector<double> x;
    for (std::size_t j : free) x.push_back(specs[j].to_scaled(start[j]));
    points.push_back(x);
  }
  lsq::Options options;
  options.block_per_residual = false;
  const lsq::Summary summary = lsq::solve(problem, options, lsq::starts_at(points));
  const double neutral_gap = summary_gap(lab, features_of(apply_effects(sim, {{&effect, neutral}}, scale), lab));
  if (!summary.best) return neutral;
  const std::vector<double> best = value_of(summary.x);
  return summary_gap(lab, features_of(apply_effects(sim, {{&effect, best}}, scale), lab)) < neutral_gap ? best : neutral;
}

// Model-only effect (one parameter): FE runs at the ends of the plausible range (the neutral
// model is the given simulation), then at the minimum of the piecewise-linear interpolant of
// the features, until `runs` are spent. A grid parameter (three nodes per wire or two) is run
// at its grid values only. The answer is the best value actually run.
struct ModelSearch {
  double value;
  ForceCurve curve;
  int runs = 0;
  std::vector<std::pair<std::vector<double>, std::vector<double>>> samples;
  std::vector<std::vector<double>> peak_at_end;  // as SummaryCandidate::peak_at_end
  double seconds = 0.0;  // wall
};

bool any_needs_peak(const std::vector<SummaryFeature>& lab) {
  return std::any_of(lab.begin(), lab.end(), [](const SummaryFeature& f) { return feature_needs_peak(f.name); });
}

ModelSearch search_model_effect(const ForceCurve& sim, const CurveScale& scale, const EffectSpec& effect,
                                const std::vector<SummaryFeature>& lab, const ModelRunner& runner,
                                std::size_t runs) {
  const auto started = std::chrono::steady_clock::now();
  const ParameterSpec spec = effect.parameters(scale).front();
  std::map<double, std::vector<double>> sampled;  // value -> features
  std::map<double, ForceCurve> curves;
  std::vector<std::vector<double>> peak_at_end;
  sampled[effect.neutral] = features_of(sim, lab);
  curves[effect.neutral] = sim;
  int spent = 0;
  auto run = [&](double v) {
    if (sampled.count(v) || static_cast<std::size_t>(spent) >= runs) return;
    ForceCurve c = oriented(runner({{&effect, {v}}}));
    validate_force_curve(c);
    if (any_needs_peak(lab) && peak_at_curve_end(c)) peak_at_end.push_back({v});
    sampled[v] = features_of(c, lab);
    curves[v] = c;
    ++spent;
  };
  if (spec.grid.empty()) {
    run(spec.plausible_lower);
    run(spec.plausible_upper);
  }
  for (double v : spec.grid) run(v);
  while (spec.grid.empty() && static_cast<std::size_t>(spent) < runs) {
    // Minimum of the interpolated gap on a fine scan of the sampled interval.
    const double lo = sampled.begin()->first, hi = sampled.rbegin()->first;
    double best_v = lo, best_gap = INFINITY;
    for (int k = 0; k <= 400; ++k) {
      const double v = lo + (hi - lo) * k / 400.0;
      auto right = sampled.lower_bound(v);
      if (right == sampled.end()) --right;
      auto left = right == sampled.begin() ? right : std::prev(right);
      const double t = right->first > left->first ? (v - left->first) / (right->first - left->first) : 0.0;
      std::vector<double> f;
      for (std::size_t i = 0; i < lab.size(); ++i)
        f.push_back(left->second[i] + t * (right->second[i] - left->second[i]));
      const double g = summary_gap(lab, f);
      if (g < best_gap) {
        best_gap = g;
        best_v = v;
      }
    }
    std::vector<double> values;
    double best_run = effect.neutral, best_run_gap = INFINITY;
    for (const auto& [v, f] : sampled) {
      values.push_back(v);
      if (const double g = summary_gap(lab, f); g < best_run_gap) {
        best_run_gap = g;
        best_run = v;
      }
    }
    const std::optional<double> next = next_model_value(values, best_v, best_run);
    if (!next || sampled.count(*next)) break;
    run(*next);
  }
  ModelSearch out{effect.neutral, sim, spent, {}, peak_at_end, 0.0};
  for (const auto& [v, f] : sampled) out.samples.push_back({{v}, f});
  double best_gap = INFINITY;
  for (const auto& [v, f] : sampled) {
    const double g = summary_gap(lab, f);
    if (g < best_gap) {
      best_gap = g;
      out.value = v;
      out.curve = curves[v];
    }
  }
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return out;
}

// Features of a single model-only effect at value v: piecewise linear between its FE runs.
std::vector<double> interpolated(const std::vector<std::pair<std::vector<double>, std::vector<double>>>& samples,
                                 double v) {
  auto sorted = samples;
  std::sort(sorted.begin(), sorted.end());
  std::size_t k = 1;
  while (k + 1 < sorted.size() && sorted[k].first[0] < v) ++k;
  const auto& [x0, f0] = sorted[k - 1];
  const auto& [x1, f1] = sorted[k];
  const double t = x1[0] > x0[0] ? std::clamp((v - x0[0]) / (x1[0] - x0[0]), 0.0, 1.0) : 0.0;
  std::vector<double> f;
  for (std::size_t i = 0; i < f0.size(); ++i) f.push_back(f0[i] + t * (f1[i] - f0[i]));
  return f;
}

// Start of a pair of model-only effects without an FE run: the changes of the features that
// each single effect's runs show, added (superposition), minimised on a 41 x 41 grid over the
// values run. The model effect's value comes first.
std::vector<double> superposition_start(const SummaryCandidate& a, const SummaryCandidate& b,
                                        const EffectSpec* first, const std::vector<SummaryFeature>& lab) {
  const SummaryCandidate& p = a.fitted.front().effect == first ? a : b;
  const SummaryCandidate& q = a.fitted.front().effect == first ? b : a;
  const std::vector<double> base = interpolated(p.samples, p.fitted.front().effect->neutral);
  auto range = [](const SummaryCandidate& c) {
    double lo = INFINITY, hi = -INFINITY;
    for (const auto& [x, f] : c.samples) {
      lo = std::min(lo, x[0]);
      hi = std::max(hi, x[0]);
    }
    return std::make_pair(lo, hi);
  };
  const auto [p_lo, p_hi] = range(p);
  const auto [q_lo, q_hi] = range(q);
  std::vector<double> best = {p.fitted.front().params[0], q.fitted.front().params[0]};
  double best_gap = INFINITY;
  for (int i = 0; i <= 40; ++i)
    for (int j = 0; j <= 40; ++j) {
      const double vp = p_lo + (p_hi - p_lo) * i / 40.0, vq = q_lo + (q_hi - q_lo) * j / 40.0;
      const auto fp = interpolated(p.samples, vp), fq = interpolated(q.samples, vq);
      std::vector<double> f;
      for (std::size_t k = 0; k < base.size(); ++k) f.push_back(fp[k] + fq[k] - base[k]);
      const double g = summary_gap(lab, f);
      if (g < best_gap) {
        best_gap = g;
        best = {vp, vq};
      }
    }
  return best;
}

// AICc with known sd (SummaryCandidate::aic).
double aic_of(const std::vector<SummaryFeature>& lab, double gap, int parameters) {
  const double n = static_cast<double>(lab.size()), k = parameters;
  const double correction = n - k - 1 > 0 ? 2 * k * (k + 1) / (n - k - 1) : 1e9;
  return n * gap * gap + 2.0 * k + correction;
}

// Whether AICc can weigh a candidate of this many parameters on these figures at all.
bool judgeable(const std::vector<SummaryFeature>& lab, int parameters) {
  return static_cast<double>(lab.size()) - parameters - 1 > 0;
}

// Fitted parameters only: shape parameters are held at their basic form here.
int parameter_count(const std::vector<AppliedEffect>& effects) {
  int k = 0;
  for (const AppliedEffect& a : effects)
    for (const ParameterSpec& s : a.effect->parameters(CurveScale{}))
      k += !s.shape_neutral;
  return k;
}

// The figures of a candidate's curve against the laboratory's: gap, shrink, plausibility (the
// product over its effects), score, Akaike's criterion. Whether it qualifies is the caller's rule.
void assess(SummaryCandidate& c, const SummaryDiagnosis& d, const CurveScale& scale) {
  c.features = features_of(c.curve, d.lab);
  c.gap_after = summary_gap(d.lab, c.features);
  c.shrink = d.gap_before > 0 ? 1.0 - c.gap_after / d.gap_before : 0.0;
  c.plausibility = 1.0;
  for (const AppliedEffect& e : c.fitted) c.plausibility *= plausibility(*e.effect, e.params, scale);
  c.score = c.plausibility * std::max(0.0, c.shrink);
  c.parameters = parameter_count(c.fitted);
  c.aic = aic_of(d.lab, c.gap_after, c.parameters);
  c.beyond_range = magnitudes_beyond_range(c.fitted, scale);
  c.implausible = !c.beyond_range.empty();
}

// Every rule of a cause but the plausible range.
bool closes_enough(const SummaryCandidate& c, const SummaryDiagnosis& d) {
  return d.gap_before > d.noise_floor && c.shrink >= kSummaryMinimumShrink;
}

// A curve-mode magnitude fitted past its plausible range's edge is the edge when the features,
// refitted with it held there, stay within what the laboratory's sds tell: the sum of squared
// z-scores rises by at most 1, the one-sigma profile interval of one parameter with known sd
// (Bates and Watts 1988, ch. 6), as the curve mode's rule judges its profile against the noise.
// Model-only effects are searched within their ranges; a pair's model-only partner keeps its
// value (no further model run: the test is then stricter than the profile). Such a candidate is
// not implausible and keeps its fitted values; `at_range_edge` names the magnitude.
void judge_range_edge(SummaryCandidate& c, const SummaryDiagnosis& d, const CurveScale& scale, std::mt19937& rng) {
  if (!c.implausible) return;
  const AppliedEffect& curve_member = c.fitted.back();
  if (curve_member.effect->needs_model) return;
  if (c.fitted.size() > 1 && c.model_curve.size() == 0) return;
  for (const BeyondRange& b : c.beyond_range)
    if (b.effect != curve_member.effect->name) return;
  const BeyondRange& beyond = c.beyond_range.front();
  const double edge = beyond.value > beyond.plausible_upper ? beyond.plausible_upper : beyond.plausible_lower;
  const ForceCurve& base = c.fitted.size() == 1 ? d.sim : c.model_curve;
  const std::vector<double> held = fit_curve_effect(base, scale, *curve_member.effect, d.lab, rng, edge);
  const double held_gap = summary_gap(d.lab, features_of(apply_effects(base, {{curve_member.effect, held}}, scale), d.lab));
  const double figures = static_cast<double>(d.lab.size());
  if (figures * (held_gap * held_gap - c.gap_after * c.gap_after) > 1.0) return;
  c.at_range_edge = c.beyond_range;
  c.beyond_range.clear();
  c.implausible = false;
}

bool single_qualifies(SummaryCandidate& c, const SummaryDiagnosis& d) {
  c.qualifies_but_implausible = closes_enough(c, d) && c.implausible;
  return closes_enough(c, d) && c.plausibility >= 0.5 && !c.implausible;
}

// The one member of a fitted pair that is not at its neutral value, if the other one is: such a
// pair is that effect alone, at a point its own search did not reach.
const AppliedEffect* sole_active_member(const SummaryCandidate& pair) {
  const AppliedEffect* active = nullptr;
  int neutral = 0;
  for (const AppliedEffect& a : pair.fitted) {
    if (a.params[a.effect->magnitude] == a.effect->neutral)
      ++neutral;
    else
      active = &a;
  }
  return neutral == 1 && pair.fitted.size() == 2 ? active : nullptr;
}

// A pair with a model-only effect from its single fits: the model-only parameters by the bounded
// pattern search (at most `points` FE runs), a curve-mode partner refitted on every FE curve.
std::optional<SummaryCandidate> fit_pair(const CurveScale& scale, const SummaryCandidate& a,
                          const SummaryCandidate& b, const std::vector<SummaryFeature>& lab,
                          const ModelRunner& runner, std::size_t points, std::mt19937& rng) {
  const AppliedEffect& fa = a.fitted.front();
  const AppliedEffect& fb = b.fitted.front();
  const bool both_model = fa.effect->needs_model && fb.effect->needs_model;
  const AppliedEffect& model = fa.effect->needs_model ? fa : fb;
  const AppliedEffect& other = fa.effect->needs_model ? fb : fa;
  const auto started = std::chrono::steady_clock::now();
  SummaryCandidate c;
  std::map<std::vector<double>, std::pair<std::vector<AppliedEffect>, ForceCurve>> tried;
  std::map<std::vector<double>, ForceCurve> model_curves;  // before the curve-mode partner
  const auto evaluate = [&](const std::vector<double>& x) {
    std::vector<AppliedEffect> effects = {{model.effect, {x[0]}}};
    if (both_model) effects.push_back({other.effect, {x[1]}});
    ForceCurve curve = oriented(runner(effects));
    validate_force_curve(curve);
    if (any_needs_peak(lab) && peak_at_curve_end(curve)) c.peak_at_end.push_back(x);
    if (!both_model) {
      model_curves[x] = curve;
      effects.push_back({other.effect, fit_curve_effect(curve, scale, *other.effect, lab, rng)});
      curve = apply_effects(curve, {effects.back()}, scale);
    }
    const auto f = features_of(curve, lab);
    c.samples.push_back({x, f});
    tried[x] = {effects, curve};
    return summary_gap(lab, f);
  };
  std::vector<ParameterSpec> specs = {model.effect->parameters(scale).front()};
  std::vector<std::pair<std::vector<double>, double>> known;
  std::vector<double> start = {model.params[0]};
  if (both_model) {
    specs.push_back(other.effect->parameters(scale).front());
    known = {{{model.params[0], other.effect->neutral}, (fa.effect == model.effect ? a : b).gap_after},
             {{model.effect->neutral, other.params[0]}, (fa.effect == model.effect ? b : a).gap_after}};
    start.push_back(other.params[0]);
  }
  std::vector<std::vector<double>> starts = {start};
  if (both_model) starts.insert(starts.begin(), superposition_start(a, b, model.effect, lab));
  const PatternSearch s = pattern_search(specs, known, starts, evaluate, points);
  c.runs = static_cast<int>(s.points);
  c.model_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  if (!tried.count(s.best)) return std::nullopt;  // no point beats the singles: the pair adds nothing
  c.fitted = tried[s.best].first;
  c.curve = tried[s.best].second;
  if (!both_model) c.model_curve = model_curves[s.best];
  std::vector<std::string> names = {fa.effect->name, fb.effect->name};
  c.effect = evidence::joined_name(names);
  return c;
}

}  // namespace

bool fitted_peak_at_end(const SummaryCandidate& c) {
  return c.fitted.size() == 1 && c.fitted.front().effect->needs_model &&
         std::find(c.peak_at_end.begin(), c.peak_at_end.end(), c.fitted.front().params) != c.peak_at_end.end();
}

double summary_gap(const std::vector<SummaryFeature>& lab, const std::vector<double>& features) {
  double sum = 0.0;
  for (std::size_t i = 0; i < lab.size(); ++i) {
    const double z = (features[i] - lab[i].mean) / lab[i].sd;
    sum += z * z;
  }
  return std::sqrt(sum / static_cast<double>(lab.size()));
}

SummaryDiagnosis diagnose_summary(const ForceCurve& sim_in, const std::vector<SummaryFeature>& lab,
                                  const SummaryOptions& options) {
  if (lab.empty()) throw InputError("--lab-summary", "give at least one feature");
  validate_force_curve(sim_in);
  SummaryDiagnosis d;
  d.lab = lab;
  d.sim = oriented(sim_in, &d.compression);
  const double reach_mm = *std::max_element(d.sim.u.begin(), d.sim.u.end()) * 1e3;
  const double largest_force = *std::max_element(d.sim.f.begin(), d.sim.f.end());
  for (const SummaryFeature& f : lab) {
    if (const auto mm = force_at_displacement_mm(f.name); mm && *mm > reach_mm)
      throw InputError("--lab-summary", f.name + ": the simulated curve reaches only " + std::to_string(reach_mm) +
                                            " mm; give a displacement within its travel");
    if (const auto level = displacement_at_force_N(f.name); level && *level > largest_force)
      throw InputError("--lab-summary", f.name + ": the simulated force reaches only " + std::to_string(largest_force) +
                                            " N; give a force the simulation reaches");
  }
  d.sim_features = features_of(d.sim, lab);
  d.gap_before = summary_gap(lab, d.sim_features);
  const CurveScale scale = curve_scale(d.sim);

  std::vector<const EffectSpec*> requested;
  if (options.effects.empty())
    for (const EffectSpec& e : effect_catalogue()) requested.push_back(&e);
  else
    for (const std::string& name : options.effects) requested.push_back(&find_effect(name));
  std::mt19937 rng(options.seed);
  const auto testable = [&](const EffectSpec& e) {
    return !options.inapplicable.count(e.name) && (!e.needs_model || (options.model && !options.model_unsupported.count(e.name)));
  };
  // The model-only searches are independent of each other and of the random stream: with
  // jobs > 1 they run first, side by side, the costliest first (a long search started last runs
  // alone at the end), and the loop below takes their results.
  const auto searches_started = std::chrono::steady_clock::now();
  std::map<std::string, ModelSearch> searched;
  std::vector<const EffectSpec*> to_search;
  for (const EffectSpec* e : requested)
    if (e->needs_model && testable(*e)) to_search.push_back(e);
  std::stable_sort(to_search.begin(), to_search.end(), [](const EffectSpec* a, const EffectSpec* b) {
    return a->relative_run_cost > b->relative_run_cost;
  });
  if (options.jobs > 1 && to_search.size() > 1) {
    std::vector<std::optional<ModelSearch>> results(to_search.size());
    std::vector<std::exception_ptr> errors(to_search.size());
    std::atomic<std::size_t> next{0};
    const auto work = [&] {
      for (std::size_t i = next++; i < to_search.size(); i = next++) {
        try {
          results[i] = search_model_effect(d.sim, scale, *to_search[i], lab, options.model, options.model_runs);
        } catch (...) {
          errors[i] = std::current_exception();
        }
      }
    };
    std::vector<std::thread> threads;
    for (unsigned t = 0; t < std::min<std::size_t>(options.jobs, to_search.size()); ++t) threads.emplace_back(work);
    for (std::thread& t : threads) t.join();
    for (const std::exception_ptr& error : errors)
      if (error) std::rethrow_exception(error);
    for (std::size_t i = 0; i < to_search.size(); ++i) searched.emplace(to_search[i]->name, *results[i]);
  }
  for (const EffectSpec* e : requested) {
    if (const auto inapplicable = options.inapplicable.find(e->name); inapplicable != options.inapplicable.end()) {
      d.not_tested.push_back(e->name);
      d.not_tested_reason[e->name] = inapplicable->second;
      continue;
    }
    const auto unsupported = options.model_unsupported.find(e->name);
    if (e->needs_model && (!options.model || unsupported != options.model_unsupported.end())) {
      d.not_tested.push_back(e->name);
      d.not_tested_reason[e->name] = options.model ? unsupported->second : "needs --model";
      continue;
    }
    SummaryCandidate c;
    c.effect = e->name;
    ForceCurve model;
    if (e->needs_model) {
      const auto done = searched.find(e->name);
      const ModelSearch s = done != searched.end() ? done->second
                                                   : search_model_effect(d.sim, scale, *e, lab, options.model, options.model_runs);
      c.fitted = {{e, {s.value}}};
      c.runs = s.runs;
      c.model_seconds = s.seconds;
      c.samples = s.samples;
      c.peak_at_end = s.peak_at_end;
      model = s.curve;
    } else {
      c.fitted = {{e, fit_curve_effect(d.sim, scale, *e, lab, rng)}};
      model = apply_effects(d.sim, c.fitted, scale);
    }
    c.curve = model;
    assess(c, d, scale);
    judge_range_edge(c, d, scale, rng);
    c.qualifies = single_qualifies(c, d);
    d.ranking.push_back(c);
  }
  // Pairs with a model-only effect, when no single effect brings the features within the scatter.
  // A pair counts as a cause only when its AICc is below every single's and it cuts the best
  // single's gap by 20 %; else its score is divided by 10. On three figures or fewer the pair's
  // two parameters leave AICc no figure to judge it by (n <= k + 1): it is searched and ranked,
  // never the cause (two effects fitted to three numbers reproduce almost any three).
  // Only singles that can be the cause count: one that matches the figures only beyond its
  // range neither spares the pairs their search nor sets their bar (as in curve mode).
  const std::size_t singles = d.ranking.size();
  double best_gap = INFINITY, best_aic = INFINITY;
  for (const SummaryCandidate& c : d.ranking) {
    if (c.implausible) continue;
    best_gap = std::min(best_gap, c.gap_after);
    best_aic = std::min(best_aic, c.aic);
  }
  if (options.try_pairs && options.model && d.gap_before > d.noise_floor && best_gap > d.noise_floor) {
    std::vector<std::size_t> order(singles);
    for (std::size_t i = 0; i < singles; ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return d.ranking[a].gap_after < d.ranking[b].gap_after; });
    order.resize(std::min(order.size(), kSummaryPairCandidates));
    for (std::size_t i = 0; i < order.size(); ++i)
      for (std::size_t j = i + 1; j < order.size(); ++j) {
        const SummaryCandidate& a = d.ranking[order[i]];
        const SummaryCandidate& b = d.ranking[order[j]];
        if (!a.fitted.front().effect->needs_model && !b.fitted.front().effect->needs_model) continue;
        std::optional<SummaryCandidate> pair = fit_pair(scale, a, b, lab, options.model, options.model_runs, rng);
        if (!pair) continue;
        SummaryCandidate c = *pair;
        assess(c, d, scale);
        judge_range_edge(c, d, scale, rng);
        if (const AppliedEffect* alone = sole_active_member(c)) {
          // Not a pair: the single effect's better point replaces its own search's answer.
          const auto single = std::find_if(d.ranking.begin(), d.ranking.begin() + static_cast<std::ptrdiff_t>(singles),
                                           [&](const SummaryCandidate& s) { return s.effect == alone->effect->name; });
          if (single == d.ranking.begin() + static_cast<std::ptrdiff_t>(singles) || !(c.gap_after < single->gap_after))
            continue;
          SummaryCandidate better = *single;
          better.fitted = {*alone};
          better.curve = c.curve;
          better.runs += c.runs;
          better.model_seconds += c.model_seconds;
          if (alone->effect->needs_model && any_needs_peak(lab) && peak_at_curve_end(c.curve))
            better.peak_at_end.push_back(alone->params);
          if (alone->effect->needs_model) better.samples.push_back({alone->params, c.features});
          assess(better, d, scale);
          judge_range_edge(better, d, scale, rng);
          better.qualifies = single_qualifies(better, d);
          *single = better;
          continue;
        }
        d.ranking.push_back(c);
      }
    // A pair is judged against the best single, as the singles stand after every pair's search.
    for (std::size_t i = 0; i < singles; ++i) {
      if (d.ranking[i].implausible) continue;
      best_gap = std::min(best_gap, d.ranking[i].gap_after);
      best_aic = std::min(best_aic, d.ranking[i].aic);
    }
    for (std::size_t i = singles; i < d.ranking.size(); ++i) {
      SummaryCandidate& c = d.ranking[i];
      const bool beats_singles =
          judgeable(d.lab, c.parameters) && c.aic < best_aic && c.gap_after < kPairGapRatio * best_gap;
      c.qualifies = !c.implausible && c.shrink >= kSummaryMinimumShrink && c.plausibility >= 0.5 && beats_singles;
      c.qualifies_but_implausible = c.implausible && c.shrink >= kSummaryMinimumShrink && beats_singles;
      if (!beats_singles) c.score *= 0.1;
    }
  }
  if (options.model)
    d.model_elapsed_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - searches_started).count();
  std::stable_sort(d.ranking.begin(), d.ranking.end(),
                   [](const SummaryCandidate& a, const SummaryCandidate& b) { return a.score > b.score; });
  auto cause = std::find_if(d.ranking.begin(), d.ranking.end(),
                                  [](const SummaryCandidate& c) { return c.qualifies; });
  const auto refused = std::find_if(d.ranking.begin(), d.ranking.end(),
                                    [](const SummaryCandidate& c) { return c.qualifies_but_implausible; });
  if (d.gap_before <= d.noise_floor) {
    d.verdict = "within_noise";
    d.reason = "the simulated features lie within one laboratory standard deviation (rms z-score " +
               std::to_string(d.gap_before) + ")";
  } else if (d.ranking.empty()) {  // as in curve mode: nothing was tried, so nothing failed to close
    d.verdict = "nothing_tested";
    d.reason = "no effect could be tested on these figures (see not_tested)";
  } else if (refused != d.ranking.end() &&
             (cause == d.ranking.end() ||
              (cause->gap_after > d.noise_floor && cause->shrink < kOutdoneRatio * refused->shrink))) {
    d.verdict = "beyond_plausible_range";
    d.refused_effect = refused->effect;
    std::string needs;
    for (const BeyondRange& b : refused->beyond_range) needs += (needs.empty() ? "" : " and ") + b.text();
    d.reason = "no cause within the plausible ranges: " + refused->effect + " explains " +
               std::to_string(static_cast<int>(std::lround(100 * refused->shrink))) + " % of the gap but needs " + needs;
    if (cause != d.ranking.end())
      d.reason += "; the best plausible effect, " + cause->effect + ", explains " +
                  std::to_string(static_cast<int>(std::lround(100 * cause->shrink))) + " %";
    cause = d.ranking.end();
  } else if (cause == d.ranking.end()) {
    d.verdict = "no_effect_closes";
    const auto best = std::min_element(d.ranking.begin(), d.ranking.end(), [](const SummaryCandidate& a, const SummaryCandidate& b) {
      return a.gap_after < b.gap_after;
    });
    d.reason = best == d.ranking.end() || !(best->shrink > 0)
                   ? "no effect reduces the gap"
                   : "no plausible effect removes 30 % of the gap: the best, " + best->effect + ", removes " +
                         std::to_string(static_cast<int>(std::lround(100 * best->shrink))) + " %";
  } else {
    d.verdict = "cause";
    d.cause = cause->effect;
    d.reason = cause->gap_after <= d.noise_floor ? "brings the features within the laboratory scatter"
                                                 : "reduces the gap most, but not to the laboratory scatter";
    d.reason += evidence::at_edge_text(cause->at_range_edge);
    if (fitted_peak_at_end(*cause))
      d.reason += "; the run at its fitted value ended before the specimen failed (its largest force at the curve's "
                  "end), so its peak figures are lower bounds";
    if (cause->gap_after <= d.noise_floor)
      d.reason += evidence::also_closing(d.ranking, *cause, d.noise_floor, "AIC",
                                         [](const SummaryCandidate& c) { return c.aic; }, &d.also_closes);
  }
  d.best_model = d.ranking.empty() ? d.sim
                                    : (cause != d.ranking.end() ? *cause : d.ranking.front()).curve;
  return d;
}

}  // namespace dtwire::gap
