#include "start_order.hpp"

#include <algorithm>
#include <numeric>
#include <stdexcept>
#include <string>

namespace dtwire::app {

std::vector<double> levels(const std::vector<std::vector<std::size_t>>& waits_for, const std::vector<double>& seconds) {
  if (waits_for.size() != seconds.size())
    throw std::invalid_argument("levels: " + std::to_string(waits_for.size()) + " steps but " +
                                std::to_string(seconds.size()) + " step times");
  const std::size_t n = seconds.size();
  std::vector<double> chain(seconds);  // in reverse file order: every step waiting for i comes later
  for (std::size_t i = n; i-- > 0;)
    for (const std::size_t j : waits_for[i]) {
      if (j >= i)
        throw std::invalid_argument("levels: step " + std::to_string(i) + " waits for step " + std::to_string(j) +
                                    ", not an earlier one");
      chain[j] = std::max(chain[j], seconds[j] + chain[i]);
    }
  return chain;
}

std::vector<std::size_t> start_order(const std::vector<std::vector<std::size_t>>& waits_for,
                                     const std::vector<std::optional<double>>& earlier_seconds) {
  double known_sum = 0.0;
  std::size_t known = 0;
  for (const auto& s : earlier_seconds)
    if (s && *s >= 0.0) {
      known_sum += *s;
      ++known;
    }
  const double unknown = known > 0 ? known_sum / static_cast<double>(known) : 1.0;
  std::vector<double> seconds;
  for (const auto& s : earlier_seconds) seconds.push_back(s && *s >= 0.0 ? *s : unknown);
  const std::vector<double> level = levels(waits_for, seconds);
  std::vector<std::size_t> order(level.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return level[a] > level[b]; });
  return order;
}

namespace {

// When the running steps' expected ends free `cores` (seconds from now), if every end needed is known.
std::optional<double> cores_free_at(std::vector<RunningStep> running, int free, int cores) {
  std::sort(running.begin(), running.end(), [](const RunningStep& a, const RunningStep& b) {
    return a.expected_remaining_seconds.value_or(1e300) < b.expected_remaining_seconds.value_or(1e300);
  });
  for (const RunningStep& step : running) {
    if (!step.expected_remaining_seconds) return std::nullopt;
    free += step.cores;
    if (free >= cores) return *step.expected_remaining_seconds;
  }
  return std::nullopt;
}

}  // namespace

std::vector<std::size_t> steps_to_start(const std::vector<ReadyStep>& ready_in_order,
                                        const std::vector<RunningStep>& running, int jobs) {
  std::vector<RunningStep> busy = running;
  int free = jobs;
  for (const RunningStep& step : busy) free -= step.cores;
  std::vector<std::size_t> starting;
  bool reserved = false;
  std::optional<double> reservation;  // when the waiting step's cores are expected free
  for (const ReadyStep& step : ready_in_order) {
    const bool fits = busy.empty() || step.cores <= free;
    if (!reserved && !fits) {
      reserved = true;
      reservation = cores_free_at(busy, free, step.cores);
      continue;
    }
    if (!fits) continue;
    if (reserved && !(reservation && step.expected_seconds && *step.expected_seconds <= *reservation)) continue;
    starting.push_back(step.index);
    free -= step.cores;
    busy.push_back({step.cores, step.expected_seconds});
  }
  return starting;
}

}  // namespace dtwire::app
