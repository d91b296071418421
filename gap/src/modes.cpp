#include "dtwire/gap/modes.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <random>
#include <set>

#include "dtwire/core/error.hpp"
#include "dtwire/gap/fracture.hpp"
#include "dtwire/gap/gap_report.hpp"
#include "dtwire/gap/loading_mode.hpp"
#include "dtwire/gap/model_search.hpp"
#include "evidence.hpp"
#include "parsimony.hpp"

namespace dtwire::gap {
namespace {

struct Group {
  FitProblem problem;
  std::vector<double> sim_forces_first;  // simulation at the first lab's points
  double curves = 0.0;
};

struct Combined {
  std::vector<Group> groups;
  std::vector<FitProblem> problems;
  std::vector<std::size_t> segment_group;  // group of each entry of `where`
  std::vector<GapSegment> where;
  double curves = 0.0;
};

// The candidate's effects on each group: one block per mode for test-setup effects, one shared
// block for specimen effects; -1 where the effect does not apply or cannot be tested.
struct Candidate {
  JointEffect joint;
  std::string untested;  // why not testable anywhere (empty: testable)
};

// The largest displacement of a mode's simulated and laboratory curves [m].
double largest_displacement(const ModeInput& in) {
  double largest = 0.0;
  for (const double u : in.sim.u) largest = std::max(largest, std::abs(u));
  for (const ForceCurve& lab : in.labs)
    for (const double u : lab.u) largest = std::max(largest, std::abs(u));
  return largest;
}

Candidate candidate_for(const EffectSpec& e, const std::vector<ModeInput>& inputs) {
  Candidate c{{&e, std::vector<int>(inputs.size(), -1), 0}, ""};
  for (std::size_t m = 0; m < inputs.size(); ++m) {
    const ModeInput& in = inputs[m];
    std::string why = effect_inapplicable(e, in.mode, largest_displacement(in));
    const auto unsupported = in.model_unsupported.find(e.name);
    if (why.empty() && e.needs_model && !in.model) why = "needs --model";
    if (why.empty() && e.needs_model && unsupported != in.model_unsupported.end()) why = unsupported->second;
    if (!why.empty()) {
      c.untested += (c.untested.empty() ? "" : "; ") + in.mode + ": " + why;
      continue;
    }
    c.joint.block_of[m] = effect_per_mode(e) ? c.joint.blocks++ : 0;
    if (!effect_per_mode(e)) c.joint.blocks = 1;
  }
  if (c.joint.blocks > 0) c.untested.clear();
  return c;
}

// `models[g][k]`: the model against curve k of group g (each record at its damage clock).
double combined_gap(const Combined& cb, const std::vector<std::vector<ForceCurve>>& models) {
  double sum = 0.0;
  for (std::size_t g = 0; g < cb.groups.size(); ++g)
    for (std::size_t k = 0; k < cb.groups[g].problem.labs.size(); ++k)
      sum += normalised_area(models[g][k], cb.groups[g].problem.labs[k]);
  return sum / cb.curves;
}

RankedEffect rank_combined(const Combined& cb, const std::vector<JointEffect>& effects, const JointFit& fit,
                           const std::vector<std::string>& modes, double gap_before) {
  RankedEffect r;
  std::vector<std::string> names;
  for (const JointEffect& e : effects) names.push_back(e.effect->name);
  r.effect = evidence::joined_name(names);
  r.parameters = fit.parameter_count;
  std::vector<std::vector<ForceCurve>> models;
  for (std::size_t g = 0; g < cb.groups.size(); ++g) {
    const FitProblem& p = cb.groups[g].problem;
    models.push_back(record_models(p, fit.per_problem[g]));
    if (!fit.per_problem[g].empty()) {
      r.fitted_by_mode.emplace_back(modes[g], fit.per_problem[g]);
      if (r.fitted.empty()) r.fitted = fit.per_problem[g];
    }
  }
  r.gap_after = combined_gap(cb, models);
  r.shrink = gap_before > 0 ? 1.0 - r.gap_after / gap_before : 0.0;
  std::vector<std::vector<double>> forces;
  for (std::size_t g = 0; g < cb.groups.size(); ++g) {
    const Comparison& first = cb.groups[g].problem.labs.front();
    forces.push_back(model_forces_at_lab(models[g].front(), first));
    r.frechet_after += cb.groups[g].curves * frechet_distance(models[g].front(), first) / cb.curves;
    r.pcm_after += cb.groups[g].curves * partial_curve_mapping(models[g].front(), first) / cb.curves;
  }
  std::vector<double> change;
  for (std::size_t k = 0; k < cb.where.size(); ++k) {
    const GapSegment& s = cb.where[k];
    const std::size_t g = cb.segment_group[k];
    const Comparison& first = cb.groups[g].problem.labs.front();
    r.gap_after_by_segment.push_back(segment_gaps({s}, first, forces[g]).front());
    double area = 0.0;
    for (std::size_t i = s.begin; i < s.end; ++i)
      area += first.weight[i] * std::abs(forces[g][i] - cb.groups[g].sim_forces_first[i]);
    change.push_back(area);
  }
  const auto signature = evidence::shares(change);
  double distance = 0.0;
  for (std::size_t k = 0; k < cb.where.size(); ++k) distance += std::abs(signature[k] - cb.where[k].share);
  r.region_match = 1.0 - 0.5 * distance;
  // Plausibility of every parameter set once, on the scale of the first mode using it.
  for (std::size_t k = 0; k < effects.size(); ++k)
    for (int b = 0; b < effects[k].blocks; ++b) {
      const auto g = static_cast<std::size_t>(std::find(effects[k].block_of.begin(), effects[k].block_of.end(), b) -
                                              effects[k].block_of.begin());
      r.plausibility *= plausibility(*effects[k].effect, fit.blocks[k][static_cast<std::size_t>(b)],
                                     cb.groups[g].problem.scale);
    }
  return r;
}

// Starts of a joint fit from the per-mode fits of the same effect: a shared block takes each
// mode's value in turn, per-mode blocks their own mode's value (the plausible centre when the
// mode did not fit it).
using Start = std::vector<std::vector<std::vector<double>>>;  // [effect][block] parameters

std::vector<Start> starts_from_modes(const JointEffect& e, const std::vector<ModeDiagnosis>& modes,
                                     const Combined& cb) {
  std::vector<std::vector<double>> per_mode(modes.size());
  for (std::size_t m = 0; m < modes.size(); ++m)
    for (const RankedEffect& r : modes[m].diagnosis.ranking)
      if (r.effect == e.effect->name) per_mode[m] = r.fitted.front().params;
  std::vector<Start> starts;
  if (e.blocks == 1 && !effect_per_mode(*e.effect)) {
    for (std::size_t m = 0; m < modes.size(); ++m)
      if (e.block_of[m] == 0 && !per_mode[m].empty()) starts.push_back({{per_mode[m]}});
    return starts;
  }
  std::vector<std::vector<double>> blocks(static_cast<std::size_t>(e.blocks));
  for (std::size_t m = 0; m < modes.size(); ++m) {
    if (e.block_of[m] < 0) continue;
    std::vector<double> p = per_mode[m];
    if (p.empty())
      for (const auto& s : e.effect->parameters(cb.groups[m].problem.scale))
        p.push_back(s.grid.empty() ? 0.5 * (s.plausible_lower + s.plausible_upper) : 0.0);
    blocks[static_cast<std::size_t>(e.block_of[m])] = p;
  }
  starts.push_back({blocks});
  return starts;
}

// A pair with a model-only effect over all modes: the model-only parameters (specimen effects:
// one value for all modes) by the bounded pattern search, at most `points` points (each at most
// one FE run per mode); a curve-mode partner refitted jointly on every point's FE curves.
JointFit model_pair(const Combined& cb, const std::vector<JointEffect>& pair, const JointFit& fa,
                    const JointFit& fb, std::size_t points, std::mt19937& rng, int* spent) {
  const CurveScale& scale = cb.problems.front().scale;
  const auto with_model = [&](const std::vector<std::pair<std::size_t, double>>& values) {
    std::vector<std::vector<AppliedEffect>> applied(cb.problems.size());
    for (const auto& [k, v] : values)
      for (std::size_t g = 0; g < cb.problems.size(); ++g)
        if (pair[k].block_of[g] >= 0) applied[g].push_back({pair[k].effect, {v}});
    return applied;
  };
  const double pa = fa.blocks[0][0][0], pb = fb.blocks[0][0][0];
  if (pair[0].effect->needs_model && pair[1].effect->needs_model) {
    const auto objective = [&](const std::vector<double>& x) {
      return evaluate_joint(cb.problems, with_model({{0, x[0]}, {1, x[1]}})).weighted_sse;
    };
    const PatternSearch s = pattern_search(
        {pair[0].effect->parameters(scale)[0], pair[1].effect->parameters(scale)[0]},
        {{{pa, pair[1].effect->neutral}, fa.weighted_sse}, {{pair[0].effect->neutral, pb}, fb.weighted_sse}},
        {{pa, pb}}, objective, points);
    *spent = static_cast<int>(s.points);
    JointFit out = evaluate_joint(cb.problems, with_model({{0, s.best[0]}, {1, s.best[1]}}));
    out.blocks = {{{s.best[0]}}, {{s.best[1]}}};
    out.parameter_count = 2;
    return out;
  }
  const std::size_t m = pair[0].effect->needs_model ? 0 : 1;
  const JointFit& curve_single = m == 0 ? fb : fa;
  // The curve-mode partner fitted jointly on the FE curves at model parameter x.
  const auto partner = [&](double x) {
    std::vector<FitProblem> on_runs = cb.problems;
    for (std::size_t g = 0; g < on_runs.size(); ++g) {
      if (pair[m].block_of[g] >= 0) on_runs[g].sim = cb.problems[g].runner({{pair[m].effect, {x}}});
      on_runs[g].runner = nullptr;
    }
    return fit_joint(on_runs, {pair[1 - m]}, {{curve_single.blocks[0]}}, 0, rng);
  };
  const PatternSearch s = pattern_search({pair[m].effect->parameters(scale)[0]}, {}, {{m == 0 ? pa : pb}},
                                         [&](const std::vector<double>& x) { return partner(x[0]).weighted_sse; },
                                         points);
  *spent = static_cast<int>(s.points);
  const JointFit best = partner(s.best[0]);
  auto applied = with_model({{m, s.best[0]}});
  for (std::size_t g = 0; g < applied.size(); ++g)
    applied[g].insert(applied[g].end(), best.per_problem[g].begin(), best.per_problem[g].end());
  JointFit out = evaluate_joint(cb.problems, applied);
  out.blocks.resize(2);
  out.blocks[m] = {{s.best[0]}};
  out.blocks[1 - m] = best.blocks[0];
  out.parameter_count = 1 + best.parameter_count;
  return out;
}

// A model-only effect (a specimen effect: one value over every mode) fitted jointly without
// derivatives (issue 51): the bounded pattern search from each mode's own answer, at most
// `points` values (each at most one model run per mode; the modes' own runs are cached).
JointFit joint_model_single(const Combined& cb, const JointEffect& e, const std::vector<Start>& starts,
                            std::size_t points, int* spent) {
  const auto applied = [&](double v) {
    std::vector<std::vector<AppliedEffect>> out(cb.problems.size());
    for (std::size_t g = 0; g < cb.problems.size(); ++g)
      if (e.block_of[g] >= 0) out[g].push_back({e.effect, {v}});
    return out;
  };
  std::vector<std::vector<double>> from_modes;
  for (const Start& start : starts) from_modes.push_back({start.at(0).at(0).at(0)});
  if (from_modes.empty()) from_modes.push_back({e.effect->neutral});
  const PatternSearch s = pattern_search({e.effect->parameters(cb.problems.front().scale)[0]}, {}, from_modes,
                                         [&](const std::vector<double>& x) {
                                           return evaluate_joint(cb.problems, applied(x[0])).weighted_sse;
                                         },
                                         std::max<std::size_t>(points, from_modes.size()));
  *spent = static_cast<int>(s.points);
  JointFit out = evaluate_joint(cb.problems, applied(s.best[0]));
  out.blocks = {{{s.best[0]}}};
  out.parameter_count = 1;
  return out;
}

Diagnosis combine(const std::vector<ModeInput>& inputs, const std::vector<ModeDiagnosis>& modes,
                  const DiagnosisOptions& options) {
  Diagnosis c;
  Combined cb;
  std::vector<std::string> mode_names;
  double weighted_gap = 0.0, noise_area = 0.0;
  std::string sims;
  for (std::size_t m = 0; m < modes.size(); ++m) {
    const Diagnosis& d = modes[m].diagnosis;
    mode_names.push_back(modes[m].mode);
    Group g;
    g.problem.sim = d.sim;
    g.problem.scale = curve_scale(d.sim);
    for (const ForceCurve& lab : d.labs)
      g.problem.scale.test_end_m = std::max(g.problem.scale.test_end_m, *std::max_element(lab.u.begin(), lab.u.end()));
    if (inputs[m].model)
      g.problem.runner = [runner = inputs[m].model](const std::vector<AppliedEffect>& effects) {
        return oriented(runner(effects));
      };
    for (std::size_t k = 0; k < d.labs.size(); ++k) {
      g.problem.labs.push_back(make_comparison(d.labs[k]));
      g.problem.labs.back().fracture_m = k < d.fracture_m.size() ? d.fracture_m[k] : 0.0;
    }
    set_damage_clocks(g.problem.labs);
    g.sim_forces_first = model_forces_at_lab(d.sim, g.problem.labs.front());
    g.curves = static_cast<double>(d.labs.size());
    cb.curves += g.curves;
    weighted_gap += g.curves * d.gap_before;
    c.gap_before += g.curves * d.gap_before;
    c.noise_floor += g.curves * d.noise_floor;
    c.noise_sigma_N += g.curves * d.noise_sigma_N;
    c.frechet_before += g.curves * d.frechet_before;
    c.pcm_before += g.curves * d.pcm_before;
    noise_area += g.curves * std::sqrt(2.0 / M_PI) * d.noise_sigma_N / g.problem.labs.front().f_scale;
    c.compression = c.compression || d.compression;
    c.labs.insert(c.labs.end(), d.labs.begin(), d.labs.end());
    c.fracture_m.insert(c.fracture_m.end(), d.fracture_m.begin(), d.fracture_m.end());
    sims += (sims.empty() ? "" : ", ") + d.sim.source;
    cb.problems.push_back(g.problem);
    cb.groups.push_back(std::move(g));
  }
  for (double* v : {&c.gap_before, &c.noise_floor, &c.noise_sigma_N, &c.frechet_before, &c.pcm_before, &noise_area})
    *v /= cb.curves;
  c.sim.source = sims;
  c.best_model = c.sim;
  // Where: every mode's segments, their shares weighted by the mode's part of the total gap.
  for (std::size_t m = 0; m < modes.size(); ++m)
    for (GapSegment s : modes[m].diagnosis.where) {
      const double part = weighted_gap > 0 ? cb.groups[m].curves * modes[m].diagnosis.gap_before / weighted_gap
                                           : 1.0 / static_cast<double>(modes.size());
      s.share *= part;
      s.mode = modes[m].mode;
      cb.where.push_back(s);
      cb.segment_group.push_back(m);
    }
  c.where = cb.where;
  const evidence::Thresholds thresholds{c.gap_before, c.noise_floor, noise_area};

  std::vector<const EffectSpec*> requested;
  if (options.effects.empty())
    for (const EffectSpec& e : effect_catalogue()) requested.push_back(&e);
  else
    for (const std::string& name : options.effects) requested.push_back(&find_effect(name));
  std::vector<JointEffect> singles;
  for (const EffectSpec* e : requested) {
    const Candidate candidate = candidate_for(*e, inputs);
    if (candidate.joint.blocks == 0) {
      c.not_tested.push_back(e->name);
      c.not_tested_reason[e->name] = candidate.untested;
    } else {
      singles.push_back(candidate.joint);
    }
  }

  std::mt19937 rng(options.seed);
  const JointFit baseline = evaluate_joint(cb.problems, std::vector<std::vector<AppliedEffect>>(cb.problems.size()));
  const double baseline_mse = baseline.weighted_sse / cb.curves;
  std::vector<JointFit> fits;
  std::vector<std::vector<JointEffect>> fitted_effects;
  std::vector<RankedEffect> ranking;
  for (const JointEffect& e : singles) {
    int runs = 0;
    const auto started = std::chrono::steady_clock::now();
    fits.push_back(e.effect->needs_model ? joint_model_single(cb, e, starts_from_modes(e, modes, cb), options.model_runs, &runs)
                                         : fit_joint(cb.problems, {e}, starts_from_modes(e, modes, cb), options.random_starts, rng));
    fitted_effects.push_back({e});
    ranking.push_back(rank_combined(cb, {e}, fits.back(), mode_names, c.gap_before));
    ranking.back().model_runs = runs;
    if (e.effect->needs_model)
      ranking.back().model_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  }
  const auto rescore = [&] {
    std::vector<evidence::FitStatistics> statistics;
    for (const JointFit& f : fits) statistics.push_back({f.weighted_sse, f.residual});
    evidence::score(ranking, statistics, cb.curves, baseline_mse, thresholds, &c.lag1_autocorrelation,
                    &c.effective_sample_size);
  };
  rescore();

  std::vector<CurveScale> scales;
  for (const FitProblem& problem : cb.problems) scales.push_back(problem.scale);
  // As in one mode (diagnose): a magnitude beyond its range is the edge when, held there and
  // every other parameter refitted over the modes, the gap stays within 0.3 x the noise area.
  const auto edge_fits = [&](std::size_t index) {
    const std::vector<JointEffect>& effects = fitted_effects[index];
    for (const JointEffect& e : effects)
      if (e.effect->needs_model) return false;  // no extra model run for this
    // Each block's magnitudes beyond their range held at the edge, on the scale of the first
    // mode the block applies to; a partner pushed past its own edge is held too, and the fit
    // repeated (at most once per effect).
    const auto plausible = [&](const JointFit& f) {
      for (std::size_t g = 0; g < cb.problems.size(); ++g)
        if (!magnitudes_plausible(f.per_problem[g], scales[g])) return false;
      return true;
    };
    std::vector<HeldParameter> held;
    JointFit at_edge = fits[index];
    for (std::size_t round = 0; round < effects.size(); ++round) {
      for (std::size_t k = 0; k < effects.size(); ++k)
        for (int b = 0; b < effects[k].blocks; ++b) {
          const auto& block_of = effects[k].block_of;
          const auto g = static_cast<std::size_t>(std::find(block_of.begin(), block_of.end(), b) - block_of.begin());
          const AppliedEffect applied{effects[k].effect, at_edge.blocks[k][static_cast<std::size_t>(b)]};
          for (const BeyondRange& beyond : magnitudes_beyond_range({applied}, scales.at(g)))
            held.push_back({k, b, effects[k].effect->magnitude,
                            beyond.value > effects[k].effect->neutral ? beyond.plausible_upper : beyond.plausible_lower});
        }
      at_edge = fit_joint(cb.problems, effects, {fits[index].blocks}, 0, rng, held);
      if (plausible(at_edge)) break;
    }
    return plausible(at_edge) && rank_combined(cb, effects, at_edge, mode_names, c.gap_before).gap_after -
                                         ranking[index].gap_after <=
                                     kMinimumReduction * noise_area;
  };
  // As in one mode: the best gap of a single that can be the cause (its magnitudes within their
  // ranges in every mode, or at an edge within what the data tell) decides whether pairs are
  // searched and sets the bar they must clear.
  const auto within_ranges = [&](const RankedEffect& r) {
    for (std::size_t m = 0; m < r.fitted_by_mode.size(); ++m)
      if (!magnitudes_beyond_range(r.fitted_by_mode[m].second, scales.at(m)).empty()) return false;
    return r.fitted_by_mode.empty() ? magnitudes_beyond_range(r.fitted, scales.at(0)).empty() : true;
  };
  double single_gap = INFINITY;
  for (std::size_t i = 0; i < ranking.size(); ++i)
    if (ranking[i].gap_after < single_gap && (within_ranges(ranking[i]) || edge_fits(i))) single_gap = ranking[i].gap_after;

  // Pairs, when no such single brings the gap down to 1.5 x the noise floor; pairs with a
  // model-only effect by the bounded search (at most options.model_runs points each).
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < ranking.size(); ++i) order.push_back(i);
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return ranking[a].gap_after < ranking[b].gap_after; });
  if (options.try_pairs && c.gap_before > c.noise_floor && single_gap > 1.5 * c.noise_floor) {
    order.resize(std::min(order.size(), kCombinedPairCandidates));
    const std::size_t first_pair = ranking.size();
    for (std::size_t a = 0; a < order.size(); ++a)
      for (std::size_t b = a + 1; b < order.size(); ++b) {
        const std::vector<JointEffect> pair = {singles[order[a]], singles[order[b]]};
        int points = 0;
        if (pair[0].effect->needs_model || pair[1].effect->needs_model) {
          if (options.model_runs == 0) continue;
          fits.push_back(model_pair(cb, pair, fits[order[a]], fits[order[b]], options.model_runs, rng, &points));
        } else {
          const std::vector<Start> starts = {{fits[order[a]].blocks[0], fits[order[b]].blocks[0]}};
          fits.push_back(fit_joint(cb.problems, pair, starts, 1, rng));
        }
        fitted_effects.push_back(pair);
        ranking.push_back(rank_combined(cb, pair, fits.back(), mode_names, c.gap_before));
        ranking.back().search_points = points;
      }
    rescore();
    evidence::demote_weak_pairs(ranking, first_pair, single_gap);
    parsimony::apply_joint(ranking, fits, fitted_effects, first_pair, cb.problems, cb.curves, rng);
  }
  evidence::mark_implausible(ranking, scales, edge_fits);
  std::sort(ranking.begin(), ranking.end(),
            [](const RankedEffect& a, const RankedEffect& b) { return a.score > b.score; });
  c.ranking = ranking;
  evidence::decide(c, !singles.empty());
  c.predictive.note = "per loading mode: see modes[].predictive_check";
  return c;
}

}  // namespace

MultiModeDiagnosis diagnose_modes(const std::vector<ModeInput>& inputs, const DiagnosisOptions& options) {
  if (inputs.empty()) throw InputError("--lab", "give at least one laboratory curve");
  std::set<std::string> seen;
  MultiModeDiagnosis out;
  for (const ModeInput& in : inputs) {
    if (!seen.insert(in.mode).second) throw InputError("--mode", "loading mode " + in.mode + " given twice");
    if (in.labs.empty()) throw InputError("--lab", "loading mode " + in.mode + " has no laboratory curve");
  }
  for (const ModeInput& in : inputs) {
    DiagnosisOptions o = options;
    o.model = in.model;
    o.model_unsupported = in.model_unsupported;
    for (const EffectSpec& e : effect_catalogue())
      if (const std::string why = effect_inapplicable(e, in.mode, largest_displacement(in)); !why.empty())
        o.inapplicable[e.name] = why;
    out.modes.push_back({in.mode, in.basis, diagnose(in.labs, in.sim, o)});
  }
  out.combined = inputs.size() == 1 ? out.modes.front().diagnosis : combine(inputs, out.modes, options);
  return out;
}

nlohmann::json multimode_json(const MultiModeDiagnosis& d) {
  nlohmann::json out = diagnosis_json(d.combined);
  nlohmann::json modes = nlohmann::json::array();
  for (const ModeDiagnosis& m : d.modes) {
    nlohmann::json entry = diagnosis_json(m.diagnosis);
    entry["mode"] = m.mode;
    entry["mode_basis"] = m.basis;
    entry["curves"] = entry.at("lab");
    modes.push_back(entry);
  }
  out["modes"] = modes;
  return out;
}

std::string multimode_markdown(const MultiModeDiagnosis& d) {
  if (d.modes.size() == 1) return diagnosis_markdown(d.combined);
  std::string out = "## Combined over the loading modes\n\n" + diagnosis_markdown(d.combined);
  for (const ModeDiagnosis& m : d.modes)
    out += "\n## Loading mode " + m.mode + " (" + m.basis + ")\n\n" + diagnosis_markdown(m.diagnosis);
  return out;
}

}  // namespace dtwire::gap
