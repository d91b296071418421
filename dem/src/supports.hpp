#pragma once
// Edge supports of a `dem run` panel and the switch from the draping phase (edges free in the
// plane) to the supports the tool phase uses.
#include <array>
#include <string>

#include "dtwire/dem/run.hpp"

namespace dtwire::dem {

struct HeldComponents {
  std::array<bool, 3> translation{};
  bool rotation = false;
};

// The components a supported node holds: pinned and hinged hold every translation (pinned also
// the rotations, hinged leaves them free as PFC's `ball fix velocity`); a slider holds gravity's
// direction and the in-plane normal of its edge(s).
HeldComponents held_components(unsigned sides, EdgeSupport support);

// Sets the fixity of every node on a supported side; `draping`: held along gravity only.
void apply_supports(HexMesh& mesh, const RunInput& in, bool draping);

// After draping: the supported nodes held where they are, as the input's support says.
void hold_supports_in_place(Engine& engine, const HexMesh& mesh, const RunInput& in);

}  // namespace dtwire::dem
