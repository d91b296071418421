#include "dtwire/meshes/parameters.hpp"

#include <cmath>
#include <sstream>

#include "dtwire/core/error.hpp"

namespace dtwire::meshes {
namespace {

constexpr double kPi = 3.14159265358979323846;

double to_si(const std::string& unit) {
  if (unit == "mm") return 1e-3;
  if (unit == "deg") return kPi / 180.0;
  return 1.0;
}

std::string format(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

}  // namespace

MeshParameters default_parameters(WireKind kind) {
  MeshParameters parameters;
  parameters.kind = kind;
  return parameters;
}

const std::vector<ParameterField>& parameter_fields() {
  using P = MeshParameters;
  static const std::vector<ParameterField> fields = {
      {"d", "mm", "steel wire diameter", true, true, true, &P::diameter, nullptr},
      {"length", "mm", "wire length (SW); axis length from twist to twist (segment)", true, false, true,
       &P::length, nullptr},
      {"twist-length", "mm", "twist length L_dt (40 rockfall, 35 gabion)", false, true, true,
       &P::twist_length, nullptr},
      {"half-turns", "1", "half turns of the wire pair over the twist", false, true, true, nullptr,
       &P::half_turns},
      {"arm-length", "mm", "axis length of each SW arm beyond the twist", false, true, false,
       &P::arm_length, nullptr},
      {"arm-angle", "deg", "angle between each arm (segment: its straight part) and the twist axis (8x10: asin(40/60))",
       false, true, true, &P::arm_angle, nullptr},
      {"bend-radius", "mm", "axis bend radius where a wire leaves or enters a twist", false, true, true,
       &P::bend_radius, nullptr},
      {"gap", "mm", "clearance between the two wire surfaces in the twist", false, true, true, &P::gap,
       nullptr},
      {"coating", "mm", "PVC sheath thickness t (0: no coating)", true, true, true, &P::coating,
       nullptr},
      {"grip-length", "mm", "gripped length at each wire end (segment: held inside each twist; 0: no grip regions)",
       true, true, true, &P::grip_length, nullptr},
      {"level", "1", "refinement level 0..3", true, true, true, nullptr, &P::level},
  };
  return fields;
}

bool used_by(const ParameterField& field, WireKind kind) {
  switch (kind) {
    case WireKind::Single: return field.single_wire;
    case WireKind::DoubleTwist: return field.double_twist;
    case WireKind::Segment: return field.segment;
  }
  return false;
}

const char* kind_name(WireKind kind) {
  switch (kind) {
    case WireKind::Single: return "sw";
    case WireKind::DoubleTwist: return "dt";
    case WireKind::Segment: return "segment";
  }
  return "";
}

const ParameterField* find_parameter_field(const std::string& name) {
  for (const auto& field : parameter_fields())
    if (field.name == name) return &field;
  return nullptr;
}

void set_user_value(MeshParameters& parameters, const ParameterField& field, double value) {
  if (field.real) parameters.*field.real = value * to_si(field.unit);
  if (field.integer) parameters.*field.integer = static_cast<int>(value);
}

double user_value(const MeshParameters& parameters, const ParameterField& field) {
  if (field.real) return parameters.*field.real / to_si(field.unit);
  return parameters.*field.integer;
}

void throw_field_error(const FieldLocations& locations, const std::string& field,
                       const std::string& message) {
  const auto found = locations.find(field);
  if (found == locations.end()) throw InputError(field, message);
  const FieldLocation& where = found->second;
  const bool names_field = where.source == "--" + field;  // a command-line option
  throw InputError(where.source, where.line, where.column, names_field ? message : field + ": " + message);
}

double maximum_gap(const MeshParameters& parameters) { return 0.05 * parameters.diameter; }

void validate(const MeshParameters& p, const FieldLocations& where) {
  auto mm = [](double metres) { return format(metres * 1e3) + " mm"; };
  // An infinite length or angle passes the order checks below and then fills the mesh with NaN.
  for (const ParameterField& field : parameter_fields())
    if (field.real && used_by(field, p.kind) && !std::isfinite(p.*field.real))
      throw_field_error(where, field.name, "expected a finite number, got " + format(user_value(p, field)));
  if (!(p.diameter > 0)) throw_field_error(where, "d", "expected a diameter > 0 mm, got " + mm(p.diameter));
  if (p.level < 0 || p.level > 3)
    throw_field_error(where, "level", "expected a refinement level 0..3, got " + std::to_string(p.level));
  if (!(p.coating >= 0))
    throw_field_error(where, "coating", "expected a thickness >= 0 mm, got " + mm(p.coating));
  if (!(p.grip_length >= 0))
    throw_field_error(where, "grip-length", "expected a length >= 0 mm, got " + mm(p.grip_length));
  if (p.kind == WireKind::Single) {
    if (!(p.length > 2 * p.grip_length))
      throw_field_error(where, "length",
                        "expected a wire length > 2 x grip-length = " + mm(2 * p.grip_length) +
                            ", got " + mm(p.length));
    return;
  }
  if (p.half_turns < 0)
    throw_field_error(where, "half-turns",
                      "expected 0 half turns (a straight pair, the start of a twisting run) or more, got " +
                          std::to_string(p.half_turns));
  if (!(p.twist_length > 0))
    throw_field_error(where, "twist-length", "expected a length > 0 mm, got " + mm(p.twist_length));
  // A segment's length is checked against its two bends where its axis is built.
  if (p.kind == WireKind::Segment && !(p.length > 0))
    throw_field_error(where, "length", "expected an axis length > 0 mm between the twists, got " + mm(p.length));
  if (!(p.gap >= 0))
    throw_field_error(where, "gap", "expected a gap >= 0 mm (wires must not interpenetrate), got " + mm(p.gap));
  if (p.gap > maximum_gap(p))
    throw_field_error(where, "gap",
                      "gap " + mm(p.gap) + " is so large that the wires do not touch; expected <= " +
                          mm(maximum_gap(p)) + " (5 % of d)");
  const double outer_diameter = p.diameter + 2 * p.coating;
  if (!(p.bend_radius >= outer_diameter))
    throw_field_error(where, "bend-radius",
                      "expected a bend radius >= the outer wire diameter " + mm(outer_diameter) +
                          " (a tighter bend folds the wire onto itself), got " + mm(p.bend_radius));
  const bool straight_pair = p.half_turns == 0;  // arms may then go straight on (angle 0)
  if (!((straight_pair ? p.arm_angle >= 0 : p.arm_angle > 0) && p.arm_angle < kPi))
    throw_field_error(where, "arm-angle",
                      std::string("expected an angle ") + (straight_pair ? "from 0" : "between 0") +
                          " to 180 deg, got " + format(p.arm_angle * 180 / kPi) + " deg");
}

}  // namespace dtwire::meshes
