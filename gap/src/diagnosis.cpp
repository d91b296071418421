#include "dtwire/gap/diagnosis.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>

#include "dtwire/core/error.hpp"
#include "dtwire/gap/noise.hpp"

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

double mean_gap(const ForceCurve& model, const std::vector<Comparison>& labs) {
  double sum = 0.0;
  for (const Comparison& c : labs) sum += normalised_area(model, c);
  return sum / static_cast<double>(labs.size());
}

double aicc(double mse, double n_eff, int k) {
  const double kk = k;
  const double correction = n_eff - kk - 1 > 0 ? 2 * kk * (kk + 1) / (n_eff - kk - 1) : 1e9;
  return n_eff * std::log(std::max(mse, 1e-300)) + 2 * kk + correction;
}

std::string joined_name(const std::vector<AppliedEffect>& effects) {
  std::vector<std::string> names;
  for (const AppliedEffect& a : effects) names.push_back(a.effect->name);
  std::sort(names.begin(), names.end());
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : "+") + n;
  return out;
}

// Shares of `values` (non-negative); uniform when they sum to zero.
std::vector<double> shares(const std::vector<double>& values) {
  double total = 0.0;
  for (double v : values) total += v;
  std::vector<double> out(values.size(), values.empty() ? 0.0 : 1.0 / static_cast<double>(values.size()));
  if (total > 0)
    for (std::size_t i = 0; i < values.size(); ++i) out[i] = values[i] / total;
  return out;
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
  const ForceCurve model = augment(ctx.problem.sim, fit.effects, ctx.problem.scale, ctx.problem.runner);
  r.gap_after = mean_gap(model, ctx.problem.labs);
  r.shrink = ctx.gap_before > 0 ? 1.0 - r.gap_after / ctx.gap_before : 0.0;
  const Comparison& first = ctx.problem.labs.front();
  const auto forces = model_forces_at_lab(model, first);
  r.gap_after_by_segment = segment_gaps(ctx.where, first, forces);
  r.frechet_after = frechet_distance(model, first);
  r.pcm_after = partial_curve_mapping(model, first);
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
  const auto signature = shares(change);
  double distance = 0.0;
  for (std::size_t k = 0; k < ctx.where.size(); ++k)
    distance += std::abs(signature[k] - ctx.where[k].share);
  r.region_match = 1.0 - 0.5 * distance;
  return r;
}

void score_ranking(std::vector<RankedEffect>& ranking, const std::vector<EffectFit>& fits,
                   const Context& ctx, double baseline_mse, Diagnosis& d) {
  // One effective sample size for every candidate: from the residual of the best fit, whose
  // autocorrelation is closest to that of the noise.
  std::size_t best = 0;
  for (std::size_t i = 1; i < fits.size(); ++i)
    if (fits[i].weighted_sse < fits[best].weighted_sse) best = i;
  d.lag1_autocorrelation = fits.empty() ? 0.0 : lag1_autocorrelation(fits[best].residual);
  const std::size_t n = fits.empty() ? 0 : fits[best].residual.size();
  d.effective_sample_size = effective_sample_size(n, d.lag1_autocorrelation, 8.0);
  const double n_eff = d.effective_sample_size;
  const double labs = static_cast<double>(ctx.problem.labs.size());
  const double baseline = aicc(baseline_mse, n_eff, 0);
  double lowest = baseline;
  for (std::size_t i = 0; i < ranking.size(); ++i) {
    const double mse = fits[i].weighted_sse / labs;
    ranking[i].aicc = aicc(mse, n_eff, ranking[i].parameters);
    ranking[i].bic = n_eff * std::log(std::max(mse, 1e-300)) + ranking[i].parameters * std::log(n_eff);
    ranking[i].delta_aicc = ranking[i].aicc - baseline;
    lowest = std::min(lowest, ranking[i].aicc);
  }
  double total = std::exp(-0.5 * (baseline - lowest));
  for (const RankedEffect& r : ranking) total += std::exp(-0.5 * (r.aicc - lowest));
  for (RankedEffect& r : ranking) {
    const double weight = std::exp(-0.5 * (r.aicc - lowest)) / total;
    r.score = weight * r.plausibility * 0.5 * (1.0 + r.region_match);
    r.qualifies = ctx.gap_before > ctx.floor && ctx.gap_before - r.gap_after > kMinimumReduction * ctx.noise_area &&
                  r.delta_aicc < -kInformationMargin;
  }
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
    d.labs.push_back(densified(oriented(lab, &flipped)));
    d.compression = d.compression || flipped;
    check_force(d.labs.back());
    check_overlap(d.labs.back(), d.sim);
  }

  Context ctx;
  ctx.problem.sim = d.sim;
  ctx.problem.scale = curve_scale(d.sim);
  if (options.model) {
    ctx.problem.runner = [runner = options.model](const std::vector<AppliedEffect>& effects) {
      return oriented(runner(effects));
    };
  }
  for (const ForceCurve& lab : d.labs) ctx.problem.labs.push_back(make_comparison(lab));
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
    d.noise_floor = std::max(d.noise_floor, d.scatter_gap);
  }
  ctx.floor = d.noise_floor;
  ctx.noise_area = std::sqrt(2.0 / M_PI) * d.noise_sigma_N / first.f_scale;

  ctx.sim_forces_first = model_forces_at_lab(d.sim, first);
  d.gap_before = mean_gap(d.sim, ctx.problem.labs);
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
    if (e->needs_model && !options.model) {
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
  for (const EffectSpec* e : candidates)
    fits.push_back(fit_effects(ctx.problem, {e}, {}, options.random_starts, rng));
  std::vector<RankedEffect> ranking;
  for (const EffectFit& f : fits) ranking.push_back(rank_entry(ctx, f));
  score_ranking(ranking, fits, ctx, baseline_mse, d);

  // Pairs, when no single effect brings the gap down to the noise floor.
  const auto best_single = std::min_element(ranking.begin(), ranking.end(),
      [](const RankedEffect& a, const RankedEffect& b) { return a.gap_after < b.gap_after; });
  if (options.try_pairs && best_single != ranking.end() && d.gap_before > d.noise_floor &&
      best_single->gap_after > 1.5 * d.noise_floor) {
    std::vector<std::size_t> order(ranking.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(),
              [&](std::size_t a, std::size_t b) { return ranking[a].gap_after < ranking[b].gap_after; });
    order.resize(std::min<std::size_t>(order.size(), 6));
    const double single_gap = best_single->gap_after;
    const std::size_t singles = ranking.size();
    for (std::size_t a = 0; a < order.size(); ++a)
      for (std::size_t b = a + 1; b < order.size(); ++b) {
        const RankedEffect& ra = ranking[order[a]];
        const RankedEffect& rb = ranking[order[b]];
        const std::vector<const EffectSpec*> pair = {ra.fitted[0].effect, rb.fitted[0].effect};
        const auto pa = params_of(ra), pb = params_of(rb);
        const auto& spec_a = pair[0]->parameters(ctx.problem.scale);
        const auto& spec_b = pair[1]->parameters(ctx.problem.scale);
        auto centre = [](const std::vector<ParameterSpec>& specs) {
          std::vector<double> p;
          for (const auto& s : specs) p.push_back(s.grid.empty() ? 0.5 * (s.plausible_lower + s.plausible_upper) : 0.0);
          return p;
        };
        std::vector<std::vector<std::vector<double>>> starts = {
            {pa[0], pb[0]}, {pa[0], centre(spec_b)}, {centre(spec_a), pb[0]}};
        fits.push_back(fit_effects(ctx.problem, pair, starts, 1, rng));
        ranking.push_back(rank_entry(ctx, fits.back()));
      }
    score_ranking(ranking, fits, ctx, baseline_mse, d);
    for (std::size_t i = singles; i < ranking.size(); ++i)
      if (!(ranking[i].gap_after < kPairGapRatio * single_gap)) {
        ranking[i].qualifies = false;
        ranking[i].score *= 0.1;  // a refinement of a single effect, not a second cause
      }
  }
  std::sort(ranking.begin(), ranking.end(),
            [](const RankedEffect& a, const RankedEffect& b) { return a.score > b.score; });
  d.ranking = ranking;

  const RankedEffect* cause = nullptr;
  for (const RankedEffect& r : d.ranking)
    if (r.qualifies) {
      cause = &r;
      break;
    }
  if (d.gap_before <= d.noise_floor) {
    d.reason = "the gap is within the noise floor";
  } else if (!cause) {
    d.reason = candidates.empty() ? "no curve-mode effect was requested"
                                  : "no effect reduces the gap by more than the noise floor";
  } else {
    d.cause = cause->effect;
    d.reason = cause->gap_after <= d.noise_floor ? "closes the gap to the noise floor"
                                                 : "reduces the gap most, but not to the noise floor";
  }
  const RankedEffect* shown = cause ? cause : (d.ranking.empty() ? nullptr : &d.ranking.front());
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
    const ForceCurve model = augment(d.sim, fit.effects, ctx.problem.scale, ctx.problem.runner);
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
