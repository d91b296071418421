// FE solver benchmark (not a test): SW tension to failure (experiments/default/sw_tension.prm)
// at three mesh levels, with MUMPS and with GMRES + GAMG (rigid-body modes). Reports DoFs,
// steps, Newton iterations per step, assembly and solve time per iteration, total time, peak
// memory and the peak force. 1 vs 2 ranks: run it under `mpirun -np 2`.
#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include <fstream>
#include <sstream>
#include <stdexcept>

#include "dtwire/fem/run.hpp"
#include "fem_bench_case.hpp"

namespace {

std::string sw_tension_prm() {
  return read_text(std::string(DTWIRE_SOURCE_DIR) + "/experiments/default/sw_tension.prm");
}


// Level 0: 8-gon quarter section, 15 axial cells; 1: the default (30 cells); 2: 16-gon, 60 cells.
void sw_tension(benchmark::State& state, int level, const std::string& linear_solver) {
  std::string prm = sw_tension_prm();
  set_entry(prm, "Radial refinements", level < 2 ? "1" : "2");
  set_entry(prm, "Axial cells", std::to_string(15 << level));
  set_entry(prm, "Fields", "false");
  prm += "subsection Newton\n  set Linear solver = " + linear_solver + "\nend\n";
  const std::string key = "sw_tension_" + std::to_string(level) + "_" + linear_solver;
  run_fem_case(state, prm, key, "bench_fem_sw_tension");
}

}  // namespace

BENCHMARK_CAPTURE(sw_tension, level0_direct, 0, "direct")->Iterations(1)->Unit(benchmark::kSecond);
BENCHMARK_CAPTURE(sw_tension, level1_direct, 1, "direct")->Iterations(1)->Unit(benchmark::kSecond);
BENCHMARK_CAPTURE(sw_tension, level2_direct, 2, "direct")->Iterations(1)->Unit(benchmark::kSecond);
BENCHMARK_CAPTURE(sw_tension, level1_gmres_amg, 1, "gmres-amg")->Iterations(1)->Unit(benchmark::kSecond);
BENCHMARK_CAPTURE(sw_tension, level2_gmres_amg, 2, "gmres-amg")->Iterations(1)->Unit(benchmark::kSecond);

int main(int argc, char** argv) { return run_fem_benchmarks(argc, argv); }
