#include "dtwire/gap/effect_fit.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <optional>

#include "dtwire/lsq/least_squares.hpp"

namespace dtwire::gap {
namespace {

// A least-squares problem on a flat parameter vector: `residuals` gives sqrt(w) r for it.
struct FlatObjective {
  std::vector<ParameterSpec> specs;
  std::vector<std::optional<double>> held;  // per spec: the value the fit holds it at, if any
  std::size_t count = 0;
  std::function<std::vector<double>(const std::vector<double>&)> residuals;
  double sse(const std::vector<double>& flat) const {
    double s = 0.0;
    for (double r : residuals(flat)) s += r * r;
    return s;
  }
};

// The engine's problem on the continuous parameters, the grid ones and those the objective
// holds at their values in `held` (a start's or a grid trial's).
struct ContinuousProblem {
  const FlatObjective& objective;
  std::vector<double> held;
  std::vector<std::size_t> free;
  lsq::Problem problem;

  ContinuousProblem(const FlatObjective& o, std::vector<double> held_values) : objective(o), held(std::move(held_values)) {
    for (std::size_t j = 0; j < objective.specs.size(); ++j)
      if (objective.specs[j].grid.empty() && !objective.held[j]) free.push_back(j);
    problem.parameter_count = free.size();
    problem.residual_count = objective.count;
    problem.difference_step = 1e-4;  // curves are piecewise linear: a step above the kinks' scale
    for (std::size_t j : free) {
      problem.lower.push_back(objective.specs[j].to_scaled(objective.specs[j].lower));
      problem.upper.push_back(objective.specs[j].to_scaled(objective.specs[j].upper));
    }
    problem.residuals = [this](const std::vector<double>& x, std::vector<double>& r) {
      std::vector<double> flat = held;  // unclamped: the engine keeps x within the bounds
      for (std::size_t j = 0; j < free.size(); ++j)
        flat[free[j]] = objective.specs[free[j]].plausible_lower + x[j] * objective.specs[free[j]].width();
      r = objective.residuals(flat);
    };
  }
  std::vector<double> x_of(const std::vector<double>& flat) const {
    std::vector<double> x;
    for (std::size_t j : free) {
      const ParameterSpec& s = objective.specs[j];
      x.push_back(s.to_scaled(std::clamp(flat[j], s.lower, s.upper)));
    }
    return x;
  }
  std::vector<double> flat_of(const std::vector<double>& x) const {
    std::vector<double> flat = held;
    for (std::size_t j = 0; j < free.size(); ++j) flat[free[j]] = objective.specs[free[j]].from_scaled(x[j]);
    return flat;
  }
};

lsq::Options solver_options() {
  lsq::Options options;
  options.max_iterations = 60;
  options.function_tolerance = 1e-9;
  options.parameter_tolerance = 1e-9;
  options.block_per_residual = false;
  return options;
}

// The engine's multi-start solve of the continuous parameters from starts that share their
// grid values; the best start's answer as a flat vector (the first start's if every one fails).
std::vector<double> solve_continuous(const FlatObjective& objective, const std::vector<std::vector<double>>& starts) {
  const ContinuousProblem continuous(objective, starts.front());
  if (continuous.free.empty()) return starts.front();
  std::vector<std::vector<double>> points;
  for (const auto& start : starts) points.push_back(continuous.x_of(start));
  const lsq::Summary summary = lsq::solve(continuous.problem, solver_options(), lsq::starts_at(points));
  return summary.best ? continuous.flat_of(summary.x) : starts.front();
}

// Each grid value of each grid parameter in turn, the continuous parameters refitted for it.
std::vector<double> search_grid(const FlatObjective& objective, std::vector<double> flat) {
  for (std::size_t j = 0; j < objective.specs.size(); ++j) {
    if (objective.specs[j].grid.empty() || objective.held[j]) continue;
    double best = objective.sse(flat);
    std::vector<double> best_flat = flat;
    for (double v : objective.specs[j].grid) {
      std::vector<double> trial = flat;
      trial[j] = v;
      trial = solve_continuous(objective, {trial});
      const double sse = objective.sse(trial);
      if (sse < best) {
        best = sse;
        best_flat = trial;
      }
    }
    flat = best_flat;
  }
  return flat;
}

// The starts given, then the plausible centre, the basic forms, the effects switched off (`neutral`) and random
// plausible values, so the fit can always fall back to the bare simulation; starts with the
// same grid values are one multi-start solve. The best answer is refined on the grid. A held
// parameter keeps its value in every start.
std::vector<double> minimise(const FlatObjective& objective, std::vector<std::vector<double>> starts,
                             const std::vector<double>& neutral, std::size_t random_starts,
                             std::mt19937& rng) {
  std::vector<double> centre;
  for (const ParameterSpec& s : objective.specs)
    centre.push_back(s.grid.empty() ? 0.5 * (s.plausible_lower + s.plausible_upper) : 0.0);
  starts.push_back(centre);
  // The effects' basic forms (every shape parameter at its basic value, e.g. a rate that differs
  // from the start): the form most laboratory records show, which the centre of a shape
  // parameter's range (a rate changed half-way) may not reach.
  std::vector<double> basic = centre;
  for (std::size_t j = 0; j < objective.specs.size(); ++j)
    if (objective.specs[j].shape_neutral && objective.specs[j].grid.empty()) basic[j] = *objective.specs[j].shape_neutral;
  if (basic != centre) starts.push_back(basic);
  for (std::size_t j = 0; j < objective.specs.size(); ++j)
    for (double value : objective.specs[j].scan_starts) {
      std::vector<double> scan = basic;
      scan[j] = value;
      starts.push_back(scan);
    }
  starts.push_back(neutral);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (std::size_t k = 0; k < random_starts; ++k) {
    std::vector<double> flat;
    for (const ParameterSpec& s : objective.specs)
      flat.push_back(s.grid.empty() ? s.plausible_lower + unit(rng) * s.width() : 0.0);
    starts.push_back(flat);
  }
  const auto hold = [&](std::vector<double>& flat) {
    for (std::size_t j = 0; j < flat.size() && j < objective.held.size(); ++j)
      if (objective.held[j]) flat[j] = *objective.held[j];
  };
  for (auto& start : starts) hold(start);
  std::map<std::vector<double>, std::vector<std::vector<double>>> by_grid_values;
  std::vector<std::vector<double>> order;  // grid-value sets in the order first met
  for (const auto& start : starts) {
    if (start.size() != objective.specs.size()) continue;
    std::vector<double> grid_values;
    for (std::size_t j = 0; j < start.size(); ++j)
      if (!objective.specs[j].grid.empty()) grid_values.push_back(start[j]);
    if (!by_grid_values.count(grid_values)) order.push_back(grid_values);
    by_grid_values[grid_values].push_back(start);
  }
  std::vector<double> best = neutral;
  hold(best);
  double best_sse = INFINITY;
  for (const auto& grid_values : order) {
    const std::vector<double> flat = solve_continuous(objective, by_grid_values[grid_values]);
    const double sse = objective.sse(flat);
    if (sse < best_sse) {
      best_sse = sse;
      best = flat;
    }
  }
  return search_grid(objective, best);
}

std::vector<double> weighted(const FitProblem& problem, const EffectFit& fit) {
  std::vector<double> r(fit.residual.size());
  std::size_t k = 0;
  for (const Comparison& c : problem.labs)
    for (std::size_t i = 0; i < c.lab.size() && k < r.size(); ++i, ++k)
      r[k] = std::sqrt(c.weight[i]) * fit.residual[k];
  return r;
}

std::size_t residual_count(const FitProblem& p) {
  std::size_t n = 0;
  for (const Comparison& c : p.labs) n += c.lab.size();
  return n;
}

// Flat layout of a joint fit: effect k, block b occupies specs [offset[k][b], +size of k).
struct JointLayout {
  std::vector<std::vector<std::size_t>> offset;
  std::vector<ParameterSpec> specs;
};

JointLayout joint_layout(const std::vector<JointEffect>& effects, const CurveScale& scale) {
  JointLayout l;
  for (const JointEffect& e : effects) {
    const auto specs = e.effect->parameters(scale);
    l.offset.emplace_back();
    for (int b = 0; b < e.blocks; ++b) {
      l.offset.back().push_back(l.specs.size());
      l.specs.insert(l.specs.end(), specs.begin(), specs.end());
    }
  }
  return l;
}

std::vector<double> block_of(const JointLayout& l, const std::vector<JointEffect>& effects,
                             const std::vector<double>& flat, std::size_t k, int b) {
  const std::size_t size = effects[k].effect->parameters(CurveScale{}).size();
  const auto first = flat.begin() + static_cast<std::ptrdiff_t>(l.offset[k][static_cast<std::size_t>(b)]);
  return std::vector<double>(first, first + static_cast<std::ptrdiff_t>(size));
}

std::vector<std::vector<AppliedEffect>> per_problem(const JointLayout& l,
                                                    const std::vector<JointEffect>& effects,
                                                    const std::vector<double>& flat,
                                                    std::size_t problems) {
  std::vector<std::vector<AppliedEffect>> out(problems);
  for (std::size_t k = 0; k < effects.size(); ++k)
    for (std::size_t p = 0; p < problems; ++p)
      if (effects[k].block_of[p] >= 0)
        out[p].push_back({effects[k].effect, block_of(l, effects, flat, k, effects[k].block_of[p])});
  return out;
}

}  // namespace

std::vector<ForceCurve> record_models(const FitProblem& problem, const std::vector<AppliedEffect>& effects) {
  const bool clocked = std::any_of(effects.begin(), effects.end(), [](const AppliedEffect& a) { return a.effect->runs_to_fracture; });
  if (!clocked) return std::vector<ForceCurve>(problem.labs.size(), augment(problem.sim, effects, problem.scale, problem.runner));
  std::vector<AppliedEffect> model_effects, curve_effects;
  for (const AppliedEffect& a : effects) (a.effect->needs_model ? model_effects : curve_effects).push_back(a);
  // The model run once; the curve-mode effects per clock on top of it.
  const ForceCurve run = model_effects.empty() ? problem.sim : augment(problem.sim, model_effects, problem.scale, problem.runner);
  std::map<double, ForceCurve> by_clock;
  std::vector<ForceCurve> out;
  for (const Comparison& c : problem.labs) {
    auto it = by_clock.find(c.damage_clock);
    if (it == by_clock.end()) {
      CurveScale scale = problem.scale;
      scale.damage_clock = c.damage_clock;
      it = by_clock.emplace(c.damage_clock, apply_effects(run, curve_effects, scale)).first;
    }
    out.push_back(it->second);
  }
  return out;
}

EffectFit evaluate_fit(const FitProblem& problem, std::vector<AppliedEffect> effects) {
  EffectFit fit;
  for (const AppliedEffect& a : effects) fit.parameter_count += static_cast<int>(a.params.size());
  const auto forces = forces_with_scatter(record_models(problem, effects), problem.labs, problem.scatter);
  for (std::size_t k = 0; k < problem.labs.size(); ++k) {
    const Comparison& c = problem.labs[k];
    const auto r = normalised_residual(forces[k], c);
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
                      std::size_t random_starts, std::mt19937& rng, const std::vector<HeldParameter>& held) {
  std::vector<JointEffect> joint;
  for (const EffectSpec* e : effects) joint.push_back({e, {0}, 1});
  std::vector<std::vector<std::vector<std::vector<double>>>> joint_starts;
  for (const auto& start : starts) {
    joint_starts.emplace_back();
    for (const auto& p : start) joint_starts.back().push_back({p});
  }
  const JointFit fit = fit_joint({problem}, joint, joint_starts, random_starts, rng, held);
  EffectFit out = evaluate_fit(problem, fit.per_problem.front());
  out.parameter_count = fit.parameter_count;
  return out;
}

JointFit evaluate_joint(const std::vector<FitProblem>& problems,
                        std::vector<std::vector<AppliedEffect>> per_problem) {
  JointFit out;
  for (std::size_t p = 0; p < problems.size(); ++p) {
    const EffectFit fit = evaluate_fit(problems[p], per_problem[p]);
    out.weighted_sse += fit.weighted_sse;
    out.residual.insert(out.residual.end(), fit.residual.begin(), fit.residual.end());
  }
  out.per_problem = std::move(per_problem);
  return out;
}

JointFit fit_joint(const std::vector<FitProblem>& problems, const std::vector<JointEffect>& effects,
                   const std::vector<std::vector<std::vector<std::vector<double>>>>& starts,
                   std::size_t random_starts, std::mt19937& rng, const std::vector<HeldParameter>& held) {
  const CurveScale& scale = problems.front().scale;  // parameter layout only (sizes, grids)
  const JointLayout layout = joint_layout(effects, scale);
  FlatObjective objective;
  for (const FitProblem& p : problems) objective.count += residual_count(p);
  // Bounds and plausible ranges scale with the simulated curve: each block takes them from the
  // first problem it applies to.
  objective.specs = layout.specs;
  for (std::size_t k = 0; k < effects.size(); ++k)
    for (int b = 0; b < effects[k].blocks; ++b)
      for (std::size_t p = 0; p < problems.size(); ++p)
        if (effects[k].block_of[p] == b) {
          const auto specs = effects[k].effect->parameters(problems[p].scale);
          std::copy(specs.begin(), specs.end(),
                    objective.specs.begin() + static_cast<std::ptrdiff_t>(layout.offset[k][static_cast<std::size_t>(b)]));
          break;
        }
  objective.held.resize(objective.specs.size());
  for (const HeldParameter& h : held)
    for (std::size_t b = 0; b < layout.offset.at(h.effect).size(); ++b)
      if (h.block < 0 || static_cast<std::size_t>(h.block) == b)
        objective.held.at(layout.offset[h.effect][b] + h.parameter) = h.value;
  objective.residuals = [&](const std::vector<double>& flat) {
    const auto applied = per_problem(layout, effects, flat, problems.size());
    std::vector<double> r;
    for (std::size_t p = 0; p < problems.size(); ++p) {
      const auto w = weighted(problems[p], evaluate_fit(problems[p], applied[p]));
      r.insert(r.end(), w.begin(), w.end());
    }
    return r;
  };
  std::vector<std::vector<double>> flat_starts;
  for (const auto& start : starts) {
    std::vector<double> flat;
    for (const auto& blocks : start)
      for (const auto& p : blocks) flat.insert(flat.end(), p.begin(), p.end());
    if (flat.size() == objective.specs.size()) flat_starts.push_back(flat);
  }
  std::vector<double> neutral;
  for (const ParameterSpec& s : objective.specs)
    neutral.push_back(s.grid.empty() ? 0.5 * (s.plausible_lower + s.plausible_upper) : 0.0);
  for (std::size_t k = 0; k < effects.size(); ++k)
    for (std::size_t offset : layout.offset[k]) neutral[offset + effects[k].effect->magnitude] = effects[k].effect->neutral;
  const std::vector<double> best = minimise(objective, flat_starts, neutral, random_starts, rng);
  JointFit out = evaluate_joint(problems, per_problem(layout, effects, best, problems.size()));
  out.parameter_count = static_cast<int>(
      std::count_if(objective.held.begin(), objective.held.end(), [](const std::optional<double>& h) { return !h; }));
  for (std::size_t k = 0; k < effects.size(); ++k) {
    out.blocks.emplace_back();
    for (int b = 0; b < effects[k].blocks; ++b) out.blocks.back().push_back(block_of(layout, effects, best, k, b));
  }
  return out;
}

}  // namespace dtwire::gap
