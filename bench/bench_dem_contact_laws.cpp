// Contact updates per second per core of every DEM contact law on one mixed path: pull + biaxial
// bending into plasticity, unloading, elastic vibration with shear and torsion, reloading. Run in
// DEM order (every bond advanced by one step, then the next step) on a set of independent bonds;
// each pass starts from fresh bonds (clone of a prototype; the clones are a small part of a pass).
#include <benchmark/benchmark.h>

#include <cmath>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "dtwire/dem/contact_law.hpp"

namespace {

using dtwire::dem::ContactLaw;
using dtwire::dem::ParameterMap;
using dtwire::dem::Vector6;

Vector6 generalised(double u, double vy, double vz, double tx, double ty, double tz) {
  Vector6 q;
  q << u, vy, vz, tx, ty, tz;
  return q;
}

struct PathBuilder {
  std::vector<Vector6> increments;
  Vector6 position = Vector6::Zero();
  PathBuilder& to(const Vector6& target, int steps) {
    const Vector6 step = (target - position) / steps;
    for (int i = 0; i < steps; ++i) increments.push_back(step);
    position = target;
    return *this;
  }
};

// The mixed path (1000 increments of a DEM-like size, ~2.5 um and ~1 mrad): a pull onto the
// tension cap, unloading, elastic vibration of all six components, then a reload with bending.
// The share of plastic increments is measured and reported (plastic_share).
std::vector<Vector6> mixed_path() {
  PathBuilder path;
  path.to(generalised(0.5e-3, 0.0, 0.0, 0.0, 0.0, 0.0), 200)   // pull: elastic, then tension cap
      .to(generalised(0.35e-3, 0.0, 0.0, 0.0, 0.0, 0.0), 60);  // unloading
  for (int cycle = 0; cycle < 6; ++cycle)                        // elastic vibration
    path.to(generalised(0.37e-3, 2e-6, -1e-6, 0.002, 0.04, -0.02), 50)
        .to(generalised(0.33e-3, -2e-6, 1e-6, -0.002, -0.04, 0.02), 50);
  path.to(generalised(0.6e-3, 0.0, 0.0, 0.0, 0.15, 0.05), 140);  // reload with bending
  return path.increments;
}
// Breakdown: only elastic increments; only tension-cap plastic flow; bending with pull at low
// axial force (the stiff regime of the published flow rule).
std::vector<Vector6> elastic_path() {
  PathBuilder path;
  for (int cycle = 0; cycle < 10; ++cycle)
    path.to(generalised(0.1e-3, 2e-6, -1e-6, 0.002, 0.04, -0.02), 50)
        .to(generalised(-0.05e-3, -2e-6, 1e-6, -0.002, -0.04, 0.02), 50);
  return path.increments;
}
std::vector<Vector6> tension_path() {
  PathBuilder path;
  path.to(generalised(0.18e-3, 0.0, 0.0, 0.0, 0.0, 0.0), 1)
      .to(generalised(2.68e-3, 0.0, 0.0, 0.0, 0.0, 0.0), 1000);
  return path.increments;
}
std::vector<Vector6> bending_path() {
  PathBuilder path;
  path.to(generalised(0.0, 0.0, 0.0, 0.0, 0.2, 0.0), 1)
      .to(generalised(0.5e-3, 0.0, 0.0, 0.0, 0.3, 0.1), 1000);
  return path.increments;
}

ParameterMap thesis_single_wire() {
  return {{"D_m", 0.0027},   {"EA_N", 1.6e7},   {"EI_Nm2_per_deg_convention", 0.122},
          {"N0_N", 2750},    {"Nult_N", 3200},  {"Nc_N", 1650},
          {"m_f", 0.0285},   {"beta_f", 0.195}, {"k_F", 2.39e4},
          {"k_M", 1.12e3},   {"m_g", 4.78},     {"alpha_g", 0.5},
          {"beta_g", 0.0358}, {"W1_J", 9.21},   {"W2_J", 140.01},
          {"alpha_d", 2.7}};
}

// macro3d with its RK2(3) substepping instead of the default implicit return (the reference
// the implicit return is measured against; the integration before issue 18).
ParameterMap thesis_single_wire_rk() {
  ParameterMap p = thesis_single_wire();
  p["implicit_return"] = 0.0;
  return p;
}

ParameterMap parallel_bond_wire() {
  return {{"E_Pa", 2.0e11}, {"diameter_m", 2.7e-3}, {"length_m", 0.06},
          {"tensile_strength_Pa", 1.0e10}, {"shear_strength_Pa", 1.0e10}};  // strength checked, not reached
}

// WirePM with the bundled 2.7 mm backbone (experiments/data/sw_2.7mm_dem_backbone.csv).
ParameterMap wirepm_wire() {
  ParameterMap p = {{"reference_length_m", 0.06}, {"diameter_m", 2.7e-3}};
  std::ifstream file(std::string(DTWIRE_SOURCE_DIR) + "/experiments/data/sw_2.7mm_dem_backbone.csv");
  std::string line;
  int index = 0;
  while (std::getline(file, line)) {
    if (line.empty() || line[0] == '#' || line.find("strain") != std::string::npos) continue;
    std::istringstream fields(line);
    double strain = 0.0, stress = 0.0;
    char comma = 0;
    if (!(fields >> strain >> comma >> stress)) continue;
    p["backbone_" + std::to_string(index) + "_strain_1"] = strain;
    p["backbone_" + std::to_string(index) + "_stress_Pa"] = stress;
    ++index;
  }
  return p;
}

// Share of the increments with plastic flow (measured once, outside the timing).
double plastic_share(const ContactLaw& prototype, const std::vector<Vector6>& path) {
  auto law = prototype.clone();
  int plastic = 0;
  for (const Vector6& increment : path) {
    const double before = law->energy().plastic;
    law->update(increment);
    if (law->energy().plastic != before) ++plastic;
  }
  return static_cast<double>(plastic) / static_cast<double>(path.size());
}

void contact_updates(benchmark::State& state, const std::string& law, const ParameterMap& parameters,
                     const std::vector<Vector6>& path) {
  std::unique_ptr<ContactLaw> prototype;
  try {
    prototype = dtwire::dem::make_contact_law(law, parameters);
  } catch (const std::exception& error) {
    state.SkipWithError(error.what());
    return;
  }
  std::vector<std::unique_ptr<ContactLaw>> bonds(256);
  for (auto _ : state) {
    for (auto& bond : bonds) bond = prototype->clone();
    for (const Vector6& increment : path)
      for (auto& bond : bonds) bond->update(increment);
    benchmark::DoNotOptimize(bonds.front()->forces());
  }
  const double updates = static_cast<double>(path.size() * bonds.size());
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * updates));
  state.counters["ns_per_update"] =
      benchmark::Counter(updates * 1e-9, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.counters["plastic_share"] = plastic_share(*prototype, path);
}

#define DTWIRE_LAW_BENCHMARKS(path_name)                                                                     \
  BENCHMARK_CAPTURE(contact_updates, path_name##_parallel_bond, std::string("parallel_bond"), parallel_bond_wire(), \
                    path_name##_path())                                                                        \
      ->Unit(benchmark::kMillisecond);                                                                         \
  BENCHMARK_CAPTURE(contact_updates, path_name##_macro3d, std::string("macro3d"), thesis_single_wire(),       \
                    path_name##_path())                                                                        \
      ->Unit(benchmark::kMillisecond);                                                                         \
  BENCHMARK_CAPTURE(contact_updates, path_name##_macro3d_rk, std::string("macro3d"), thesis_single_wire_rk(), \
                    path_name##_path())                                                                        \
      ->Unit(benchmark::kMillisecond);                                                                         \
  BENCHMARK_CAPTURE(contact_updates, path_name##_thesis, std::string("thesis"), thesis_single_wire(),         \
                    path_name##_path())                                                                        \
      ->Unit(benchmark::kMillisecond);                                                                         \
  BENCHMARK_CAPTURE(contact_updates, path_name##_wirepm, std::string("wirepm"), wirepm_wire(), path_name##_path()) \
      ->Unit(benchmark::kMillisecond)

DTWIRE_LAW_BENCHMARKS(mixed);
DTWIRE_LAW_BENCHMARKS(elastic);
DTWIRE_LAW_BENCHMARKS(tension);
DTWIRE_LAW_BENCHMARKS(bending);

}  // namespace

BENCHMARK_MAIN();
