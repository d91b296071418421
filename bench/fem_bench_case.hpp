#pragma once
// Shared by the FE benchmarks: run one .prm text as a benchmark case and report the solver's
// figures (DoFs, steps, Newton iterations, assembly and solve time per iteration, assembly
// throughput, total time, peak memory, peak force) as Google Benchmark counters.
#include <benchmark/benchmark.h>
#include <deal.II/base/mpi.h>
#include <sys/resource.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "dtwire/fem/run.hpp"

inline std::string read_text(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// Replaces the value of `set key = ...` in a .prm text.
inline void set_entry(std::string& prm, const std::string& key, const std::string& value) {
  const auto pos = prm.find("set " + key + " =");
  if (pos == std::string::npos) throw std::runtime_error("no entry " + key);
  prm.replace(pos, prm.find('\n', pos) - pos, "set " + key + " = " + value);
}

inline dtwire::fem::RunSummary run_fem_case(benchmark::State& state, const std::string& prm_text,
                                            const std::string& key, const std::string& bench_name) {
  const auto dir = std::filesystem::temp_directory_path() / ("dtwire_bench_fem_" + key);
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "case.prm") << prm_text;
  dtwire::fem::RunOptions options;
  options.parameter_file = dir / "case.prm";
  options.output_directory = dir / "out";
  options.command_line = bench_name + " " + key;
  options.echo = false;
  dtwire::fem::RunSummary s;
  for (auto _ : state) s = dtwire::fem::run_experiment(options);
  const double iterations = static_cast<double>(s.newton_iterations + s.steps);  // + predictor solves
  state.counters["dofs"] = static_cast<double>(s.dofs);
  state.counters["ranks"] = s.ranks;
  state.counters["steps"] = static_cast<double>(s.steps);
  state.counters["newton_per_step"] = static_cast<double>(s.newton_iterations) / static_cast<double>(s.steps);
  state.counters["cutbacks"] = static_cast<double>(s.cutbacks);
  state.counters["assembly_s_per_it"] = s.assembly_seconds / iterations;
  state.counters["solve_s_per_it"] = s.solve_seconds / iterations;
  state.counters["dof_its_per_s_assembly"] = static_cast<double>(s.dofs) * iterations / s.assembly_seconds;
  state.counters["total_s"] = s.wall_seconds;
  state.counters["peak_force_kN"] = s.peak_force_N * 1e-3;
  state.counters["u_at_peak_mm"] = s.displacement_at_peak_mm;
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  state.counters["peak_rss_MB"] = static_cast<double>(usage.ru_maxrss) / 1024.0;
  return s;
}

// main() of an FE benchmark: MPI and PETSc live for the whole run (under mpirun for 2 ranks).
inline int run_fem_benchmarks(int argc, char** argv) {
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv);
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
