#include "contact_parameters.hpp"

#include <deal.II/base/parameter_handler.h>

#include <cmath>
#include <sstream>

#include "dtwire/core/error.hpp"

namespace dtwire::fem::contact {
namespace {

namespace Patterns = dealii::Patterns;

std::array<double, 3> parse_vector(const std::string& text, const std::string& file, const std::string& entry) {
  std::istringstream in(text);
  std::array<double, 3> v{};
  for (auto& x : v)
    if (!(in >> x) || !std::isfinite(x))
      throw InputError(file, "Contact: '" + entry + "': expected three numbers, found '" + text + "'");
  std::string rest;
  if (in >> rest) throw InputError(file, "Contact: '" + entry + "': expected three numbers, found '" + text + "'");
  return v;
}

std::array<double, 3> unit(std::array<double, 3> v, const std::string& file, const std::string& entry) {
  const double n = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  if (!(n > 0.0)) throw InputError(file, "Contact: '" + entry + "': expected a non-zero direction");
  for (auto& x : v) x /= n;
  return v;
}

}  // namespace

void declare_contact_parameters(dealii::ParameterHandler& prm) {
  prm.enter_subsection("Contact");
  prm.declare_entry("Boundary id", "0", Patterns::Anything(),
                    "wire boundary ids in contact with the tools, comma-separated (SW: 0 lateral surface; "
                    "DT mesh: 3, 13)");
  prm.declare_entry("Friction coefficient", "0", Patterns::Double(0.0), "Coulomb mu");
  prm.declare_entry("Normal penalty factor", "10", Patterns::Double(0.0),
                    "epsilon_N = factor * E / h, h the smallest contact face size before junction refinement");
  prm.declare_entry("Tangential penalty factor", "10", Patterns::Double(0.0), "epsilon_T = factor * E / h");
  prm.declare_entry("Augmentations", "0", Patterns::Integer(0),
                    "augmented-Lagrange (Uzawa) updates per load step; 0: pure penalty");
  prm.declare_entry("Gap tolerance (mm)", "1e-3", Patterns::Double(0.0),
                    "penetration accepted without a further augmentation");
  for (unsigned i = 1; i <= kMaximumTools; ++i) {
    prm.enter_subsection("Tool " + std::to_string(i));
    prm.declare_entry("Shape", "none", Patterns::Selection("none|plane|cylinder|grooved plate"),
                      "rigid analytic tool");
    prm.declare_entry("Point (mm)", "0 0 0", Patterns::Anything(), "plane: a point on it; cylinder: on its axis");
    prm.declare_entry("Direction", "0 0 1", Patterns::Anything(),
                      "plane: outward normal (towards the wire); cylinder: axis");
    prm.declare_entry("Radius (mm)", "0", Patterns::Double(0.0), "cylinder; groove of a grooved plate");
    prm.declare_entry("Groove axis", "1 0 0", Patterns::Anything(),
                      "grooved plate: direction of the groove, in the plate (perpendicular to Direction)");
    prm.declare_entry("Path (mm)", "0: 0 0 0", Patterns::Anything(),
                      "comma-separated 'pseudo-time: dx dy dz' tool displacements, piecewise linear");
    prm.leave_subsection();
  }
  prm.leave_subsection();

  prm.enter_subsection("Wire contact");
  prm.declare_entry("Enabled", "false", Patterns::Bool(), "frictional contact between the two wires of a DT mesh");
  prm.declare_entry("Slave boundary ids", std::to_string(regions::kWireALateral), Patterns::Anything(),
                    "surface whose Gauss points are checked (DT mesh: wire A's lateral surface)");
  prm.declare_entry("Master boundary ids", std::to_string(regions::kWireBLateral), Patterns::Anything(),
                    "surface of bilinear faces projected onto (DT mesh: wire B's lateral surface)");
  prm.declare_entry("Friction coefficient", "0.2", Patterns::Double(0.0), "Coulomb mu between the wires");
  prm.declare_entry("Normal penalty factor", "10", Patterns::Double(0.0), "epsilon_N = factor * E / h");
  prm.declare_entry("Tangential penalty factor", "10", Patterns::Double(0.0), "epsilon_T = factor * E / h");
  prm.declare_entry("Augmentations", "0", Patterns::Integer(0), "Uzawa updates per load step; 0: pure penalty");
  prm.declare_entry("Gap tolerance (mm)", "1e-3", Patterns::Double(0.0),
                    "penetration accepted without a further augmentation");
  prm.declare_entry("Search distance (mm)", "0", Patterns::Double(0.0),
                    "candidate master faces within this distance of a slave face; 0: d / 4");
  prm.declare_entry("Gauss points per direction", "2", Patterns::Integer(1, 6), "on each slave face");
  prm.declare_entry("Gap offset (mm)", "0", Patterns::Double(),
                    "added to every wire-wire gap: extra initial clearance (> 0, slack of the twist) or "
                    "interference (< 0, a twist tighter than meshed)");
  prm.declare_entry("Status flip limit", "4", Patterns::Integer(1),
                    "stick/slip changes or master-face switches of a point within one step before its "
                    "status is frozen for the rest of the step (chattering guard)");
  prm.declare_entry("Smoothed normals", "false", Patterns::Bool(),
                    "master normal interpolated from averaged vertex normals, continuous over facet edges "
                    "(smooth forces when points slide around the faceted wire; false: the facet's normal)");
  prm.leave_subsection();
}

std::vector<unsigned> parse_id_list(const std::string& text, const std::string& file, const std::string& entry) {
  std::vector<unsigned> ids;
  std::stringstream list(text);
  std::string item;
  while (std::getline(list, item, ',')) {
    if (item.find_first_not_of(" \t") == std::string::npos) continue;
    try {
      std::size_t used = 0;
      const int id = std::stoi(item, &used);
      if (item.find_first_not_of(" \t", used) != std::string::npos || id < 0 || id > 255)
        throw std::invalid_argument("bad id");
      ids.push_back(static_cast<unsigned>(id));
    } catch (const std::exception&) {
      throw InputError(file, "'" + entry + "': expected comma-separated boundary ids 0-255, found '" + item + "'");
    }
  }
  if (ids.empty()) throw InputError(file, "'" + entry + "': expected at least one boundary id");
  return ids;
}

WireContactParameters parse_wire_contact_parameters(dealii::ParameterHandler& prm, const std::string& file) {
  WireContactParameters w;
  prm.enter_subsection("Wire contact");
  w.enabled = prm.get_bool("Enabled");
  w.slave_ids = parse_id_list(prm.get("Slave boundary ids"), file, "Wire contact/Slave boundary ids");
  w.master_ids = parse_id_list(prm.get("Master boundary ids"), file, "Wire contact/Master boundary ids");
  for (const unsigned id : w.slave_ids)
    for (const unsigned other : w.master_ids)
      if (id == other)
        throw InputError(file, "'Wire contact': boundary id " + std::to_string(id) + " is both slave and master");
  w.friction = prm.get_double("Friction coefficient");
  w.normal_penalty_factor = prm.get_double("Normal penalty factor");
  w.tangential_penalty_factor = prm.get_double("Tangential penalty factor");
  if (!(w.normal_penalty_factor > 0.0) || !(w.tangential_penalty_factor > 0.0))
    throw InputError(file, "'Wire contact': expected positive penalty factors");
  w.maximum_augmentations = prm.get_integer("Augmentations");
  w.gap_tolerance = prm.get_double("Gap tolerance (mm)") * 1e-3;
  w.search_distance = prm.get_double("Search distance (mm)") * 1e-3;
  w.points_per_direction = prm.get_integer("Gauss points per direction");
  w.gap_offset = prm.get_double("Gap offset (mm)") * 1e-3;
  if (!(w.gap_offset > -0.25e-3))  // deeper interference would reach beyond the contact search
    throw InputError(file, "'Wire contact/Gap offset (mm)': expected an interference smaller than 0.25 mm");
  w.flip_limit = prm.get_integer("Status flip limit");
  w.smoothed_normals = prm.get_bool("Smoothed normals");
  prm.leave_subsection();
  return w;
}

ContactParameters parse_contact_parameters(dealii::ParameterHandler& prm, const std::string& file,
                                           const std::vector<double>& knot_times) {
  ContactParameters c;
  prm.enter_subsection("Contact");
  c.boundary_ids = parse_id_list(prm.get("Boundary id"), file, "Contact/Boundary id");
  c.friction = prm.get_double("Friction coefficient");
  c.normal_penalty_factor = prm.get_double("Normal penalty factor");
  c.tangential_penalty_factor = prm.get_double("Tangential penalty factor");
  c.maximum_augmentations = prm.get_integer("Augmentations");
  c.gap_tolerance = prm.get_double("Gap tolerance (mm)") * 1e-3;
  for (unsigned i = 1; i <= kMaximumTools; ++i) {
    const std::string name = "Tool " + std::to_string(i);
    prm.enter_subsection(name);
    const std::string shape = prm.get("Shape");
    if (shape != "none") {
      ToolParameters t;
      t.shape = shape == "plane"      ? ToolShape::plane
                : shape == "cylinder" ? ToolShape::cylinder
                                      : ToolShape::grooved_plate;
      t.point = parse_vector(prm.get("Point (mm)"), file, name + "/Point (mm)");
      for (auto& x : t.point) x *= 1e-3;
      t.direction = unit(parse_vector(prm.get("Direction"), file, name + "/Direction"), file, name + "/Direction");
      t.radius = prm.get_double("Radius (mm)") * 1e-3;
      if (t.shape != ToolShape::plane && !(t.radius > 0.0))
        throw InputError(file, "Contact: '" + name + "/Radius (mm)': expected a positive radius for " + shape);
      if (t.shape == ToolShape::grooved_plate) {
        const std::string entry = name + "/Groove axis";
        t.groove_axis = unit(parse_vector(prm.get("Groove axis"), file, entry), file, entry);
        double cosine = 0.0;
        for (unsigned k = 0; k < 3; ++k) cosine += t.groove_axis[k] * t.direction[k];
        if (std::abs(cosine) > 1e-9)
          throw InputError(file, "Contact: '" + name + "/Groove axis': expected a direction perpendicular to Direction");
      }
      std::stringstream list(prm.get("Path (mm)"));
      std::string item;
      while (std::getline(list, item, ',')) {
        const auto colon = item.find(':');
        const std::string entry = name + "/Path (mm)";
        double time = 0.0;
        try {
          if (colon == std::string::npos) throw std::invalid_argument("no colon");
          time = std::stod(item.substr(0, colon));
        } catch (const std::exception&) {
          throw InputError(file, "Contact: '" + entry + "': expected 'time: dx dy dz' items, found '" + item + "'");
        }
        auto d = parse_vector(item.substr(colon + 1), file, entry);
        for (auto& x : d) x *= 1e-3;
        if (!t.path.empty() && !(time > t.path.back().first))
          throw InputError(file, "Contact: '" + entry + "': pseudo-times must increase strictly");
        t.path.emplace_back(time, d);
      }
      if (t.path.empty() || t.path.front().first != 0.0)
        throw InputError(file, "Contact: '" + name + "/Path (mm)': expected a first item at pseudo-time 0");
      for (const auto& knot : t.path) {
        if (knot_times.empty() || knot.first > knot_times.back()) continue;
        bool found = false;
        for (const double k : knot_times) found = found || std::abs(k - knot.first) <= 1e-12 * (1.0 + std::abs(k));
        if (!found)
          throw InputError(file, "Contact: '" + name + "/Path (mm)': pseudo-time " + std::to_string(knot.first) +
                                     " is not a knot of 'Load path (mm)' (add it there so that a step ends on it)");
      }
      c.tools.push_back(t);
    }
    prm.leave_subsection();
  }
  prm.leave_subsection();
  return c;
}

std::array<double, 3> tool_displacement(const ToolParameters& tool, double t) {
  const auto& path = tool.path;
  if (t <= path.front().first) return path.front().second;
  for (std::size_t i = 1; i < path.size(); ++i)
    if (t <= path[i].first) {
      const double s = (t - path[i - 1].first) / (path[i].first - path[i - 1].first);
      std::array<double, 3> d{};
      for (unsigned k = 0; k < 3; ++k) d[k] = path[i - 1].second[k] + s * (path[i].second[k] - path[i - 1].second[k]);
      return d;
    }
  return path.back().second;
}

}  // namespace dtwire::fem::contact
