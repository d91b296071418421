#pragma once
// The campaign's critical path: the chain of steps, each waiting for the one before it
// (campaign_graph.hpp), whose step times add up to the most. It is the floor of the campaign's
// wall time on any number of cores: no step of the chain can start before the one it waits for
// has finished. Longest path in a DAG by one pass in topological order; the file's step order
// is one, since a step only waits for earlier steps.
#include <cstddef>
#include <vector>

namespace dtwire::app {

struct CriticalPath {
  std::vector<std::size_t> steps;  // first to last
  double seconds = 0.0;            // the chain's summed step time
};

// waits_for[i]: the earlier steps step i waits for; seconds[i]: its step time (0 for a step
// that did not run). Throws std::invalid_argument if the sizes differ, a step waits for itself
// or a later step, or a time is negative or not finite.
CriticalPath critical_path(const std::vector<std::vector<std::size_t>>& waits_for,
                           const std::vector<double>& seconds);

}  // namespace dtwire::app
