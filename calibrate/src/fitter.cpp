#include "dtwire/calibrate/fitter.hpp"

#include <chrono>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <limits>
#include <ostream>
#include <sstream>

#include <Eigen/Eigenvalues>
#include <nlohmann/json.hpp>

#include "dtwire/calibrate/sampling.hpp"
#include "dtwire/core/atomic_file.hpp"
#include "dtwire/core/csv.hpp"
#include "dtwire/core/error.hpp"
#include "dtwire/core/provenance.hpp"
#include "dtwire/lsq/least_squares.hpp"

namespace dtwire::calibrate {
namespace {

using Clock = std::chrono::steady_clock;

// The fit as the engine sees it: z = value / scale, the evaluator's residuals and Jacobian in
// z, one residual group (own variance) per curve channel, its peak rows with it.
lsq::Problem engine_problem(ProblemEvaluator& evaluator) {
  lsq::Problem problem;
  problem.parameter_count = evaluator.parameters().size();
  problem.residual_count = evaluator.residual_count();
  for (const auto& p : evaluator.parameters()) {
    problem.lower.push_back(p.to_coordinate(p.lower));
    problem.upper.push_back(p.to_coordinate(p.upper));
  }
  problem.residuals = [&evaluator](const std::vector<double>& z, std::vector<double>& r) {
    r = evaluator.residuals(z);
  };
  problem.residuals_and_jacobian = [&evaluator](const std::vector<double>& z, std::vector<double>& r,
                                                std::vector<double>& J) { evaluator.residuals_and_jacobian(z, r, J); };
  for (const auto& experiment : evaluator.experiments())
    for (std::size_t size : residual_groups(experiment)) problem.residual_groups.push_back(size);
  return problem;
}

lsq::Options engine_options(const FitOptions& options) {
  lsq::Options o;
  o.max_iterations = options.max_iterations;
  o.loss = options.loss == LossKind::Huber    ? lsq::Loss::Huber
           : options.loss == LossKind::Cauchy ? lsq::Loss::Cauchy
                                              : lsq::Loss::Squared;
  o.loss_scale = options.loss_scale;
  o.function_tolerance = options.function_tolerance;
  o.parameter_tolerance = options.parameter_tolerance;
  o.gradient_tolerance = options.gradient_tolerance;
  // Jacobi scaling comes from a solve's first Jacobian only: a resumed solve would scale
  // differently. The parameters are already scaled (z = value / scale).
  o.jacobi_scaling = false;
  o.initial_trust_region_radius = 1e4;
  o.parallel_starts = options.parallel_starts;
  for (const StartScreening& stage : options.screening) o.screening.push_back({stage.iterations, stage.cost_ratio});
  o.value_only_line_search = options.value_only_line_search;
  return o;
}

std::string join(const std::vector<double>& v) {
  std::ostringstream out;
  out << std::setprecision(6);
  for (std::size_t i = 0; i < v.size(); ++i) out << (i ? ", " : "") << v[i];
  return out.str();
}

// ---- checkpoint ------------------------------------------------------------------------

nlohmann::json to_json(const lsq::Start& s) {
  return {{"start_z", s.start}, {"z", s.x},         {"radius", s.radius},
          {"iterations", s.iterations}, {"cost", s.cost}, {"state", lsq::to_string(s.state)},
          {"message", s.message}, {"screened", s.screened}};
}

lsq::Start from_json(const nlohmann::json& j) {
  lsq::Start s;
  s.start = j.at("start_z").get<std::vector<double>>();
  s.x = j.at("z").get<std::vector<double>>();
  s.radius = j.at("radius").get<double>();
  s.iterations = j.at("iterations").get<int>();
  s.cost = j.at("cost").get<double>();
  s.state = lsq::start_state_from_string(j.at("state").get<std::string>());
  s.message = j.at("message").get<std::string>();
  s.screened = j.value("screened", 0);  // checkpoints written before the screening: none passed
  return s;
}

void write_checkpoint(const std::filesystem::path& path, const std::string& identity,
                      const std::vector<lsq::Start>& starts) {
  if (path.empty()) return;
  nlohmann::json j;
  j["format"] = "dtwire-fit-checkpoint-1";
  j["fit_identity"] = identity;
  for (const auto& s : starts) j["starts"].push_back(to_json(s));
  // nlohmann writes doubles with 17 significant digits: they read back exactly.
  write_file_atomically(path, [&](std::ostream& out) { out << j.dump(1) << "\n"; });
}

std::optional<std::vector<lsq::Start>> read_checkpoint(const std::filesystem::path& path,
                                                       const std::string& identity) {
  if (path.empty() || !std::filesystem::exists(path)) return std::nullopt;
  std::ifstream in(path);
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& error) {
    throw InputError(path.string(), std::string("unreadable checkpoint: ") + error.what());
  }
  if (j.value("fit_identity", "") != identity)
    throw InputError(path.string(),
                     "checkpoint belongs to a different fit definition; remove it or drop --resume");
  std::vector<lsq::Start> starts;
  try {
    for (const auto& s : j.at("starts")) starts.push_back(from_json(s));
  } catch (const std::exception& error) {
    throw InputError(path.string(), std::string("unreadable checkpoint: ") + error.what());
  }
  return starts;
}

// The pseudo-inverse of a rank-deficient J^T J, or round-off, gives a covariance that is only
// semi-definite: some combination of the parameters then shows a variance of zero. Judged on the
// correlation matrix: the SI covariance mixes units (EA in N against ratios) by 1e16 and more.
std::string covariance_definiteness(const Eigen::MatrixXd& correlation, const std::vector<double>& sigma) {
  for (double s : sigma)
    if (!(s > 0.0) || !std::isfinite(s)) return "not positive definite (a parameter with a variance of zero or not finite)";
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(correlation, Eigen::EigenvaluesOnly);
  const Eigen::VectorXd& eigen = solver.eigenvalues();  // ascending
  if (eigen.size() == 0 || eigen(0) > 1e-12 * eigen(eigen.size() - 1)) return "positive definite";
  std::ostringstream os;
  os << "not positive definite (correlation eigenvalues " << eigen(0) << " to " << eigen(eigen.size() - 1) << ")";
  return os.str();
}

}  // namespace

std::string fit_identity(const ProblemEvaluator& evaluator, const FitOptions& options) {
  std::ostringstream text;
  text << std::setprecision(17);
  for (const auto& e : evaluator.experiments()) {
    text << "experiment " << e.name << " weight " << e.weight << " abscissa " << e.abscissa << " "
         << static_cast<int>(e.kind) << " tol " << e.branch_tolerance << "\n"
         << e.simulator->identity() << "\n" << format_csv(e.target);
    for (const auto& c : e.channels) text << c.quantity << " " << c.weight << " " << c.scale << "\n";
    for (const auto& p : e.peaks) text << "peak " << p.quantity << " " << p.weight << " " << p.scale << "\n";
  }
  for (const auto& p : evaluator.parameters())
    text << "parameter " << p.name << " " << p.initial << " " << p.lower << " " << p.upper << " "
         << p.effective_scale() << (p.logarithmic ? " log" : "")
         << (p.offset_from.empty() ? "" : " offset_from " + p.offset_from) << "\n";
  text << "options " << options.max_iterations << " " << static_cast<int>(options.loss) << " "
       << options.loss_scale << " " << options.starts << " " << options.seed << " "
       << options.function_tolerance << " " << options.parameter_tolerance << " "
       << options.gradient_tolerance << "\n";
  // Only a screened fit's identity names its stages: checkpoints of unscreened fits stay valid.
  for (const StartScreening& stage : options.screening)
    text << "screening " << stage.iterations << " " << stage.cost_ratio << "\n";
  // Likewise only the non-default line search is named (it changes the steps a start takes).
  if (options.value_only_line_search) text << "line_search values\n";
  if (options.polish_relative_step > 0.0) text << "polish " << options.polish_relative_step << "\n";
  return sha256_text(text.str());
}

FitResult run_fit(ProblemEvaluator& evaluator, const FitOptions& options) {
  const auto started = Clock::now();
  const auto& parameters = evaluator.parameters();
  const std::size_t n = parameters.size(), m = evaluator.residual_count();
  if (m <= n) throw InputError("fit", "need more residuals (" + std::to_string(m) +
                                          ") than parameters (" + std::to_string(n) + ")");
  if (options.starts < 1) throw std::invalid_argument("starts must be >= 1");
  const std::string identity = fit_identity(evaluator, options);

  // Start points: the initial values, then a Latin hypercube in the bounds.
  std::vector<lsq::Start> starts;
  if (options.resume) {
    if (auto restored = read_checkpoint(options.checkpoint, identity)) starts = *restored;
  }
  if (starts.empty()) {
    std::vector<double> initial, lower, upper;
    std::vector<bool> logarithmic;
    for (const auto& p : parameters) {
      initial.push_back(p.initial);
      lower.push_back(p.lower);
      upper.push_back(p.upper);
      logarithmic.push_back(p.logarithmic);
    }
    std::vector<std::vector<double>> points{evaluator.to_scaled(initial)};
    for (const auto& point : latin_hypercube(static_cast<std::size_t>(options.starts - 1), lower, upper,
                                             logarithmic, options.seed))
      points.push_back(evaluator.to_scaled(point));
    starts = lsq::starts_at(points);
  }

  const lsq::Problem problem = engine_problem(evaluator);
  lsq::Options engine = engine_options(options);
  int iterations_this_run = 0;
  engine.after_iteration = [&](const lsq::Iteration& it, const std::vector<lsq::Start>& states) {
    write_checkpoint(options.checkpoint, identity, states);
    if (options.progress) {
      const auto stats = evaluator.statistics();
      const double elapsed = std::chrono::duration<double>(Clock::now() - started).count();
      *options.progress << "fit start " << it.start + 1 << "/" << states.size() << " iteration "
                        << it.iteration << ": cost " << std::setprecision(6) << it.cost
                        << (it.step_accepted ? "" : " (step rejected)") << ", |gradient| "
                        << it.gradient_max_norm << ", runs " << stats.simulations << " (cached "
                        << stats.cache_hits << ", failed " << stats.failures << "), "
                        << std::setprecision(3) << elapsed << " s\n"
                        << std::flush;
    }
    ++iterations_this_run;
    return !((options.stop_after_iterations >= 0 && iterations_this_run > options.stop_after_iterations) ||
             (options.stop_requested && options.stop_requested->load()));
  };
  engine.after_start = [&](std::size_t s, const std::vector<lsq::Start>& states) {
    if (options.progress)
      *options.progress << "fit start " << s + 1 << "/" << states.size() << " "
                        << lsq::to_string(states[s].state) << ": " << states[s].message << "\n";
    write_checkpoint(options.checkpoint, identity, states);
  };
  const lsq::Summary summary = lsq::solve(problem, engine, starts);
  write_checkpoint(options.checkpoint, identity, summary.starts);

  FitResult result;
  result.parameters = parameters;
  result.residual_count = m;
  for (const auto& st : summary.starts)
    result.starts.push_back({evaluator.from_scaled(st.start),
                             st.x.empty() ? std::vector<double>{} : evaluator.from_scaled(st.x),
                             st.cost, st.iterations, lsq::to_string(st.state), st.message});
  result.statistics = evaluator.statistics();
  if (!summary.completed) {
    result.completed = false;
    result.wall_seconds = std::chrono::duration<double>(Clock::now() - started).count();
    return result;
  }
  if (!summary.best) {
    std::string messages;
    for (const auto& st : summary.starts) messages += " [" + st.message + "]";
    throw ComputationError("fit failed from every start:" + messages);
  }
  result.best_start = *summary.best;
  std::vector<double> best_x = summary.x;
  double best_cost = summary.cost;
  if (options.polish_relative_step > 0.0) {
    PolishSummary& polish = result.polish;
    polish.run = true;
    polish.relative_step = options.polish_relative_step;
    polish.cost_before = summary.cost;
    const double fine_step = evaluator.relative_step();
    evaluator.set_relative_step(options.polish_relative_step);
    lsq::Options coarse = engine;
    coarse.screening.clear();
    coarse.parallel_starts = 1;
    coarse.after_start = nullptr;
    // The checkpoint keeps the multi-start's ends; a resumed fit polishes them again.
    coarse.after_iteration = [&](const lsq::Iteration& it, const std::vector<lsq::Start>&) {
      if (options.progress)
        *options.progress << "fit polish (relative step " << options.polish_relative_step << ") iteration "
                          << it.iteration << ": cost " << std::setprecision(6) << it.cost
                          << (it.step_accepted ? "" : " (step rejected)") << "\n" << std::flush;
      ++iterations_this_run;
      return !((options.stop_after_iterations >= 0 && iterations_this_run > options.stop_after_iterations) ||
               (options.stop_requested && options.stop_requested->load()));
    };
    const lsq::Summary polished = lsq::solve(problem, coarse, lsq::starts_at({summary.x}));
    evaluator.set_relative_step(fine_step);
    result.statistics = evaluator.statistics();
    if (!polished.completed) {
      result.completed = false;
      result.wall_seconds = std::chrono::duration<double>(Clock::now() - started).count();
      return result;
    }
    const lsq::Start& end = polished.starts.front();
    polish.iterations = end.iterations;
    polish.message = end.message;
    polish.cost_after = polished.best ? polished.cost : std::numeric_limits<double>::quiet_NaN();
    polish.taken = polished.best && polished.cost < summary.cost;
    if (polish.taken) {
      best_x = polished.x;
      best_cost = polished.cost;
    }
    if (options.progress)
      *options.progress << "fit polish: cost " << summary.cost << " -> " << polish.cost_after << " in "
                        << polish.iterations << " iterations, " << (polish.taken ? "taken" : "not taken (no lower cost)")
                        << ": " << polish.message << "\n";
  }
  result.completed = true;
  result.fitted_values = evaluator.from_scaled(best_x);
  result.values = resolve_offsets(parameters, result.fitted_values);
  result.cost = best_cost;
  result.residual_variance = 2.0 * result.cost / static_cast<double>(m - n);

  // Covariance in z (the engine's grouped sandwich: each curve channel its own variance,
  // since curves are weighted by the user, not necessarily by their noise), then of the fitted
  // values in SI, then of the parameters' own values (offsets resolved: A Cov A^T).
  const lsq::Uncertainty u = lsq::uncertainty_at(problem, engine, best_x);
  if (u.covariance) {
    Eigen::MatrixXd fitted_cov(n, n), corr(n, n);
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = 0; j < n; ++j)
        fitted_cov(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) =
            (*u.covariance)(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) *
            parameters[i].derivative(best_x[i]) * parameters[j].derivative(best_x[j]);
    for (std::size_t i = 0; i < n; ++i)
      result.fitted_sigma.push_back(
          std::sqrt(std::max(fitted_cov(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(i)), 0.0)));
    const Eigen::MatrixXd cov = resolve_covariance(parameters, fitted_cov);
    for (std::size_t i = 0; i < n; ++i) result.sigma.push_back(std::sqrt(std::max(cov(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(i)), 0.0)));
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = 0; j < n; ++j) {
        const double d = result.sigma[i] * result.sigma[j];
        const auto I = static_cast<Eigen::Index>(i), J = static_cast<Eigen::Index>(j);
        corr(I, J) = i == j ? 1.0 : (d > 0 ? cov(I, J) / d : 0.0);
      }
    result.covariance = cov;
    result.correlation = corr;
    result.covariance_status = covariance_definiteness(corr, result.sigma);
    if (result.covariance_status != "positive definite")
      result.warnings.push_back("covariance " + result.covariance_status + ": the sigma are not standard errors");
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = i + 1; j < n; ++j)
        if (std::abs(corr(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j))) > 0.95)
          result.warnings.push_back("parameters '" + parameters[i].name + "' and '" +
                                    parameters[j].name + "' are strongly correlated (r = " +
                                    std::to_string(corr(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j))) +
                                    "): poorly identified separately");
    for (std::size_t i = 0; i < n; ++i)
      if (result.sigma[i] > std::abs(result.values[i]))
        result.warnings.push_back("parameter '" + parameters[i].name +
                                  "' is poorly identified: sigma exceeds |value|");
  } else {
    result.covariance_status = "not computed (rank-deficient Jacobian)";
    result.warnings.push_back("covariance could not be computed (rank-deficient Jacobian)");
  }

  // The secant covariance: each parameter's own value stepped by +-tol/2 of itself (bounds and
  // failed runs make a side one-sided), for the identification's rule 3 (identifiability.hpp).
  if (u.covariance) {
    std::vector<double> steps(n);
    for (std::size_t j = 0; j < n; ++j) {
      const double own = std::abs(result.values[j]) > 0 ? std::abs(result.values[j]) : parameters[j].upper - parameters[j].lower;
      steps[j] = 0.5 * options.identification_tolerance * own / parameters[j].derivative(best_x[j]);
    }
    lsq::Problem secant = problem;
    secant.residuals_and_jacobian = [&evaluator, steps](const std::vector<double>& z, std::vector<double>& r,
                                                        std::vector<double>& J) {
      evaluator.residuals_and_secant_jacobian(z, steps, r, J);
    };
    try {
      const lsq::Uncertainty s = lsq::uncertainty_at(secant, engine, best_x);
      if (s.covariance) {
        Eigen::MatrixXd fitted_cov(n, n);
        for (std::size_t i = 0; i < n; ++i)
          for (std::size_t j = 0; j < n; ++j)
            fitted_cov(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) =
                (*s.covariance)(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) *
                parameters[i].derivative(best_x[i]) * parameters[j].derivative(best_x[j]);
        const Eigen::MatrixXd cov = resolve_covariance(parameters, fitted_cov);
        for (std::size_t i = 0; i < n; ++i)
          result.secant_sigma.push_back(std::sqrt(std::max(cov(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(i)), 0.0)));
      } else {
        result.warnings.push_back("the secant Jacobian at the identification tolerance's scale is rank-deficient: "
                                  "identification judged by the finite-difference Jacobian alone");
      }
    } catch (const ComputationError& error) {
      result.warnings.push_back(std::string("no secant Jacobian at the identification tolerance's scale (") + error.what() +
                                "): identification judged by the finite-difference Jacobian alone");
    }
  }

  // Identifiability: singular values of the Jacobian with unit-norm columns.
  for (std::size_t j : u.insensitive)
    result.warnings.push_back("parameter '" + coordinate_name(parameters[j]) + "' does not affect the residuals at the optimum");
  result.singular_values = u.singular_values;
  const auto& sv = u.singular_values;
  for (std::size_t i = 0; i < sv.size(); ++i) {
    if (sv[0] > 0 && sv[i] / sv[0] < 1e-3) {
      std::ostringstream direction;
      direction << std::setprecision(3);
      for (std::size_t j = 0; j < sv.size(); ++j)
        direction << (j ? ", " : "") << coordinate_name(parameters[j]) << " "
                  << u.singular_directions(static_cast<Eigen::Index>(j), static_cast<Eigen::Index>(i));
      result.warnings.push_back("poorly identified direction (singular value ratio " +
                                std::to_string(sv[i] / sv[0]) + "): " + direction.str());
    }
  }
  for (std::size_t i = 0; i < n; ++i) {
    const auto& p = parameters[i];
    const double tol = 1e-6 * (p.upper - p.lower);
    if (result.fitted_values[i] <= p.lower + tol || result.fitted_values[i] >= p.upper - tol)
      result.warnings.push_back("parameter '" + p.name + "' ended at a bound" +
                                (p.offset_from.empty() ? "" : " of its offset " + coordinate_name(p)) +
                                "; its sigma is not meaningful");
  }

  // Which parameters the data identify (the Jacobian's covariance, the bounds and the other
  // starts' ends); the others are named.
  std::vector<StartEnd> ends;
  for (const auto& st : result.starts) ends.push_back({st.state == "done" ? st.end : std::vector<double>{}, st.cost});
  const bool stepped_here = evaluator.last_jacobian_point() == best_x;  // uncertainty_at's Jacobian
  std::vector<double> correlation;
  if (result.correlation)
    for (Eigen::Index i = 0; i < result.correlation->rows(); ++i)
      for (Eigen::Index j = 0; j < result.correlation->cols(); ++j) correlation.push_back((*result.correlation)(i, j));
  result.identification = identify(parameters, result.fitted_values, result.sigma,
                                   stepped_here ? evaluator.last_step_failures() : std::vector<std::string>{},
                                   result.cost, result.residual_variance, ends, options.identification_tolerance,
                                   result.secant_sigma,
                                   covariance_doubts(parameters, u.insensitive,
                                                     result.covariance_status == "positive definite", result.sigma,
                                                     correlation));
  for (std::size_t i = 0; i < n; ++i)
    if (!result.identification[i].identified) {
      std::ostringstream text;
      text << "parameter '" << parameters[i].name << "' is NOT IDENTIFIED by the data (to "
           << 100 * options.identification_tolerance << " %): " << result.identification[i].reason;
      result.warnings.push_back(text.str());
    }

  // Fitted curves and per-curve quality.
  const auto curves = evaluator.simulate(result.fitted_values);
  for (std::size_t e = 0; e < curves.size(); ++e) {
    const auto& experiment = evaluator.experiments()[e];
    result.fitted.push_back(simulated_at_target(experiment, curves[e]));
    for (auto& q : fit_quality(experiment, curves[e])) result.quality.push_back(q);
    for (auto& q : peak_quality(experiment, curves[e])) result.peaks.push_back(q);
  }
  result.statistics = evaluator.statistics();
  result.wall_seconds = std::chrono::duration<double>(Clock::now() - started).count();
  if (options.progress) {
    *options.progress << "fit done: cost " << result.cost << " at [" << join(result.values)
                      << "] after " << result.statistics.simulations << " simulation runs, "
                      << result.wall_seconds << " s\n";
    for (const auto& [kind, count] : result.statistics.failure_kinds)
      *options.progress << "failed runs: " << count << " x " << kind << "\n";
    for (const auto& w : result.warnings) *options.progress << "warning: " << w << "\n";
  }
  return result;
}

}  // namespace dtwire::calibrate
