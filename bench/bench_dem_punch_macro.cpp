// Timed run (not a test): the campaign's 3 x 3 m macro-element punch with the thesis sets in the
// set-up the study settled on (slack state: settled 40 s onto a wall 0.1 m below; platter kn 1e8,
// ks 1e7; docs/dem_engine.md "Speed"), on 1 and 2 threads: wall time, steps, time per step, the
// speed-up, and the peak and onset (the curve must not depend on the thread count: the engine's
// sums run in a fixed order). Issue 35's goal: under 2 minutes on 2 cores.
//   build/bench/bench_dem_punch_macro [THREADS...]   (default: 1 2)
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <vector>

#include "dtwire/dem/run.hpp"

using namespace dtwire::dem;

int main(int argc, char** argv) {
  std::vector<int> thread_counts;
  for (int i = 1; i < argc; ++i) thread_counts.push_back(std::atoi(argv[i]));
  if (thread_counts.empty()) thread_counts = {1, 2};
  const std::filesystem::path file = std::string(DTWIRE_SOURCE_DIR) + "/experiments/dem/punch_macro.toml";
  const RunInput input = read_run_input(file, {"boundary.pretension_strain=0.0", "boundary.wall_below_m=0.1",
                                               "dynamics.settle_s=40.0", "tool.kn_N_per_m=1e8", "tool.ks_N_per_m=1e7"});
  const auto dir = std::filesystem::temp_directory_path() / "dtwire_bench_dem_punch_macro";
  double one_thread_seconds = 0.0;
  for (int threads : thread_counts) {
    RunOptions options;
    options.out = dir / ("threads_" + std::to_string(threads));
    options.quiet = true;
    options.write_frames = false;
    options.threads = threads;
    const RunSummary run = run_simulation(input, options);
    if (threads == 1) one_thread_seconds = run.wall_seconds;
    std::cout << threads << " thread(s): " << run.wall_seconds << " s wall, " << run.steps << " steps, "
              << 1e3 * run.wall_seconds / static_cast<double>(run.steps) << " ms per step";
    if (one_thread_seconds > 0.0 && threads != 1) std::cout << ", speed-up " << one_thread_seconds / run.wall_seconds;
    std::cout << "; peak " << run.peak_force / 1000.0 << " kN at " << 1000.0 * run.displacement_at_peak << " mm, onset "
              << 1000.0 * run.onset << " mm\n";
  }
  return 0;
}
