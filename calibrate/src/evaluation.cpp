#include "dtwire/calibrate/evaluation.hpp"

#include <algorithm>
#include <cmath>
#include <cctype>
#include <exception>
#include <iterator>
#include <thread>

#include "dtwire/core/csv.hpp"
#include "dtwire/core/error.hpp"
#include "dtwire/core/provenance.hpp"

namespace dtwire::calibrate {
namespace {

// Runs task(i) for i in [0, count) on up to `threads` threads.
template <class Task>
void parallel_for(std::size_t count, unsigned threads, const Task& task) {
  const std::size_t workers = std::min<std::size_t>(std::max(1u, threads), count);
  if (workers <= 1) {
    for (std::size_t i = 0; i < count; ++i) task(i);
    return;
  }
  std::atomic<std::size_t> next{0};
  std::vector<std::thread> pool;
  for (std::size_t w = 0; w < workers; ++w)
    pool.emplace_back([&] {
      for (std::size_t i = next++; i < count; i = next++) task(i);
    });
  for (auto& t : pool) t.join();
}

}  // namespace

std::string failure_kind(const std::string& message) {
  // The experiment's name is kept as it is (it may hold digits: pull_angle_47deg).
  const std::size_t body = message.rfind("experiment '", 0) == 0 ? message.find("': ") : std::string::npos;
  std::string out = body == std::string::npos ? "" : message.substr(0, body + 3);
  const auto digit = [](char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; };
  for (std::size_t i = out.size(); i < message.size();) {
    const bool sign = (message[i] == '-' || message[i] == '+') && i + 1 < message.size() && digit(message[i + 1]) &&
                      (i == 0 || !std::isalnum(static_cast<unsigned char>(message[i - 1])));
    if (!digit(message[i]) && !sign) {
      out += message[i++];
      continue;
    }
    // A number: sign, digits, fraction, exponent.
    i += sign ? 1 : 0;
    while (i < message.size() && (digit(message[i]) || message[i] == '.')) ++i;
    if (i + 1 < message.size() && (message[i] == 'e' || message[i] == 'E') &&
        (digit(message[i + 1]) || ((message[i + 1] == '-' || message[i + 1] == '+') && i + 2 < message.size() &&
                                   digit(message[i + 2])))) {
      i += 2;
      while (i < message.size() && digit(message[i])) ++i;
    }
    out += '#';
  }
  return out;
}

std::string evaluation_key(const Simulator& simulator, const ParameterValues& parameters) {
  std::string text = simulator.identity();
  text += "\n--- parameters\n";
  for (const auto& [name, value] : parameters) text += name + "=" + format_number(value) + "\n";
  return sha256_text(text);
}

ResultsCache::ResultsCache(std::filesystem::path directory) : directory_(std::move(directory)) {
  if (!directory_.empty()) std::filesystem::create_directories(directory_);
}

std::optional<ResultsCache::Entry> ResultsCache::find(const std::string& key) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    const auto found = entries_.find(key);
    if (found != entries_.end()) return found->second;
  }
  if (directory_.empty()) return std::nullopt;
  const auto file = directory_ / (key + ".csv");
  if (!std::filesystem::exists(file)) return std::nullopt;
  Entry entry{read_csv(file), {}};
  std::lock_guard<std::mutex> lock(mutex_);
  entries_[key] = entry;
  return entry;
}

void ResultsCache::store(const std::string& key, const Entry& entry) {
  if (!directory_.empty() && entry.curve) write_csv(*entry.curve, directory_ / (key + ".csv"));
  std::lock_guard<std::mutex> lock(mutex_);
  entries_[key] = entry;
}

ProblemEvaluator::ProblemEvaluator(std::vector<Experiment> experiments,
                                   std::vector<ParameterDefinition> parameters,
                                   EvaluationOptions options)
    : experiments_(std::move(experiments)),
      parameters_(std::move(parameters)),
      options_(options),
      cache_(options.cache_directory) {
  validate(parameters_);
  if (experiments_.empty()) throw std::invalid_argument("no experiments to fit");
  if (options_.threads == 0) options_.threads = std::max(1u, std::thread::hardware_concurrency());
  if (!(options_.relative_step > 0 && options_.relative_step < 1))
    throw std::invalid_argument("relative_step must lie in (0, 1)");
  for (const auto& e : experiments_) {
    validate(e);
    residual_count_ += calibrate::residual_count(e);
    if (!e.simulator->thread_safe() && !serial_locks_.count(e.simulator.get()))
      serial_locks_[e.simulator.get()] = std::make_unique<std::mutex>();
  }
}

std::vector<double> ProblemEvaluator::to_scaled(const std::vector<double>& values) const {
  std::vector<double> z(values.size());
  for (std::size_t i = 0; i < values.size(); ++i) z[i] = parameters_[i].to_coordinate(values[i]);
  return z;
}

std::vector<double> ProblemEvaluator::from_scaled(const std::vector<double>& z) const {
  std::vector<double> x(z.size());
  for (std::size_t i = 0; i < z.size(); ++i) x[i] = parameters_[i].from_coordinate(z[i]);
  return x;
}

Curve ProblemEvaluator::run(std::size_t experiment, const ParameterValues& values) {
  const Simulator& simulator = *experiments_[experiment].simulator;
  const std::string key = evaluation_key(simulator, values);
  if (auto hit = cache_.find(key)) {
    ++cache_hits_;
    if (!hit->failure.empty()) throw ComputationError(hit->failure);
    return *hit->curve;
  }
  std::unique_lock<std::mutex> serial;
  if (const auto lock = serial_locks_.find(&simulator); lock != serial_locks_.end())
    serial = std::unique_lock<std::mutex>(*lock->second);
  // A run slot after the simulator's own lock: a thread waiting for that lock holds no slot.
  {
    std::unique_lock<std::mutex> slots(slots_mutex_);
    slot_freed_.wait(slots, [&] { return runs_in_progress_ < options_.threads; });
    ++runs_in_progress_;
  }
  struct SlotRelease {
    ProblemEvaluator& self;
    ~SlotRelease() {
      {
        const std::lock_guard<std::mutex> slots(self.slots_mutex_);
        --self.runs_in_progress_;
      }
      self.slot_freed_.notify_one();
    }
  } release{*this};
  ++simulations_;
  try {
    Curve curve = simulator.simulate(values);
    cache_.store(key, {curve, {}});
    return curve;
  } catch (const ComputationError& error) {
    ++failures_;
    const std::string message = "experiment '" + experiments_[experiment].name + "': " + error.what();
    {
      std::lock_guard<std::mutex> lock(failure_kinds_mutex_);
      ++failure_kinds_[failure_kind(message)];
    }
    cache_.store(key, {std::nullopt, message});
    throw ComputationError(message);
  }
}

std::vector<ProblemEvaluator::Outcome> ProblemEvaluator::evaluate_points(
    const std::vector<std::vector<double>>& z_points) {
  const std::size_t n_exp = experiments_.size();
  std::vector<std::vector<double>> parts(z_points.size() * n_exp);
  std::vector<std::string> failures(parts.size());
  std::vector<ParameterValues> values;
  for (const auto& z : z_points) values.push_back(to_values(parameters_, from_scaled(z)));
  parallel_for(parts.size(), options_.threads, [&](std::size_t task) {
    const std::size_t point = task / n_exp, e = task % n_exp;
    try {
      parts[task] = calibrate::residuals(experiments_[e], run(e, values[point]));
    } catch (const ComputationError& error) {
      failures[task] = error.what();
    } catch (const std::exception& error) {
      // A simulator that rejects trial values with another exception type still only fails
      // this evaluation.
      failures[task] = "experiment '" + experiments_[e].name + "': " + error.what();
    }
  });
  std::vector<Outcome> out(z_points.size());
  for (std::size_t p = 0; p < z_points.size(); ++p) {
    for (std::size_t e = 0; e < n_exp; ++e) {
      const std::size_t task = p * n_exp + e;
      if (!failures[task].empty() && out[p].failure.empty()) out[p].failure = failures[task];
      out[p].residuals.insert(out[p].residuals.end(), parts[task].begin(), parts[task].end());
    }
  }
  return out;
}

std::vector<double> ProblemEvaluator::residuals(const std::vector<double>& z) {
  Outcome outcome = std::move(evaluate_points({z}).front());
  if (!outcome.failure.empty()) throw ComputationError(outcome.failure);
  return std::move(outcome.residuals);
}

void ProblemEvaluator::residuals_and_jacobian(const std::vector<double>& z,
                                              std::vector<double>& residuals,
                                              std::vector<double>& jacobian) {
  const std::size_t n = z.size(), m = residual_count_;
  std::vector<double> lower(n), upper(n), h(n);
  for (std::size_t j = 0; j < n; ++j) {
    lower[j] = parameters_[j].to_coordinate(parameters_[j].lower);
    upper[j] = parameters_[j].to_coordinate(parameters_[j].upper);
    h[j] = options_.relative_step * std::max(std::abs(z[j]), 1.0);
  }
  // The base point first: where it fails (e.g. a set the law rejects, Nult < N0, which the
  // bounds alone do not exclude) there is no Jacobian to take, and running its stencil would
  // only add n failed runs per experiment.
  auto base = evaluate_points({z});
  if (!base[0].failure.empty()) throw ComputationError(base[0].failure);
  residuals = std::move(base[0].residuals);

  // Step directions per column: forward (or central), away from a bound it would cross.
  std::vector<std::vector<double>> points{z};
  std::vector<std::pair<std::size_t, double>> columns;  // (column, signed step) per point
  columns.emplace_back(n, 0.0);
  for (std::size_t j = 0; j < n; ++j) {
    double step = z[j] + h[j] <= upper[j] ? h[j] : -h[j];
    std::vector<double> p = z;
    p[j] += step;
    points.push_back(p);
    columns.emplace_back(j, step);
    if (options_.central_differences && z[j] - h[j] >= lower[j] && z[j] + h[j] <= upper[j]) {
      p[j] = z[j] - h[j];
      points.push_back(p);
      columns.emplace_back(j, -h[j]);
    }
  }
  std::vector<Outcome> outcomes(1);
  {
    auto perturbed = evaluate_points(std::vector<std::vector<double>>(points.begin() + 1, points.end()));
    std::move(perturbed.begin(), perturbed.end(), std::back_inserter(outcomes));
  }

  {
    const std::lock_guard<std::mutex> lock(last_jacobian_mutex_);
    last_jacobian_point_ = z;
    last_step_failures_.assign(n, "");
    for (std::size_t k = 1; k < points.size(); ++k)
      if (!outcomes[k].failure.empty() && last_step_failures_[columns[k].first].empty())
        last_step_failures_[columns[k].first] = outcomes[k].failure;
  }

  // Retry failed perturbed runs: opposite direction, then a tenth of the step.
  for (int attempt = 0; attempt < 2; ++attempt) {
    std::vector<std::size_t> failed;
    for (std::size_t k = 1; k < points.size(); ++k)
      if (!outcomes[k].failure.empty()) failed.push_back(k);
    if (failed.empty()) break;
    std::vector<std::vector<double>> retry;
    for (std::size_t k : failed) {
      auto& [j, step] = columns[k];
      step = attempt == 0 ? -step : step / 10.0;
      if (z[j] + step > upper[j] || z[j] + step < lower[j]) step = -step;
      std::vector<double> p = z;
      p[j] += step;
      retry.push_back(p);
    }
    auto again = evaluate_points(retry);
    for (std::size_t r = 0; r < failed.size(); ++r) outcomes[failed[r]] = std::move(again[r]);
  }

  jacobian.assign(m * n, 0.0);
  std::vector<int> samples(n, 0);
  for (std::size_t k = 1; k < points.size(); ++k) {
    if (!outcomes[k].failure.empty())
      throw ComputationError("finite difference for parameter '" + parameters_[columns[k].first].name +
                             "' failed: " + outcomes[k].failure);
    ++samples[columns[k].first];
  }
  // One sample: one-sided difference; two: central difference (r+ - r-) / (2h).
  for (std::size_t k = 1; k < points.size(); ++k) {
    const auto [j, step] = columns[k];
    for (std::size_t i = 0; i < m; ++i) {
      const double slope = (outcomes[k].residuals[i] - residuals[i]) / step;
      jacobian[i * n + j] += slope / samples[j];
    }
  }
}

void ProblemEvaluator::residuals_and_secant_jacobian(const std::vector<double>& z, const std::vector<double>& steps,
                                                     std::vector<double>& residuals, std::vector<double>& jacobian) {
  const std::size_t n = z.size(), m = residual_count_;
  if (steps.size() != n) throw std::invalid_argument("residuals_and_secant_jacobian: one step per coordinate");
  std::vector<std::vector<double>> points{z};
  std::vector<std::pair<std::size_t, double>> columns{{n, 0.0}};  // (column, signed step) per point
  for (std::size_t j = 0; j < n; ++j) {
    const double lower = parameters_[j].to_coordinate(parameters_[j].lower);
    const double upper = parameters_[j].to_coordinate(parameters_[j].upper);
    for (const double step : {steps[j], -steps[j]}) {
      if (z[j] + step > upper || z[j] + step < lower) continue;
      std::vector<double> p = z;
      p[j] += step;
      points.push_back(p);
      columns.emplace_back(j, step);
    }
  }
  std::vector<Outcome> outcomes = evaluate_points(points);
  if (!outcomes[0].failure.empty()) throw ComputationError(outcomes[0].failure);
  residuals = outcomes[0].residuals;
  jacobian.assign(m * n, 0.0);
  std::vector<std::vector<std::size_t>> sides(n);
  for (std::size_t k = 1; k < points.size(); ++k)
    if (outcomes[k].failure.empty()) sides[columns[k].first].push_back(k);
  for (std::size_t j = 0; j < n; ++j) {
    if (sides[j].empty())
      throw ComputationError("secant for parameter '" + parameters_[j].name + "': no side runs");
    // Two sides: the central difference (r+ - r-) / 2s; one: one-sided from the point.
    for (std::size_t i = 0; i < m; ++i) {
      const std::size_t a = sides[j].front();
      jacobian[i * n + j] =
          sides[j].size() == 2
              ? (outcomes[a].residuals[i] - outcomes[sides[j].back()].residuals[i]) / (2.0 * columns[a].second)
              : (outcomes[a].residuals[i] - residuals[i]) / columns[a].second;
    }
  }
}

std::vector<Curve> ProblemEvaluator::simulate(const std::vector<double>& values) {
  std::vector<Curve> curves;
  const ParameterValues named = to_values(parameters_, values);
  for (std::size_t e = 0; e < experiments_.size(); ++e) curves.push_back(run(e, named));
  return curves;
}

void ProblemEvaluator::set_relative_step(double relative_step) {
  if (!(relative_step > 0 && relative_step < 1)) throw std::invalid_argument("relative_step must lie in (0, 1)");
  options_.relative_step = relative_step;
}

EvaluationStatistics ProblemEvaluator::statistics() const {
  std::lock_guard<std::mutex> lock(failure_kinds_mutex_);
  return {simulations_.load(), cache_hits_.load(), failures_.load(), failure_kinds_};
}

}  // namespace dtwire::calibrate
