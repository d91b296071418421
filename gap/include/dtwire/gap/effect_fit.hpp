#pragma once
// Least-squares fit of one or more catalogue effects to laboratory curves (Ceres, bounded,
// multi-start). Kept in this one file so that it can move onto calibrate/'s fitter later.
#include <random>
#include <vector>

#include "dtwire/gap/curve_metrics.hpp"
#include "dtwire/gap/effects.hpp"
#include "dtwire/gap/specimen_scatter.hpp"

namespace dtwire::gap {

struct FitProblem {
  ForceCurve sim;
  CurveScale scale;
  std::vector<Comparison> labs;  // residuals of all curves are stacked
  ModelRunner runner;            // --model mode only
  SpecimenScatter scatter;       // repeated curves: profiled out of every residual
};

struct EffectFit {
  std::vector<AppliedEffect> effects;  // fitted parameters, in the order given
  double weighted_sse = 0.0;           // sum over labs of sum w r^2 (normalised residual)
  std::vector<double> residual;        // normalised residuals, stacked in lab order
  int parameter_count = 0;
};

// The model compared with each laboratory curve of `problem`, in its order: the simulation
// with `effects` (model-only ones run once), each record at its own damage clock when an effect
// runs to fracture (records of one clock share a curve).
std::vector<ForceCurve> record_models(const FitProblem& problem, const std::vector<AppliedEffect>& effects);

// Fitted residual vector and weighted SSE for given parameters.
EffectFit evaluate_fit(const FitProblem& problem, std::vector<AppliedEffect> effects);

// A parameter the fit holds at `value` while it fits the rest (the misfit's profile there):
// parameter `parameter` of effect `effect` (indices into the fit's effects), in its block
// `block` of a joint fit (-1: every block).
struct HeldParameter {
  std::size_t effect = 0;
  int block = -1;
  std::size_t parameter = 0;
  double value = 0.0;
};

// Fits `effects` (starting values: each start is a full parameter vector per effect; the
// plausible-range centre and random plausible values are added). Grid parameters are searched
// over their grid around the continuous fit.
EffectFit fit_effects(const FitProblem& problem, const std::vector<const EffectSpec*>& effects,
                      std::vector<std::vector<std::vector<double>>> starts, std::size_t random_starts,
                      std::mt19937& rng, const std::vector<HeldParameter>& held = {});

// Joint fit over several problems (e.g. one per loading mode). An effect has `blocks` parameter
// sets; `block_of[p]` is the set used on problem p, or -1 where the effect does not apply. One
// block shared by every problem fits one value over all of them.
struct JointEffect {
  const EffectSpec* effect;
  std::vector<int> block_of;  // per problem
  int blocks = 1;
};

struct JointFit {
  std::vector<std::vector<AppliedEffect>> per_problem;  // effects as applied to each problem
  std::vector<std::vector<std::vector<double>>> blocks; // [effect][block] fitted parameters
  double weighted_sse = 0.0;     // summed over problems
  std::vector<double> residual;  // stacked in problem order
  int parameter_count = 0;       // the fitted ones (held parameters not counted)
};

JointFit evaluate_joint(const std::vector<FitProblem>& problems,
                        std::vector<std::vector<AppliedEffect>> per_problem);

// `starts`: each a [effect][block] parameter set; the plausible centre, the effects switched
// off and `random_starts` random plausible values are added.
JointFit fit_joint(const std::vector<FitProblem>& problems, const std::vector<JointEffect>& effects,
                   const std::vector<std::vector<std::vector<std::vector<double>>>>& starts,
                   std::size_t random_starts, std::mt19937& rng, const std::vector<HeldParameter>& held = {});

}  // namespace dtwire::gap
