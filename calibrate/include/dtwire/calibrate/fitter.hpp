#pragma once
// Bounded nonlinear least squares (the lsq engine: Ceres Levenberg-Marquardt) on the scaled parameters,
// robust losses, multi-start from a Latin hypercube, a checkpoint after every iteration that a
// later run resumes from (ending where an uninterrupted fit ends), and the covariance of the
// estimate: (J^T J)^-1 (dense SVD), scaled by the residual variance of
// each curve channel (grouped sandwich; the classical s^2 (J^T J)^-1 when all are equal).
#include <Eigen/Core>
#include <atomic>
#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "dtwire/calibrate/evaluation.hpp"
#include "dtwire/calibrate/identifiability.hpp"

namespace dtwire::calibrate {

enum class LossKind { Squared, Huber, Cauchy };

// A screening stage of the multi-start (the lsq engine's ScreeningStage): once every start has
// run `iterations` iterations or ended, a start whose cost exceeds cost_ratio x the lowest cost
// of all starts is stopped; the others go on to the end they would reach without it.
struct StartScreening {
  int iterations = 0;
  double cost_ratio = 0.0;
};

struct FitOptions {
  int max_iterations = 50;
  LossKind loss = LossKind::Squared;
  double loss_scale = 1.0;  // residual size where the robust loss starts to bend
  int starts = 1;           // 1: the initial values only; k: plus k-1 Latin hypercube points
                            // (in ln(value) for logarithmic parameters)
  std::uint64_t seed = 1;
  // Relative precision below which a parameter counts as identified (identifiability.hpp).
  double identification_tolerance = 0.05;
  double function_tolerance = 1e-10;
  double parameter_tolerance = 1e-10;
  double gradient_tolerance = 1e-12;
  std::filesystem::path checkpoint;  // empty: no checkpoint
  bool resume = false;               // continue from `checkpoint` if it exists
  // Stop as if interrupted once this process has completed this many iterations (tests).
  int stop_after_iterations = -1;
  // Starts solved side by side (fit --jobs); their simulator runs share the evaluator's
  // threads. Each start ends where it would alone, so the result does not depend on it.
  unsigned parallel_starts = 1;
  std::vector<StartScreening> screening;  // in order; empty: every start runs to its end
  // The bounded solve's line search from values alone (lsq::Options::value_only_line_search):
  // [fit] line_search = "values"; the default "gradients" is Ceres' cubic interpolation.
  bool value_only_line_search = false;
  // > 0: the polish. After the multi-start, the best start's end is solved once more with this
  // finite-difference step (EvaluationOptions::relative_step, in z) and taken if its cost is
  // lower. A simulator whose response moves in small jumps (a DEM specimen's links yielding one
  // load increment apart) makes a fine step's Jacobian see the jumps, not the trend, and
  // Levenberg-Marquardt stops at the first one ("parameter tolerance reached"); a step wider
  // than the jumps follows the trend. [fit] polish_relative_step; 0: none.
  double polish_relative_step = 0.0;
  const std::atomic<bool>* stop_requested = nullptr;  // e.g. set by a SIGINT handler
  std::ostream* progress = nullptr;
};

struct StartSummary {
  std::vector<double> start;  // fitted values (SI; an offset parameter's offset, as the optimiser sees it)
  std::vector<double> end;
  double cost = 0.0;  // Ceres cost 1/2 sum rho(r^2) at the end
  int iterations = 0;
  std::string state;  // "pending", "running", "done", "failed"
  std::string message;
};

// The polish's outcome (FitOptions::polish_relative_step).
struct PolishSummary {
  bool run = false;
  double relative_step = 0.0;
  double cost_before = 0.0;  // the best start's
  double cost_after = 0.0;   // the polish's end (not finite: it failed)
  int iterations = 0;
  bool taken = false;        // its end replaced the best start's
  std::string message;
};

struct FitResult {
  bool completed = false;  // false: interrupted, resume from the checkpoint
  std::vector<ParameterDefinition> parameters;
  // The parameters' own values (SI), what the simulator reads: offsets resolved
  // (parameter.hpp). values, covariance, correlation, sigma and identification are of these.
  std::vector<double> values;
  std::optional<Eigen::MatrixXd> covariance;  // SI, scaled by the residual variances
  std::optional<Eigen::MatrixXd> correlation;
  std::vector<double> sigma;                  // sqrt(diag covariance); empty without covariance
  // The optimiser's values: an offset parameter's offset (else its value), with their sigma.
  std::vector<double> fitted_values;
  std::vector<double> fitted_sigma;
  // Of the parameters' own values, from the secant Jacobian at the identification tolerance's
  // scale (identifiability.hpp, rule 3); empty if not computed (no covariance, a failed run).
  std::vector<double> secant_sigma;
  // "positive definite", or why not (then sigma are not standard errors: a direction of the
  // parameters has no finite variance); in parameters.json, the report and on the console.
  std::string covariance_status;
  std::vector<double> singular_values;        // of the column-normalised Jacobian, descending
  std::vector<Identification> identification;  // per parameter (identifiability.hpp)
  double cost = 0.0;
  double residual_variance = 0.0;  // pooled: 2 cost / (m - n)
  std::size_t residual_count = 0;
  std::size_t best_start = 0;
  std::vector<StartSummary> starts;
  PolishSummary polish;
  std::vector<std::string> warnings;
  std::vector<ChannelQuality> quality;
  std::vector<PeakQuality> peaks;  // the experiments' peak rows, target against fitted
  std::vector<Curve> fitted;  // simulated channels at the targets' points, one per experiment
  EvaluationStatistics statistics;
  double wall_seconds = 0.0;
};

// Runs the fit. Throws ComputationError if every start fails, InputError if a checkpoint to
// resume from belongs to a different fit definition.
FitResult run_fit(ProblemEvaluator& evaluator, const FitOptions& options);

// Identity of the fit definition (experiments, targets, parameters, options that change the
// trajectory): a checkpoint only resumes the fit it was written for.
std::string fit_identity(const ProblemEvaluator& evaluator, const FitOptions& options);

}  // namespace dtwire::calibrate
