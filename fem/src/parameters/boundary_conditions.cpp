// The .prm reader of one concern (parameters_reading.hpp): Boundary conditions: ends, grips, load and rotation paths, control.
#include <deal.II/base/parameter_handler.h>

#include <cmath>
#include <sstream>

#include "dtwire/core/error.hpp"
#include "parameters_reading.hpp"

namespace dtwire::fem::prm_reading {

using dealii::ParameterHandler;
namespace Patterns = dealii::Patterns;

void declare_boundary_conditions(ParameterHandler& prm) {
  prm.enter_subsection("Boundary conditions");
  prm.declare_entry("Bottom end", "clamped", Patterns::Selection("clamped|axial|guided|symmetry"),
                    "z = 0: clamped (u = 0), axial (u_z = 0), guided (u_x = u_z = 0: free to move along y "
                    "only, e.g. a double twist resting on rollers), symmetry (mid-plane: u_z = 0, "
                    "curve displacement and energies doubled)");
  prm.declare_entry("Top end", "clamped", Patterns::Selection("clamped|axial|free"),
                    "z = length: the load-path displacement; clamped also fixes the other components, "
                    "axial leaves them free; free: no constraint (loaded by contact tools, e.g. bending)");
  prm.declare_entry("Load direction", "axial", Patterns::Selection("axial|lateral"),
                    "axial: top u_z prescribed (tension, compression); lateral: top u_x (cantilever)");
  prm.declare_entry("Load path (mm)", "0:0, 1:1", Patterns::Anything(),
                    "pseudo-time:top displacement pairs, piecewise linear (unload/reload/cycles)");
  prm.declare_entry("Control", "displacement", Patterns::Selection("displacement|force"),
                    "displacement: Load path (mm) on the top face; force: Force path (N), the top face "
                    "moving as one along z (axial load only)");
  prm.declare_entry("Force path (N)", "0:0, 1:0", Patterns::Anything(),
                    "Control = force: pseudo-time:total axial force pairs (whole specimen), piecewise linear");
  prm.declare_entry("Bottom boundary ids", "1", Patterns::Anything(),
                    "boundary ids of the bottom end (SW: 1; DT mesh: its lower grips, e.g. 4, 14)");
  prm.declare_entry("Top boundary ids", "2", Patterns::Anything(),
                    "boundary ids of the loaded end (SW: 2; DT mesh: its upper grips, e.g. 5, 15)");
  prm.declare_entry("Pull direction", "", Patterns::Anything(),
                    "Top end = clamped: 'x y z' direction of the load-path displacement (pull at an angle); "
                    "empty: the Load direction");
  prm.declare_entry("Rotation path (deg)", "", Patterns::Anything(),
                    "Top end = clamped: pseudo-time:angle pairs of a rigid rotation of the top end "
                    "(hybrid tension-bending); empty: none");
  prm.declare_entry("Rotation axis", "0 1 0", Patterns::Anything(), "unit axis of the top-end rotation");
  prm.declare_entry("Rotation centre (mm)", "", Patterns::Anything(),
                    "'x y z' of the rotation and moment centre; empty: centroid of the top end's vertices");
  prm.declare_entry("Grip interface", "clamped", Patterns::Selection("clamped|bonded"),
                    "clamped: the grip surfaces (Bottom/Top boundary ids) are held; bonded: a penalty bond ties "
                    "them to the grips, and the top grips' bond slides at the Grip bond strength (a coating "
                    "sliding on the steel)");
  prm.declare_entry("Grip bond strength (MPa)", "0", Patterns::Double(),
                    "Grip interface = bonded: shear strength tau_b of the top grips' bond (> 0)");
  prm.declare_entry("Grip bond stiffness factor", "1", Patterns::Double(),
                    "Grip interface = bonded: penalty k = factor * E / h, h the smallest grip face (> 0)");
  prm.leave_subsection();
}

void read_boundary_conditions(const Source& source, Parameters& p) {
  ParameterHandler& prm = source.prm;
  const std::string& name = source.name;
  prm.enter_subsection("Boundary conditions");
  p.load.bottom = end_condition(prm.get("Bottom end"));
  p.load.top = end_condition(prm.get("Top end"));
  p.load.direction = prm.get("Load direction") == "lateral" ? LoadDirection::lateral : LoadDirection::axial;
  if (p.load.direction == LoadDirection::lateral && (p.geometry.quarter || p.load.bottom != EndCondition::clamped))
    throw InputError(name, "Load direction = lateral needs Cross section = full and Bottom end = clamped");
  constexpr const char* kSection = "Boundary conditions";
  for (const auto& [t, u] : source.pairs(kSection, "Load path (mm)")) p.load.path.emplace_back(t, u * 1e-3);
  if (p.load.path.size() < 2 || p.load.path.front().first != 0.0 || p.load.path.front().second != 0.0)
    source.fail(kSection, "Load path (mm)", "expected at least two pairs starting with 0:0");
  for (std::size_t i = 1; i < p.load.path.size(); ++i)
    if (!(p.load.path[i].first > p.load.path[i - 1].first))
      source.fail(kSection, "Load path (mm)", "pseudo-times must increase strictly");
  if (prm.get("Control") == "force") {
    if (p.load.direction != LoadDirection::axial || p.load.top == EndCondition::free)
      throw InputError(name, "Control = force needs Load direction = axial and Top end = clamped or axial");
    p.load.force_control = true;
    p.load.force_path = source.pairs(kSection, "Force path (N)");
    const auto& f = p.load.force_path;
    if (f.size() < 2 || f.front().first != 0.0 || f.front().second != 0.0)
      source.fail(kSection, "Force path (N)", "expected at least two pairs starting with 0:0");
    for (std::size_t i = 1; i < f.size(); ++i)
      if (!(f[i].first > f[i - 1].first))
        source.fail(kSection, "Force path (N)", "pseudo-times must increase strictly");
    p.load.path.clear();
    for (const auto& knot : f) p.load.path.emplace_back(knot.first, 0.0);
  }
  p.load.bottom_ids = contact::parse_id_list(prm.get("Bottom boundary ids"), name, "Bottom boundary ids");
  p.load.top_ids = contact::parse_id_list(prm.get("Top boundary ids"), name, "Top boundary ids");
  if (!prm.get("Pull direction").empty()) {
    const auto d = source.unit("Pull direction");
    p.load.pull_direction.assign(d.begin(), d.end());
  }
  if (!prm.get("Rotation path (deg)").empty()) {
    for (const auto& [t, angle] : source.pairs(kSection, "Rotation path (deg)"))
      p.load.rotation_path.emplace_back(t, angle * M_PI / 180.0);
    if (p.load.rotation_path.empty() || p.load.rotation_path.front().first != 0.0 ||
        p.load.rotation_path.front().second != 0.0)
      source.fail(kSection, "Rotation path (deg)", "expected pairs starting with 0:0");
    for (const auto& knot : p.load.rotation_path) {
      bool found = false;
      for (const auto& k : p.load.path) found = found || std::abs(k.first - knot.first) <= 1e-12 * (1.0 + k.first);
      if (!found)
        throw InputError(name, "'Rotation path (deg)': pseudo-time " + std::to_string(knot.first) +
                                   " is not a knot of 'Load path (mm)'");
    }
    p.load.rotation_axis = source.unit("Rotation axis");
  }
  if (!prm.get("Rotation centre (mm)").empty()) {
    p.load.rotation_centre = source.vector3("Rotation centre (mm)");
    for (auto& x : p.load.rotation_centre) x *= 1e-3;
    p.load.rotation_centre_given = true;
  }
  if ((!p.load.pull_direction.empty() || !p.load.rotation_path.empty()) &&
      (p.load.top != EndCondition::clamped || p.load.force_control))
    throw InputError(name, "'Pull direction' and 'Rotation path (deg)' need Top end = clamped and displacement control");
  if (p.forming.release_after_path && (p.load.top != EndCondition::clamped || p.load.force_control))
    throw InputError(name, "'As made/Release after path' needs Top end = clamped and displacement control (the "
                           "clamped top grips are what lets go)");
  if (prm.get("Grip interface") == "bonded") {
    auto& grip = p.load.grip;
    grip.bonded = true;
    grip.strength = prm.get_double("Grip bond strength (MPa)") * 1e6;
    grip.stiffness_factor = prm.get_double("Grip bond stiffness factor");
    if (!(grip.strength > 0.0))
      throw InputError(name, "'Grip bond strength (MPa)': Grip interface = bonded needs a strength > 0, found '" +
                                 prm.get("Grip bond strength (MPa)") + "'");
    if (!(grip.stiffness_factor > 0.0))
      throw InputError(name, "'Grip bond stiffness factor': expected a factor > 0, found '" +
                                 prm.get("Grip bond stiffness factor") + "'");
    if (p.load.bottom != EndCondition::clamped || p.load.top != EndCondition::clamped || p.load.force_control)
      throw InputError(name, "'Grip interface = bonded' needs Bottom end = clamped, Top end = clamped and "
                             "displacement control (the bond replaces the clamps)");
    if (p.forming.release_after_path)
      throw InputError(name, "'As made/Release after path' needs Grip interface = clamped (the clamps let go)");
    if (!p.forming.state_file.empty())
      throw InputError(name, "'As made/State file' needs Grip interface = clamped (the bond's slip history is not "
                             "part of the saved state)");
  }
  prm.leave_subsection();
}

}  // namespace dtwire::fem::prm_reading
