#pragma once
// A hexahedral wire mesh with its region ids (dtwire/core/region_ids.hpp; docs/meshes.md lists them).
#include <array>
#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "dtwire/core/region_ids.hpp"
#include "dtwire/meshes/vec3.hpp"

namespace dtwire::meshes {

using regions::boundary_id;
using regions::is_lateral_boundary;
using regions::material_id;
using regions::wire_of_id;
using regions::WirePart;
using regions::WireSurface;

std::string material_name(int wire, WirePart part, bool coating, bool double_twist);
std::string boundary_name(int wire, WireSurface surface, bool double_twist);

struct HexMesh {
  std::vector<Vec3> nodes;
  std::vector<std::array<std::size_t, 8>> hexes;  // gmsh/VTK hexahedron node order
  std::vector<int> hex_material;
  std::vector<std::array<std::size_t, 4>> quads;  // boundary faces
  std::vector<int> quad_boundary;
  std::map<int, std::string> volume_names;
  std::map<int, std::string> surface_names;
};

// A station of a wire's axis (m): the forming history of fem/ bends a straight wire into it.
struct AxisSample {
  double arc_length = 0;  // from the wire's first station
  Vec3 point, tangent;
  Vec3 curvature;  // d(tangent)/ds (1/m), towards the centre of curvature
};

// The mesh with what the checks compare against.
struct WireMesh {
  HexMesh mesh;
  int wire_count = 1;
  double steel_radius = 0;
  double coating = 0;
  std::vector<double> axis_lengths;  // per wire, exact arc length of the axis
  std::vector<std::vector<AxisSample>> axes;  // per wire, the stations the section was swept along
  double lay_angle = 0;              // DT helix lay angle (rad), 0 for the SW
  double gap = 0;                    // DT nominal gap between the wire surfaces
  double axis_allowance = 0;         // DT extra axis separation (see MeshParameters)
  double min_surface_distance = 0;   // DT, see MeshCheck
};

}  // namespace dtwire::meshes
