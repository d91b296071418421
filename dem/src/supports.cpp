// The panel's edge supports and its initial state before the tool moves (docs/dem_engine.md,
// "Supports and initial state"): pinned, hinged or slider edges (the thesis's pre-load, Previtali
// ch. 3.4: edge nodes held along gravity and along the pulling direction, free along the edge),
// and the slack state of the thesis's cyclic tests (ch. 3.8: the net settled under its weight
// onto a wall below it, its edges drawn in while it drapes).
#include "supports.hpp"

#include <algorithm>
#include <stdexcept>

namespace dtwire::dem {

EdgeSupport parse_edge_support(const std::string& name) {
  if (name == "pinned") return EdgeSupport::Pinned;
  if (name == "hinged") return EdgeSupport::Hinged;
  if (name == "slider") return EdgeSupport::Slider;
  throw std::invalid_argument("expected pinned, hinged or slider");
}

std::string edge_support_name(EdgeSupport support) {
  switch (support) {
    case EdgeSupport::Pinned: return "pinned";
    case EdgeSupport::Hinged: return "hinged";
    case EdgeSupport::Slider: return "slider";
  }
  return "pinned";
}

HeldComponents held_components(unsigned sides, EdgeSupport support) {
  HeldComponents held;
  held.translation = {true, true, true};
  held.rotation = support == EdgeSupport::Pinned;
  if (support == EdgeSupport::Slider) {
    // Normal to the edge in the plane (x for left/right, y for bottom/top) and along gravity;
    // a corner is on two edges and so held in both in-plane directions.
    held.translation[0] = (sides & (kLeft | kRight)) != 0;
    held.translation[1] = (sides & (kBottom | kTop)) != 0;
  }
  return held;
}

void apply_supports(HexMesh& mesh, const RunInput& in, bool draping) {
  for (std::size_t n = 0; n < mesh.net.nodes.size(); ++n) {
    if (!(mesh.sides[n] & in.pinned_sides)) continue;
    NetNode& node = mesh.net.nodes[n];
    if (in.support == EdgeSupport::Pinned && !draping) {
      node.fixity = NodeFixity::Pinned;  // translations and rotations (the engine's fixed node)
      continue;
    }
    // Draping onto the wall: held along gravity only, so the edges are drawn in as the net sags.
    const HeldComponents held =
        draping ? HeldComponents{{false, false, true}, false} : held_components(mesh.sides[n], in.support);
    node.fixity = NodeFixity::Free;
    node.held_translation = held.translation;
    node.held_rotation = held.rotation;
  }
}

void hold_supports_in_place(Engine& engine, const HexMesh& mesh, const RunInput& in) {
  for (std::size_t n = 0; n < mesh.net.nodes.size(); ++n) {
    if (!(mesh.sides[n] & in.pinned_sides)) continue;
    const HeldComponents held = held_components(mesh.sides[n], in.support);
    engine.set_support(n, held.translation, held.rotation);
  }
}

}  // namespace dtwire::dem
