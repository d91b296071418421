#include "dtwire/gap/model_search.hpp"

#include <algorithm>
#include <cmath>
#include <map>

namespace dtwire::gap {

PatternSearch pattern_search(const std::vector<ParameterSpec>& specs,
                             const std::vector<std::pair<std::vector<double>, double>>& known,
                             const std::vector<std::vector<double>>& starts,
                             const std::function<double(const std::vector<double>&)>& objective,
                             std::size_t points) {
  PatternSearch out;
  out.value = INFINITY;
  auto clamped = [&](std::vector<double> x) {
    for (std::size_t d = 0; d < specs.size(); ++d) x[d] = specs[d].snapped(std::clamp(x[d], specs[d].lower, specs[d].upper));
    return x;
  };
  auto seen = [&](const std::vector<double>& x) {
    for (const auto& [y, v] : out.samples) {
      bool same = true;
      for (std::size_t d = 0; d < x.size(); ++d) same = same && std::abs(x[d] - y[d]) <= 1e-12 * (1 + std::abs(y[d]));
      if (same) return true;
    }
    return false;
  };
  auto record = [&](const std::vector<double>& x, double v) {
    out.samples.emplace_back(x, v);
    if (v < out.value) {
      out.value = v;
      out.best = x;
      return true;
    }
    return false;
  };
  // Returns true when x improves on the best.
  auto evaluate = [&](const std::vector<double>& x) {
    ++out.points;
    return record(x, objective(x));
  };
  for (const auto& [x, v] : known) record(clamped(x), v);
  for (const auto& start : starts) {
    const auto x = clamped(start);
    if (out.points < points && !seen(x)) evaluate(x);
  }
  if (out.samples.empty()) return out;
  // A grid parameter steps from one grid value to the next and never refines below that.
  const auto grid_spacing = [](const ParameterSpec& s) {
    double spacing = INFINITY;
    for (std::size_t i = 1; i < s.grid.size(); ++i) spacing = std::min(spacing, std::abs(s.grid[i] - s.grid[i - 1]));
    return spacing;
  };
  std::vector<double> step;
  for (const ParameterSpec& s : specs)
    step.push_back(s.grid.size() > 1 ? grid_spacing(s) : 0.25 * (s.plausible_upper - s.plausible_lower));
  // The last successful direction is tried first again (a pattern move, Hooke and Jeeves 1961).
  std::size_t last_d = 0;
  double last_sign = 1.0;
  while (out.points < points) {
    std::vector<std::pair<std::size_t, double>> directions = {{last_d, last_sign}};
    for (std::size_t d = 0; d < specs.size(); ++d)
      for (double sign : {1.0, -1.0})
        if (d != last_d || sign != last_sign) directions.emplace_back(d, sign);
    bool moved = false;
    for (const auto& [d, sign] : directions) {
      std::vector<double> x = out.best;
      x[d] += sign * step[d];
      x = clamped(x);
      if (seen(x)) continue;
      if (out.points >= points) break;
      if (evaluate(x)) {
        moved = true;
        last_d = d;
        last_sign = sign;
        break;
      }
    }
    if (moved) continue;
    bool fine = true;
    for (std::size_t d = 0; d < specs.size(); ++d) {
      if (!specs[d].grid.empty()) continue;
      step[d] *= 0.5;
      fine = fine && step[d] < 0.02 * (specs[d].plausible_upper - specs[d].plausible_lower);
    }
    if (fine) break;
  }
  return out;
}

std::optional<double> next_model_value(const std::vector<double>& values_run, double interpolated_minimum,
                                       double best_run) {
  if (values_run.size() < 2) return std::nullopt;
  std::vector<double> values = values_run;
  std::sort(values.begin(), values.end());
  const double range = values.back() - values.front();
  if (!(range > 0.0)) return std::nullopt;
  bool known = false;
  for (double v : values) known = known || std::abs(v - interpolated_minimum) < 0.02 * range;
  if (!known) return interpolated_minimum;
  const auto at = std::lower_bound(values.begin(), values.end(), best_run);
  const double below = at == values.begin() ? 0.0 : best_run - *std::prev(at);
  const double above = std::next(at) == values.end() ? 0.0 : *std::next(at) - best_run;
  if (std::max(below, above) < 0.04 * range) return std::nullopt;
  return below > above ? best_run - 0.5 * below : best_run + 0.5 * above;
}

ModelEffectSearch search_model_effect(const FitProblem& problem, const EffectSpec& effect, std::size_t runs) {
  const ParameterSpec spec = effect.parameters(problem.scale).front();
  std::vector<double> weight;
  for (const Comparison& c : problem.labs) weight.insert(weight.end(), c.weight.begin(), c.weight.end());
  std::map<double, EffectFit> sampled;
  EffectFit neutral = evaluate_fit(problem, {});
  neutral.effects = {{&effect, {effect.neutral}}};
  neutral.parameter_count = 1;
  sampled.emplace(effect.neutral, neutral);
  ModelEffectSearch out;
  const auto run = [&](double v) {
    v = spec.snapped(std::clamp(v, spec.lower, spec.upper));
    if (sampled.count(v) || out.runs >= runs) return;
    sampled.emplace(v, evaluate_fit(problem, {{&effect, {v}}}));
    ++out.runs;
  };
  if (spec.grid.empty()) {
    // The end farther from the neutral value first: with one run, the stronger effect.
    const bool upper_first = std::abs(spec.plausible_upper - effect.neutral) >= std::abs(spec.plausible_lower - effect.neutral);
    run(upper_first ? spec.plausible_upper : spec.plausible_lower);
    run(upper_first ? spec.plausible_lower : spec.plausible_upper);
  }
  for (double v : spec.grid) run(v);
  while (spec.grid.empty() && out.runs < runs) {
    const double lo = sampled.begin()->first, hi = sampled.rbegin()->first;
    double best_v = lo, best_sse = INFINITY;
    for (int k = 0; k <= 400; ++k) {
      const double v = lo + (hi - lo) * k / 400.0;
      auto right = sampled.lower_bound(v);
      if (right == sampled.end()) --right;
      const auto left = right == sampled.begin() ? right : std::prev(right);
      const double t = right->first > left->first ? (v - left->first) / (right->first - left->first) : 0.0;
      double sse = 0.0;
      for (std::size_t i = 0; i < weight.size(); ++i) {
        const double r = left->second.residual[i] + t * (right->second.residual[i] - left->second.residual[i]);
        sse += weight[i] * r * r;
      }
      if (sse < best_sse) {
        best_sse = sse;
        best_v = v;
      }
    }
    std::vector<double> values;
    double best_run = effect.neutral;
    for (const auto& [v, fit] : sampled) {
      values.push_back(v);
      if (fit.weighted_sse < sampled.at(best_run).weighted_sse) best_run = v;
    }
    const std::optional<double> next = next_model_value(values, best_v, best_run);
    if (!next || sampled.count(spec.snapped(*next))) break;
    run(*next);
  }
  const EffectFit* best = nullptr;
  for (const auto& [v, fit] : sampled) {
    out.samples.emplace_back(v, fit.weighted_sse);
    if (!best || fit.weighted_sse < best->weighted_sse) best = &fit;
  }
  out.fit = *best;
  return out;
}

}  // namespace dtwire::gap
