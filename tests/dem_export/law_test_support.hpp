#pragma once
// Shared helpers of the contact-law tests: the published parameter sets and the thesis' driver
// loadings as increment sequences.
#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "dtwire/dem/contact_law.hpp"

namespace dtwire::dem::test {

constexpr double pi = 3.141592653589793238462643383279502884;

// "single_wire" or "double_twist" of experiments/data/macroelement_thesis_params.json.
inline ParameterMap thesis_parameters(const std::string& wire) {
  std::ifstream file(std::string(DTWIRE_SOURCE_DIR) + "/experiments/data/macroelement_thesis_params.json");
  if (!file) throw std::runtime_error("cannot open macroelement_thesis_params.json");
  const nlohmann::json json = nlohmann::json::parse(file);
  ParameterMap parameters;
  for (const auto& [key, value] : json.at(wire).items())
    if (value.is_number()) parameters[key] = value.get<double>();
  return parameters;
}

inline Vector6 generalised(double axial, double rotation_y, double rotation_z = 0.0) {
  Vector6 q = Vector6::Zero();
  q[0] = axial;
  q[4] = rotation_y;
  q[5] = rotation_z;
  return q;
}

// A path is a list of increments; each leg goes linearly to a target total displacement.
struct PathBuilder {
  Vector6 position = Vector6::Zero();
  std::vector<Vector6> increments;

  PathBuilder& to(const Vector6& target, int steps) {
    const Vector6 step = (target - position) / steps;
    for (int i = 0; i < steps; ++i) increments.push_back(step);
    position = target;
    return *this;
  }
};

// All six generalised displacements (axial, shear y, shear z, torsion, bending y, bending z).
inline Vector6 full(double u, double vy, double vz, double tx, double ty, double tz) {
  Vector6 q;
  q << u, vy, vz, tx, ty, tz;
  return q;
}

// Five legs through tension, compression, biaxial bending with reversals, shear and torsion.
inline PathBuilder mixed_3d_legs(int steps_per_leg) {
  return PathBuilder{}
      .to(full(0.3e-3, 0.1e-3, 0.0, 0.02, 0.10, 0.05), steps_per_leg)
      .to(full(0.1e-3, -0.1e-3, 0.05e-3, -0.03, -0.05, 0.20), steps_per_leg)
      .to(full(-0.4e-3, 0.0, 0.1e-3, 0.0, 0.10, -0.10), steps_per_leg)
      .to(full(0.8e-3, 0.2e-3, 0.0, 0.05, -0.20, -0.25), steps_per_leg)
      .to(full(2.0e-3, 0.0, 0.0, 0.0, 0.30, 0.10), steps_per_leg);
}

// The thesis' driver loadings (a) axial pull, (b) compression, (c) spin, (d) pull + spin; the
// free oscillation (e) is dynamic, see the oscillation test. Magnitudes for the 2.7 mm wire.
inline std::vector<Vector6> axial_pull(double elongation, int steps) {
  return PathBuilder{}.to(generalised(elongation, 0.0), steps).increments;
}
inline std::vector<Vector6> compression(double shortening, int steps) {
  return PathBuilder{}.to(generalised(-shortening, 0.0), steps).increments;
}
inline std::vector<Vector6> spin(double rotation, int steps) {
  return PathBuilder{}.to(generalised(0.0, rotation), steps).increments;
}
inline std::vector<Vector6> pull_spin(double elongation, double rotation, int steps) {
  return PathBuilder{}.to(generalised(elongation, rotation), steps).increments;
}
// Loading, unloading into compression and bending reversal, reloading: planar cycles.
inline std::vector<Vector6> planar_cycles(int steps_per_leg) {
  return PathBuilder{}
      .to(generalised(0.6e-3, 0.05), steps_per_leg)
      .to(generalised(0.2e-3, -0.08), steps_per_leg)
      .to(generalised(-0.3e-3, 0.0), steps_per_leg)
      .to(generalised(1.2e-3, 0.12), steps_per_leg)
      .to(generalised(0.9e-3, -0.2), steps_per_leg)
      .increments;
}

// Runs a path, calling `check(step)` after every update; stops at break.
inline void run(ContactLaw& law, const std::vector<Vector6>& increments,
                const std::function<void(std::size_t)>& check = {}) {
  for (std::size_t i = 0; i < increments.size() && !law.broken(); ++i) {
    law.update(increments[i]);
    if (check) check(i);
  }
}

// The published yield surface, written out independently of the library (normalised: 0 on the
// surface): tension (M/D)^2 + m_f h (F^2 - Ny^2) = 0, compression F^2/Nc^2 + (M/M_Y)^2 = 1.
inline double published_surface(const ParameterMap& p, double F, double M, double Ny) {
  const double D = p.at("D_m"), m_f = p.at("m_f");
  if (F >= 0.0) {
    const double h = std::exp(-std::pow(F / (2.0 * Ny), 2) / p.at("beta_f"));
    return ((M / D) * (M / D) + m_f * h * (F * F - Ny * Ny)) / (m_f * Ny * Ny);
  }
  const double MY = D * std::sqrt(m_f) * Ny;
  return F * F / (p.at("Nc_N") * p.at("Nc_N")) + (M / MY) * (M / MY) - 1.0;
}

}  // namespace dtwire::dem::test
