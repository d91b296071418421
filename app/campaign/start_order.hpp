#pragma once
// Which ready steps start when steps run side by side (`campaign --jobs N`): list scheduling by
// highest level first (HLFET; Adam, Chandy & Dickson 1974) with EASY backfilling (Lifka 1995).
// A step's level is the longest chain of step times from it to the campaign's end, itself
// included, so the steps that lead the critical path are offered cores first. The first ready
// step that needs more cores than are free holds its place: a step offered after it starts only
// if its time in an earlier run says that it ends before the running steps free the waiting
// step's cores. Before, any step that fitted started, in the file's order, and a two-thread step
// waited behind every one-thread step that fitted beside a running one (the default campaign's
// `dt_specimen_fit`, on its critical path, waited so for 15 minutes on 2 cores).
#include <cstddef>
#include <optional>
#include <vector>

namespace dtwire::app {

// levels[i]: step i's time plus the longest chain of the steps that wait for it, directly or
// not. waits_for as critical_path (each step waits for earlier steps only).
std::vector<double> levels(const std::vector<std::vector<std::size_t>>& waits_for, const std::vector<double>& seconds);

// The steps in the order they are offered cores: highest level first, ties in the file's order.
// Step times are each step's time in an earlier run where known, else the mean of the known
// ones, else 1 s for every step (a fresh folder: the chains count steps).
std::vector<std::size_t> start_order(const std::vector<std::vector<std::size_t>>& waits_for,
                                     const std::vector<std::optional<double>>& earlier_seconds);

struct ReadyStep {
  std::size_t index;
  int cores;
  std::optional<double> expected_seconds;  // its time in an earlier run
};
struct RunningStep {
  int cores;
  std::optional<double> expected_remaining_seconds;  // none: unknown, or past its earlier time
};

// The ready steps (in start order) that start now beside `running` on `jobs` cores: each in
// turn while it fits (any step when nothing runs). The first that does not fit is reserved the
// time at which the running steps' expected ends free its cores; after it, a step starts only if
// it fits and its expected time ends by then (none when a time needed is unknown).
std::vector<std::size_t> steps_to_start(const std::vector<ReadyStep>& ready_in_order,
                                        const std::vector<RunningStep>& running, int jobs);

}  // namespace dtwire::app
