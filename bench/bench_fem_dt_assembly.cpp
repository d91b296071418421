// FE solver benchmark (not a test): what plasticity costs in the assembly. The double twist in
// tension (experiments/dt/dt_tension.prm, bundled level-0 mesh, wire-wire contact with friction)
// to 9 mm, once with the steel's hardening table (most points plastic) and once with a yield
// stress no point reaches (the same log-strain Hencky elasticity, no return mapping), both
// assembled by the same F-bar element. Reports each case's assembly rate in DoF-iterations per
// second and, on the plastic case, the ratio plastic / elastic (issue 18's goal: >= 0.8).
// Run: bench_fem_dt_assembly [--benchmark_filter=...]; under mpirun for 2 ranks.
#include <benchmark/benchmark.h>

#include <string>

#include "fem_bench_case.hpp"

namespace {

double elastic_rate = 0.0;  // DoF-iterations per second of the elastic case (run first)

std::string dt_tension_prm() {
  const std::string dt = std::string(DTWIRE_SOURCE_DIR) + "/experiments/dt/";
  std::string prm = read_text(dt + "dt_tension.prm");
  set_entry(prm, "Mesh file", dt + "dt_level0.msh");
  set_entry(prm, "Fields", "false");
  set_entry(prm, "Load path (mm)", "0:0, 0.2:9");
  return prm;
}

void dt_elastic(benchmark::State& state) {
  std::string prm = dt_tension_prm();
  set_entry(prm, "Hardening law", "linear\n  set Yield stress (MPa) = 1e7");
  run_fem_case(state, prm, "dt_elastic", "bench_fem_dt_assembly");
  elastic_rate = state.counters["dof_its_per_s_assembly"];
}

void dt_plastic(benchmark::State& state) {
  run_fem_case(state, dt_tension_prm(), "dt_plastic", "bench_fem_dt_assembly");
  if (elastic_rate > 0.0)
    state.counters["assembly_rate_vs_elastic"] = state.counters["dof_its_per_s_assembly"] / elastic_rate;
}

}  // namespace

BENCHMARK(dt_elastic)->Iterations(1)->Unit(benchmark::kSecond);
BENCHMARK(dt_plastic)->Iterations(1)->Unit(benchmark::kSecond);

int main(int argc, char** argv) { return run_fem_benchmarks(argc, argv); }
