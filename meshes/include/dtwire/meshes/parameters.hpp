#pragma once
// Parameters of the single-wire (SW) and double-twist (DT) meshes, in SI units (m, rad).
// Command line and .prm files use mm and degrees; the field table converts.
#include <map>
#include <string>
#include <vector>

namespace dtwire::meshes {

// Single: a straight wire. DoubleTwist: the twist with four SW arms. Segment: one SW segment of
// the mesh as it runs between two twists (it leaves a twist, bends, runs slanted, bends into
// the next twist; wire_geometry.hpp).
enum class WireKind { Single, DoubleTwist, Segment };
// The `dtwire mesh` subcommand of a kind: "sw", "dt", "segment".
const char* kind_name(WireKind kind);

struct MeshParameters {
  WireKind kind = WireKind::Single;
  double diameter = 2.7e-3;        // steel wire diameter d
  double length = 60e-3;           // SW: wire length (Dundee SW segment); segment: axis length between the twists
  double twist_length = 40e-3;     // DT: twist length L_dt (40 mm rockfall, 35 mm gabion)
  int half_turns = 3;              // DT: half turns n of the pair (EN 10223-3)
  double arm_length = 30e-3;       // DT: axis length of each SW arm beyond the twist
  double arm_angle = 0.7297276562269663;  // DT: arm to twist axis, asin(40/60) for 8x10
  double bend_radius = 5.4e-3;     // DT: axis bend radius where an arm leaves the twist
  double gap = 0.01e-3;            // DT: clearance between the two wire surfaces
  double coating = 0.0;            // PVC sheath thickness t (0: none)
  double grip_length = 10e-3;      // gripped length at each wire end
  int level = 1;                   // refinement level 0..3
  // Not a user parameter: added to the helix axis separation by build_wire_mesh when the
  // faceted surfaces would otherwise come closer than `gap` (coated, steep twists).
  double axis_allowance = 0.0;
};

MeshParameters default_parameters(WireKind kind);

// Where a parameter value came from, for error messages (an option name, or file:line:column).
struct FieldLocation {
  std::string source;
  int line = 0;
  int column = 0;
};
using FieldLocations = std::map<std::string, FieldLocation>;

// One user-facing parameter: its name (CLI option without "--", .prm name), unit and access.
struct ParameterField {
  std::string name;
  std::string unit;  // "mm", "deg" or "1" (integer count)
  std::string help;
  bool single_wire;  // used by `mesh sw`
  bool double_twist; // used by `mesh dt`
  bool segment;      // used by `mesh segment`
  double MeshParameters::*real = nullptr;
  int MeshParameters::*integer = nullptr;
};
const std::vector<ParameterField>& parameter_fields();
bool used_by(const ParameterField& field, WireKind kind);
const ParameterField* find_parameter_field(const std::string& name);

// Sets a field from a value in its user unit (mm, deg, count).
void set_user_value(MeshParameters& parameters, const ParameterField& field, double value);
double user_value(const MeshParameters& parameters, const ParameterField& field);

// Throws InputError at the field's location (or naming the field) when the parameters cannot
// give a valid mesh: d <= 0, n < 1, level outside 0..3, gap < 0 or so large the wires do not
// touch, bend tighter than the wire. Arms too short for bend and grip and arms crossing the
// twist are checked when the DT axis paths are built (wire_geometry.hpp).
void validate(const MeshParameters& parameters, const FieldLocations& locations = {});

// The InputError for `field` at its location.
[[noreturn]] void throw_field_error(const FieldLocations& locations, const std::string& field,
                                    const std::string& message);

// Largest gap accepted: beyond it the two wires of a DT would not touch under the contact
// search band of the FE module (5 % of d).
double maximum_gap(const MeshParameters& parameters);

}  // namespace dtwire::meshes
