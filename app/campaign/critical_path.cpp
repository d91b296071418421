#include "critical_path.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace dtwire::app {

CriticalPath critical_path(const std::vector<std::vector<std::size_t>>& waits_for,
                           const std::vector<double>& seconds) {
  if (waits_for.size() != seconds.size())
    throw std::invalid_argument("critical path: " + std::to_string(waits_for.size()) + " steps but " +
                                std::to_string(seconds.size()) + " step times");
  const std::size_t n = seconds.size();
  std::vector<double> finish(n, 0.0);       // the longest chain ending with step i
  std::vector<std::size_t> previous(n, n);  // its step before i (n: none)
  CriticalPath path;
  std::size_t last = n;
  for (std::size_t i = 0; i < n; ++i) {
    if (!(seconds[i] >= 0.0) || !std::isfinite(seconds[i]))
      throw std::invalid_argument("critical path: step " + std::to_string(i) + " has time " + std::to_string(seconds[i]));
    double start = 0.0;
    for (const std::size_t j : waits_for[i]) {
      if (j >= i)
        throw std::invalid_argument("critical path: step " + std::to_string(i) + " waits for step " +
                                    std::to_string(j) + ", not an earlier one");
      if (finish[j] > start) {
        start = finish[j];
        previous[i] = j;
      }
    }
    finish[i] = start + seconds[i];
    if (last == n || finish[i] > finish[last]) last = i;
  }
  if (last == n) return path;
  path.seconds = finish[last];
  for (std::size_t i = last; i != n; i = previous[i]) path.steps.insert(path.steps.begin(), i);
  return path;
}

}  // namespace dtwire::app
