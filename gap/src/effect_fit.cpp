#include "dtwire/gap/effect_fit.hpp"

#include <ceres/ceres.h>

#include <algorithm>
#include <cmath>

namespace dtwire::gap {
namespace {

struct Layout {
  std::vector<const EffectSpec*> effects;
  std::vector<ParameterSpec> specs;     // flattened
  std::vector<std::size_t> offset;      // first flat index of each effect
};

Layout make_layout(const std::vector<const EffectSpec*>& effects, const CurveScale& scale) {
  Layout l;
  l.effects = effects;
  for (const EffectSpec* e : effects) {
    l.offset.push_back(l.specs.size());
    for (const ParameterSpec& s : e->parameters(scale)) l.specs.push_back(s);
  }
  return l;
}

std::vector<AppliedEffect> unflatten(const Layout& l, const std::vector<double>& flat) {
  std::vector<AppliedEffect> out;
  for (std::size_t k = 0; k < l.effects.size(); ++k) {
    const std::size_t end = k + 1 < l.effects.size() ? l.offset[k + 1] : flat.size();
    out.push_back({l.effects[k], std::vector<double>(flat.begin() + static_cast<std::ptrdiff_t>(l.offset[k]),
                                                     flat.begin() + static_cast<std::ptrdiff_t>(end))});
  }
  return out;
}

// Scaled coordinates: x = (p - plausible_lower) / plausible width, so every unknown is O(1).
double width_of(const ParameterSpec& s) {
  const double w = s.plausible_upper - s.plausible_lower;
  return w > 0 ? w : std::max(s.upper - s.lower, 1e-12);
}

struct Residuals {
  const FitProblem* problem;
  const Layout* layout;
  std::vector<double> fixed;  // full flat vector; free entries overwritten
  std::vector<std::size_t> free;
  std::size_t count;

  bool operator()(double const* const* x, double* r) const {
    std::vector<double> flat = fixed;
    for (std::size_t j = 0; j < free.size(); ++j) {
      const ParameterSpec& s = layout->specs[free[j]];
      flat[free[j]] = s.plausible_lower + x[0][j] * width_of(s);
    }
    const EffectFit fit = evaluate_fit(*problem, unflatten(*layout, flat));
    if (fit.residual.size() != count) return false;
    std::size_t k = 0;
    for (const Comparison& c : problem->labs)
      for (std::size_t i = 0; i < c.lab.size(); ++i, ++k)
        r[k] = std::sqrt(c.weight[i]) * fit.residual[k];
    return true;
  }
};

std::size_t residual_count(const FitProblem& p) {
  std::size_t n = 0;
  for (const Comparison& c : p.labs) n += c.lab.size();
  return n;
}

// Ceres on the continuous parameters, grid ones held at their values in `flat`.
std::vector<double> solve_continuous(const FitProblem& problem, const Layout& layout,
                                     std::vector<double> flat) {
  auto functor = std::make_unique<Residuals>();
  functor->problem = &problem;
  functor->layout = &layout;
  functor->fixed = flat;
  functor->count = residual_count(problem);
  for (std::size_t j = 0; j < layout.specs.size(); ++j)
    if (layout.specs[j].grid.empty()) functor->free.push_back(j);
  const std::size_t m = functor->free.size();
  if (m == 0) return flat;
  std::vector<double> x(m);
  for (std::size_t j = 0; j < m; ++j) {
    const ParameterSpec& s = layout.specs[functor->free[j]];
    x[j] = (std::clamp(flat[functor->free[j]], s.lower, s.upper) - s.plausible_lower) / width_of(s);
  }
  const std::vector<std::size_t> free = functor->free;
  const std::size_t count = functor->count;
  ceres::NumericDiffOptions diff;
  diff.relative_step_size = 1e-4;  // curves are piecewise linear: a step above the kinks' scale
  auto* cost = new ceres::DynamicNumericDiffCostFunction<Residuals, ceres::CENTRAL>(
      functor.release(), ceres::TAKE_OWNERSHIP, diff);
  cost->AddParameterBlock(static_cast<int>(m));
  cost->SetNumResiduals(static_cast<int>(count));
  ceres::Problem ceres_problem;
  ceres_problem.AddResidualBlock(cost, nullptr, x.data());
  for (std::size_t j = 0; j < m; ++j) {
    const ParameterSpec& s = layout.specs[free[j]];
    ceres_problem.SetParameterLowerBound(x.data(), static_cast<int>(j),
                                         (s.lower - s.plausible_lower) / width_of(s));
    ceres_problem.SetParameterUpperBound(x.data(), static_cast<int>(j),
                                         (s.upper - s.plausible_lower) / width_of(s));
  }
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::DENSE_QR;
  options.max_num_iterations = 60;
  options.function_tolerance = 1e-9;
  options.parameter_tolerance = 1e-9;
  options.logging_type = ceres::SILENT;
  options.minimizer_progress_to_stdout = false;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &ceres_problem, &summary);
  for (std::size_t j = 0; j < m; ++j) {
    const ParameterSpec& s = layout.specs[free[j]];
    flat[free[j]] = std::clamp(s.plausible_lower + x[j] * width_of(s), s.lower, s.upper);
  }
  return flat;
}

double sse_of(const FitProblem& problem, const Layout& layout, const std::vector<double>& flat) {
  return evaluate_fit(problem, unflatten(layout, flat)).weighted_sse;
}

// Each grid value of each grid parameter in turn, the continuous parameters refitted for it.
std::vector<double> search_grid(const FitProblem& problem, const Layout& layout,
                                std::vector<double> flat) {
  for (std::size_t j = 0; j < layout.specs.size(); ++j) {
    if (layout.specs[j].grid.empty()) continue;
    double best = sse_of(problem, layout, flat);
    std::vector<double> best_flat = flat;
    for (double v : layout.specs[j].grid) {
      std::vector<double> trial = flat;
      trial[j] = v;
      trial = solve_continuous(problem, layout, trial);
      const double sse = sse_of(problem, layout, trial);
      if (sse < best) {
        best = sse;
        best_flat = trial;
      }
    }
    flat = best_flat;
  }
  return flat;
}

}  // namespace

EffectFit evaluate_fit(const FitProblem& problem, std::vector<AppliedEffect> effects) {
  EffectFit fit;
  for (const AppliedEffect& a : effects) fit.parameter_count += static_cast<int>(a.params.size());
  const ForceCurve model = augment(problem.sim, effects, problem.scale, problem.runner);
  for (const Comparison& c : problem.labs) {
    const auto r = normalised_residual(model_forces_at_lab(model, c), c);
    for (std::size_t i = 0; i < r.size(); ++i) {
      fit.weighted_sse += c.weight[i] * r[i] * r[i];
      fit.residual.push_back(r[i]);
    }
  }
  fit.effects = std::move(effects);
  return fit;
}

EffectFit fit_effects(const FitProblem& problem, const std::vector<const EffectSpec*>& effects,
                      std::vector<std::vector<std::vector<double>>> starts,
                      std::size_t random_starts, std::mt19937& rng) {
  const Layout layout = make_layout(effects, problem.scale);
  std::vector<std::vector<double>> flat_starts;
  for (const auto& start : starts) {
    std::vector<double> flat;
    for (const auto& p : start) flat.insert(flat.end(), p.begin(), p.end());
    if (flat.size() == layout.specs.size()) flat_starts.push_back(flat);
  }
  std::vector<double> centre;
  for (const ParameterSpec& s : layout.specs)
    centre.push_back(s.grid.empty() ? 0.5 * (s.plausible_lower + s.plausible_upper) : 0.0);
  flat_starts.push_back(centre);
  // The effect switched off: the fit can always fall back to the bare simulation.
  std::vector<double> neutral = centre;
  for (std::size_t k = 0; k < layout.effects.size(); ++k)
    neutral[layout.offset[k] + layout.effects[k]->magnitude] = layout.effects[k]->neutral;
  flat_starts.push_back(neutral);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (std::size_t k = 0; k < random_starts; ++k) {
    std::vector<double> flat;
    for (const ParameterSpec& s : layout.specs)
      flat.push_back(s.grid.empty() ? s.plausible_lower + unit(rng) * width_of(s) : 0.0);
    flat_starts.push_back(flat);
  }
  std::vector<double> best;
  double best_sse = INFINITY;
  for (const auto& start : flat_starts) {
    const std::vector<double> flat = solve_continuous(problem, layout, start);
    const double sse = sse_of(problem, layout, flat);
    if (sse < best_sse) {
      best_sse = sse;
      best = flat;
    }
  }
  best = search_grid(problem, layout, best);
  return evaluate_fit(problem, unflatten(layout, best));
}

}  // namespace dtwire::gap
