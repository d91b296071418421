#pragma once
// Evaluation of all experiments at parameter points: results cache keyed by SHA-256 of the
// inputs, parallel runs, and forward/central finite-difference Jacobians whose step suits
// solver noise. Works on the scaled parameters z = value / scale the optimiser sees.
#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "dtwire/calibrate/experiment.hpp"
#include "dtwire/calibrate/parameter.hpp"

namespace dtwire::calibrate {

// SHA-256 of the simulator identity and the exact parameter values (shortest round-trip text).
std::string evaluation_key(const Simulator& simulator, const ParameterValues& parameters);

// Simulated curves by key, in memory and optionally as CSV files in a directory (so a resumed
// fit does not re-run FE simulations). Failures are remembered in memory only. Thread safe.
class ResultsCache {
 public:
  explicit ResultsCache(std::filesystem::path directory = {});

  struct Entry {
    std::optional<Curve> curve;
    std::string failure;  // non-empty if the simulation threw ComputationError
  };
  std::optional<Entry> find(const std::string& key);
  void store(const std::string& key, const Entry& entry);

 private:
  std::filesystem::path directory_;
  std::mutex mutex_;
  std::map<std::string, Entry> entries_;
};

struct EvaluationOptions {
  // Simulator runs at once, over every caller (starts side by side share them); 0:
  // std::thread::hardware_concurrency().
  unsigned threads = 0;
  double relative_step = 1e-4;   // finite-difference step h = relative_step * max(|z|, 1)
  bool central_differences = false;
  std::filesystem::path cache_directory;  // empty: memory only
};

struct EvaluationStatistics {
  std::size_t simulations = 0;  // simulator runs
  std::size_t cache_hits = 0;
  std::size_t failures = 0;     // runs that threw ComputationError
  // Failed runs by kind: the error message with its numbers replaced by '#'
  // ("experiment 'tension': dem_specimen: not converged at grip displacement # mm ...").
  std::map<std::string, std::size_t> failure_kinds;
};

// A failure message with every number replaced by '#', so that failures of one kind count
// together.
std::string failure_kind(const std::string& message);

class ProblemEvaluator {
 public:
  ProblemEvaluator(std::vector<Experiment> experiments, std::vector<ParameterDefinition> parameters,
                   EvaluationOptions options);

  const std::vector<Experiment>& experiments() const { return experiments_; }
  const std::vector<ParameterDefinition>& parameters() const { return parameters_; }
  std::size_t residual_count() const { return residual_count_; }

  std::vector<double> to_scaled(const std::vector<double>& values) const;
  std::vector<double> from_scaled(const std::vector<double>& z) const;

  // Residuals at z. Throws ComputationError if a simulation fails.
  std::vector<double> residuals(const std::vector<double>& z);
  // Residuals and the Jacobian d r / d z (row-major, residual_count x n). The point itself runs
  // first: if it fails, throws ComputationError without running the perturbed points. A
  // perturbed run that fails is retried with the opposite step, then with a tenth of the step;
  // throws ComputationError if all fail.
  void residuals_and_jacobian(const std::vector<double>& z, std::vector<double>& residuals,
                              std::vector<double>& jacobian);

  // Residuals at z and the secant Jacobian with the given step per coordinate (z units):
  // central differences (r(z + s e_j) - r(z - s e_j)) / 2s, one-sided where a side crosses a
  // bound or its run fails; throws ComputationError if the point or both sides of a column fail.
  // The sensitivity at the scale of the steps, for the identification (fitter.cpp).
  void residuals_and_secant_jacobian(const std::vector<double>& z, const std::vector<double>& steps,
                                     std::vector<double>& residuals, std::vector<double>& jacobian);

  // Of the last residuals_and_jacobian: its point, and per parameter the failure of the first
  // perturbed run (empty: it ran), i.e. a parameter whose step of h left the region where the
  // simulator runs.
  const std::vector<double>& last_jacobian_point() const { return last_jacobian_point_; }
  const std::vector<std::string>& last_step_failures() const { return last_step_failures_; }

  // Simulated curves (one per experiment) at fitted values (SI; offsets not yet resolved, as
  // from_scaled gives them).
  std::vector<Curve> simulate(const std::vector<double>& values);

  EvaluationStatistics statistics() const;

  // The finite-difference step of residuals_and_jacobian (EvaluationOptions::relative_step);
  // the fit's polish (fitter.hpp) solves with a coarser one. Not while a Jacobian is taken.
  double relative_step() const { return options_.relative_step; }
  void set_relative_step(double relative_step);

 private:
  struct Outcome {
    std::vector<double> residuals;
    std::string failure;
  };
  // Residual vectors at several points, computed in parallel (one task per point and experiment).
  std::vector<Outcome> evaluate_points(const std::vector<std::vector<double>>& z_points);
  Curve run(std::size_t experiment, const ParameterValues& values);

  std::vector<Experiment> experiments_;
  std::vector<ParameterDefinition> parameters_;
  EvaluationOptions options_;
  std::size_t residual_count_ = 0;
  ResultsCache cache_;
  std::map<const Simulator*, std::unique_ptr<std::mutex>> serial_locks_;
  std::mutex slots_mutex_;  // at most options_.threads runs at once
  std::condition_variable slot_freed_;
  unsigned runs_in_progress_ = 0;
  std::atomic<std::size_t> simulations_{0}, cache_hits_{0}, failures_{0};
  std::mutex last_jacobian_mutex_;  // starts side by side take Jacobians at once
  std::vector<double> last_jacobian_point_;
  std::vector<std::string> last_step_failures_;
  mutable std::mutex failure_kinds_mutex_;
  std::map<std::string, std::size_t> failure_kinds_;
};

}  // namespace dtwire::calibrate
