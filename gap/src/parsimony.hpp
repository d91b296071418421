#pragma once
// Parsimony: a pair of effects is a cause only when the evidence for it beats the best single
// effect by an information criterion with the effective sample size of the single's residual,
// and when it predicts laboratory points it was not fitted on.
#include <cstddef>
#include <random>
#include <vector>

#include "dtwire/gap/diagnosis.hpp"
#include "dtwire/gap/effect_fit.hpp"

namespace dtwire::gap::parsimony {

// BIC (Schwarz 1978) on `n_eff` effective points: n_eff ln(mse) + k ln(n_eff).
double bic(double mse, double n_eff, int k);

// The problem with the odd of `blocks` consecutive blocks of every curve given weight 0 (the
// held-out points), and a mask of those points in stacked residual order.
FitProblem training_problem(const FitProblem& problem, int blocks, std::vector<bool>* held_out);

// Weighted SSE of `residual` on the masked points.
double held_out_error(const std::vector<double>& residual, const std::vector<bool>& held_out);

// Fills `against_single` of the pairs (entries from `first_pair` on). A pair that qualified
// but gains less than kPairBicMargin BIC over the best single, or whose held-out error is not
// below kPairHeldOutRatio x the single's, stops qualifying, is marked `also_possible` and its
// score is divided by 10. Pairs with a model-only effect get the BIC test only (a held-out
// refit would cost FE runs).
void apply(std::vector<RankedEffect>& ranking, const std::vector<EffectFit>& fits, std::size_t first_pair,
           const FitProblem& problem, std::mt19937& rng);

// The same rule in the joint ranking of several loading modes: `fits[i]` is entry i's joint fit
// of `effects[i]` over `problems` (one per mode), `curves` the laboratory curves in all; the
// held-out blocks are cut in every curve of every mode.
void apply_joint(std::vector<RankedEffect>& ranking, const std::vector<JointFit>& fits,
                 const std::vector<std::vector<JointEffect>>& effects, std::size_t first_pair,
                 const std::vector<FitProblem>& problems, double curves, std::mt19937& rng);

}  // namespace dtwire::gap::parsimony
