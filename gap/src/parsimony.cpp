#include "parsimony.hpp"

#include <algorithm>
#include <cmath>
#include <functional>

#include "dtwire/gap/noise.hpp"

namespace dtwire::gap::parsimony {
namespace {

std::vector<const EffectSpec*> effects_of(const RankedEffect& r) {
  std::vector<const EffectSpec*> out;
  for (const AppliedEffect& a : r.fitted) out.push_back(a.effect);
  return out;
}

std::vector<std::vector<double>> params_of(const RankedEffect& r) {
  std::vector<std::vector<double>> out;
  for (const AppliedEffect& a : r.fitted) out.push_back(a.params);
  return out;
}

bool needs_model(const RankedEffect& r) {
  return std::any_of(r.fitted.begin(), r.fitted.end(), [](const AppliedEffect& a) { return a.effect->needs_model; });
}

// Refit on the training blocks (from the full-data optimum), error on the held-out blocks.
double held_out_refit(const RankedEffect& r, const FitProblem& problem, const FitProblem& training,
                      const std::vector<bool>& held_out, std::mt19937& rng) {
  const EffectFit fit = fit_effects(training, effects_of(r), {params_of(r)}, 0, rng);
  return held_out_error(evaluate_fit(problem, fit.effects).residual, held_out);
}

}  // namespace

double bic(double mse, double n_eff, int k) {
  return n_eff * std::log(std::max(mse, 1e-300)) + k * std::log(n_eff);
}

FitProblem training_problem(const FitProblem& problem, int blocks, std::vector<bool>* held_out) {
  FitProblem out = problem;
  held_out->clear();
  for (Comparison& c : out.labs) {
    const std::size_t n = c.weight.size();
    for (std::size_t i = 0; i < n; ++i) {
      const bool odd = (i * static_cast<std::size_t>(blocks) / std::max<std::size_t>(n, 1)) % 2 == 1;
      if (odd) c.weight[i] = 0.0;
      held_out->push_back(odd);
    }
  }
  return out;
}

double held_out_error(const std::vector<double>& residual, const std::vector<bool>& held_out) {
  double sse = 0.0;
  for (std::size_t k = 0; k < residual.size() && k < held_out.size(); ++k)
    if (held_out[k]) sse += residual[k] * residual[k];
  return sse;
}

namespace {

// What the rule needs of the fits behind a ranking: the weighted SSE and residual of entry i,
// whether it has a model-only effect, and its held-out error (refitted on the training blocks,
// weighted SSE on the held-out ones).
struct FitAccess {
  std::function<double(std::size_t)> weighted_sse;
  std::function<const std::vector<double>&(std::size_t)> residual;
  std::function<bool(std::size_t)> needs_model;
  std::function<double(std::size_t)> held_out_error;
};

void judge(std::vector<RankedEffect>& ranking, std::size_t first_pair, double curves, const FitAccess& fits) {
  if (first_pair == 0 || first_pair >= ranking.size()) return;
  std::size_t best = 0;
  for (std::size_t i = 1; i < first_pair; ++i)
    if (fits.weighted_sse(i) < fits.weighted_sse(best)) best = i;
  // The effective sample size of the single's residual: a pair that only absorbs the smooth,
  // strongly autocorrelated misfit of an effect of another shape gains little on few effective
  // points (n_eff = n (1 - rho1) / (1 + rho1), Wilks, Statistical Methods in the Atmospheric
  // Sciences, eq. 5.12; BIC after Schwarz 1978, margin 6 = "strong" in Kass and Raftery 1995).
  const double lag1 = lag1_autocorrelation(fits.residual(best));
  const double n_eff = effective_sample_size(fits.residual(best).size(), lag1, 8.0);
  const double bic_single = bic(fits.weighted_sse(best) / curves, n_eff, ranking[best].parameters);
  bool single_heldout_done = false;
  double single_heldout = 0.0;
  for (std::size_t i = first_pair; i < ranking.size(); ++i) {
    RankedEffect& pair = ranking[i];
    PairEvidence& e = pair.against_single;
    e.done = true;
    e.single = ranking[best].effect;
    e.lag1 = lag1;
    e.n_eff = n_eff;
    e.bic_single = bic_single;
    e.bic_pair = bic(fits.weighted_sse(i) / curves, n_eff, pair.parameters);
    e.information_ok = e.bic_pair < bic_single - kPairBicMargin;
    const bool model_pair = fits.needs_model(i) || fits.needs_model(best);
    // The held-out refit only for a pair that could still be the cause (it costs two fits).
    if (pair.qualifies && e.information_ok && !model_pair) {
      if (!single_heldout_done) {
        single_heldout = fits.held_out_error(best);
        single_heldout_done = true;
      }
      e.heldout_done = true;
      e.heldout_error_single = single_heldout;
      e.heldout_error_pair = fits.held_out_error(i);
      e.heldout_ok = e.heldout_error_pair < kPairHeldOutRatio * e.heldout_error_single;
    }
    const bool passes = e.information_ok && (model_pair || e.heldout_ok);
    if (pair.qualifies && !passes) {
      pair.qualifies = false;
      pair.also_possible = true;
      pair.score *= 0.1;
    }
  }
}

}  // namespace

void apply(std::vector<RankedEffect>& ranking, const std::vector<EffectFit>& fits, std::size_t first_pair,
           const FitProblem& problem, std::mt19937& rng) {
  std::vector<bool> held_out;
  const FitProblem training = training_problem(problem, kHeldOutBlocks, &held_out);
  FitAccess access;
  access.weighted_sse = [&](std::size_t i) { return fits[i].weighted_sse; };
  access.residual = [&](std::size_t i) -> const std::vector<double>& { return fits[i].residual; };
  access.needs_model = [&](std::size_t i) { return needs_model(ranking[i]); };
  access.held_out_error = [&](std::size_t i) { return held_out_refit(ranking[i], problem, training, held_out, rng); };
  judge(ranking, first_pair, static_cast<double>(problem.labs.size()), access);
}

void apply_joint(std::vector<RankedEffect>& ranking, const std::vector<JointFit>& fits,
                 const std::vector<std::vector<JointEffect>>& effects, std::size_t first_pair,
                 const std::vector<FitProblem>& problems, double curves, std::mt19937& rng) {
  // The held-out blocks are cut in every curve of every mode, stacked in problem order as the
  // joint residual is.
  std::vector<FitProblem> training;
  std::vector<bool> held_out;
  for (const FitProblem& problem : problems) {
    std::vector<bool> mask;
    training.push_back(training_problem(problem, kHeldOutBlocks, &mask));
    held_out.insert(held_out.end(), mask.begin(), mask.end());
  }
  FitAccess access;
  access.weighted_sse = [&](std::size_t i) { return fits[i].weighted_sse; };
  access.residual = [&](std::size_t i) -> const std::vector<double>& { return fits[i].residual; };
  access.needs_model = [&](std::size_t i) {
    return std::any_of(effects[i].begin(), effects[i].end(), [](const JointEffect& e) { return e.effect->needs_model; });
  };
  access.held_out_error = [&](std::size_t i) {
    const JointFit refit = fit_joint(training, effects[i], {fits[i].blocks}, 0, rng);
    return held_out_error(evaluate_joint(problems, refit.per_problem).residual, held_out);
  };
  judge(ranking, first_pair, curves, access);
}

}  // namespace dtwire::gap::parsimony
