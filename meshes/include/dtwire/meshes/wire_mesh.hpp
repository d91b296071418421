#pragma once
// A hexahedral wire mesh with its region ids (docs/meshes.md lists them).
//   volumes  (deal.II material_id): 10 w + 1 + part + 3 c
//   surfaces (deal.II boundary_id): 10 w + 1 + surface
// with w = 0 for wire A (the SW), 1 for wire B; part 0 free, 1 start grip, 2 end grip;
// c = 1 for the coating; surface 0 start face, 1 end face, 2 lateral (contact candidate),
// 3 start grip lateral, 4 end grip lateral. Internal faces carry no id (deal.II: 0).
#include <array>
#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "dtwire/meshes/vec3.hpp"

namespace dtwire::meshes {

enum class WirePart { Free = 0, StartGrip = 1, EndGrip = 2 };
enum class WireSurface { StartFace = 0, EndFace = 1, Lateral = 2, StartGripLateral = 3, EndGripLateral = 4 };

int material_id(int wire, WirePart part, bool coating);
int boundary_id(int wire, WireSurface surface);
std::string material_name(int wire, WirePart part, bool coating, bool double_twist);
std::string boundary_name(int wire, WireSurface surface, bool double_twist);
// The wire (0 or 1) and whether a region is part of its outer lateral surface.
int wire_of_id(int id);
bool is_lateral_boundary(int id);

struct HexMesh {
  std::vector<Vec3> nodes;
  std::vector<std::array<std::size_t, 8>> hexes;  // gmsh/VTK hexahedron node order
  std::vector<int> hex_material;
  std::vector<std::array<std::size_t, 4>> quads;  // boundary faces
  std::vector<int> quad_boundary;
  std::map<int, std::string> volume_names;
  std::map<int, std::string> surface_names;
};

// The mesh with what the checks compare against.
struct WireMesh {
  HexMesh mesh;
  int wire_count = 1;
  double steel_radius = 0;
  double coating = 0;
  std::vector<double> axis_lengths;  // per wire, exact arc length of the axis
  double lay_angle = 0;              // DT helix lay angle (rad), 0 for the SW
  double gap = 0;                    // DT nominal gap between the wire surfaces
  double axis_allowance = 0;         // DT extra axis separation (see MeshParameters)
  double min_surface_distance = 0;   // DT, see MeshCheck
};

}  // namespace dtwire::meshes
