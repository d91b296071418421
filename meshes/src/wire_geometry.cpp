#include "dtwire/meshes/wire_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "dtwire/meshes/mesh_check.hpp"

namespace dtwire::meshes {
namespace {

constexpr double kPi = 3.14159265358979323846;

std::string mm(double metres) {
  std::ostringstream out;
  out.precision(4);
  out << metres * 1e3 << " mm";
  return out.str();
}

double helix_radius(const MeshParameters& p) {
  return 0.5 * (p.diameter + 2 * p.coating + p.gap + p.axis_allowance);
}
double helix_rate(const MeshParameters& p) { return p.half_turns * kPi / p.twist_length; }

AxisPiece helix_piece(const MeshParameters& p, double phase) {
  const double radius = helix_radius(p), rate = helix_rate(p);
  const double stretch = std::sqrt(1 + radius * radius * rate * rate);  // ds / dz
  // The section follows the principal normal, which turns about the axis by the torsion
  // integral, rate L / stretch, against a rotation-minimising frame.
  const double section_turn = rate * p.twist_length / stretch;
  const int min_layers = static_cast<int>(std::ceil(section_turn / resolution(p.level, p.diameter).max_section_turn));
  return {[=](double s) {
            const double z = s / stretch, theta = rate * z + phase;
            const Vec3 radial{std::cos(theta), std::sin(theta), 0};
            return Station{radius * radial + Vec3{0, 0, z},
                           (1 / stretch) * Vec3{-radius * rate * radial.y, radius * rate * radial.x, 1},
                           -radial};  // principal normal: towards the twist axis and the other wire
          },
          p.twist_length * stretch, WirePart::Free, min_layers};
}

// The bend and the straight arm leaving `start` (tangent pointing away from the twist).
std::vector<AxisPiece> arm_pieces(const MeshParameters& p, const Station& start, const Vec3& direction,
                                  WirePart grip, const FieldLocations& where) {
  const double angle = std::acos(std::clamp(dot(start.tangent, direction), -1.0, 1.0));
  std::vector<AxisPiece> pieces;
  Station arm_start = start;
  if (angle > 1e-12) {
    pieces.push_back(bend_piece(start, direction, p.bend_radius, angle));
    arm_start = pieces.back().at(pieces.back().length);
    arm_start.tangent = direction;
  }
  const double bend_length = p.bend_radius * angle;
  const double straight = p.arm_length - bend_length;
  if (straight < p.grip_length)
    throw_field_error(where, "arm-length",
                      "expected an arm length >= bend (" + mm(bend_length) + ") + grip-length (" +
                          mm(p.grip_length) + ") = " + mm(bend_length + p.grip_length) + ", got " +
                          mm(p.arm_length));
  pieces.push_back(straight_piece(arm_start, straight - p.grip_length, WirePart::Free));
  Station grip_start = arm_start;
  grip_start.point = arm_start.point + (straight - p.grip_length) * direction;
  pieces.push_back(straight_piece(grip_start, p.grip_length, grip));
  return pieces;
}

struct AxisSample {
  Vec3 point;
  double s;
};

std::vector<AxisSample> fine_samples(const std::vector<AxisPiece>& pieces, double spacing) {
  std::vector<AxisSample> samples;
  double offset = 0;
  for (const AxisPiece& piece : pieces) {
    const int n = std::max(1, static_cast<int>(std::ceil(piece.length / spacing)));
    for (int k = 0; k <= n; ++k) samples.push_back({piece.at(piece.length * k / n).point, offset + piece.length * k / n});
    offset += piece.length;
  }
  return samples;
}

// Arms must stay at least the contact distance from the other wire and the outer diameter
// from their own twist (beyond half a turn of the tightest bend along the axis).
void check_clearance(const MeshParameters& p, const std::vector<AxisPiece> (&axes)[2],
                     const FieldLocations& where) {
  const double outer = p.diameter + 2 * p.coating;
  const double contact = outer + p.gap;
  const std::vector<AxisSample> samples[2] = {fine_samples(axes[0], p.diameter / 4),
                                              fine_samples(axes[1], p.diameter / 4)};
  double closest_other = 1e300, closest_self = 1e300;
  for (const auto& a : samples[0])
    for (const auto& b : samples[1]) closest_other = std::min(closest_other, distance(a.point, b.point));
  const double neighbourhood = kPi * std::max(p.bend_radius, helix_radius(p));
  for (const auto& wire : samples)
    for (std::size_t i = 0; i < wire.size(); ++i)
      for (std::size_t j = i + 1; j < wire.size(); ++j)
        if (wire[j].s - wire[i].s > neighbourhood)
          closest_self = std::min(closest_self, distance(wire[i].point, wire[j].point));
  if (closest_other < contact * (1 - 1e-9))
    throw_field_error(where, "arm-angle",
                      "an arm would intersect the other wire (its twist or arm): the two wire axes come within " +
                          mm(closest_other) + ", less than d + 2 coating + gap = " + mm(contact) +
                          "; reduce arm-angle or bend-radius");
  if (closest_self < outer)
    throw_field_error(where, "arm-angle",
                      "an arm would intersect its own wire (twist or other arm): the axis comes back within " +
                          mm(closest_self) + ", less than the wire diameter " + mm(outer) +
                          "; reduce arm-angle");
}

}  // namespace

double helix_lay_angle(const MeshParameters& p) { return std::atan(helix_radius(p) * helix_rate(p)); }

std::vector<AxisPiece> double_twist_axis(const MeshParameters& p, int wire, const FieldLocations& where) {
  const AxisPiece helix = helix_piece(p, wire * kPi);
  const Station start = flipped(helix.at(0)), end = helix.at(helix.length);
  const double sin_b = std::sin(p.arm_angle), cos_b = std::cos(p.arm_angle);
  // Each arm leaves towards the side of the mesh plane its wire is on.
  const double start_side = start.point.x > 0 ? 1 : -1, end_side = end.point.x > 0 ? 1 : -1;
  const auto start_arm = arm_pieces(p, start, {start_side * sin_b, 0, -cos_b}, WirePart::StartGrip, where);
  const auto end_arm = arm_pieces(p, end, {end_side * sin_b, 0, cos_b}, WirePart::EndGrip, where);
  std::vector<AxisPiece> pieces;
  for (auto it = start_arm.rbegin(); it != start_arm.rend(); ++it) pieces.push_back(reversed(*it));
  pieces.push_back(helix);
  pieces.insert(pieces.end(), end_arm.begin(), end_arm.end());
  return pieces;
}

std::vector<AxisPiece> segment_axis(const MeshParameters& p, const FieldLocations& where) {
  const AxisPiece helix = helix_piece(p, 0);
  const Station leave = helix.at(helix.length);  // wire A leaves the first twist here
  const double side = leave.point.x > 0 ? 1 : -1;
  const Vec3 run{side * std::sin(p.arm_angle), 0, std::cos(p.arm_angle)};
  // The half turn about the midpoint's normal to the mesh plane maps the segment onto itself run
  // backwards, so it enters the next twist along the leaving tangent with y reversed.
  const Vec3 enter{leave.tangent.x, -leave.tangent.y, leave.tangent.z};
  const double angle = std::acos(std::clamp(dot(leave.tangent, run), -1.0, 1.0));
  const double straight = p.length - 2 * p.bend_radius * angle;
  if (!(straight > 0))
    throw_field_error(where, "length",
                      "expected an axis length between the twists > its two bends (2 x " +
                          mm(p.bend_radius * angle) + "), got " + mm(p.length));
  std::vector<AxisPiece> pieces;
  pieces.push_back(straight_piece({leave.point - p.grip_length * leave.tangent, leave.tangent, leave.normal},
                                  p.grip_length, WirePart::StartGrip));
  Station cursor = leave;
  auto bend_towards = [&](const Vec3& direction) {
    if (angle <= 1e-12) return;
    pieces.push_back(bend_piece(cursor, direction, p.bend_radius, angle));
    cursor = pieces.back().at(pieces.back().length);
    cursor.tangent = direction;
  };
  bend_towards(run);
  pieces.push_back(straight_piece(cursor, straight, WirePart::Free));
  cursor.point = cursor.point + straight * run;
  bend_towards(enter);
  pieces.push_back(straight_piece(cursor, p.grip_length, WirePart::EndGrip));
  // The chord (in the (x, z) plane by the symmetry) turned onto +z about y, its start at 0.
  const Vec3 chord = cursor.point - leave.point;
  const double turn = std::atan2(chord.x, chord.z);
  for (AxisPiece& piece : pieces) piece = rigidly_moved(piece, leave.point, {0, -1, 0}, turn);
  return pieces;
}

WireMesh build_wire_mesh(const MeshParameters& p, const FieldLocations& where) {
  validate(p, where);
  const bool dt = p.kind == WireKind::DoubleTwist;
  const Resolution res = resolution(p.level, p.diameter);
  const CrossSection section = make_o_grid_section(0.5 * p.diameter, p.coating, res);
  WireMesh result;
  result.steel_radius = 0.5 * p.diameter;
  result.coating = p.coating;
  if (p.kind == WireKind::Segment) {
    const SampledAxis axis = sample_axis(segment_axis(p, where), res.axial_cell_length);
    sweep_wire(result.mesh, section, axis, 0, false);
    result.axis_lengths = {axis.length};
    result.axes = {axis_samples(axis)};
    return result;
  }
  if (!dt) {
    const Station start{{0, 0, 0}, {0, 0, 1}, {1, 0, 0}};
    const double g = p.grip_length;
    const std::vector<AxisPiece> pieces = {
        straight_piece(start, g, WirePart::StartGrip),
        straight_piece({{0, 0, g}, {0, 0, 1}, {1, 0, 0}}, p.length - 2 * g, WirePart::Free),
        straight_piece({{0, 0, p.length - g}, {0, 0, 1}, {1, 0, 0}}, g, WirePart::EndGrip)};
    const SampledAxis axis = sample_axis(pieces, res.axial_cell_length);
    sweep_wire(result.mesh, section, axis, 0, false);
    result.axis_lengths = {axis.length};
    result.axes = {axis_samples(axis)};
    return result;
  }
  // The facets of a steep (e.g. coated) twist can come closer than the exact tubes: widen
  // the axis separation by the measured shortfall until the faceted surfaces keep the gap.
  MeshParameters q = p;
  q.axis_allowance = 0;
  for (int attempt = 0;; ++attempt) {
    const std::vector<AxisPiece> axes[2] = {double_twist_axis(q, 0, where), double_twist_axis(q, 1, where)};
    check_clearance(q, axes, where);
    WireMesh trial = result;
    trial.wire_count = 2;
    trial.lay_angle = helix_lay_angle(q);
    trial.gap = p.gap;
    trial.axis_allowance = q.axis_allowance;
    for (int wire = 0; wire < 2; ++wire) {
      const SampledAxis axis = sample_axis(axes[wire], res.axial_cell_length);
      sweep_wire(trial.mesh, section, axis, wire, true);
      trial.axis_lengths.push_back(axis.length);
      trial.axes.push_back(axis_samples(axis));
    }
    trial.min_surface_distance = min_surface_distance(trial.mesh, 0, 1, 0.5 * p.diameter + p.coating);
    const double shortfall = p.gap - trial.min_surface_distance;
    if (shortfall <= 0 || attempt == 8) return trial;
    // The facets gain about 0.6 of the added separation: overshoot a little.
    q.axis_allowance += 2 * shortfall + 1e-6 * p.diameter;
  }
}

}  // namespace dtwire::meshes
