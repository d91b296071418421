// The engine's private state, shared by its set-up and accessors (engine.cpp) and its step
// (engine_step.cpp); not part of the public interface (engine.hpp).
#pragma once

#include <array>
#include <cstddef>
#include <memory>
#include <vector>

#include "dtwire/dem/engine.hpp"

namespace dtwire::dem {
namespace engine_detail {

struct LinkState {
  Vector3 transverse = Vector3::UnitX();  // local y axis t1
  Vector3 axis = Vector3::UnitX();        // this step's a -> b
  Vector3 binormal = Vector3::UnitZ();    // t2 = axis x t1
  double length = 0.0;
  Vector6 increment = Vector6::Zero();    // this step's, of the six generalised displacements
  bool broken = false;
};

// What a link puts on its nodes, apart from its state: the nodes gather these at random, so they
// sit in a compact array of their own.
struct LinkLoad {
  Vector3 force_on_a = Vector3::Zero();
  std::array<Vector3, 2> moment{Vector3::Zero(), Vector3::Zero()};  // on end a, on end b
};

// A node's link, as the node loop gathers it: which end the node is (0: a, 1: b) indexes the
// link's moments and gives the force's sign without a branch (the ends come in no order, and a
// mispredicted branch per link cost more than the gather's arithmetic).
struct NodeLinkEntry {
  int link = 0;
  int end = 0;
};

struct ToolState {
  std::unique_ptr<Tool> tool;
  std::vector<Vector3> shear, force_on_node, moment_on_node, contact_point;
  std::vector<double> contact_energy, friction_increment;
  std::vector<char> touching;
  Vector3 previous_position = Vector3::Zero();
  Vector3 force_on_tool = Vector3::Zero(), moment_on_tool = Vector3::Zero();
  Vector3 previous_force_on_nodes = Vector3::Zero();
  std::size_t contacts = 0;
  bool parked = false;  // acts on nothing, not in the stability bound, until placed
};

// A roller and its contact with each link (roller.hpp).
struct RollerState {
  Roller roller;
  std::vector<double> link_radius;
  std::vector<Vector3> shear, on_a, on_b;
  std::vector<double> contact_energy, friction_increment;
  std::vector<char> touching;
  Vector3 previous_point = Vector3::Zero();
  Vector3 force_on_roller = Vector3::Zero(), previous_force_on_links = Vector3::Zero();
  std::size_t contacts = 0;
};

}  // namespace engine_detail

struct Engine::State {
  std::vector<NetNode> nodes;
  std::vector<Vector3> x, x_previous, v, w;
  std::vector<double> inverse_mass, inverse_inertia;  // inertial (scaled); 0 for held nodes
  std::vector<double> radius;  // contact radius against tools, contiguous for the tool loop
  std::vector<Vector3> force, moment, damping_previous, damping_moment_previous, reaction_previous;
  std::vector<double> node_damping_work, node_support_work, node_gravity_work, node_kinetic;
  std::vector<EngineLink> links;
  std::vector<engine_detail::LinkState> link_state;
  std::vector<engine_detail::LinkLoad> link_load;
  // Node i's links: node_link_entries[node_link_start[i] .. node_link_start[i + 1]) (compressed rows).
  std::vector<std::size_t> node_link_start;
  std::vector<engine_detail::NodeLinkEntry> node_link_entries;
  std::vector<engine_detail::ToolState> tools;
  std::vector<engine_detail::RollerState> rollers;
  bool imposed_pending = false;
  bool held_tools = false;
};

}  // namespace dtwire::dem
