// Geometry of the SW and DT meshes against closed-form values: tube volume pi r^2 L (Pappus,
// exact for a tube around a curve with curvature radius > r), wire-wire clearance = gap.
#include <gtest/gtest.h>

#include <cmath>

#include "dtwire/meshes/mesh_check.hpp"
#include "dtwire/meshes/wire_geometry.hpp"

using namespace dtwire::meshes;

namespace {

constexpr double kPi = 3.14159265358979323846;

MeshParameters dt_parameters(int level) {
  MeshParameters p = default_parameters(WireKind::DoubleTwist);
  p.level = level;
  return p;
}

}  // namespace

class Levels : public ::testing::TestWithParam<int> {};

TEST_P(Levels, SingleWireVolumeWithinHalfPercentOfTube) {
  MeshParameters p = default_parameters(WireKind::Single);
  p.level = GetParam();
  const WireMesh mesh = build_wire_mesh(p);
  const MeshCheck check = check_mesh(mesh);
  const double tube = kPi * 0.25 * p.diameter * p.diameter * p.length;  // closed form, not the mesh's own figure
  EXPECT_NEAR(check.steel_volume / tube, 1.0, 0.005);  // issue #3: within 0.5 %
  EXPECT_GT(check.min_scaled_jacobian, 0.5);
}

TEST_P(Levels, DoubleTwistVolumeWithinHalfPercentOfTube) {
  const MeshParameters p = dt_parameters(GetParam());
  const WireMesh mesh = build_wire_mesh(p);
  const MeshCheck check = check_mesh(mesh);
  // Closed-form axis length of one wire: helix L_dt sqrt(1 + (R k)^2), two bends rho psi, arms.
  const double radius = 0.5 * (p.diameter + p.gap), rate = p.half_turns * kPi / p.twist_length;
  const double helix = p.twist_length * std::sqrt(1 + radius * radius * rate * rate);
  const double lay = std::atan(radius * rate);
  const double bend_angle = std::acos(std::cos(lay) * std::cos(p.arm_angle));
  const double straight_arm = p.arm_length - p.bend_radius * bend_angle;
  const double wire_length = helix + 2 * (p.bend_radius * bend_angle + straight_arm);
  const double tube = 2 * kPi * 0.25 * p.diameter * p.diameter * wire_length;
  EXPECT_NEAR(check.steel_volume / tube, 1.0, 0.005);  // issue #3: within 0.5 %
  EXPECT_GT(check.min_scaled_jacobian, 0.5);
  EXPECT_NEAR(check.lay_angle, lay, 1e-12);
}

TEST_P(Levels, DoubleTwistSurfacesTouchWithinGapPlusOnePercentOfD) {
  const MeshParameters p = dt_parameters(GetParam());
  const MeshCheck check = check_mesh(build_wire_mesh(p));
  EXPECT_GE(check.min_surface_distance, 0.0);                             // no interpenetration
  EXPECT_GE(check.min_surface_distance, p.gap * (1 - 1e-9));              // the facets keep the gap
  EXPECT_LE(check.min_surface_distance, p.gap + 0.01 * p.diameter);       // issue #3 tolerance
}

INSTANTIATE_TEST_SUITE_P(OneToThree, Levels, ::testing::Values(1, 2, 3));

TEST(DoubleTwist, ZeroGapWiresTouchWithoutInterpenetrating) {
  MeshParameters p = dt_parameters(2);
  p.gap = 0;
  const MeshCheck check = check_mesh(build_wire_mesh(p));
  EXPECT_GE(check.min_surface_distance, 0.0);
  EXPECT_LE(check.min_surface_distance, 0.01 * p.diameter);
}

TEST(DoubleTwist, CoatingIsItsOwnRegionWithTheSheathVolume) {
  MeshParameters p = dt_parameters(1);
  p.diameter = 3.1e-3;  // gabion wire with a 0.5 mm PVC sheath
  p.twist_length = 35e-3;
  p.coating = 0.5e-3;
  p.bend_radius = 8e-3;
  p.arm_length = 40e-3;
  const WireMesh mesh = build_wire_mesh(p);
  const MeshCheck check = check_mesh(mesh);
  EXPECT_NEAR(check.coating_volume / check.coating_volume_exact, 1.0, 0.005);
  EXPECT_NEAR(check.steel_volume / check.steel_volume_exact, 1.0, 0.005);
  EXPECT_EQ(mesh.mesh.volume_names.count(material_id(0, WirePart::Free, true)), 1u);
  EXPECT_EQ(mesh.mesh.volume_names.count(material_id(1, WirePart::EndGrip, true)), 1u);
  // The coatings, not the steel, touch: clearance is the gap between the sheaths (the steep
  // coated twist needs the axis allowance to keep its facets apart).
  EXPECT_GE(check.min_surface_distance, p.gap * (1 - 1e-9));
  EXPECT_LE(check.min_surface_distance, p.gap + 0.01 * p.diameter);
}

TEST(DoubleTwist, HelixAxesAreDPlusGapApartAndTwistThroughNHalfTurns) {
  const MeshParameters p = dt_parameters(1);
  const auto a = double_twist_axis(p, 0), b = double_twist_axis(p, 1);
  const AxisPiece& helix_a = a[3];  // grip, free arm, bend, helix, ...
  const AxisPiece& helix_b = b[3];
  for (double f : {0.0, 0.3, 0.5, 1.0}) {
    const Station sa = helix_a.at(f * helix_a.length), sb = helix_b.at(f * helix_b.length);
    EXPECT_NEAR(distance(sa.point, sb.point), p.diameter + p.gap, 1e-12);
    EXPECT_NEAR(sa.point.z, f * p.twist_length, 1e-12);
  }
  // Three half turns: wire A starts on +x and ends on -x.
  EXPECT_NEAR(helix_a.at(0).point.x, 0.5 * (p.diameter + p.gap), 1e-12);
  EXPECT_NEAR(helix_a.at(helix_a.length).point.x, -0.5 * (p.diameter + p.gap), 1e-12);
}

TEST(DoubleTwist, ArmsLeaveAtTheArmAngleInTheMeshPlane) {
  const MeshParameters p = dt_parameters(1);
  for (int wire = 0; wire < 2; ++wire) {
    const auto pieces = double_twist_axis(p, wire);
    const Station end = pieces.back().at(pieces.back().length);
    EXPECT_NEAR(std::acos(end.tangent.z), p.arm_angle, 1e-9);
    EXPECT_NEAR(end.tangent.y, 0.0, 1e-12);
    const Station start = pieces.front().at(0);  // the axis runs from the lower arm end upwards
    EXPECT_NEAR(std::acos(start.tangent.z), p.arm_angle, 1e-9);
    EXPECT_NEAR(start.tangent.y, 0.0, 1e-12);
  }
}

// The SW segment between two twists (issue 36): its axis against the closed forms of the DT's
// own axes, which it reuses (helix tangent at the twist end, bends of bend-radius).
TEST(Segment, ChordAlongZBendsAtTheTwistTangentAndHalfTurnSymmetry) {
  MeshParameters p = default_parameters(WireKind::Segment);
  const auto pieces = segment_axis(p);
  ASSERT_EQ(pieces.size(), 5u);  // grip, bend, straight, bend, grip
  const Station leave = pieces[1].at(0), enter = pieces[4].at(0);
  const Station first = pieces.front().at(0), last = pieces.back().at(pieces.back().length);
  // The chord runs along +z from the origin.
  EXPECT_NEAR(norm(leave.point), 0.0, 1e-15);
  EXPECT_NEAR(enter.point.x, 0.0, 1e-12);
  EXPECT_NEAR(enter.point.y, 0.0, 1e-12);
  // Leaving and entering tangents make the closed-form bend angle acos(cos(lay) cos(arm angle))
  // with the straight part, and the segment maps onto itself under the half turn about y
  // through its midpoint.
  const double lay = helix_lay_angle(p);
  const double bend = std::acos(std::cos(lay) * std::cos(p.arm_angle));
  const Vec3 run = pieces[2].at(0).tangent;
  EXPECT_NEAR(std::acos(dot(leave.tangent, run)), bend, 1e-9);
  EXPECT_NEAR(std::acos(dot(enter.tangent, run)), bend, 1e-9);
  const Vec3 middle = 0.5 * (leave.point + enter.point);
  const Vec3 turned = {2 * middle.x - first.point.x, first.point.y, 2 * middle.z - first.point.z};
  EXPECT_NEAR(distance(turned, last.point), 0.0, 1e-12);
  // Axis length between the twists is `length`; the grips add grip-length each.
  double free_length = 0;
  for (std::size_t k = 1; k + 1 < pieces.size(); ++k) free_length += pieces[k].length;
  EXPECT_NEAR(free_length, p.length, 1e-12);
  // Chord = the two arcs' chords (2 R sin(bend / 2) along the bisector of their end tangents)
  // plus the straight part.
  const double arc_chord = 2 * p.bend_radius * std::sin(0.5 * bend);
  const Vec3 chord = arc_chord * normalized(leave.tangent + run) + pieces[2].length * run +
                     arc_chord * normalized(run + enter.tangent);
  EXPECT_NEAR(distance(chord, enter.point - leave.point), 0.0, 1e-12);
  EXPECT_NEAR(pieces[2].length, p.length - 2 * p.bend_radius * bend, 1e-12);
}

TEST(Segment, VolumeWithinHalfPercentOfTubeAndGripsAsSingleWire) {
  MeshParameters p = default_parameters(WireKind::Segment);
  const WireMesh mesh = build_wire_mesh(p);
  const MeshCheck check = check_mesh(mesh);
  const double tube = kPi * 0.25 * p.diameter * p.diameter * (p.length + 2 * p.grip_length);
  EXPECT_NEAR(check.steel_volume / tube, 1.0, 0.005);
  EXPECT_GT(check.min_scaled_jacobian, 0.5);
  EXPECT_EQ(mesh.wire_count, 1);
  EXPECT_EQ(check.faces_per_boundary.count(4), 1u);  // grip laterals the FE holds
  EXPECT_EQ(check.faces_per_boundary.count(5), 1u);
}
