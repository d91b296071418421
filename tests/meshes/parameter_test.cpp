#include <gtest/gtest.h>

#include <string>

#include "dtwire/core/error.hpp"
#include "dtwire/meshes/parameter_file.hpp"
#include "dtwire/meshes/wire_geometry.hpp"

using namespace dtwire::meshes;
using dtwire::InputError;

namespace {

std::string build_error(const MeshParameters& p) {
  try {
    build_wire_mesh(p);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

std::string parse_error(const std::string& text, WireKind kind = WireKind::DoubleTwist) {
  MeshParameters p = default_parameters(kind);
  FieldLocations locations;
  try {
    parse_parameter_text(text, "dt.prm", p, locations);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

}  // namespace

TEST(ParameterErrors, NonPositiveDiameterNamesD) {
  MeshParameters p = default_parameters(WireKind::Single);
  p.diameter = 0;
  EXPECT_TRUE(contains(build_error(p), "d: expected a diameter > 0")) << build_error(p);
}

TEST(ParameterErrors, NegativeHalfTurns) {
  MeshParameters p = default_parameters(WireKind::DoubleTwist);
  p.half_turns = -1;
  EXPECT_TRUE(contains(build_error(p), "half-turns")) << build_error(p);
  p.half_turns = 1;
  p.arm_angle = 0;  // arms straight on: only for a straight pair
  EXPECT_TRUE(contains(build_error(p), "arm-angle")) << build_error(p);
}

// Zero half turns, arms straight on: two parallel straight wires d + gap apart (the start of a
// twisting run), whose axis file has no curvature.
TEST(StraightPair, TwoParallelStraightWires) {
  MeshParameters p = default_parameters(WireKind::DoubleTwist);
  p.half_turns = 0;
  p.arm_angle = 0;
  p.level = 0;
  const WireMesh m = build_wire_mesh(p);
  ASSERT_EQ(m.axes.size(), 2u);
  for (int wire = 0; wire < 2; ++wire)
    for (const auto& s : m.axes[wire]) {
      EXPECT_NEAR(std::abs(s.point.x), 0.5 * (p.diameter + p.gap), 1e-12);
      EXPECT_NEAR(s.point.y, 0.0, 1e-12);
      EXPECT_NEAR(s.curvature.x * s.curvature.x + s.curvature.y * s.curvature.y + s.curvature.z * s.curvature.z, 0.0,
                  1e-18);
    }
  EXPECT_NEAR(m.axis_lengths[0], p.twist_length + 2 * p.arm_length, 1e-12);
  EXPECT_NEAR(m.min_surface_distance, p.gap, 0.05 * p.diameter);
}

TEST(ParameterErrors, ArmsFoldingBackAcrossTheTwist) {
  // One half turn, arms at 120 deg with a tight bend: the lower arm of wire A runs up the +x
  // side and meets the upper arm of wire B coming down.
  MeshParameters p = default_parameters(WireKind::DoubleTwist);
  p.half_turns = 1;
  p.arm_angle = 120 * 3.14159265358979323846 / 180;
  p.bend_radius = 2.7e-3;
  p.arm_length = 60e-3;
  std::string message = build_error(p);
  EXPECT_TRUE(contains(message, "arm-angle: an arm would intersect the other wire")) << message;
  p.half_turns = 2;  // now wire A's own arms meet
  message = build_error(p);
  EXPECT_TRUE(contains(message, "arm-angle: an arm would intersect its own wire")) << message;
  p.arm_length = 20e-3;  // short arms at the same angle stay clear
  EXPECT_EQ(build_error(p), "no error");
}

TEST(ParameterErrors, GapSoLargeTheWiresDoNotTouch) {
  MeshParameters p = default_parameters(WireKind::DoubleTwist);
  p.gap = 0.5e-3;
  EXPECT_TRUE(contains(build_error(p), "do not touch")) << build_error(p);
  p.gap = -0.01e-3;
  EXPECT_TRUE(contains(build_error(p), "gap")) << build_error(p);
}

TEST(ParameterErrors, ArmTooShortForBendAndGrip) {
  MeshParameters p = default_parameters(WireKind::DoubleTwist);
  p.arm_length = 12e-3;
  EXPECT_TRUE(contains(build_error(p), "arm-length")) << build_error(p);
}

TEST(ParameterErrors, LevelOutsideZeroToThree) {
  MeshParameters p = default_parameters(WireKind::Single);
  p.level = 4;
  EXPECT_TRUE(contains(build_error(p), "level")) << build_error(p);
}

TEST(ParameterErrors, ErrorsNameTheFileLineAndColumnOfTheValue) {
  MeshParameters p = default_parameters(WireKind::DoubleTwist);
  FieldLocations locations;
  parse_parameter_text("# a DT\nset half turns = -1\n", "dt.prm", p, locations);
  try {
    build_wire_mesh(p, locations);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("dt.prm:2:18: half-turns:", 0), 0u) << e.what();
  }
}

TEST(ParameterFile, ReadsValuesInMillimetresAndDegrees) {
  MeshParameters p = default_parameters(WireKind::DoubleTwist);
  FieldLocations locations;
  parse_parameter_text("set d = 3.1   # mm\nset twist_length = 35\nset Arm-Angle = 45\nset level = 2\n", "x.prm",
                       p, locations);
  EXPECT_DOUBLE_EQ(p.diameter, 3.1e-3);
  EXPECT_DOUBLE_EQ(p.twist_length, 35e-3);
  EXPECT_NEAR(p.arm_angle, 0.25 * 3.14159265358979323846, 1e-15);
  EXPECT_EQ(p.level, 2);
  EXPECT_EQ(locations.at("twist-length").line, 2);
}

TEST(ParameterFile, SyntaxErrorsNameLineAndColumn) {
  EXPECT_TRUE(contains(parse_error("set d = 2.7\nset colour = 3\n"), "dt.prm:2:5: unknown parameter 'colour'"))
      << parse_error("set colour = 3");
  EXPECT_TRUE(contains(parse_error("set d = abc\n"), "dt.prm:1:9: expected a number"));
  EXPECT_TRUE(contains(parse_error("d = 2.7\n"), "dt.prm:1:1: expected 'set"));
  EXPECT_TRUE(contains(parse_error("set d 2.7\n"), "dt.prm:1:5: expected '='"));
  EXPECT_TRUE(contains(parse_error("set level = 1.5\n"), "whole number"));
  EXPECT_TRUE(contains(parse_error("set d = 2.7\nset d = 2.8\n"), "set twice"));
  EXPECT_TRUE(contains(parse_error("set twist-length = 40\n", WireKind::Single), "not used by mesh sw"));
  EXPECT_TRUE(contains(parse_error("set twist-lenght = 40\n"), "(did you mean 'twist-length'?)"))
      << parse_error("set twist-lenght = 40\n");
  // An empty or comment-only file would mesh on the defaults without a word (issue 20).
  EXPECT_TRUE(contains(parse_error(""), "dt.prm: no 'set <name> = <value>' line")) << parse_error("");
  EXPECT_TRUE(contains(parse_error("# only a comment\n\n"), "no 'set <name> = <value>' line"));
}

TEST(ParameterErrors, SegmentTooShortForItsTwoBendsNamesLength) {
  MeshParameters p = default_parameters(WireKind::Segment);
  p.length = 8e-3;  // two 4.2 mm bends do not fit
  EXPECT_TRUE(contains(build_error(p), "length")) << build_error(p);
  EXPECT_TRUE(contains(parse_error("set arm-length = 30\n", WireKind::Segment), "not used by mesh segment"))
      << parse_error("set arm-length = 30\n", WireKind::Segment);
}
