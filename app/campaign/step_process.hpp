#pragma once
// A campaign step runs as a child dtwire process whose console output goes to a log file; the
// campaign reads the step's own progress (FE pseudo-time, fit start and iteration) from that
// log and from the logs the command writes beside its outputs.
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace dtwire::app {

// Runs `executable args...` in its own process group with stdout and stderr to `log`
// (truncated), stdin from /dev/null. Calls `tick(elapsed_seconds)` about once a second while it
// runs. When the campaign is interrupted (interruption.hpp), passes the signal on to the step's
// process group, and kills the group if it still runs 30 s later. Returns the exit code
// (128 + signal if it was killed).
// The step dies with the runner: on Linux the kernel sends it SIGTERM when the runner dies
// (prctl PR_SET_PDEATHSIG, set between fork and exec, then a check that the parent is still
// the runner), whatever killed the runner, SIGKILL included; a step's own steps started the same
// way (a gap run's `dem run`s) die with it in turn. `track(group, running)` is called when the
// step has started and when it has ended: the campaign lock records the running groups
// (campaign_lock.hpp).
int run_step_process(const std::filesystem::path& executable, const std::vector<std::string>& args,
                     const std::filesystem::path& log, const std::function<void(double)>& tick,
                     const std::function<void(int, bool)>& track = {});

// The newest progress the logs show, e.g. "FE step 12, t = 0.43" or "fit start 2/4, iteration 17";
// else the last line of the first log (shortened); "" if there is none. Only the tail of each
// file is read.
std::string step_progress(const std::vector<std::filesystem::path>& logs);

// The last non-empty line of a text file ("" if none).
std::string last_line(const std::filesystem::path& file);

}  // namespace dtwire::app
