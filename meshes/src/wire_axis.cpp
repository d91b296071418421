#include "dtwire/meshes/wire_axis.hpp"

#include <algorithm>
#include <cmath>

namespace dtwire::meshes {
namespace {

// Rodrigues rotation of v about the unit axis k by angle.
Vec3 rotate(const Vec3& v, const Vec3& k, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  return c * v + s * cross(k, v) + (1 - c) * dot(k, v) * k;
}

// d(tangent)/ds of the piece at s, by central differences inside the piece (one-sided at its
// ends, so that a station shared by two pieces takes the curvature of the piece it closes).
Vec3 piece_curvature(const AxisPiece& piece, double s) {
  const double h = 1e-4 * piece.length;
  const double a = std::max(0.0, s - h), b = std::min(piece.length, s + h);
  return (1.0 / (b - a)) * (piece.at(b).tangent - piece.at(a).tangent);
}

}  // namespace

Station flipped(const Station& station) { return {station.point, -station.tangent, station.normal}; }

AxisPiece reversed(const AxisPiece& piece) {
  auto at = piece.at;
  const double length = piece.length;
  return {[at, length](double s) { return flipped(at(length - s)); }, length, piece.part, piece.min_layers};
}

AxisPiece straight_piece(const Station& start, double length, WirePart part) {
  return {[start](double s) { return Station{start.point + s * start.tangent, start.tangent, start.normal}; },
          length, part};
}

AxisPiece bend_piece(const Station& start, const Vec3& direction, double radius, double angle) {
  const Vec3 t0 = start.tangent;
  const Vec3 inward = normalized(direction - dot(direction, t0) * t0);
  const Vec3 binormal = cross(t0, inward);
  return {[=](double s) {
            const double u = s / radius;
            const Vec3 point = start.point + radius * (std::sin(u) * t0 + (1 - std::cos(u)) * inward);
            return Station{point, std::cos(u) * t0 + std::sin(u) * inward,
                           rotate(start.normal, binormal, u)};
          },
          radius * angle, WirePart::Free};
}

AxisPiece rigidly_moved(const AxisPiece& piece, const Vec3& origin, const Vec3& axis, double angle) {
  auto at = piece.at;
  return {[=](double s) {
            const Station station = at(s);
            return Station{rotate(station.point - origin, axis, angle), rotate(station.tangent, axis, angle),
                           rotate(station.normal, axis, angle)};
          },
          piece.length, piece.part, piece.min_layers};
}

SampledAxis sample_axis(const std::vector<AxisPiece>& pieces, double cell_length) {
  SampledAxis axis;
  for (const AxisPiece& piece : pieces) {
    if (piece.length <= 0) continue;
    const int layers = std::max(piece.min_layers, static_cast<int>(std::ceil(piece.length / cell_length - 1e-9)));
    for (int k = axis.stations.empty() ? 0 : 1; k <= layers; ++k) {
      const double s = piece.length * k / layers;
      axis.stations.push_back(piece.at(s));
      axis.curvature.push_back(piece_curvature(piece, s));
      axis.arc_length.push_back(axis.length + s);
    }
    axis.layer_part.insert(axis.layer_part.end(), layers, piece.part);
    axis.length += piece.length;
  }
  return axis;
}

std::vector<AxisSample> axis_samples(const SampledAxis& axis) {
  std::vector<AxisSample> samples;
  for (std::size_t k = 0; k < axis.stations.size(); ++k)
    samples.push_back({axis.arc_length[k], axis.stations[k].point, axis.stations[k].tangent, axis.curvature[k]});
  return samples;
}

void sweep_wire(HexMesh& mesh, const CrossSection& section, const SampledAxis& axis, int wire,
                bool double_twist) {
  const std::size_t per_station = section.points.size();
  const std::size_t first = mesh.nodes.size();
  for (const Station& station : axis.stations) {
    const Vec3 v_direction = cross(station.tangent, station.normal);
    for (const auto& p : section.points)
      mesh.nodes.push_back(station.point + p[0] * station.normal + p[1] * v_direction);
  }
  auto node = [&](std::size_t station, std::size_t point) { return first + station * per_station + point; };
  auto name_volume = [&](WirePart part, bool coating) {
    mesh.volume_names[material_id(wire, part, coating)] = material_name(wire, part, coating, double_twist);
  };
  auto add_face = [&](const std::array<std::size_t, 4>& face, WireSurface surface) {
    const int id = boundary_id(wire, surface);
    mesh.quads.push_back(face);
    mesh.quad_boundary.push_back(id);
    mesh.surface_names[id] = boundary_name(wire, surface, double_twist);
  };
  for (std::size_t k = 0; k + 1 < axis.stations.size(); ++k) {
    const WirePart part = axis.layer_part[k];
    for (std::size_t q = 0; q < section.quads.size(); ++q) {
      const auto& quad = section.quads[q];
      mesh.hexes.push_back({node(k, quad[0]), node(k, quad[1]), node(k, quad[2]), node(k, quad[3]),
                            node(k + 1, quad[0]), node(k + 1, quad[1]), node(k + 1, quad[2]),
                            node(k + 1, quad[3])});
      mesh.hex_material.push_back(material_id(wire, part, section.quad_in_coating[q]));
      name_volume(part, section.quad_in_coating[q]);
    }
    const WireSurface lateral = part == WirePart::Free        ? WireSurface::Lateral
                                : part == WirePart::StartGrip ? WireSurface::StartGripLateral
                                                              : WireSurface::EndGripLateral;
    // (a_k, b_k, b_k+1, a_k+1) with the counter-clockwise edge (a, b): outward normal.
    for (const auto& edge : section.outer_edges)
      add_face({node(k, edge[0]), node(k, edge[1]), node(k + 1, edge[1]), node(k + 1, edge[0])}, lateral);
  }
  const std::size_t last = axis.stations.size() - 1;
  for (const auto& quad : section.quads) {
    add_face({node(0, quad[0]), node(0, quad[3]), node(0, quad[2]), node(0, quad[1])}, WireSurface::StartFace);
    add_face({node(last, quad[0]), node(last, quad[1]), node(last, quad[2]), node(last, quad[3])},
             WireSurface::EndFace);
  }
}

}  // namespace dtwire::meshes
