#pragma once
// dtwire's one bounded nonlinear least-squares engine (calibrate's fits and gap's effect fits).
// Ceres-shaped: a Problem (residuals of x, bounds, optional Jacobian), Options, and a Summary
// of a multi-start Levenberg-Marquardt solve (Ceres trust region, dense QR) whose per-start
// state can be saved after any iteration and resumed to the same end; then the uncertainty at
// the answer: covariance (J^T J)^-1 by dense SVD, scaled by the residual variance of each
// residual group (the grouped sandwich; the classical s^2 (J^T J)^-1 when the groups' variances
// are equal), and the singular values of the column-normalised Jacobian (identifiability).
//
// x is the solver's coordinate: callers pass coordinates of order one (scaled parameters), so
// that tolerances, trust-region radii and finite-difference steps mean the same in every fit.
// A residual function that throws dtwire::ComputationError rejects the point (the step is
// retried shorter); any other exception ends the solve and is rethrown to the caller.
#include <Eigen/Core>
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace dtwire::lsq {

using ResidualFunction = std::function<void(const std::vector<double>& x, std::vector<double>& residuals)>;
// Residuals and the Jacobian d r_i / d x_j, row-major (residual_count x parameter_count).
using JacobianFunction = std::function<void(const std::vector<double>& x, std::vector<double>& residuals,
                                            std::vector<double>& jacobian)>;

struct Problem {
  std::size_t parameter_count = 0;
  std::size_t residual_count = 0;
  std::vector<double> lower, upper;  // bounds on x; empty: unbounded
  ResidualFunction residuals;        // required
  JacobianFunction residuals_and_jacobian;  // optional: central differences of `residuals` when absent
  double difference_step = 1e-6;     // relative step of the central differences
  // Sizes of consecutive residual groups with a variance of their own (e.g. curve channels);
  // empty: one group. Used by the covariance only.
  std::vector<std::size_t> residual_groups;
};

enum class Loss { Squared, Huber, Cauchy };

struct Iteration {
  std::size_t start = 0;
  int iteration = 0;         // counted over resumed runs of the start
  double cost = 0.0;         // 1/2 sum rho(r^2)
  double gradient_max_norm = 0.0;
  bool step_accepted = true;
};

enum class StartState { Pending, Running, Done, Failed };
std::string to_string(StartState state);
StartState start_state_from_string(const std::string& text);  // throws std::invalid_argument

// One start of a multi-start solve; everything needed to resume it.
struct Start {
  std::vector<double> start;  // x where it began
  std::vector<double> x;      // last accepted iterate (the answer once done)
  double radius = 0.0;        // trust-region radius for the next iteration
  int iterations = 0;
  double cost = 0.0;
  StartState state = StartState::Pending;
  std::string message;
  int screened = 0;  // screening stages passed (Options::screening)
};

// A screening stage of a multi-start solve: once every start has run `iterations` iterations
// (or ended), a start still running whose cost exceeds cost_ratio x the lowest cost of all starts
// at that point is stopped (Done, the message says so). The decision waits for every start, so
// it does not depend on the order or the number of starts run side by side; a start that passes
// goes on from its last accepted iterate and ends where it would without the stage.
struct ScreeningStage {
  int iterations = 0;       // > 0, increasing from stage to stage
  double cost_ratio = 0.0;  // > 1
};

struct Options {
  int max_iterations = 50;  // per start, over resumed runs
  Loss loss = Loss::Squared;
  double loss_scale = 1.0;  // residual size where a robust loss starts to bend
  double function_tolerance = 1e-6;
  double parameter_tolerance = 1e-8;
  double gradient_tolerance = 1e-10;
  bool jacobi_scaling = true;  // off for resumable solves: Ceres scales from a solve's first Jacobian
  double initial_trust_region_radius = 1e4;
  // Ceres residual blocks: one per residual (a robust loss acts point by point) or all residuals
  // in one (squared loss only; fewer blocks, and the summation order gap's fits were tuned with).
  bool block_per_residual = true;
  // After every iteration, with every start's state (already updated: a checkpoint written
  // here resumes to the same end, bit for bit); return false to stop: the summary is then not
  // completed and its starts resume from their last accepted iterate (a run stopped again
  // before it gets past the rejected steps it repeats makes no progress).
  std::function<bool(const Iteration&, const std::vector<Start>&)> after_iteration;
  // When a start has ended (done or failed).
  std::function<void(std::size_t start, const std::vector<Start>&)> after_start;
  // Starts solved side by side, on threads (the problem's residuals must then be thread safe);
  // each start ends where it would alone. The callbacks are called one at a time.
  unsigned parallel_starts = 1;
  // Applied in order (empty: every start runs to its end).
  std::vector<ScreeningStage> screening;
};

std::vector<Start> starts_at(const std::vector<std::vector<double>>& points);

struct Summary {
  bool completed = false;  // false: stopped by after_iteration; resume with `starts`
  std::vector<Start> starts;
  std::optional<std::size_t> best;  // lowest-cost done start (first on ties)
  std::vector<double> x;            // the best start's answer
  double cost = 0.0;
};

// Solves from every start not yet done or failed, in order (with parallel_starts > 1, up to that
// many at once); starts outside the bounds are clamped into them.
Summary solve(const Problem& problem, const Options& options, std::vector<Start> starts);

struct Uncertainty {
  std::vector<double> residuals;  // as seen by the loss (robust-corrected)
  Eigen::MatrixXd jacobian;       // of those residuals, in x
  std::optional<Eigen::MatrixXd> covariance;  // in x; empty when rank-deficient
  std::vector<double> singular_values;        // of the column-normalised Jacobian, descending
  Eigen::MatrixXd singular_directions;        // columns: right singular vectors
  std::vector<std::size_t> insensitive;       // parameters whose Jacobian column is zero
};

// Uncertainty of the answer x of `problem` (needs more residuals than parameters).
Uncertainty uncertainty_at(const Problem& problem, const Options& options, const std::vector<double>& x);

}  // namespace dtwire::lsq
