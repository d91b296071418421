#include "parsimony.hpp"

#include <algorithm>
#include <cmath>

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

void apply(std::vector<RankedEffect>& ranking, const std::vector<EffectFit>& fits, std::size_t first_pair,
           const FitProblem& problem, std::mt19937& rng) {
  if (first_pair == 0 || first_pair >= ranking.size()) return;
  std::size_t best = 0;
  for (std::size_t i = 1; i < first_pair; ++i)
    if (fits[i].weighted_sse < fits[best].weighted_sse) best = i;
  // The effective sample size of the single's residual: a pair that only absorbs the smooth,
  // strongly autocorrelated misfit of an effect of another shape gains little on few effective
  // points (n_eff = n (1 - rho1) / (1 + rho1), Wilks, Statistical Methods in the Atmospheric
  // Sciences, eq. 5.12; BIC after Schwarz 1978, margin 6 = "strong" in Kass and Raftery 1995).
  const double lag1 = lag1_autocorrelation(fits[best].residual);
  const double n_eff = effective_sample_size(fits[best].residual.size(), lag1, 8.0);
  const double curves = static_cast<double>(problem.labs.size());
  const double bic_single = bic(fits[best].weighted_sse / curves, n_eff, ranking[best].parameters);

  std::vector<bool> held_out;
  const FitProblem training = training_problem(problem, kHeldOutBlocks, &held_out);
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
    e.bic_pair = bic(fits[i].weighted_sse / curves, n_eff, pair.parameters);
    e.information_ok = e.bic_pair < bic_single - kPairBicMargin;
    const bool model_pair = needs_model(pair) || needs_model(ranking[best]);
    // The held-out refit only for a pair that could still be the cause (it costs two fits).
    if (pair.qualifies && e.information_ok && !model_pair) {
      if (!single_heldout_done) {
        single_heldout = held_out_refit(ranking[best], problem, training, held_out, rng);
        single_heldout_done = true;
      }
      e.heldout_done = true;
      e.heldout_error_single = single_heldout;
      e.heldout_error_pair = held_out_refit(pair, problem, training, held_out, rng);
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

}  // namespace dtwire::gap::parsimony
