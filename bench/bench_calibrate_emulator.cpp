// The Gaussian-process emulator of `dem propagate --emulator` (calibrate/emulator.hpp): the
// time to train it (leave-one-out fit of 13 hyperparameters) on n runs of 12 parameters, the
// propagation's size, and to predict one set, against the strip it replaces (about 17 CPU s).
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>

#include "dtwire/calibrate/emulator.hpp"

namespace {

struct Data {
  std::vector<std::vector<double>> x;
  std::vector<double> f;
};

// A one-sided response in two of 12 parameters with scatter, the strip strength's shape.
Data data(std::size_t n) {
  std::mt19937_64 generator(5);
  std::normal_distribution<double> normal;
  Data d;
  for (std::size_t j = 0; j < n; ++j) {
    std::vector<double> p(12);
    for (double& v : p) v = normal(generator);
    d.f.push_back(70.0 - 8.0 * std::log1p(std::exp(2.0 * p[1])) + 1.5 * p[0] + 0.5 * normal(generator));
    d.x.push_back(p);
  }
  return d;
}

void BM_EmulatorTrain(benchmark::State& state) {
  const Data d = data(static_cast<std::size_t>(state.range(0)));
  for (auto _ : state) {
    dtwire::calibrate::GaussianProcessEmulator emulator(d.x, d.f);
    benchmark::DoNotOptimize(emulator.q_squared());
  }
}
BENCHMARK(BM_EmulatorTrain)->Arg(30)->Arg(60)->Arg(120)->Unit(benchmark::kMillisecond);

void BM_EmulatorPredict(benchmark::State& state) {
  const Data d = data(static_cast<std::size_t>(state.range(0)));
  const dtwire::calibrate::GaussianProcessEmulator emulator(d.x, d.f);
  const std::vector<double> point(12, 0.3);
  for (auto _ : state) benchmark::DoNotOptimize(emulator.predict(point));
}
BENCHMARK(BM_EmulatorPredict)->Arg(60)->Arg(120)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
