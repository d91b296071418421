#include "dtwire/calibrate/fitter.hpp"

#include <ceres/ceres.h>

#include <Eigen/SVD>
#include <chrono>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iomanip>
#include <ostream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "dtwire/calibrate/sampling.hpp"
#include "dtwire/core/atomic_file.hpp"
#include "dtwire/core/csv.hpp"
#include "dtwire/core/error.hpp"
#include "dtwire/core/provenance.hpp"

namespace dtwire::calibrate {
namespace {

using Clock = std::chrono::steady_clock;

// All residuals and the Jacobian at the last point Ceres asked for. Ceres evaluates the
// residual blocks one after another at the same point (num_threads = 1), so one simulation
// round serves them all; the parallelism is inside ProblemEvaluator.
class SharedEvaluation {
 public:
  explicit SharedEvaluation(ProblemEvaluator& evaluator) : evaluator_(evaluator) {}

  bool evaluate(const double* z, bool need_jacobian) {
    const std::size_t n = evaluator_.parameters().size();
    const bool same = valid_ && std::memcmp(z, z_.data(), n * sizeof(double)) == 0;
    if (same && (!need_jacobian || has_jacobian_)) return failure_.empty();
    z_.assign(z, z + n);
    valid_ = true;
    has_jacobian_ = need_jacobian;
    failure_.clear();
    try {
      if (need_jacobian)
        evaluator_.residuals_and_jacobian(z_, residuals_, jacobian_);
      else
        residuals_ = evaluator_.residuals(z_);
    } catch (const ComputationError& error) {
      failure_ = error.what();
    }
    if (!failure_.empty() && last_failure_ != failure_) last_failure_ = failure_;
    return failure_.empty();
  }
  double residual(std::size_t i) const { return residuals_[i]; }
  const double* jacobian_row(std::size_t i) const {
    return jacobian_.data() + i * evaluator_.parameters().size();
  }
  const std::string& last_failure() const { return last_failure_; }

 private:
  ProblemEvaluator& evaluator_;
  std::vector<double> z_, residuals_, jacobian_;
  bool valid_ = false, has_jacobian_ = false;
  std::string failure_, last_failure_;
};

// One residual as a Ceres residual block, so robust losses act point by point.
class PointResidual final : public ceres::CostFunction {
 public:
  PointResidual(SharedEvaluation& shared, std::size_t index, int parameter_count)
      : shared_(shared), index_(index) {
    set_num_residuals(1);
    mutable_parameter_block_sizes()->push_back(parameter_count);
  }
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    const bool need_jacobian = jacobians != nullptr && jacobians[0] != nullptr;
    if (!shared_.evaluate(parameters[0], need_jacobian)) return false;  // Ceres rejects the step
    residuals[0] = shared_.residual(index_);
    if (need_jacobian) {
      const double* row = shared_.jacobian_row(index_);
      std::copy(row, row + parameter_block_sizes()[0], jacobians[0]);
    }
    return true;
  }

 private:
  SharedEvaluation& shared_;
  std::size_t index_;
};

ceres::LossFunction* make_loss(const FitOptions& options) {
  switch (options.loss) {
    case LossKind::Huber: return new ceres::HuberLoss(options.loss_scale);
    case LossKind::Cauchy: return new ceres::CauchyLoss(options.loss_scale);
    case LossKind::Squared: break;
  }
  return nullptr;
}

// The Ceres problem on the parameter block z (scaled values), with bounds.
struct CeresProblem {
  CeresProblem(ProblemEvaluator& evaluator, const FitOptions& options, std::vector<double>& z)
      : shared(evaluator) {
    ceres::Problem::Options problem_options;
    problem_options.loss_function_ownership = ceres::TAKE_OWNERSHIP;
    problem = std::make_unique<ceres::Problem>(problem_options);
    const int n = static_cast<int>(z.size());
    for (std::size_t i = 0; i < evaluator.residual_count(); ++i)
      problem->AddResidualBlock(new PointResidual(shared, i, n), make_loss(options), z.data());
    for (int j = 0; j < n; ++j) {
      const auto& p = evaluator.parameters()[static_cast<std::size_t>(j)];
      problem->SetParameterLowerBound(z.data(), j, p.lower / p.effective_scale());
      problem->SetParameterUpperBound(z.data(), j, p.upper / p.effective_scale());
    }
  }
  SharedEvaluation shared;
  std::unique_ptr<ceres::Problem> problem;
};

std::string join(const std::vector<double>& v) {
  std::ostringstream out;
  out << std::setprecision(6);
  for (std::size_t i = 0; i < v.size(); ++i) out << (i ? ", " : "") << v[i];
  return out.str();
}

// ---- checkpoint ------------------------------------------------------------------------

struct StartState {
  std::vector<double> start_z;
  std::vector<double> z;  // last accepted iterate
  double radius = 0.0;    // trust region radius for the next iteration
  int iterations = 0;
  double cost = 0.0;
  std::string state = "pending";
  std::string message;
};

nlohmann::json to_json(const StartState& s) {
  return {{"start_z", s.start_z}, {"z", s.z},         {"radius", s.radius},
          {"iterations", s.iterations}, {"cost", s.cost}, {"state", s.state},
          {"message", s.message}};
}

StartState from_json(const nlohmann::json& j) {
  StartState s;
  s.start_z = j.at("start_z").get<std::vector<double>>();
  s.z = j.at("z").get<std::vector<double>>();
  s.radius = j.at("radius").get<double>();
  s.iterations = j.at("iterations").get<int>();
  s.cost = j.at("cost").get<double>();
  s.state = j.at("state").get<std::string>();
  s.message = j.at("message").get<std::string>();
  return s;
}

void write_checkpoint(const std::filesystem::path& path, const std::string& identity,
                      const std::vector<StartState>& starts) {
  if (path.empty()) return;
  nlohmann::json j;
  j["format"] = "dtwire-fit-checkpoint-1";
  j["fit_identity"] = identity;
  for (const auto& s : starts) j["starts"].push_back(to_json(s));
  // nlohmann writes doubles with 17 significant digits: they read back exactly.
  write_file_atomically(path, [&](std::ostream& out) { out << j.dump(1) << "\n"; });
}

std::optional<std::vector<StartState>> read_checkpoint(const std::filesystem::path& path,
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
  std::vector<StartState> starts;
  for (const auto& s : j.at("starts")) starts.push_back(from_json(s));
  return starts;
}

// ---- one start -------------------------------------------------------------------------

class CheckpointingCallback final : public ceres::IterationCallback {
 public:
  CheckpointingCallback(const std::vector<double>& z, StartState& state, int done_before,
                        std::function<void()> save, std::function<bool()> should_stop,
                        std::function<void(const ceres::IterationSummary&)> report)
      : z_(z), state_(state), done_before_(done_before), save_(std::move(save)),
        should_stop_(std::move(should_stop)), report_(std::move(report)) {}

  ceres::CallbackReturnType operator()(const ceres::IterationSummary& summary) override {
    // Only accepted iterates are resumable states (an iteration that rejects its step leaves
    // the iterate unchanged; a resumed run repeats it and takes the same decisions).
    if (summary.iteration == 0 || summary.step_is_successful) {
      state_.z = z_;
      state_.radius = summary.trust_region_radius;
      state_.iterations = done_before_ + summary.iteration;
      state_.cost = summary.cost;
    }
    save_();
    report_(summary);
    return should_stop_() ? ceres::SOLVER_ABORT : ceres::SOLVER_CONTINUE;
  }

 private:
  const std::vector<double>& z_;
  StartState& state_;
  int done_before_;
  std::function<void()> save_;
  std::function<bool()> should_stop_;
  std::function<void(const ceres::IterationSummary&)> report_;
};

constexpr double kInitialTrustRegionRadius = 1e4;

ceres::Solver::Options solver_options(const FitOptions& options) {
  ceres::Solver::Options o;
  o.minimizer_type = ceres::TRUST_REGION;
  o.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  o.linear_solver_type = ceres::DENSE_QR;
  // Jacobi scaling is computed from the first Jacobian of a solve only; a resumed solve would
  // scale differently. The parameters are already scaled (z = value / scale).
  o.jacobi_scaling = false;
  o.num_threads = 1;  // residual blocks share one evaluation; parallelism is per simulation
  o.update_state_every_iteration = true;
  o.function_tolerance = options.function_tolerance;
  o.parameter_tolerance = options.parameter_tolerance;
  o.gradient_tolerance = options.gradient_tolerance;
  o.logging_type = ceres::SILENT;
  o.minimizer_progress_to_stdout = false;
  return o;
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
  }
  for (const auto& p : evaluator.parameters())
    text << "parameter " << p.name << " " << p.initial << " " << p.lower << " " << p.upper << " "
         << p.effective_scale() << "\n";
  text << "options " << options.max_iterations << " " << static_cast<int>(options.loss) << " "
       << options.loss_scale << " " << options.starts << " " << options.seed << " "
       << options.function_tolerance << " " << options.parameter_tolerance << " "
       << options.gradient_tolerance << "\n";
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
  std::vector<StartState> starts;
  if (options.resume) {
    if (auto restored = read_checkpoint(options.checkpoint, identity)) starts = *restored;
  }
  if (starts.empty()) {
    std::vector<double> initial, lower, upper;
    for (const auto& p : parameters) {
      initial.push_back(p.initial);
      lower.push_back(p.lower);
      upper.push_back(p.upper);
    }
    starts.push_back(StartState{evaluator.to_scaled(initial), {}, 0.0, 0, 0.0, "pending", {}});
    for (const auto& point :
         latin_hypercube(static_cast<std::size_t>(options.starts - 1), lower, upper, options.seed))
      starts.push_back(StartState{evaluator.to_scaled(point), {}, 0.0, 0, 0.0, "pending", {}});
  }

  int iterations_this_run = 0;
  bool interrupted = false;
  const auto save = [&] { write_checkpoint(options.checkpoint, identity, starts); };
  const auto should_stop = [&] {
    ++iterations_this_run;
    interrupted = (options.stop_after_iterations >= 0 &&
                   iterations_this_run > options.stop_after_iterations) ||
                  (options.stop_requested && options.stop_requested->load());
    return interrupted;
  };

  for (std::size_t s = 0; s < starts.size() && !interrupted; ++s) {
    StartState& state = starts[s];
    if (state.state == "done" || state.state == "failed") continue;
    const bool continuing = state.state == "running";
    std::vector<double> z = continuing ? state.z : state.start_z;
    const int done_before = continuing ? state.iterations : 0;
    state.state = "running";
    if (done_before >= options.max_iterations) {
      state.state = "done";
      state.message = "maximum number of iterations reached";
      save();
      continue;
    }
    CeresProblem problem(evaluator, options, z);
    ceres::Solver::Options solver = solver_options(options);
    solver.max_num_iterations = options.max_iterations - done_before;
    solver.initial_trust_region_radius = continuing ? state.radius : kInitialTrustRegionRadius;
    const auto report = [&](const ceres::IterationSummary& it) {
      if (!options.progress) return;
      const auto stats = evaluator.statistics();
      const double elapsed = std::chrono::duration<double>(Clock::now() - started).count();
      *options.progress << "fit start " << s + 1 << "/" << starts.size() << " iteration "
                        << done_before + it.iteration << ": cost " << std::setprecision(6)
                        << it.cost << (it.step_is_successful || it.iteration == 0 ? "" : " (step rejected)")
                        << ", |gradient| " << it.gradient_max_norm << ", runs " << stats.simulations
                        << " (cached " << stats.cache_hits << ", failed " << stats.failures << "), "
                        << std::setprecision(3) << elapsed << " s\n"
                        << std::flush;
    };
    CheckpointingCallback callback(z, state, done_before, save, should_stop, report);
    solver.callbacks.push_back(&callback);
    ceres::Solver::Summary summary;
    ceres::Solve(solver, problem.problem.get(), &summary);
    if (interrupted) {
      save();
      break;
    }
    if (summary.termination_type == ceres::CONVERGENCE ||
        summary.termination_type == ceres::NO_CONVERGENCE) {
      state.state = "done";
      state.z = z;
      state.cost = summary.final_cost;
      state.iterations = done_before + static_cast<int>(summary.iterations.size()) - 1;
      state.message = summary.message;
    } else {
      state.state = "failed";
      state.message = summary.message + (problem.shared.last_failure().empty()
                                             ? std::string()
                                             : " (" + problem.shared.last_failure() + ")");
    }
    if (options.progress)
      *options.progress << "fit start " << s + 1 << "/" << starts.size() << " " << state.state
                        << ": " << state.message << "\n";
    save();
  }

  FitResult result;
  result.parameters = parameters;
  result.residual_count = m;
  for (const auto& st : starts)
    result.starts.push_back({evaluator.from_scaled(st.start_z),
                             st.z.empty() ? std::vector<double>{} : evaluator.from_scaled(st.z),
                             st.cost, st.iterations, st.state, st.message});
  result.statistics = evaluator.statistics();
  if (interrupted) {
    result.completed = false;
    result.wall_seconds = std::chrono::duration<double>(Clock::now() - started).count();
    return result;
  }
  std::optional<std::size_t> best;
  for (std::size_t s = 0; s < starts.size(); ++s)
    if (starts[s].state == "done" && (!best || starts[s].cost < starts[*best].cost)) best = s;
  if (!best) {
    std::string messages;
    for (const auto& st : starts) messages += " [" + st.message + "]";
    throw ComputationError("fit failed from every start:" + messages);
  }
  result.completed = true;
  result.best_start = *best;
  std::vector<double> z = starts[*best].z;
  result.values = evaluator.from_scaled(z);
  result.cost = starts[*best].cost;
  result.residual_variance = 2.0 * result.cost / static_cast<double>(m - n);

  // Jacobian and residuals at the optimum (z space; with a robust loss, as corrected by it).
  CeresProblem problem(evaluator, options, z);
  ceres::CRSMatrix crs;
  std::vector<double> r;
  double cost = 0;
  problem.problem->Evaluate(ceres::Problem::EvaluateOptions(), &cost, &r, nullptr, &crs);
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(crs.num_rows, crs.num_cols);
  for (int row = 0; row < crs.num_rows; ++row)
    for (int k = crs.rows[static_cast<std::size_t>(row)]; k < crs.rows[static_cast<std::size_t>(row) + 1]; ++k)
      J(row, crs.cols[static_cast<std::size_t>(k)]) = crs.values[static_cast<std::size_t>(k)];

  // Covariance: C = (J^T J)^-1 from ceres::Covariance (dense SVD), scaled by the residual
  // variance. Curves are weighted by the user, not necessarily by their noise, so the variance
  // is estimated per curve channel g (s_g^2 = sum r_g^2 / its share of the m - n degrees of
  // freedom) and combined as C (sum_g s_g^2 J_g^T J_g) C (the grouped sandwich estimator); with
  // equal s_g this is the classical s^2 (J^T J)^-1.
  ceres::Covariance::Options covariance_options;
  covariance_options.algorithm_type = ceres::DENSE_SVD;
  covariance_options.null_space_rank = -1;  // pseudo-inverse: drop directions below the threshold
  covariance_options.min_reciprocal_condition_number = 1e-14;
  covariance_options.num_threads = 1;
  ceres::Covariance covariance(covariance_options);
  std::vector<std::pair<const double*, const double*>> blocks{{z.data(), z.data()}};
  if (covariance.Compute(blocks, problem.problem.get())) {
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> cz(n, n);
    covariance.GetCovarianceBlock(z.data(), z.data(), cz.data());
    const Eigen::MatrixXd C = cz;
    Eigen::MatrixXd meat = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(n));
    const double dof_share = static_cast<double>(m - n) / static_cast<double>(m);
    Eigen::Index begin = 0;
    for (const auto& experiment : evaluator.experiments())
      for (std::size_t c = 0; c < experiment.channels.size(); ++c) {
        const auto size = static_cast<Eigen::Index>(experiment.target.size());
        double ss = 0;
        for (Eigen::Index i = begin; i < begin + size; ++i) ss += r[static_cast<std::size_t>(i)] * r[static_cast<std::size_t>(i)];
        const double variance = ss / (dof_share * static_cast<double>(size));
        const auto Jg = J.middleRows(begin, size);
        meat += variance * Jg.transpose() * Jg;
        begin += size;
      }
    const Eigen::MatrixXd cov_z = C * meat * C;
    Eigen::MatrixXd cov(n, n), corr(n, n);
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = 0; j < n; ++j)
        cov(i, j) = cov_z(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) *
                    parameters[i].effective_scale() * parameters[j].effective_scale();
    for (std::size_t i = 0; i < n; ++i) result.sigma.push_back(std::sqrt(std::max(cov(i, i), 0.0)));
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = 0; j < n; ++j) {
        const double d = result.sigma[i] * result.sigma[j];
        corr(i, j) = i == j ? 1.0 : (d > 0 ? cov(i, j) / d : 0.0);
      }
    result.covariance = cov;
    result.correlation = corr;
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = i + 1; j < n; ++j)
        if (std::abs(corr(i, j)) > 0.95)
          result.warnings.push_back("parameters '" + parameters[i].name + "' and '" +
                                    parameters[j].name + "' are strongly correlated (r = " +
                                    std::to_string(corr(i, j)) + "): poorly identified separately");
    for (std::size_t i = 0; i < n; ++i)
      if (result.sigma[i] > std::abs(result.values[i]))
        result.warnings.push_back("parameter '" + parameters[i].name +
                                  "' is poorly identified: sigma exceeds |value|");
  } else {
    result.warnings.push_back("covariance could not be computed (rank-deficient Jacobian)");
  }

  // Identifiability: singular values of the Jacobian with unit-norm columns.
  Eigen::MatrixXd jacobian = J;
  for (Eigen::Index j = 0; j < jacobian.cols(); ++j) {
    const double norm = jacobian.col(j).norm();
    if (norm > 0) jacobian.col(j) /= norm;
    else result.warnings.push_back("parameter '" + parameters[static_cast<std::size_t>(j)].name +
                                   "' does not affect the residuals at the optimum");
  }
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(jacobian, Eigen::ComputeThinV);
  const Eigen::VectorXd sv = svd.singularValues();
  for (Eigen::Index i = 0; i < sv.size(); ++i) result.singular_values.push_back(sv(i));
  for (Eigen::Index i = 0; i < sv.size(); ++i) {
    if (sv(0) > 0 && sv(i) / sv(0) < 1e-3) {
      std::ostringstream direction;
      direction << std::setprecision(3);
      for (Eigen::Index j = 0; j < sv.size(); ++j)
        direction << (j ? ", " : "") << parameters[static_cast<std::size_t>(j)].name << " "
                  << svd.matrixV()(j, i);
      result.warnings.push_back("poorly identified direction (singular value ratio " +
                                std::to_string(sv(i) / sv(0)) + "): " + direction.str());
    }
  }
  for (std::size_t i = 0; i < n; ++i) {
    const auto& p = parameters[i];
    const double tol = 1e-6 * (p.upper - p.lower);
    if (result.values[i] <= p.lower + tol || result.values[i] >= p.upper - tol)
      result.warnings.push_back("parameter '" + p.name + "' ended at a bound; its sigma is not meaningful");
  }

  // Fitted curves and per-curve quality.
  const auto curves = evaluator.simulate(result.values);
  for (std::size_t e = 0; e < curves.size(); ++e) {
    const auto& experiment = evaluator.experiments()[e];
    result.fitted.push_back(simulated_at_target(experiment, curves[e]));
    for (auto& q : fit_quality(experiment, curves[e])) result.quality.push_back(q);
  }
  result.statistics = evaluator.statistics();
  result.wall_seconds = std::chrono::duration<double>(Clock::now() - started).count();
  if (options.progress) {
    *options.progress << "fit done: cost " << result.cost << " at [" << join(result.values)
                      << "] after " << result.statistics.simulations << " simulation runs, "
                      << result.wall_seconds << " s\n";
    for (const auto& w : result.warnings) *options.progress << "warning: " << w << "\n";
  }
  return result;
}

}  // namespace dtwire::calibrate
