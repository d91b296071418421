#pragma once
// Region ids of the meshes `dtwire mesh` writes (gmsh physical groups; deal.II material and
// boundary ids), in one place for meshes/, fem/ and app/ (docs/meshes.md lists them):
//   volumes  (material_id): 10 w + 1 + part + 3 c
//   surfaces (boundary_id): 10 w + 1 + surface
// with w = 0 for wire A (the SW), 1 for wire B; c = 1 for the coating. Internal faces carry no
// id (deal.II: 0). fem's own generated straight wire (no mesh file) has ids of its own
// (fem/src/wire_mesh.hpp).
namespace dtwire::regions {

enum class WirePart { Free = 0, StartGrip = 1, EndGrip = 2 };
enum class WireSurface { StartFace = 0, EndFace = 1, Lateral = 2, StartGripLateral = 3, EndGripLateral = 4 };

constexpr int material_id(int wire, WirePart part, bool coating = false) {
  return 10 * wire + 1 + static_cast<int>(part) + (coating ? 3 : 0);
}
constexpr int boundary_id(int wire, WireSurface surface) { return 10 * wire + 1 + static_cast<int>(surface); }
// The wire (0 or 1) of a region id, and whether a surface is part of a wire's outer lateral surface.
constexpr int wire_of_id(int id) { return (id - 1) / 10; }
constexpr bool is_lateral_boundary(int id) { return (id - 1) % 10 >= static_cast<int>(WireSurface::Lateral); }
constexpr bool is_grip_lateral_boundary(int id) {
  const int surface = (id - 1) % 10;
  return id > 0 && (surface == static_cast<int>(WireSurface::StartGripLateral) ||
                    surface == static_cast<int>(WireSurface::EndGripLateral));
}

// The double twist's wire-wire contact pair and grips, as the DT experiments use them.
constexpr int kWireALateral = boundary_id(0, WireSurface::Lateral);                 // 3
constexpr int kWireBLateral = boundary_id(1, WireSurface::Lateral);                 // 13
constexpr int kWireAStartGrip = boundary_id(0, WireSurface::StartGripLateral);      // 4
constexpr int kWireAEndGrip = boundary_id(0, WireSurface::EndGripLateral);          // 5
constexpr int kWireBStartGrip = boundary_id(1, WireSurface::StartGripLateral);      // 14
constexpr int kWireBEndGrip = boundary_id(1, WireSurface::EndGripLateral);          // 15
constexpr int kFirstWireBMaterial = material_id(1, WirePart::Free);                 // 11

}  // namespace dtwire::regions
