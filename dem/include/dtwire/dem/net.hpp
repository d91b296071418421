#pragma once
// The wire net a DEM run advances: nodes (spheres with mass and rotational inertia) and links
// (one contact-library law per wire segment). SI units; positions in metres.
#include <Eigen/Core>
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "dtwire/dem/contact_law.hpp"

namespace dtwire::dem {

using Vector3 = Eigen::Vector3d;

enum class NodeFixity { Free, Pinned, Guided };  // Guided: moves at a prescribed velocity

struct NetNode {
  Vector3 position = Vector3::Zero();
  double mass = 0.0;                // gravitational mass [kg]
  double rotational_inertia = 0.0;  // [kg m^2], sphere-like (isotropic)
  double radius = 0.0;              // contact radius against tools [m]
  NodeFixity fixity = NodeFixity::Free;
  Vector3 guided_velocity = Vector3::Zero();  // [m/s], Guided nodes; held components of sliders
  // Free nodes only: translation components (x, y, z) and rotations held at zero velocity, a
  // slider support (e.g. a grip guided in x and z, free along y); the engine's unbalanced force
  // of a held component is minus the support's reaction.
  std::array<bool, 3> held_translation{};
  bool held_rotation = false;
};

// Which parameter set a link takes: single wire, double twist, selvedge wire.
enum class LinkTag { SingleWire, DoubleTwist, Selvedge };
std::string link_tag_name(LinkTag tag);  // "sw", "dt", "selvedge"

struct NetLink {
  int a = 0, b = 0;  // node indices; the local x axis points from a to b
  LinkTag tag = LinkTag::SingleWire;
  // The generator's link index in the two-node mesh this link is, or is a part of (a wire split
  // at its midpoint keeps its distortion draw); -1: not from the generator.
  int wire = -1;
  // The number of equal links in series the wire is split into (1: the whole wire).
  int parts = 1;
};

struct Net {
  std::vector<NetNode> nodes;
  std::vector<NetLink> links;
};

}  // namespace dtwire::dem
