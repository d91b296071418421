// Meshing time of the SW and DT meshes per refinement level (build, including the DT
// wire-wire clearance search, and MSH write).
#include <benchmark/benchmark.h>

#include <filesystem>
#include <unistd.h>

#include "dtwire/meshes/mesh_io.hpp"
#include "dtwire/meshes/wire_geometry.hpp"

namespace {

using namespace dtwire::meshes;

void build(benchmark::State& state, WireKind kind) {
  MeshParameters p = default_parameters(kind);
  p.level = static_cast<int>(state.range(0));
  std::size_t cells = 0;
  for (auto _ : state) {
    const WireMesh mesh = build_wire_mesh(p);
    cells = mesh.mesh.hexes.size();
    benchmark::DoNotOptimize(cells);
  }
  state.counters["cells"] = static_cast<double>(cells);
}

void build_and_write(benchmark::State& state, WireKind kind) {
  MeshParameters p = default_parameters(kind);
  p.level = static_cast<int>(state.range(0));
  const auto file = std::filesystem::temp_directory_path() / ("bench_meshes_" + std::to_string(::getpid()) + ".msh");
  for (auto _ : state) write_msh(build_wire_mesh(p).mesh, file);
  std::filesystem::remove(file);
}

void BM_SingleWireBuild(benchmark::State& state) { build(state, WireKind::Single); }
void BM_DoubleTwistBuild(benchmark::State& state) { build(state, WireKind::DoubleTwist); }
void BM_DoubleTwistBuildAndWriteMsh(benchmark::State& state) { build_and_write(state, WireKind::DoubleTwist); }

}  // namespace

BENCHMARK(BM_SingleWireBuild)->DenseRange(0, 3)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DoubleTwistBuild)->DenseRange(0, 3)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DoubleTwistBuildAndWriteMsh)->DenseRange(0, 2)->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
