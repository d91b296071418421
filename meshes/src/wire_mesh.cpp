#include "dtwire/meshes/wire_mesh.hpp"

namespace dtwire::meshes {
namespace {
std::string wire_prefix(int wire, bool double_twist) {
  if (!double_twist) return "wire";
  return wire == 0 ? "wire_A" : "wire_B";
}
}  // namespace

int material_id(int wire, WirePart part, bool coating) {
  return 10 * wire + 1 + static_cast<int>(part) + (coating ? 3 : 0);
}

int boundary_id(int wire, WireSurface surface) { return 10 * wire + 1 + static_cast<int>(surface); }

std::string material_name(int wire, WirePart part, bool coating, bool double_twist) {
  static const char* parts[] = {"", "_start_grip", "_end_grip"};
  return wire_prefix(wire, double_twist) + parts[static_cast<int>(part)] + (coating ? "_coating" : "");
}

std::string boundary_name(int wire, WireSurface surface, bool double_twist) {
  static const char* names[] = {"_start_face", "_end_face", "_lateral", "_start_grip_lateral",
                                "_end_grip_lateral"};
  return wire_prefix(wire, double_twist) + names[static_cast<int>(surface)];
}

int wire_of_id(int id) { return (id - 1) / 10; }

bool is_lateral_boundary(int id) { return (id - 1) % 10 >= static_cast<int>(WireSurface::Lateral); }

}  // namespace dtwire::meshes
