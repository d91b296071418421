#pragma once
// Quality and geometry figures of a wire mesh (`dtwire mesh ... --check`).
#include <cstddef>
#include <map>
#include <string>

#include "dtwire/meshes/parameters.hpp"
#include "dtwire/meshes/wire_mesh.hpp"

namespace dtwire::meshes {

struct MeshCheck {
  std::size_t cells = 0;
  std::size_t nodes = 0;
  std::size_t boundary_faces = 0;
  // Minimum over cells and corners of det(e1, e2, e3) / (|e1| |e2| |e3|) of the three edges
  // leaving the corner (1: a cube corner, <= 0: an inverted cell).
  double min_scaled_jacobian = 0;
  // Maximum over cells of longest / shortest edge.
  double max_aspect_ratio = 0;
  // DT only: signed minimum distance between the lateral surfaces of the two wires (negative:
  // interpenetration), from every surface node of each wire to the triangles (both diagonals
  // of each quad) of the other.
  bool two_wires = false;
  double min_surface_distance = 0;
  double lay_angle = 0;  // rad
  double steel_volume = 0, steel_volume_exact = 0;      // exact: pi r^2 * axis length
  double coating_volume = 0, coating_volume_exact = 0;  // exact: pi ((r + t)^2 - r^2) * axis length
  std::map<int, std::size_t> cells_per_material;
  std::map<int, std::size_t> faces_per_boundary;
  double seconds_to_build = 0;  // filled by the caller
};

MeshCheck check_mesh(const WireMesh& mesh);

// Cell volume by 2x2x2 Gauss quadrature of the trilinear map (exact for trilinear hexes).
double hex_volume(const HexMesh& mesh, std::size_t hex);

// Minimum signed distance between two sets of boundary faces (ids), see MeshCheck.
double min_surface_distance(const HexMesh& mesh, int wire_a, int wire_b, double search_radius);

// A Markdown report: parameters, region ids and the figures above.
std::string format_check_markdown(const MeshParameters& parameters, const WireMesh& mesh,
                                  const MeshCheck& check);

}  // namespace dtwire::meshes
