// FE solver benchmark (not a test): the Simo (1992) necking bar at three mesh levels, F-bar and
// plain displacement elements, and the default SW tension. Reports DoFs, steps, Newton
// iterations per step, assembly and solve time per iteration, assembly throughput
// (DoF-iterations per second), total time, peak memory, the load maximum vs the Considere
// estimate and the curve difference between successive levels up to the maximum.
// Run: bench_fem_necking [--benchmark_filter=...]; under mpirun for 2 ranks.
#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include <cmath>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>

#include "dtwire/core/csv.hpp"
#include "dtwire/core/curve_ops.hpp"
#include "dtwire/fem/run.hpp"
#include "fem_bench_case.hpp"

namespace {


double considere_peak() {  // imperfect mid-section, exact homogeneous Hencky bar
  const double r = 6.413e-3 * (1 - 0.018), A0 = M_PI * r * r;
  auto sy = [](double a) { return 450e6 + 265e6 * (1 - std::exp(-16.93 * a)) + 129.24e6 * a; };
  double best = 0;
  for (double a = 0; a < 0.5; a += 1e-5) best = std::max(best, sy(a) * A0 * std::exp(-a - sy(a) / 206.9e9));
  return best;
}

std::map<std::string, dtwire::Curve> curves;  // by "element/level", for the convergence figure

void run_case(benchmark::State& state, const std::string& prm_text, const std::string& key) {
  const dtwire::fem::RunSummary s = run_fem_case(state, prm_text, key, "bench_fem_necking");
  if (key.rfind("necking", 0) == 0) {
    state.counters["peak_vs_considere_pct"] = (s.peak_force_N / considere_peak() - 1) * 100;
    if (s.root) curves[key] = dtwire::read_csv(s.curve_csv);
    // Curve change from the previous level, up to the load maximum (max |dF| / F_max).
    const auto level = key.back() - '0';
    const auto previous = curves.find(key.substr(0, key.size() - 1) + std::to_string(level - 1));
    if (s.root && previous != curves.end()) {
      const auto& fine = curves[key];
      const auto u_f = fine.si("displacement"), f_f = fine.si("force");
      const auto u_c = previous->second.si("displacement"), f_c = previous->second.si("force");
      std::vector<double> u_up_to_peak;
      for (double u : u_f)
        if (u <= s.displacement_at_peak_mm * 1e-3) u_up_to_peak.push_back(u);
      const auto f_coarse = dtwire::interpolate(u_c, f_c, u_up_to_peak);
      double diff = 0;
      for (std::size_t i = 0; i < u_up_to_peak.size(); ++i) diff = std::max(diff, std::abs(f_f[i] - f_coarse[i]));
      state.counters["curve_change_vs_coarser_pct"] = diff / s.peak_force_N * 100;
    }
  }
}

void necking(benchmark::State& state, const std::string& element, int level) {
  std::string prm = read_text(std::string(DTWIRE_SOURCE_DIR) + "/experiments/verification/necking_bar.prm");
  set_entry(prm, "Radial refinements", std::to_string(level));
  set_entry(prm, "Axial cells", std::to_string(5 << level));
  set_entry(prm, "Element", element);
  set_entry(prm, "Fields", "false");
  run_case(state, prm, "necking_" + element + "_" + std::to_string(level));
}

void sw_tension(benchmark::State& state) {
  std::string prm = read_text(std::string(DTWIRE_SOURCE_DIR) + "/experiments/default/sw_tension.prm");
  set_entry(prm, "Fields", "false");
  run_case(state, prm, "sw_tension");
}

}  // namespace

BENCHMARK_CAPTURE(necking, fbar_level1, "fbar", 1)->Iterations(1)->Unit(benchmark::kSecond);
BENCHMARK_CAPTURE(necking, fbar_level2, "fbar", 2)->Iterations(1)->Unit(benchmark::kSecond);
BENCHMARK_CAPTURE(necking, fbar_level3, "fbar", 3)->Iterations(1)->Unit(benchmark::kSecond);
BENCHMARK_CAPTURE(necking, displacement_level1, "displacement", 1)->Iterations(1)->Unit(benchmark::kSecond);
BENCHMARK_CAPTURE(necking, displacement_level2, "displacement", 2)->Iterations(1)->Unit(benchmark::kSecond);
BENCHMARK(sw_tension)->Iterations(1)->Unit(benchmark::kSecond);

int main(int argc, char** argv) { return run_fem_benchmarks(argc, argv); }
