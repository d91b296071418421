#pragma once
// A net node of the engine tests: a 5.4 mm sphere (Thoeni et al. 2013) of the given mass, its
// rotational inertia a solid sphere's.
#include "dtwire/dem/net.hpp"

namespace dtwire::dem::test {

inline NetNode make_node(const Vector3& p, double mass, NodeFixity fixity = NodeFixity::Free) {
  NetNode node;
  node.position = p;
  node.mass = mass;
  node.rotational_inertia = 0.4 * mass * 0.0054 * 0.0054;
  node.radius = 0.0054;
  node.fixity = fixity;
  return node;
}

}  // namespace dtwire::dem::test
