#include "dtwire/meshes/wire_mesh.hpp"

namespace dtwire::meshes {
namespace {
std::string wire_prefix(int wire, bool double_twist) {
  if (!double_twist) return "wire";
  return wire == 0 ? "wire_A" : "wire_B";
}
}  // namespace

std::string material_name(int wire, WirePart part, bool coating, bool double_twist) {
  static const char* parts[] = {"", "_start_grip", "_end_grip"};
  return wire_prefix(wire, double_twist) + parts[static_cast<int>(part)] + (coating ? "_coating" : "");
}

std::string boundary_name(int wire, WireSurface surface, bool double_twist) {
  static const char* names[] = {"_start_face", "_end_face", "_lateral", "_start_grip_lateral",
                                "_end_grip_lateral"};
  return wire_prefix(wire, double_twist) + names[static_cast<int>(surface)];
}

}  // namespace dtwire::meshes
