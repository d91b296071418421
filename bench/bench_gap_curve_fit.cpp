// The two kernels every trial of a `gap` fit runs: an effect applied to the simulated curve and
// the result read at the laboratory's points (model_forces_at_lab), on the GapModes tests' curves
// (the Voce wire of gap/synthetic_curves.hpp, 600 points, and a lab curve of 600 noisy points).
// The diagnosis of one laboratory set runs them some 10^5-10^6 times (pairs, held-out refits,
// several loading modes), so their cost is the diagnosis's.
#include <benchmark/benchmark.h>

#include <random>

#include "dtwire/gap/curve_metrics.hpp"
#include "dtwire/gap/effects.hpp"
#include "dtwire/gap/synthetic_curves.hpp"

namespace {

using namespace dtwire::gap;

struct Curves {
  ForceCurve sim = voce_tension_curve();
  CurveScale scale = curve_scale(sim);
  Comparison lab;
  Curves() {
    std::mt19937 rng(7);
    LabSampling s;
    s.points = 600;
    s.noise_sigma_N = 0.004 * scale.peak_force_N;
    lab = make_comparison(sample_lab_curve(sim, s, rng));
  }
};

const Curves& curves() {
  static const Curves c;
  return c;
}

void ModelForcesAtLab(benchmark::State& state) {
  const Curves& c = curves();
  for (auto _ : state) benchmark::DoNotOptimize(model_forces_at_lab(c.sim, c.lab));
}
BENCHMARK(ModelForcesAtLab);

// An effect applied and read at the lab's points, as one residual of a fit does.
void EffectThenResidual(benchmark::State& state, const char* effect, std::vector<double> parameters) {
  const Curves& c = curves();
  const EffectSpec& spec = find_effect(effect);
  for (auto _ : state) {
    const ForceCurve model = spec.apply(c.sim, parameters, c.scale);
    benchmark::DoNotOptimize(normalised_area(model_forces_at_lab(model, c.lab), c.lab));
  }
}
BENCHMARK_CAPTURE(EffectThenResidual, grip_slip_spread, "grip_slip", {400.0, 2.0, 0.0, 200.0});
BENCHMARK_CAPTURE(EffectThenResidual, machine_compliance_hertz, "machine_compliance", {0.5, 0.67});
BENCHMARK_CAPTURE(EffectThenResidual, ductile_damage, "ductile_damage", {20.0, 0.3, 2.0});

}  // namespace

BENCHMARK_MAIN();
