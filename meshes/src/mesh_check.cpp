#include "dtwire/meshes/mesh_check.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>

namespace dtwire::meshes {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Corner k of a hexahedron and its three edge neighbours in right-handed order.
constexpr int kCornerNeighbours[8][3] = {{1, 3, 4}, {2, 0, 5}, {3, 1, 6}, {0, 2, 7},
                                         {7, 5, 0}, {4, 6, 1}, {5, 7, 2}, {6, 4, 3}};
constexpr int kEdges[12][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6},
                               {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};

double scaled_jacobian(const HexMesh& mesh, std::size_t hex) {
  const auto& h = mesh.hexes[hex];
  double result = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 8; ++k) {
    const Vec3 c = mesh.nodes[h[k]];
    const Vec3 e1 = mesh.nodes[h[kCornerNeighbours[k][0]]] - c;
    const Vec3 e2 = mesh.nodes[h[kCornerNeighbours[k][1]]] - c;
    const Vec3 e3 = mesh.nodes[h[kCornerNeighbours[k][2]]] - c;
    result = std::min(result, dot(cross(e1, e2), e3) / (norm(e1) * norm(e2) * norm(e3)));
  }
  return result;
}

double aspect_ratio(const HexMesh& mesh, std::size_t hex) {
  const auto& h = mesh.hexes[hex];
  double shortest = std::numeric_limits<double>::infinity(), longest = 0;
  for (const auto& e : kEdges) {
    const double length = distance(mesh.nodes[h[e[0]]], mesh.nodes[h[e[1]]]);
    shortest = std::min(shortest, length);
    longest = std::max(longest, length);
  }
  return longest / shortest;
}

std::string number(double value, int digits = 4) {
  std::ostringstream out;
  out << std::setprecision(digits) << value;
  return out.str();
}

}  // namespace

double hex_volume(const HexMesh& mesh, std::size_t hex) {
  const auto& h = mesh.hexes[hex];
  static const double corner[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                                      {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
  const double g = 1 / std::sqrt(3.0);
  double volume = 0;
  for (double xi : {-g, g})
    for (double eta : {-g, g})
      for (double zeta : {-g, g}) {
        Vec3 d[3];
        for (int k = 0; k < 8; ++k) {
          const double a = corner[k][0], b = corner[k][1], c = corner[k][2];
          const double dxi = a * (1 + b * eta) * (1 + c * zeta) / 8;
          const double deta = b * (1 + a * xi) * (1 + c * zeta) / 8;
          const double dzeta = c * (1 + a * xi) * (1 + b * eta) / 8;
          d[0] = d[0] + dxi * mesh.nodes[h[k]];
          d[1] = d[1] + deta * mesh.nodes[h[k]];
          d[2] = d[2] + dzeta * mesh.nodes[h[k]];
        }
        volume += dot(cross(d[0], d[1]), d[2]);  // Gauss weights are 1
      }
  return volume;
}

MeshCheck check_mesh(const WireMesh& wire_mesh) {
  const HexMesh& mesh = wire_mesh.mesh;
  MeshCheck check;
  check.cells = mesh.hexes.size();
  check.nodes = mesh.nodes.size();
  check.boundary_faces = mesh.quads.size();
  check.min_scaled_jacobian = std::numeric_limits<double>::infinity();
  for (std::size_t c = 0; c < mesh.hexes.size(); ++c) {
    check.min_scaled_jacobian = std::min(check.min_scaled_jacobian, scaled_jacobian(mesh, c));
    check.max_aspect_ratio = std::max(check.max_aspect_ratio, aspect_ratio(mesh, c));
    const int id = mesh.hex_material[c];
    ++check.cells_per_material[id];
    const bool coating = (id - 1) % 10 >= 3;
    (coating ? check.coating_volume : check.steel_volume) += hex_volume(mesh, c);
  }
  for (int id : mesh.quad_boundary) ++check.faces_per_boundary[id];
  const double r = wire_mesh.steel_radius, t = wire_mesh.coating;
  for (double length : wire_mesh.axis_lengths) {
    check.steel_volume_exact += kPi * r * r * length;
    check.coating_volume_exact += kPi * ((r + t) * (r + t) - r * r) * length;
  }
  check.two_wires = wire_mesh.wire_count == 2;
  if (check.two_wires) {
    check.lay_angle = wire_mesh.lay_angle;
    check.min_surface_distance = wire_mesh.min_surface_distance;
  }
  return check;
}

std::string format_check_markdown(const MeshParameters& p, const WireMesh& wire_mesh, const MeshCheck& c) {
  const char* kind_title = p.kind == WireKind::DoubleTwist ? "double twist"
                     : p.kind == WireKind::Segment   ? "SW segment between two twists"
                                                     : "single wire";
  std::ostringstream md;
  md << "### Mesh check: " << kind_title << ", level " << p.level << "\n\n";
  md << "| parameter | value |\n|---|---|\n";
  for (const ParameterField& field : parameter_fields())
    if (used_by(field, p.kind))
      md << "| " << field.name << " | " << number(user_value(p, field), 6)
         << (field.unit == "1" ? "" : " " + field.unit) << " |\n";
  md << "\n| figure | value |\n|---|---|\n";
  md << "| cells (hexahedra) | " << c.cells << " |\n";
  md << "| nodes | " << c.nodes << " |\n";
  md << "| boundary faces | " << c.boundary_faces << " |\n";
  md << "| minimum scaled Jacobian | " << number(c.min_scaled_jacobian) << " |\n";
  md << "| maximum aspect ratio (longest / shortest edge) | " << number(c.max_aspect_ratio) << " |\n";
  if (c.two_wires) {
    md << "| minimum distance between the wire surfaces | " << number(c.min_surface_distance * 1e3)
       << " mm (gap " << number(wire_mesh.gap * 1e3) << " mm) |\n";
    md << "| helix axis separation | d + 2 coating + gap + " << number(wire_mesh.axis_allowance * 1e3)
       << " mm (allowance keeping the faceted surfaces gap apart) |\n";
    md << "| helix lay angle | " << number(c.lay_angle * 180 / kPi) << " deg |\n";
  }
  auto volume_row = [&](const char* what, double mesh_volume, double exact) {
    md << "| " << what << " volume: mesh / tube pi r^2 L | " << number(mesh_volume * 1e9, 6) << " / "
       << number(exact * 1e9, 6) << " mm^3 (" << std::showpos << number(100 * (mesh_volume / exact - 1), 3)
       << std::noshowpos << " %) |\n";
  };
  volume_row("steel", c.steel_volume, c.steel_volume_exact);
  if (p.coating > 0) volume_row("coating", c.coating_volume, c.coating_volume_exact);
  if (c.seconds_to_build > 0) md << "| meshing time | " << number(c.seconds_to_build, 3) << " s |\n";
  md << "\n| region | dim | id | count |\n|---|---|---|---|\n";
  for (const auto& [id, count] : c.cells_per_material)
    md << "| " << wire_mesh.mesh.volume_names.at(id) << " | 3 (material_id) | " << id << " | " << count << " cells |\n";
  for (const auto& [id, count] : c.faces_per_boundary)
    md << "| " << wire_mesh.mesh.surface_names.at(id) << " | 2 (boundary_id) | " << id << " | " << count << " faces |\n";
  md << "\n";
  return md.str();
}

}  // namespace dtwire::meshes
