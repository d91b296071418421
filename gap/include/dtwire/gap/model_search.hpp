#pragma once
// Bounded search over the model-only parameters of a pair of effects: every new point is one FE
// run per model, so the number of points is capped. A compass (pattern) search (Torczon 1997;
// Kolda, Lewis and Torczon 2003): from the best start, steps of a quarter of the plausible range
// along each parameter, halved when no step improves, until the budget is spent or the steps
// fall below 2 % of the range. A grid parameter (ParameterSpec::grid) only takes grid values: it
// steps to the neighbouring one and is never refined. Derivative-free, so it tolerates the threshold responses of
// buckling models.
#include <functional>
#include <optional>
#include <vector>

#include "dtwire/gap/effect_fit.hpp"
#include "dtwire/gap/effects.hpp"

namespace dtwire::gap {

struct PatternSearch {
  std::vector<double> best;
  double value = 0.0;
  std::vector<std::pair<std::vector<double>, double>> samples;  // known and evaluated points
  std::size_t points = 0;  // evaluated (objective calls)
};

// `known` points (e.g. the single effects' fits) are taken as given; `starts` are evaluated
// first. At most `points` objective calls (cached FE runs are free, so the FE runs spent are at
// most `points` per model). Parameters stay within their fit bounds.
PatternSearch pattern_search(const std::vector<ParameterSpec>& specs,
                             const std::vector<std::pair<std::vector<double>, double>>& known,
                             const std::vector<std::vector<double>>& starts,
                             const std::function<double(const std::vector<double>&)>& objective,
                             std::size_t points);

// Where the bounded search of one model-only parameter runs next, given the values already run
// (sorted or not), the minimum of the gap interpolated between them and the best value run:
// the interpolated minimum, unless a value run lies within 2 % of the range of it; then the
// middle of the wider interval beside the best value run, since a response that is not monotone
// between two runs (a DEM punch's peak against a stiffness) hides its minimum from the
// interpolation; nothing when both of those intervals are narrower than 4 % of the range.
std::optional<double> next_model_value(const std::vector<double>& values_run, double interpolated_minimum,
                                       double best_run);

// One model-only effect against laboratory curves (issue 51), derivative-free within `runs`
// model runs, as the summary mode searches it: the plausible range's ends first (a grid
// parameter: its grid values), then the minimum of the weighted SSE of the residual taken as
// linear in the parameter between the values run (next_model_value: near a value run, the middle
// of the wider interval beside the best one), until the runs are spent or the intervals beside the
// best value are narrower than 4 % of the range. The simulation is the neutral value's run. The
// answer is the best value actually run. No finite differences: a DEM run's response to a change
// of 1e-4 is its own noise, not a derivative.
struct ModelEffectSearch {
  EffectFit fit;
  std::size_t runs = 0;                          // values run (each at most one model run)
  std::vector<std::pair<double, double>> samples;  // value -> weighted SSE, the neutral one included
};
ModelEffectSearch search_model_effect(const FitProblem& problem, const EffectSpec& effect, std::size_t runs);

}  // namespace dtwire::gap
