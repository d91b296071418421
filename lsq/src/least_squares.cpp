#include "dtwire/lsq/least_squares.hpp"

#include <ceres/ceres.h>

#include <algorithm>
#include <atomic>
#include <cstring>
#include <exception>
#include <limits>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "ceres_problem.hpp"
#include "dtwire/core/error.hpp"

namespace dtwire::lsq {
namespace {

class IterationReporter final : public ceres::IterationCallback {
 public:
  IterationReporter(const std::vector<double>& x, std::vector<Start>& states, std::size_t index,
                    int done_before, const Options& options, const SharedEvaluation& shared,
                    std::mutex& states_mutex, std::atomic<bool>& stop)
      : x_(x), states_(states), state_(states[index]), index_(index), done_before_(done_before),
        options_(options), shared_(shared), states_mutex_(states_mutex), stop_(stop) {}

  ceres::CallbackReturnType operator()(const ceres::IterationSummary& summary) override {
    if (shared_.has_fatal_error()) return ceres::SOLVER_ABORT;
    // Starts side by side: one update and one callback at a time, so that a checkpoint sees
    // every start's last accepted iterate.
    const std::lock_guard<std::mutex> lock(states_mutex_);
    // Only accepted iterates are resumable states: a resumed run restarts from the last one
    // with its radius and repeats any rejected steps after it, taking the same decisions, so it
    // ends bit for bit where the uninterrupted run ends (Ceres' LM shrink factor, which grows
    // over consecutive rejections, is not visible to record).
    const bool accepted = summary.iteration == 0 || summary.step_is_successful;
    if (accepted) {
      state_.x = x_;
      state_.radius = summary.trust_region_radius;
      state_.iterations = done_before_ + summary.iteration;
      state_.cost = summary.cost;
    }
    if (!stop_ && options_.after_iteration) {
      const Iteration report{index_, done_before_ + summary.iteration, summary.cost,
                             summary.gradient_max_norm, accepted};
      if (!options_.after_iteration(report, states_)) stop_ = true;
    }
    if (!stop_) return ceres::SOLVER_CONTINUE;  // another start may have been stopped
    stopped = true;
    return ceres::SOLVER_ABORT;
  }

  bool stopped = false;

 private:
  const std::vector<double>& x_;
  const std::vector<Start>& states_;
  Start& state_;
  std::size_t index_;
  int done_before_;
  const Options& options_;
  const SharedEvaluation& shared_;
  std::mutex& states_mutex_;
  std::atomic<bool>& stop_;
};

ceres::Solver::Options solver_options(const Options& options) {
  ceres::Solver::Options o;
  o.minimizer_type = ceres::TRUST_REGION;
  o.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  o.linear_solver_type = ceres::DENSE_QR;
  o.jacobi_scaling = options.jacobi_scaling;
  o.num_threads = 1;  // residual blocks share one evaluation; parallelism is the caller's
  o.update_state_every_iteration = true;  // the callback records resumable iterates
  o.function_tolerance = options.function_tolerance;
  o.parameter_tolerance = options.parameter_tolerance;
  o.gradient_tolerance = options.gradient_tolerance;
  o.logging_type = ceres::SILENT;
  o.minimizer_progress_to_stdout = false;
  return o;
}

std::vector<double> clamped(const Problem& problem, std::vector<double> x) {
  for (std::size_t j = 0; j < x.size(); ++j) {
    if (!problem.lower.empty()) x[j] = std::max(x[j], problem.lower[j]);
    if (!problem.upper.empty()) x[j] = std::min(x[j], problem.upper[j]);
  }
  return x;
}

void check(const Problem& problem) {
  const std::size_t n = problem.parameter_count;
  if (n == 0 || problem.residual_count == 0)
    throw std::invalid_argument("least squares: a problem needs parameters and residuals");
  if (!problem.residuals) throw std::invalid_argument("least squares: no residual function");
  if ((!problem.lower.empty() && problem.lower.size() != n) ||
      (!problem.upper.empty() && problem.upper.size() != n))
    throw std::invalid_argument("least squares: bounds must have one entry per parameter");
}

// Runs (or resumes) one start up to `cap` iterations (< max_iterations: a screening stage's;
// the start then stays Running at its last accepted iterate, as a checkpoint would hold it, and
// resumes from there to the same end); returns false when the user's callback stopped it.
bool solve_start(const Problem& problem, const Options& options, int cap, std::size_t index,
                 std::vector<Start>& states, std::mutex& states_mutex, std::atomic<bool>& stop) {
  Start& state = states[index];
  std::unique_lock<std::mutex> lock(states_mutex);
  const bool continuing = state.state == StartState::Running;
  std::vector<double> x = clamped(problem, continuing ? state.x : state.start);
  const int done_before = continuing ? state.iterations : 0;
  const bool capped = cap < options.max_iterations;
  if (capped && continuing && done_before >= cap) return true;
  state.state = StartState::Running;
  if (done_before >= options.max_iterations) {
    state.state = StartState::Done;
    state.message = "maximum number of iterations reached";
    return true;
  }
  const double radius = continuing ? state.radius : options.initial_trust_region_radius;
  lock.unlock();
  CeresProblem ceres_problem(problem, options, x);
  ceres::Solver::Options solver = solver_options(options);
  solver.max_num_iterations = (capped ? cap : options.max_iterations) - done_before;
  solver.initial_trust_region_radius = radius;
  IterationReporter reporter(x, states, index, done_before, options, ceres_problem.shared, states_mutex, stop);
  solver.callbacks.push_back(&reporter);
  ceres::Solver::Summary summary;
  ceres::Solve(solver, ceres_problem.problem.get(), &summary);
  ceres_problem.shared.rethrow_fatal_error();
  if (reporter.stopped) return false;
  lock.lock();
  // NO_CONVERGENCE is the iteration limit (no time limit is set): at a stage's cap the start
  // keeps the callback's record of its last accepted iterate.
  if (capped && summary.termination_type == ceres::NO_CONVERGENCE) return true;
  if (summary.termination_type == ceres::CONVERGENCE ||
      summary.termination_type == ceres::NO_CONVERGENCE) {
    state.state = StartState::Done;
    state.x = x;
    state.cost = summary.final_cost;
    state.iterations = done_before + static_cast<int>(summary.iterations.size()) - 1;
    state.message = summary.message;
  } else {
    state.state = StartState::Failed;
    const std::string& failure = ceres_problem.shared.last_failure();
    state.message = summary.message + (failure.empty() ? std::string() : " (" + failure + ")");
  }
  return true;
}

}  // namespace

std::string to_string(StartState state) {
  switch (state) {
    case StartState::Pending: return "pending";
    case StartState::Running: return "running";
    case StartState::Done: return "done";
    case StartState::Failed: return "failed";
  }
  return "pending";
}

StartState start_state_from_string(const std::string& text) {
  for (StartState s : {StartState::Pending, StartState::Running, StartState::Done, StartState::Failed})
    if (to_string(s) == text) return s;
  throw std::invalid_argument("unknown start state '" + text + "' (pending, running, done, failed)");
}

std::vector<Start> starts_at(const std::vector<std::vector<double>>& points) {
  std::vector<Start> starts;
  for (const auto& p : points) starts.push_back(Start{p, {}, 0.0, 0, 0.0, StartState::Pending, {}});
  return starts;
}

Summary solve(const Problem& problem, const Options& options, std::vector<Start> starts) {
  check(problem);
  for (const Start& state : starts)
    if (state.state != StartState::Done && state.state != StartState::Failed &&
        state.start.size() != problem.parameter_count)
      throw std::invalid_argument("least squares: a start has the wrong number of parameters");
  for (std::size_t k = 0; k < options.screening.size(); ++k) {
    const ScreeningStage& stage = options.screening[k];
    if (stage.iterations < 1 || (k > 0 && stage.iterations <= options.screening[k - 1].iterations))
      throw std::invalid_argument("least squares: screening stages need increasing iteration counts >= 1");
    if (!(stage.cost_ratio > 1.0)) throw std::invalid_argument("least squares: a screening cost ratio must be > 1");
  }
  const auto open = [](const Start& s) { return s.state != StartState::Done && s.state != StartState::Failed; };
  Summary summary;
  std::mutex states_mutex;
  std::atomic<bool> stop{false};
  std::exception_ptr error;
  // One pass over the open starts that have passed `stage` screenings, each up to `cap`
  // iterations; each worker takes the next, and a start's path does not depend on the others.
  const auto pass = [&](int stage, int cap) {
    std::atomic<std::size_t> next{0};
    const auto work = [&] {
      for (std::size_t s = next++; s < starts.size() && !stop; s = next++) {
        if (!open(starts[s]) || starts[s].screened != stage) continue;
        try {
          if (!solve_start(problem, options, cap, s, starts, states_mutex, stop)) return;
          const std::lock_guard<std::mutex> lock(states_mutex);
          if (!open(starts[s]) && options.after_start) options.after_start(s, starts);
        } catch (...) {
          const std::lock_guard<std::mutex> lock(states_mutex);
          if (!error) error = std::current_exception();
          stop = true;
        }
      }
    };
    const std::size_t workers = std::max<std::size_t>(1, std::min<std::size_t>(options.parallel_starts, starts.size()));
    if (workers == 1) {
      work();
    } else {
      std::vector<std::thread> pool;
      for (std::size_t w = 0; w < workers; ++w) pool.emplace_back(work);
      for (auto& t : pool) t.join();
    }
  };
  const int stages = static_cast<int>(options.screening.size());
  for (int k = 0; k < stages && !stop && !error; ++k) {
    const ScreeningStage& stage = options.screening[static_cast<std::size_t>(k)];
    if (stage.iterations >= options.max_iterations) break;
    pass(k, stage.iterations);
    if (stop || error) break;
    // Every start has now run its stage's iterations or ended (a resumed solve finds the stages
    // already passed in `screened`).
    double lowest = std::numeric_limits<double>::infinity();
    for (const Start& s : starts)
      if (s.state == StartState::Done || (open(s) && s.screened == k)) lowest = std::min(lowest, s.cost);
    for (std::size_t s = 0; s < starts.size(); ++s) {
      Start& state = starts[s];
      if (!open(state) || state.screened != k) continue;
      if (state.state == StartState::Running && state.cost > stage.cost_ratio * lowest) {
        state.state = StartState::Done;
        std::ostringstream message;
        message << "screened out after " << stage.iterations << " iterations: cost " << state.cost << " > "
                << stage.cost_ratio << " x the lowest of all starts, " << lowest;
        state.message = message.str();
        if (options.after_start) options.after_start(s, starts);
      } else {
        state.screened = k + 1;
      }
    }
  }
  if (!stop && !error) {
    int passed = 0;  // the stages every open start has passed (all, or those below max_iterations)
    for (const ScreeningStage& stage : options.screening)
      if (stage.iterations < options.max_iterations) ++passed;
    pass(passed, options.max_iterations);
  }
  if (error) std::rethrow_exception(error);
  summary.completed = !stop;
  for (std::size_t s = 0; s < starts.size(); ++s)
    if (starts[s].state == StartState::Done && (!summary.best || starts[s].cost < starts[*summary.best].cost))
      summary.best = s;
  if (summary.completed && summary.best) {
    summary.x = starts[*summary.best].x;
    summary.cost = starts[*summary.best].cost;
  }
  summary.starts = std::move(starts);
  return summary;
}

}  // namespace dtwire::lsq
