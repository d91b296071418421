#pragma once
// The engine tests' closed-form systems: the linear elastic bond of a 2.7 mm wire and the one-link
// oscillator built on it (a pinned node, a free node of 4.3 g, 50 mm of wire).
#include <cmath>
#include <memory>
#include <vector>

#include "net_node_support.hpp"
#include "dtwire/dem/engine.hpp"

namespace dtwire::dem::test {

constexpr double kPi = 3.14159265358979323846;

// A linear elastic bond: k_n = E A / L.
inline std::unique_ptr<ContactLaw> elastic_bond(double length) {
  return make_contact_law("parallel_bond", {{"E_Pa", 2e11}, {"diameter_m", 0.0027}, {"length_m", length}});
}
inline double elastic_bond_stiffness(double length) { return 2e11 * kPi * 0.0027 * 0.0027 / 4.0 / length; }

struct Oscillator {
  double mass = 0.0043, length = 0.05, k = elastic_bond_stiffness(0.05);
  double omega() const { return std::sqrt(k / mass); }
  Engine make(double dt, double amplitude) const {
    std::vector<NetNode> nodes{make_node(Vector3::Zero(), mass, NodeFixity::Pinned), make_node(Vector3(length, 0, 0), mass)};
    std::vector<EngineLink> links;
    links.push_back({{0, 1, LinkTag::SingleWire}, elastic_bond(length)});
    EngineOptions options;
    options.gravity = Vector3::Zero();
    options.time_step = dt;
    options.allow_above_critical = true;
    Engine engine(nodes, std::move(links), options);
    engine.impose_positions({Vector3::Zero(), Vector3(length + amplitude, 0, 0)});
    return engine;
  }
};

}  // namespace dtwire::dem::test
