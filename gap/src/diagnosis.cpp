#include "dtwire/gap/diagnosis.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <random>
#include <sstream>

#include "dtwire/core/error.hpp"
#include "dtwire/gap/fracture.hpp"
#include "dtwire/gap/model_search.hpp"
#include "dtwire/gap/noise.hpp"
#include "evidence.hpp"
#include "parsimony.hpp"

namespace dtwire::gap {
namespace {

std::string mm(double metres) {
  std::ostringstream s;
  s.precision(4);
  s << metres * 1e3;
  return s.str();
}

void check_overlap(const ForceCurve& lab, const ForceCurve& sim) {
  const auto [lab_lo, lab_hi] = std::minmax_element(lab.u.begin(), lab.u.end());
  const auto [sim_lo, sim_hi] = std::minmax_element(sim.u.begin(), sim.u.end());
  const double overlap = std::min(*lab_hi, *sim_hi) - std::max(*lab_lo, *sim_lo);
  const double range = *lab_hi - *lab_lo;
  if (!(range > 0))
    throw InputError(lab.source, "the displacement does not change (zero range)");
  if (!(overlap > kMinimumOverlap * range))
    throw InputError(lab.source, "does not overlap the simulation " + sim.source +
                                     ": laboratory displacement " + mm(*lab_lo) + " to " +
                                     mm(*lab_hi) + " mm, simulation " + mm(*sim_lo) + " to " +
                                     mm(*sim_hi) + " mm (at least " +
                                     std::to_string(static_cast<int>(kMinimumOverlap * 100)) +
                                     " % of the laboratory range must overlap)");
}

void check_force(const ForceCurve& c) {
  const double peak = *std::max_element(c.f.begin(), c.f.end());
  if (!(peak > 0)) throw InputError(c.source, "the force is zero throughout");
}

// Mean gap over the curves (`models[k]` against curve k), the specimen scatter profiled out when
// the problem has it.
double mean_gap(const std::vector<ForceCurve>& models, const FitProblem& problem) {
  const auto forces = forces_with_scatter(models, problem.labs, problem.scatter);
  double sum = 0.0;
  for (std::size_t k = 0; k < forces.size(); ++k) sum += normalised_area(forces[k], problem.labs[k]);
  return sum / static_cast<double>(forces.size());
}

std::string joined_name(const std::vector<AppliedEffect>& effects) {
  std::vector<std::string> names;
  for (const AppliedEffect& a : effects) names.push_back(a.effect->name);
  return evidence::joined_name(names);
}

struct Context {
  FitProblem problem;
  std::vector<GapSegment> where;
  std::vector<double> sim_forces_first;  // simulation at the first lab's points
  double gap_before = 0.0;
  double floor = 0.0;
  double noise_area = 0.0;  // expected area of the noise alone
};

RankedEffect rank_entry(const Context& ctx, const EffectFit& fit) {
  RankedEffect r;
  r.effect = joined_name(fit.effects);
  r.fitted = fit.effects;
  r.parameters = fit.parameter_count;
  const std::vector<ForceCurve> models = record_models(ctx.problem, fit.effects);
  r.gap_after = mean_gap(models, ctx.problem);
  r.shrink = ctx.gap_before > 0 ? 1.0 - r.gap_after / ctx.gap_before : 0.0;
  const Comparison& first = ctx.problem.labs.front();
  const auto forces = forces_with_scatter(models, ctx.problem.labs, ctx.problem.scatter).front();
  r.gap_after_by_segment = segment_gaps(ctx.where, first, forces);
  r.frechet_after = frechet_distance(models.front(), first);
  r.pcm_after = partial_curve_mapping(models.front(), first);
  r.plausibility = 1.0;
  for (const AppliedEffect& a : fit.effects)
    r.plausibility *= plausibility(*a.effect, a.params, ctx.problem.scale);
  // Signature: where the effect changes the simulated curve, against where the gap is.
  std::vector<double> change;
  for (const GapSegment& g : ctx.where) {
    double area = 0.0;
    for (std::size_t i = g.begin; i < g.end; ++i)
      area += first.weight[i] * std::abs(forces[i] - ctx.sim_forces_first[i]);
    change.push_back(area);
  }
  const auto signature = evidence::shares(change);
  double distance = 0.0;
  for (std::size_t k = 0; k < ctx.where.size(); ++k)
    distance += std::abs(signature[k] - ctx.where[k].share);
  r.region_match = 1.0 - 0.5 * distance;
  return r;
}

void score_ranking(std::vector<RankedEffect>& ranking, const std::vector<EffectFit>& fits,
                   const Context& ctx, double baseline_mse, Diagnosis& d) {
  std::vector<evidence::FitStatistics> statistics;
  for (const EffectFit& f : fits) statistics.push_back({f.weighted_sse, f.residual});
  evidence::score(ranking, statistics, static_cast<double>(ctx.problem.labs.size()), baseline_mse,
                  {ctx.gap_before, ctx.floor, ctx.noise_area}, &d.lag1_autocorrelation,
                  &d.effective_sample_size);
}

std::vector<std::vector<double>> params_of(const RankedEffect& r) {
  std::vector<std::vector<double>> out;
  for (const AppliedEffect& a : r.fitted) out.push_back(a.params);
  return out;
}

// A sparse polyline (a digitised or published curve) is refined between its vertices so that
// the area and the regions see its segments, not only its corners.
ForceCurve densified(const ForceCurve& c) {
  if (c.size() >= kSparseCurvePoints) return c;
  for (std::size_t i = 1; i < c.size(); ++i)
    if (!(c.u[i] > c.u[i - 1])) return c;  // several branches: keep as given
  ForceCurve out;
  out.source = c.source;
  const std::size_t per_segment = 200 / (c.size() - 1) + 1;
  for (std::size_t i = 0; i + 1 < c.size(); ++i)
    for (std::size_t k = 0; k < per_segment; ++k) {
      const double t = static_cast<double>(k) / static_cast<double>(per_segment);
      out.u.push_back(c.u[i] + t * (c.u[i + 1] - c.u[i]));
      out.f.push_back(c.f[i] + t * (c.f[i + 1] - c.f[i]));
    }
  out.u.push_back(c.u.back());
  out.f.push_back(c.f.back());
  return out;
}

// A pair with one member at its neutral value is the other effect alone, found by the pair's
// wider search: that single is refitted from the pair's values and keeps the better fit, so
// that a single stuck in a local minimum does not leave its own better fit to the pair (the
// independent selfcheck's adiabatic rate softening, seed 13 trial 36, read as damage + rate
// with the damage at 0).
void refit_singles_from_pairs(const Context& ctx, std::vector<EffectFit>& fits, std::vector<RankedEffect>& ranking,
                              std::size_t singles) {
  const auto at_neutral = [&](const AppliedEffect& a) {
    const ParameterSpec spec = a.effect->parameters(ctx.problem.scale).at(a.effect->magnitude);
    return std::abs(a.params.at(a.effect->magnitude) - a.effect->neutral) <= 1e-6 * spec.width();
  };
  std::mt19937 unused;  // no random starts
  for (std::size_t p = singles; p < fits.size(); ++p) {
    if (fits[p].effects.size() != 2) continue;
    for (std::size_t m = 0; m < 2; ++m) {
      const AppliedEffect& off = fits[p].effects[m];
      const AppliedEffect& on = fits[p].effects[1 - m];
      if (off.effect->needs_model || on.effect->needs_model || !at_neutral(off)) continue;
      for (std::size_t s = 0; s < singles; ++s) {
        if (fits[s].effects.size() != 1 || fits[s].effects.front().effect != on.effect) continue;
        EffectFit refit = fit_effects(ctx.problem, {on.effect}, {{on.params}}, 0, unused);
        if (refit.weighted_sse < fits[s].weighted_sse) {
          fits[s] = std::move(refit);
          ranking[s] = rank_entry(ctx, fits[s]);
        }
      }
    }
  }
}

std::vector<double> centre_of(const EffectSpec& e, const CurveScale& scale) {
  std::vector<double> p;
  for (const auto& s : e.parameters(scale)) p.push_back(s.grid.empty() ? 0.5 * (s.plausible_lower + s.plausible_upper) : 0.0);
  return p;
}

// Start of a pair of model-only effects: each single fit's change of the residual, taken as
// linear in its parameter, added (superposition); the weighted least-squares combination of the
// two changes gives the start (clamped to the bounds). A single fitted at its neutral value shows
// no change: one FE run at its plausible centre (counted in `probes`) gives it.
std::vector<double> superposition_start(const Context& ctx, const EffectSpec& a, const EffectFit& fa,
                                        const EffectSpec& b, const EffectFit& fb, int* probes) {
  const EffectFit base = evaluate_fit(ctx.problem, {});
  auto change = [&](const EffectSpec& e, const EffectFit& f) {
    double p = f.effects[0].params[0];
    std::vector<double> r = f.residual;
    if (p == e.neutral) {
      const ParameterSpec spec = e.parameters(ctx.problem.scale)[0];
      p = 0.5 * (spec.plausible_lower + spec.plausible_upper);
      if (p == e.neutral) p = spec.plausible_upper;
      r = evaluate_fit(ctx.problem, {{&e, {p}}}).residual;
      ++*probes;
    }
    for (std::size_t k = 0; k < r.size(); ++k) r[k] -= base.residual[k];
    return std::make_pair(p, r);
  };
  const auto [pa, da] = change(a, fa);
  const auto [pb, db] = change(b, fb);
  double aa = 0, ab = 0, bb = 0, ar = 0, br = 0;
  std::size_t k = 0;
  for (const Comparison& c : ctx.problem.labs)
    for (std::size_t i = 0; i < c.lab.size(); ++i, ++k) {
      const double w = c.weight[i];
      aa += w * da[k] * da[k];
      ab += w * da[k] * db[k];
      bb += w * db[k] * db[k];
      ar += w * da[k] * base.residual[k];
      br += w * db[k] * base.residual[k];
    }
  const double det = aa * bb - ab * ab;
  if (!(std::abs(det) > 1e-12 * aa * bb)) return {fa.effects[0].params[0], fb.effects[0].params[0]};
  // Minimise |r0 + x da + y db|^2 for the fractions x, y of the changes.
  const double x = (-ar * bb + br * ab) / det, y = (-br * aa + ar * ab) / det;
  const auto sa = a.parameters(ctx.problem.scale)[0], sb = b.parameters(ctx.problem.scale)[0];
  return {std::clamp(a.neutral + x * (pa - a.neutral), sa.lower, sa.upper),
          std::clamp(b.neutral + y * (pb - b.neutral), sb.lower, sb.upper)};
}

// A pair from its single fits. Curve-mode pairs: Ceres from the single optima. With a model-only
// effect: its parameter by the bounded pattern search (at most `model_runs` points, each at most
// one FE run), a curve-mode partner refitted by Ceres on every FE curve (no FE cost).
EffectFit fit_pair(const Context& ctx, const RankedEffect& ra, const EffectFit& fa, const RankedEffect& rb,
                   const EffectFit& fb, std::size_t model_runs, std::mt19937& rng, int* points) {
  const EffectSpec* a = ra.fitted[0].effect;
  const EffectSpec* b = rb.fitted[0].effect;
  const std::vector<double>& pa = ra.fitted[0].params;
  const std::vector<double>& pb = rb.fitted[0].params;
  const CurveScale& scale = ctx.problem.scale;
  if (!a->needs_model && !b->needs_model)
    return fit_effects(ctx.problem, {a, b}, {{pa, pb}, {pa, centre_of(*b, scale)}, {centre_of(*a, scale), pb}}, 1, rng);
  if (a->needs_model && b->needs_model) {
    const std::vector<ParameterSpec> specs = {a->parameters(scale)[0], b->parameters(scale)[0]};
    const auto objective = [&](const std::vector<double>& x) {
      return evaluate_fit(ctx.problem, {{a, {x[0]}}, {b, {x[1]}}}).weighted_sse;
    };
    int probes = 0;
    const std::vector<double> start = superposition_start(ctx, *a, fa, *b, fb, &probes);
    // The single fits are the pair with the partner switched off.
    const PatternSearch s = pattern_search(specs, {{{pa[0], b->neutral}, fa.weighted_sse}, {{a->neutral, pb[0]}, fb.weighted_sse}},
                                           {start, {pa[0], pb[0]}}, objective,
                                           model_runs > static_cast<std::size_t>(probes) ? model_runs - probes : 0);
    *points = static_cast<int>(s.points) + probes;
    return evaluate_fit(ctx.problem, {{a, {s.best[0]}}, {b, {s.best[1]}}});
  }
  const bool a_model = a->needs_model;
  const EffectSpec* model = a_model ? a : b;
  const EffectSpec* curve = a_model ? b : a;
  const std::vector<double>& p_model = a_model ? pa : pb;
  const std::vector<double>& p_curve = a_model ? pb : pa;
  // The curve-mode partner fitted on the FE curve at model parameter x.
  const auto partner = [&](double x) {
    FitProblem on_run = ctx.problem;
    on_run.sim = ctx.problem.runner({{model, {x}}});
    on_run.runner = nullptr;
    return fit_effects(on_run, {curve}, {{p_curve}}, 0, rng);
  };
  const PatternSearch s = pattern_search({model->parameters(scale)[0]}, {}, {{p_model[0]}},
                                         [&](const std::vector<double>& x) { return partner(x[0]).weighted_sse; },
                                         model_runs);
  *points = static_cast<int>(s.points);
  const EffectFit best = partner(s.best[0]);
  return evaluate_fit(ctx.problem, {{model, {s.best[0]}}, {curve, best.effects[0].params}});
}

}  // namespace

ForceCurve oriented(const ForceCurve& curve, bool* flipped) {
  const auto [lo, hi] = std::minmax_element(curve.f.begin(), curve.f.end());
  const bool flip = std::abs(*lo) > std::abs(*hi);
  if (flipped) *flipped = flip;
  if (!flip) return curve;
  ForceCurve out = curve;
  for (double& u : out.u) u = -u;
  for (double& f : out.f) f = -f;
  return out;
}

Diagnosis diagnose(const std::vector<ForceCurve>& labs_in, const ForceCurve& sim_in,
                   const DiagnosisOptions& options) {
  if (labs_in.empty()) throw InputError("--lab", "give at least one laboratory curve");
  Diagnosis d;
  validate_force_curve(sim_in);
  d.sim = oriented(sim_in, &d.compression);
  check_force(d.sim);
  for (const ForceCurve& lab : labs_in) {
    validate_force_curve(lab);
    bool flipped = false;
    // A record that ends in a fracture is compared up to it; where it broke sets its damage
    // clock (gap/include/dtwire/gap/fracture.hpp).
    const ForceCurve densified_lab = densified(oriented(lab, &flipped));
    const RecordEnd end = record_end(densified_lab);
    d.labs.push_back(intact_part(densified_lab, end));
    d.fracture_m.push_back(end.fracture ? end.end_m : 0.0);
    d.compression = d.compression || flipped;
    check_force(d.labs.back());
    check_overlap(d.labs.back(), d.sim);
  }

  Context ctx;
  ctx.problem.sim = d.sim;
  ctx.problem.scale = curve_scale(d.sim);
  for (const ForceCurve& lab : d.labs)
    ctx.problem.scale.test_end_m = std::max(ctx.problem.scale.test_end_m, *std::max_element(lab.u.begin(), lab.u.end()));
  if (options.model) {
    ctx.problem.runner = [runner = options.model](const std::vector<AppliedEffect>& effects) {
      return oriented(runner(effects));
    };
  }
  for (std::size_t k = 0; k < d.labs.size(); ++k) {
    ctx.problem.labs.push_back(make_comparison(d.labs[k]));
    ctx.problem.labs.back().fracture_m = d.fracture_m[k];
  }
  set_damage_clocks(ctx.problem.labs);
  const Comparison& first = ctx.problem.labs.front();

  // Noise floor: twice the area that noise alone leaves (E|e| = sigma sqrt(2/pi)); with
  // repeated curves, at least their mean mutual gap (specimen scatter).
  double sigma = 0.0;
  for (std::size_t k = 0; k < d.labs.size(); ++k) {
    const bool sparse = labs_in[k].size() < kSparseCurvePoints;
    const double resolution = sparse ? kDigitisedResolution * ctx.problem.labs[k].f_scale : 0.0;
    sigma += std::max(estimate_noise_sigma(d.labs[k]), resolution);
  }
  d.noise_sigma_N = sigma / static_cast<double>(d.labs.size());
  d.noise_floor = kNoiseFloorFactor * std::sqrt(2.0 / M_PI) * d.noise_sigma_N / first.f_scale;
  if (d.labs.size() >= 2) {
    double sum = 0.0;
    int pairs = 0;
    for (std::size_t i = 0; i < d.labs.size(); ++i)
      for (std::size_t j = 0; j < d.labs.size(); ++j)
        if (i != j) {
          sum += normalised_area(d.labs[i], ctx.problem.labs[j]);
          ++pairs;
        }
    d.scatter_gap = sum / pairs;
    // The smooth scale scatter between the specimens is profiled out of every fit; what the
    // aligned specimens still differ by (noise, drift, shape scatter) is the floor.
    const ScatterEstimate scatter = estimate_scatter(d.labs, ctx.problem.labs);
    ctx.problem.scatter = scatter.scatter;
    d.aligned_scatter_gap = scatter.aligned_gap;
    d.specimen_force_bound = scatter.scatter.force_bound;
    d.specimen_length_bound = scatter.scatter.length_bound;
    d.noise_floor = std::max(d.noise_floor, d.aligned_scatter_gap);
  }
  ctx.floor = d.noise_floor;
  ctx.noise_area = std::sqrt(2.0 / M_PI) * d.noise_sigma_N / first.f_scale;

  ctx.sim_forces_first = forces_with_scatter(d.sim, ctx.problem.labs, ctx.problem.scatter).front();
  d.gap_before = mean_gap(record_models(ctx.problem, {}), ctx.problem);
  if (ctx.problem.scatter.active) {
    double sum = 0.0;
    for (const Comparison& c : ctx.problem.labs) sum += normalised_area(d.sim, c);
    d.gap_before_unadjusted = sum / static_cast<double>(ctx.problem.labs.size());
  }
  ctx.gap_before = d.gap_before;
  d.frechet_before = frechet_distance(d.sim, first);
  d.pcm_before = partial_curve_mapping(d.sim, first);
  d.where = locate_gap(first, ctx.sim_forces_first, name_regions(first.lab), d.noise_sigma_N);
  ctx.where = d.where;
  const EffectFit baseline = evaluate_fit(ctx.problem, {});
  const double baseline_mse = baseline.weighted_sse / static_cast<double>(d.labs.size());

  std::vector<const EffectSpec*> candidates;
  std::vector<const EffectSpec*> requested;
  if (options.effects.empty())
    for (const EffectSpec& e : effect_catalogue()) requested.push_back(&e);
  else
    for (const std::string& name : options.effects) requested.push_back(&find_effect(name));
  for (const EffectSpec* e : requested) {
    const auto unsupported = options.model_unsupported.find(e->name);
    const auto inapplicable = options.inapplicable.find(e->name);
    if (inapplicable != options.inapplicable.end()) {
      d.not_tested.push_back(e->name);
      d.not_tested_reason[e->name] = inapplicable->second;
    } else if (e->needs_model && !options.model) {
      d.not_tested.push_back(e->name);
      d.not_tested_reason[e->name] = "needs --model";
    } else if (e->needs_model && unsupported != options.model_unsupported.end()) {
      d.not_tested.push_back(e->name);
      d.not_tested_reason[e->name] = unsupported->second;
    } else {
      candidates.push_back(e);
    }
  }

  std::mt19937 rng(options.seed);
  std::vector<EffectFit> fits;
  std::vector<std::pair<std::size_t, double>> model_cost;  // per candidate: model runs, wall seconds
  for (const EffectSpec* e : candidates) {
    if (e->needs_model) {
      // Derivative-free within --model-runs (issue 51): a model run's response to a small step
      // is its noise, and the least-squares engine's differences cost runs without bound.
      const auto started = std::chrono::steady_clock::now();
      const ModelEffectSearch search = search_model_effect(ctx.problem, *e, options.model_runs);
      fits.push_back(search.fit);
      model_cost.emplace_back(search.runs, std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count());
    } else {
      // Each effect's random starts from its own stream (the seed and its name), so an effect's
      // fit does not hang on how many parameters the effects fitted before it draw.
      std::seed_seq own{options.seed, static_cast<unsigned>(std::hash<std::string>{}(e->name))};
      std::mt19937 effect_rng(own);
      fits.push_back(fit_effects(ctx.problem, {e}, {}, options.random_starts, effect_rng));
      model_cost.emplace_back(0, 0.0);
    }
  }
  std::vector<RankedEffect> ranking;
  for (std::size_t i = 0; i < fits.size(); ++i) {
    ranking.push_back(rank_entry(ctx, fits[i]));
    ranking.back().model_runs = static_cast<int>(model_cost[i].first);
    ranking.back().model_seconds = model_cost[i].second;
  }
  score_ranking(ranking, fits, ctx, baseline_mse, d);

  // A magnitude fitted beyond its range's edge by no more than the data can tell is the edge,
  // not implausible: a real set-up at the edge of the range fits a little beyond it half the
  // time. The test is the misfit's profile (Bates & Watts 1988, ch. 6): each such magnitude held
  // at its edge, every other parameter refitted (a pair's partner takes up what it can); the
  // edge fits if that leaves the gap within 0.3 x the noise-only area of the free fit's, the
  // reduction below which no effect counts as one.
  const auto edge_fits = [&](std::size_t index) {
    const RankedEffect& r = ranking[index];
    std::vector<const EffectSpec*> effects;
    for (const AppliedEffect& a : r.fitted) {
      if (a.effect->needs_model) return false;  // no extra model run for this
      effects.push_back(a.effect);
    }
    // A partner pushed past its own edge by the refit is held at that edge too, and the fit
    // repeated: at most once per effect.
    std::vector<HeldParameter> held;
    std::vector<AppliedEffect> at_edge = r.fitted;
    for (std::size_t round = 0; round < effects.size(); ++round) {
      for (std::size_t k = 0; k < at_edge.size(); ++k)
        for (const BeyondRange& b : magnitudes_beyond_range({at_edge[k]}, ctx.problem.scale))
          held.push_back({k, -1, effects[k]->magnitude, b.value > effects[k]->neutral ? b.plausible_upper : b.plausible_lower});
      at_edge = fit_effects(ctx.problem, effects, {params_of(r)}, 0, rng, held).effects;
      if (magnitudes_plausible(at_edge, ctx.problem.scale)) break;
    }
    return magnitudes_plausible(at_edge, ctx.problem.scale) &&
           mean_gap(record_models(ctx.problem, at_edge), ctx.problem) - r.gap_after <= kMinimumReduction * ctx.noise_area;
  };
  // The best gap of a single that can be the cause: its magnitudes within their ranges, or at
  // an edge within what the data tell. A single that closes the gap only with a magnitude beyond
  // its range neither spares the pairs their search nor sets the bar a pair must clear (a
  // selfcheck record: a grip slip of 10 mm/kN, its range's edge, with a rate factor of 0.853,
  // read as a slip of 50 mm/kN alone, the pair never tried).
  const auto plausible_single_gap = [&](std::size_t singles) {
    double best = INFINITY;
    for (std::size_t i = 0; i < singles; ++i)
      if (ranking[i].gap_after < best &&
          (magnitudes_beyond_range(ranking[i].fitted, ctx.problem.scale).empty() || edge_fits(i)))
        best = ranking[i].gap_after;
    return best;
  };

  // Pairs, when no such single brings the gap down to 1.5 x the noise floor.
  if (options.try_pairs && !ranking.empty() && d.gap_before > d.noise_floor &&
      plausible_single_gap(ranking.size()) > 1.5 * d.noise_floor) {
    std::vector<std::size_t> order(ranking.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(),
              [&](std::size_t a, std::size_t b) { return ranking[a].gap_after < ranking[b].gap_after; });
    order.resize(std::min<std::size_t>(order.size(), 6));
    const std::size_t singles = ranking.size();
    for (std::size_t a = 0; a < order.size(); ++a)
      for (std::size_t b = a + 1; b < order.size(); ++b) {
        const bool model_pair = ranking[order[a]].fitted[0].effect->needs_model ||
                                ranking[order[b]].fitted[0].effect->needs_model;
        if (model_pair && options.model_runs == 0) continue;  // no FE run allowed for pairs
        int points = 0;
        const auto started = std::chrono::steady_clock::now();
        fits.push_back(fit_pair(ctx, ranking[order[a]], fits[order[a]], ranking[order[b]],
                                fits[order[b]], options.model_runs, rng, &points));
        ranking.push_back(rank_entry(ctx, fits.back()));
        ranking.back().search_points = points;
        if (model_pair) {
          ranking.back().model_runs = points;
          ranking.back().model_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
        }
      }
    refit_singles_from_pairs(ctx, fits, ranking, singles);
    const double single_gap = plausible_single_gap(singles);
    score_ranking(ranking, fits, ctx, baseline_mse, d);
    evidence::demote_weak_pairs(ranking, singles, single_gap);
    parsimony::apply(ranking, fits, singles, ctx.problem, rng);
  }
  evidence::mark_implausible(ranking, {ctx.problem.scale}, edge_fits);
  std::sort(ranking.begin(), ranking.end(),
            [](const RankedEffect& a, const RankedEffect& b) { return a.score > b.score; });
  d.ranking = ranking;
  evidence::decide(d, !candidates.empty());
  const RankedEffect* cause = nullptr;
  for (const RankedEffect& r : d.ranking)
    if (r.effect == d.cause) cause = &r;
  const RankedEffect* shown = cause ? cause : (d.ranking.empty() ? nullptr : &d.ranking.front());
  // On the law's own clock (a damage as on the record that broke last, or on unbroken ones).
  d.best_model = shown ? augment(d.sim, shown->fitted, ctx.problem.scale, ctx.problem.runner) : d.sim;

  // Predictive check: the cause fitted on the first curve, applied to the second.
  if (d.labs.size() < 2) {
    d.predictive.note = "needs two or more laboratory curves";
  } else if (!cause) {
    d.predictive.note = "no cause to predict with";
  } else {
    FitProblem one = ctx.problem;
    one.labs = {ctx.problem.labs[0]};
    std::vector<const EffectSpec*> effects;
    for (const AppliedEffect& a : cause->fitted) effects.push_back(a.effect);
    const EffectFit fit = fit_effects(one, effects, {params_of(*cause)}, 1, rng);
    FitProblem other = ctx.problem;
    other.labs = {ctx.problem.labs[1]};
    const ForceCurve model = record_models(other, fit.effects).front();  // on the second curve's clock
    d.predictive.done = true;
    d.predictive.effect = cause->effect;
    d.predictive.fitted_on = d.labs[0].source;
    d.predictive.predicted = d.labs[1].source;
    d.predictive.gap_before = normalised_area(d.sim, ctx.problem.labs[1]);
    d.predictive.gap_after = normalised_area(model, ctx.problem.labs[1]);
    d.predictive.shrink = d.predictive.gap_before > 0
                              ? 1.0 - d.predictive.gap_after / d.predictive.gap_before
                              : 0.0;
  }
  return d;
}

}  // namespace dtwire::gap
