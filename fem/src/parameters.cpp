#include "parameters.hpp"

#include <deal.II/base/parameter_handler.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>
#include <regex>
#include <sstream>

#include "dtwire/core/error.hpp"
#include "link_kinematics.hpp"
#include "prm_check.hpp"

namespace dtwire::fem {
namespace {

using dealii::ParameterHandler;
namespace Patterns = dealii::Patterns;

void declare(ParameterHandler& prm) {
  prm.enter_subsection("Geometry");
  prm.declare_entry("Diameter (mm)", "2.7", Patterns::Double(0.0), "Wire diameter");
  prm.declare_entry("Length (mm)", "60", Patterns::Double(0.0), "Free length along z");
  prm.declare_entry("Cross section", "quarter", Patterns::Selection("full|quarter"),
                    "quarter: symmetry planes x = 0 and y = 0");
  prm.declare_entry("Radial refinements", "1", Patterns::Integer(0, 6),
                    "Global refinements of the cross-section disc");
  prm.declare_entry("Axial cells", "30", Patterns::Integer(1), "Cells along the length");
  prm.declare_entry("Imperfection", "0", Patterns::Double(0.0, 0.5),
                    "Relative radius reduction at the imperfection centre");
  prm.declare_entry("Imperfection centre (mm)", "30", Patterns::Double(), "z of the smallest radius");
  prm.declare_entry("Imperfection half width (mm)", "30", Patterns::Double(0.0),
                    "Half width of the cosine radius profile");
  prm.declare_entry("Mesh file", "", Patterns::Anything(),
                    "gmsh .msh of a single wire from `dtwire mesh sw` (relative to this file); "
                    "replaces the generated mesh (Diameter and Length are then taken from it)");
  prm.declare_entry("Bow imperfection (mm)", "0", Patterns::Double(),
                    "Lateral offset at mid-length, shape of the fixed-fixed buckling mode");
  prm.declare_entry("Mesh distortion", "0", Patterns::Double(0.0, 0.4),
                    "Random shift of interior vertices, fraction of the local cell size");
  prm.leave_subsection();

  prm.enter_subsection("Material");
  prm.declare_entry("Young modulus (MPa)", "200000", Patterns::Double(0.0), "");
  prm.declare_entry("Poisson ratio", "0.3", Patterns::Double(-1.0, 0.5), "");
  prm.declare_entry("Hardening law", "linear", Patterns::Selection("linear|voce|swift|table"), "");
  prm.declare_entry("Yield stress (MPa)", "250", Patterns::Double(0.0), "linear, voce");
  prm.declare_entry("Hardening modulus (MPa)", "0", Patterns::Double(), "linear, voce: linear term");
  prm.declare_entry("Saturation stress (MPa)", "0", Patterns::Double(0.0), "voce");
  prm.declare_entry("Saturation rate", "0", Patterns::Double(0.0), "voce");
  prm.declare_entry("Swift coefficient (MPa)", "0", Patterns::Double(0.0), "swift: K");
  prm.declare_entry("Swift offset", "0.002", Patterns::Double(0.0), "swift: eps0");
  prm.declare_entry("Swift exponent", "0.2", Patterns::Double(0.0), "swift: n");
  prm.declare_entry("Hardening table", "", Patterns::Anything(),
                    "table: comma-separated plastic_strain:true_stress_MPa pairs");
  prm.declare_entry("Failure d1", "0", Patterns::Double(), "Johnson-Cook eps_f = d1 + d2 exp(d3 eta); 0, 0: off");
  prm.declare_entry("Failure d2", "0", Patterns::Double(), "");
  prm.declare_entry("Failure d3", "0", Patterns::Double(), "");
  prm.declare_entry("Failure shear ductility ratio", "1", Patterns::Double(0.01, 1.0),
                    "s: strain to failure in shear (Lode angle parameter 0) over that in axisymmetric "
                    "tension at the same triaxiality, eps_f = JC(eta) (s + (1 - s) theta^2); 1: Johnson-Cook");
  prm.declare_entry("Stop at failure", "true", Patterns::Bool(), "end the run when the indicator reaches 1");
  prm.declare_entry("Kinematic modulus (MPa)", "0", Patterns::Double(0.0),
                    "Armstrong-Frederick C (0: no kinematic hardening), combined with the isotropic law");
  prm.declare_entry("Kinematic saturation rate", "0", Patterns::Double(0.0),
                    "Armstrong-Frederick gamma: backstress saturates at C/gamma (0: linear Prager)");
  prm.leave_subsection();

  prm.enter_subsection("Formulation");
  prm.declare_entry("Element", "fbar", Patterns::Selection("fbar|displacement"),
                    "fbar: locking-free mean-dilatation F-bar; displacement: plain Q1");
  prm.declare_entry("Polynomial degree", "1", Patterns::Integer(1, 2), "");
  prm.leave_subsection();

  prm.enter_subsection("As made");
  prm.declare_entry("Forming history", "false", Patterns::Bool(),
                    "start from the wires bent from straight wire into the mesh's axes (plastic strain, "
                    "backstress, damage and stress of that bending), released with the bottom grips held "
                    "(springback) before the load path; double-twist mesh files only");
  prm.declare_entry("Forming scale", "1", Patterns::Double(0.0, 2.0),
                    "fraction of each fibre's bending strain taken as forming (0: tight and stress-free)");
  prm.declare_entry("Axis file", "", Patterns::Anything(),
                    "the mesh's wire axes (CSV of `dtwire mesh`); empty: the mesh file with .axis.csv");
  prm.declare_entry("Forming increments", "20", Patterns::Integer(1, 1000), "steps of each fibre's forming path");
  prm.declare_entry("Initial release step", "0.25", Patterns::Double(1e-4, 1.0),
                    "fraction of the forming stress released in the first springback step");
  prm.declare_entry("State file", "", Patterns::Anything(),
                    "start from the as-made state an earlier run wrote (its as_made_state.bin) instead of "
                    "forming and springback again: same mesh, element, material and Forming scale; needs "
                    "Forming history = true");
  prm.declare_entry("Release after path", "false", Patterns::Bool(),
                    "after the load and rotation paths the top grips let go: their forces fall to zero in steps "
                    "(from Initial release step), the bottom grips held, as a twisting machine releases the "
                    "twist; writes as_made.csv (the state along the Axis file's stations) and "
                    "twisted_pair_state.csv (for another mesh's Twisted pair state); needs Top end = clamped "
                    "and Forming history = false");
  prm.declare_entry("Twisted pair state", "", Patterns::Anything(),
                    "the twisted_pair_state.csv of a twisting run (Release after path = true on a straight "
                    "pair, `dtwire mesh dt --half-turns 0`): inside the twist (between the heights where "
                    "the wire axes leave the helix) each point takes the state of the pair's nearest point "
                    "at the same relative height and offset from its wire's axis; the arms and junction "
                    "bends are formed by bending as without it; needs Forming history = true");
  prm.leave_subsection();

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

  prm.enter_subsection("Load stepping");
  prm.declare_entry("Initial step", "0.01", Patterns::Double(0.0), "pseudo-time");
  prm.declare_entry("Minimum step", "1e-6", Patterns::Double(0.0), "");
  prm.declare_entry("Maximum step", "0.05", Patterns::Double(0.0), "");
  prm.declare_entry("Growth factor", "1.5", Patterns::Double(1.0), "");
  prm.declare_entry("Cutback factor", "0.5", Patterns::Double(0.0, 1.0), "");
  prm.declare_entry("Easy iterations", "4", Patterns::Integer(1), "");
  prm.leave_subsection();

  prm.enter_subsection("Newton");
  prm.declare_entry("Maximum iterations", "15", Patterns::Integer(1), "");
  prm.declare_entry("Relative tolerance", "1e-10", Patterns::Double(0.0), "");
  prm.declare_entry("Line search", "true", Patterns::Bool(), "");
  prm.declare_entry("Maximum line search steps", "5", Patterns::Integer(0), "");
  prm.declare_entry("Linear solver", "direct", Patterns::Selection("direct|gmres-amg|lagged-lu"),
                    "direct: MUMPS; gmres-amg: GMRES with PETSc GAMG and the rigid-body modes (large problems); "
                    "lagged-lu: GMRES preconditioned by the MUMPS factors of an earlier tangent, factorised anew "
                    "when GMRES needs more than Lagged LU iterations");
  prm.declare_entry("Lagged LU iterations", "15", Patterns::Integer(1, 200),
                    "lagged-lu: GMRES iterations before the tangent is factorised anew");
  prm.declare_entry("Linear tolerance", "1e-12", Patterns::Double(0.0), "gmres-amg: relative residual");
  prm.declare_entry("Maximum linear iterations", "2000", Patterns::Integer(1), "gmres-amg");
  prm.declare_entry("Tangent reuse contraction", "0", Patterns::Double(0.0, 1.0),
                    "direct solver: keep the last factorisation (modified Newton) while each iteration "
                    "reduced the residual below this fraction of the previous one; 0: a fresh tangent "
                    "every iteration (full Newton)");
  prm.leave_subsection();

  prm.enter_subsection("Output");
  prm.declare_entry("Fields", "true", Patterns::Bool(), "write VTU/PVTU fields");
  prm.declare_entry("Field interval", "0", Patterns::Integer(0), "every n steps; the last always");
  prm.declare_entry("Probe points (mm)", "", Patterns::Anything(),
                    "semicolon-separated 'x y z' material points (reference configuration) whose displacement "
                    "is written every step (probe<k>_displacement_{x,y,z}_mm)");
  prm.declare_entry("Extensometer (mm)", "", Patterns::Anything(),
                    "pairs of material points 'x y z, x y z' separated by ';': a virtual extensometer whose "
                    "elongation (mean change of distance of the pairs) is written as extensometer_elongation_mm");
  prm.declare_entry("Curve displacement", "load path", Patterns::Selection("load path|extensometer"),
                    "what the curve's displacement_mm column holds: the load-path displacement, or the "
                    "extensometer elongation (the load path then goes to grip_displacement_mm)");
  prm.declare_entry("Link sections (mm)", "", Patterns::Anything(),
                    "double twist as a DEM link: bottom and top section, each 'x y z, x y z, x y z, x y z' (the "
                    "two wires' axis points, then a point off the axis in each wire, offset the same way), separated "
                    "by ';'; adds link_elongation_mm, "
                    "link_rotation_{x,y,z}_rad, link_axial_force_N, link_shear_force_N, link_moment_{x,y,z}_Nm");
  prm.declare_entry("Checkpoint interval", "0", Patterns::Integer(0),
                    "write a restart checkpoint every n steps (0: none)");
  prm.leave_subsection();

  contact::declare_contact_parameters(prm);  // contact (issue 5)
}

std::vector<std::pair<double, double>> parse_pairs(const std::string& text, const std::string& file,
                                                   const std::string& entry) {
  std::vector<std::pair<double, double>> pairs;
  std::stringstream list(text);
  std::string item;
  while (std::getline(list, item, ',')) {
    if (item.find_first_not_of(" \t") == std::string::npos) continue;
    const auto colon = item.find(':');
    try {
      if (colon == std::string::npos) throw std::invalid_argument("no colon");
      std::size_t used = 0;
      const double x = std::stod(item.substr(0, colon), &used);
      const double y = std::stod(item.substr(colon + 1), &used);
      if (!std::isfinite(x) || !std::isfinite(y)) throw std::invalid_argument("not finite");
      pairs.emplace_back(x, y);
    } catch (const std::exception&) {
      throw InputError(file, "'" + entry + "': expected number:number pairs, found '" + item + "'");
    }
  }
  return pairs;
}

// A gmsh file starts with $MeshFormat ($NOD in format 1); an empty or garbage file would otherwise reach deal.II's
// reader and fail there without naming the file.
bool looks_like_gmsh(const std::filesystem::path& mesh) {
  std::ifstream in(mesh);
  std::string line;
  while (std::getline(in, line) && line.find_first_not_of(" \t\r") == std::string::npos) {
  }
  return line.rfind("$MeshFormat", 0) == 0 || line.rfind("$NOD", 0) == 0;  // gmsh 2-4, gmsh 1
}

EndCondition end_condition(const std::string& s) {
  if (s == "axial") return EndCondition::axial;
  if (s == "symmetry") return EndCondition::symmetry;
  if (s == "guided") return EndCondition::guided;
  if (s == "free") return EndCondition::free;
  return EndCondition::clamped;
}

// `Section/Sub/Entry=value` from the command line, set on top of the file; a relative
// file (Mesh file, Axis file, State file) given this way is taken from the working directory,
// where the user typed it.
void apply_setting(ParameterHandler& prm, const std::string& setting) {
  const auto equals = setting.find('=');
  if (equals == std::string::npos || equals == 0)
    throw InputError("--set", "'" + setting + "': expected Section/Entry=value");
  std::string path = setting.substr(0, equals), value = setting.substr(equals + 1);
  std::vector<std::string> sections;
  for (auto slash = path.find('/'); slash != std::string::npos; slash = path.find('/')) {
    sections.push_back(path.substr(0, slash));
    path.erase(0, slash + 1);
  }
  const bool file_entry =
      path == "Mesh file" || path == "Axis file" || path == "State file" || path == "Twisted pair state";
  if (file_entry && !value.empty()) value = std::filesystem::absolute(value).string();
  for (const auto& s : sections) prm.enter_subsection(s);
  try {
    prm.set(path, value);
  } catch (const std::exception& e) {
    for (std::size_t i = 0; i < sections.size(); ++i) prm.leave_subsection();
    throw InputError("--set", "'" + setting + "': " + deal_ii_message(e.what()));
  }
  for (std::size_t i = 0; i < sections.size(); ++i) prm.leave_subsection();
}

}  // namespace

// deal.II's exception text is long; keep its "Additional information" on one line.
std::string deal_ii_message(const std::string& what) {
  std::string text = what;
  const auto pos = text.find("Additional information:");
  if (pos != std::string::npos) text = text.substr(pos + 23);
  const auto stack = text.find("Stacktrace:");
  if (stack != std::string::npos) text = text.substr(0, stack);
  text = std::regex_replace(text, std::regex("[\\s-]+\\n|\\s+"), " ");
  return std::regex_replace(text, std::regex("^ +| +$"), "");
}

namespace {
// The parsed file and where each entry came from, so that a bad value is reported where it was
// given: --set, the file's line, or the file (a default).
struct Source {
  ParameterHandler& prm;
  const std::filesystem::path& file;
  const std::string& name;
  const EntryLines& lines;
  const std::set<std::string>& set_on_command_line;

  // Called inside `section`.
  void require(bool ok, const std::string& section, const std::string& entry, const std::string& expected) const {
    if (ok) return;
    const std::string path = section + "/" + entry;
    const std::string message = "'" + entry + "': expected " + expected + ", found '" + prm.get(entry) + "'";
    if (set_on_command_line.count(path)) throw InputError("--set", path + ": " + message);
    const auto line = lines.find(path);
    throw InputError(name, line == lines.end() ? 0 : line->second, 0, "subsection " + section + ": " + message);
  }
  std::array<double, 3> vector3(const std::string& entry) const {
    std::istringstream in(prm.get(entry));
    std::array<double, 3> v{};
    for (auto& x : v)
      if (!(in >> x) || !std::isfinite(x)) throw InputError(name, "'" + entry + "': expected three numbers");
    std::string rest;
    if (in >> rest) throw InputError(name, "'" + entry + "': expected three numbers");
    return v;
  }
  std::array<double, 3> unit(const std::string& entry) const {
    auto v = vector3(entry);
    const double n = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (!(n > 0.0)) throw InputError(name, "'" + entry + "': expected a non-zero direction");
    for (auto& x : v) x /= n;
    return v;
  }
};

void read_geometry(Source& source, Parameters& p) {
  ParameterHandler& prm = source.prm;
  const std::string& name = source.name;
  prm.enter_subsection("Geometry");
  p.geometry.diameter = prm.get_double("Diameter (mm)") * 1e-3;
  p.geometry.length = prm.get_double("Length (mm)") * 1e-3;
  p.geometry.quarter = prm.get("Cross section") == "quarter";
  p.geometry.radial_refinements = prm.get_integer("Radial refinements");
  p.geometry.axial_cells = prm.get_integer("Axial cells");
  p.geometry.imperfection = prm.get_double("Imperfection");
  p.geometry.imperfection_centre = prm.get_double("Imperfection centre (mm)") * 1e-3;
  p.geometry.imperfection_half_width = prm.get_double("Imperfection half width (mm)") * 1e-3;
  p.geometry.mesh_distortion = prm.get_double("Mesh distortion");
  p.geometry.bow = prm.get_double("Bow imperfection (mm)") * 1e-3;
  if (!prm.get("Mesh file").empty()) {
    p.geometry.mesh_file = source.file.parent_path() / prm.get("Mesh file");
    const std::string mesh = p.geometry.mesh_file.string();
    source.require(std::filesystem::is_regular_file(p.geometry.mesh_file), "Geometry", "Mesh file",
            "a readable file (cannot open " + mesh + ")");
    source.require(looks_like_gmsh(p.geometry.mesh_file), "Geometry", "Mesh file",
            "a gmsh .msh file starting with $MeshFormat or $NOD (" + mesh + " is empty or is not one)");
    if (p.geometry.quarter || p.geometry.imperfection != 0.0 || p.geometry.bow != 0.0 || p.geometry.mesh_distortion != 0.0)
      throw InputError(name, "'Mesh file' needs Cross section = full and no imperfection, bow or distortion");
  }
  const bool generated = p.geometry.mesh_file.empty();  // a mesh file brings its own sizes
  source.require(!generated || p.geometry.diameter > 0.0, "Geometry", "Diameter (mm)", "a diameter > 0");
  source.require(!generated || p.geometry.length > 0.0, "Geometry", "Length (mm)", "a length > 0");
  if (p.geometry.bow != 0.0 && p.geometry.quarter)
    throw InputError(name, "'Bow imperfection (mm)' needs Cross section = full");
  prm.leave_subsection();
}

void read_material(Source& source, Parameters& p) {
  ParameterHandler& prm = source.prm;
  const std::string& name = source.name;
  prm.enter_subsection("Material");
  p.material.young = prm.get_double("Young modulus (MPa)") * 1e6;
  p.material.poisson = prm.get_double("Poisson ratio");
  source.require(p.material.young > 0.0, "Material", "Young modulus (MPa)", "a modulus > 0");
  source.require(p.material.poisson > -1.0 && p.material.poisson < 0.5, "Material", "Poisson ratio",
          "a ratio in (-1, 0.5) exclusive (0.5: incompressible, no bulk modulus)");
  auto& h = p.material.hardening;
  h.law = parse_hardening_law(prm.get("Hardening law"));
  p.material.failure.d1 = prm.get_double("Failure d1");
  p.material.failure.d2 = prm.get_double("Failure d2");
  p.material.failure.d3 = prm.get_double("Failure d3");
  p.material.failure.shear_ductility_ratio = prm.get_double("Failure shear ductility ratio");
  p.material.stop_at_failure = prm.get_bool("Stop at failure");
  p.material.kinematic.modulus = prm.get_double("Kinematic modulus (MPa)") * 1e6;
  p.material.kinematic.saturation_rate = prm.get_double("Kinematic saturation rate");
  h.yield_stress = prm.get_double("Yield stress (MPa)") * 1e6;
  h.linear_modulus = prm.get_double("Hardening modulus (MPa)") * 1e6;
  h.saturation_stress = prm.get_double("Saturation stress (MPa)") * 1e6;
  h.saturation_rate = prm.get_double("Saturation rate");
  h.swift_coefficient = prm.get_double("Swift coefficient (MPa)") * 1e6;
  h.swift_offset = prm.get_double("Swift offset");
  h.swift_exponent = prm.get_double("Swift exponent");
  for (const auto& [strain, stress] : parse_pairs(prm.get("Hardening table"), name, "Hardening table")) {
    h.table_plastic_strain.push_back(strain);
    h.table_stress.push_back(stress * 1e6);
  }
  try {
    IsotropicHardening check(h);
  } catch (const std::invalid_argument& e) {
    throw InputError(name, std::string("subsection Material: ") + e.what());
  }
  prm.leave_subsection();
}

void read_formulation(Source& source, Parameters& p) {
  ParameterHandler& prm = source.prm;
  prm.enter_subsection("Formulation");
  p.formulation.fbar = prm.get("Element") == "fbar";
  p.formulation.degree = prm.get_integer("Polynomial degree");
  prm.leave_subsection();
}

void read_forming(Source& source, Parameters& p) {
  ParameterHandler& prm = source.prm;
  prm.enter_subsection("As made");
  auto& f = p.forming;
  f.enabled = prm.get_bool("Forming history");
  f.scale = prm.get_double("Forming scale");
  f.increments = static_cast<unsigned>(prm.get_integer("Forming increments"));
  f.initial_release_step = prm.get_double("Initial release step");
  f.release_after_path = prm.get_bool("Release after path");
  source.require(!(f.enabled && f.release_after_path), "As made", "Release after path",
                 "false with Forming history = true (the release ends a twisting run; the forming has its own)");
  if (f.enabled || f.release_after_path) {
    source.require(!p.geometry.mesh_file.empty(), "As made", f.enabled ? "Forming history" : "Release after path",
                   "false without a mesh file (the forming bends wires into the axes of a `dtwire mesh` file; the "
                   "release records the state along them)");
    f.axis_file = prm.get("Axis file").empty() ? std::filesystem::path(p.geometry.mesh_file).replace_extension(".axis.csv")
                                               : source.file.parent_path() / prm.get("Axis file");
    source.require(std::filesystem::is_regular_file(f.axis_file), "As made", "Axis file",
                   "the mesh's axis file (cannot open " + f.axis_file.string() +
                       "; `dtwire mesh ... -o X.msh` writes X.axis.csv beside the mesh)");
    f.axes = read_axis_csv(f.axis_file);  // a bad row is named file:line before any output
  }
  if (!prm.get("State file").empty()) {
    source.require(f.enabled, "As made", "State file", "empty unless Forming history = true");
    f.state_file = source.file.parent_path() / prm.get("State file");
    source.require(std::filesystem::is_regular_file(f.state_file), "As made", "State file",
                   "the as_made_state.bin of a run with Forming history = true (cannot open " + f.state_file.string() + ")");
  }
  if (!prm.get("Twisted pair state").empty()) {
    source.require(f.enabled && f.state_file.empty(), "As made", "Twisted pair state",
                   "empty unless Forming history = true and State file is empty (a state file already holds "
                   "the twist's state)");
    f.twisted_pair_state = source.file.parent_path() / prm.get("Twisted pair state");
    source.require(std::filesystem::is_regular_file(f.twisted_pair_state), "As made", "Twisted pair state",
                   "the twisted_pair_state.csv of a run with Release after path = true (cannot open " +
                       f.twisted_pair_state.string() + ")");
  }
  prm.leave_subsection();
}

void read_boundary_conditions(Source& source, Parameters& p) {
  ParameterHandler& prm = source.prm;
  const std::string& name = source.name;
  prm.enter_subsection("Boundary conditions");
  p.load.bottom = end_condition(prm.get("Bottom end"));
  p.load.top = end_condition(prm.get("Top end"));
  p.load.direction = prm.get("Load direction") == "lateral" ? LoadDirection::lateral : LoadDirection::axial;
  if (p.load.direction == LoadDirection::lateral && (p.geometry.quarter || p.load.bottom != EndCondition::clamped))
    throw InputError(name, "Load direction = lateral needs Cross section = full and Bottom end = clamped");
  for (const auto& [t, u] : parse_pairs(prm.get("Load path (mm)"), name, "Load path (mm)"))
    p.load.path.emplace_back(t, u * 1e-3);
  if (p.load.path.size() < 2 || p.load.path.front().first != 0.0 || p.load.path.front().second != 0.0)
    throw InputError(name, "'Load path (mm)': expected at least two pairs starting with 0:0");
  for (std::size_t i = 1; i < p.load.path.size(); ++i)
    if (!(p.load.path[i].first > p.load.path[i - 1].first))
      throw InputError(name, "'Load path (mm)': pseudo-times must increase strictly");
  if (prm.get("Control") == "force") {
    if (p.load.direction != LoadDirection::axial || p.load.top == EndCondition::free)
      throw InputError(name, "Control = force needs Load direction = axial and Top end = clamped or axial");
    p.load.force_control = true;
    p.load.force_path = parse_pairs(prm.get("Force path (N)"), name, "Force path (N)");
    const auto& f = p.load.force_path;
    if (f.size() < 2 || f.front().first != 0.0 || f.front().second != 0.0)
      throw InputError(name, "'Force path (N)': expected at least two pairs starting with 0:0");
    for (std::size_t i = 1; i < f.size(); ++i)
      if (!(f[i].first > f[i - 1].first))
        throw InputError(name, "'Force path (N)': pseudo-times must increase strictly");
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
    for (const auto& [t, angle] : parse_pairs(prm.get("Rotation path (deg)"), name, "Rotation path (deg)"))
      p.load.rotation_path.emplace_back(t, angle * M_PI / 180.0);
    if (p.load.rotation_path.empty() || p.load.rotation_path.front().first != 0.0 ||
        p.load.rotation_path.front().second != 0.0)
      throw InputError(name, "'Rotation path (deg)': expected pairs starting with 0:0");
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

void read_load_stepping(Source& source, Parameters& p) {
  ParameterHandler& prm = source.prm;
  const std::string& name = source.name;
  prm.enter_subsection("Load stepping");
  p.stepping.initial_step = prm.get_double("Initial step");
  p.stepping.minimum_step = prm.get_double("Minimum step");
  p.stepping.maximum_step = prm.get_double("Maximum step");
  p.stepping.growth_factor = prm.get_double("Growth factor");
  p.stepping.cutback_factor = prm.get_double("Cutback factor");
  p.stepping.easy_iterations = prm.get_integer("Easy iterations");
  source.require(p.stepping.minimum_step > 0.0, "Load stepping", "Minimum step", "a pseudo-time step > 0");
  source.require(p.stepping.cutback_factor > 0.0 && p.stepping.cutback_factor < 1.0, "Load stepping", "Cutback factor",
          "a factor in (0, 1) exclusive");
  if (!(p.stepping.minimum_step <= p.stepping.initial_step && p.stepping.initial_step <= p.stepping.maximum_step))
    throw InputError(name, "Load stepping: expected Minimum step <= Initial step <= Maximum step");
  prm.leave_subsection();
}

void read_newton(Source& source, Parameters& p) {
  ParameterHandler& prm = source.prm;
  prm.enter_subsection("Newton");
  p.newton.maximum_iterations = prm.get_integer("Maximum iterations");
  p.newton.relative_tolerance = prm.get_double("Relative tolerance");
  p.newton.line_search = prm.get_bool("Line search");
  p.newton.maximum_line_search_steps = prm.get_integer("Maximum line search steps");
  p.newton.krylov = prm.get("Linear solver") == "gmres-amg";
  if (prm.get("Linear solver") == "lagged-lu") p.newton.lagged_lu_iterations = prm.get_integer("Lagged LU iterations");
  p.newton.linear_tolerance = prm.get_double("Linear tolerance");
  source.require(p.newton.relative_tolerance > 0.0, "Newton", "Relative tolerance", "a tolerance > 0");
  p.newton.maximum_linear_iterations = prm.get_integer("Maximum linear iterations");
  p.newton.tangent_reuse_contraction = prm.get_double("Tangent reuse contraction");
  prm.leave_subsection();
}

void read_output(Source& source, Parameters& p) {
  ParameterHandler& prm = source.prm;
  const std::string& name = source.name;
  prm.enter_subsection("Output");
  p.output.fields = prm.get_bool("Fields");
  p.output.field_interval = prm.get_integer("Field interval");
  p.output.checkpoint_interval = prm.get_integer("Checkpoint interval");
  {
    std::stringstream list(prm.get("Probe points (mm)"));
    std::string item;
    while (std::getline(list, item, ';')) {
      if (item.find_first_not_of(" \t") == std::string::npos) continue;
      std::istringstream in(item);
      std::array<double, 3> x{};
      for (auto& v : x)
        if (!(in >> v) || !std::isfinite(v))
          throw InputError(name, "'Probe points (mm)': expected 'x y z' items separated by ';', found '" + item + "'");
      for (auto& v : x) v *= 1e-3;
      p.output.probe_points.push_back(x);
    }
  }
  {
    const std::string entry = "'Extensometer (mm)'";
    std::stringstream list(prm.get("Extensometer (mm)"));
    std::string item;
    while (std::getline(list, item, ';')) {
      if (item.find_first_not_of(" \t") == std::string::npos) continue;
      std::istringstream in(item);
      std::array<double, 6> x{};
      char comma = 0;
      const bool ok = (in >> x[0] >> x[1] >> x[2]) && (in >> comma) && comma == ',' && (in >> x[3] >> x[4] >> x[5]) &&
                      (in >> std::ws).eof() && std::all_of(x.begin(), x.end(), [](double v) { return std::isfinite(v); });
      if (!ok)
        throw InputError(name, entry + ": expected pairs 'x y z, x y z' separated by ';', found '" + item + "'");
      if (x[0] == x[3] && x[1] == x[4] && x[2] == x[5])
        throw InputError(name, entry + ": the two points of '" + item + "' coincide (no gauge length)");
      const std::size_t first = p.output.probe_points.size();
      p.output.probe_points.push_back({{x[0] * 1e-3, x[1] * 1e-3, x[2] * 1e-3}});
      p.output.probe_points.push_back({{x[3] * 1e-3, x[4] * 1e-3, x[5] * 1e-3}});
      p.output.extensometer.push_back({{first, first + 1}});
    }
    p.output.extensometer_as_displacement = prm.get("Curve displacement") == "extensometer";
  }
  {
    const std::string entry = "'Link sections (mm)'";
    std::stringstream list(prm.get("Link sections (mm)"));
    std::string item;
    while (std::getline(list, item, ';')) {
      if (item.find_first_not_of(" \t") == std::string::npos) continue;
      std::istringstream in(item);
      SectionPoints section{};
      bool ok = true;
      for (unsigned k = 0; k < 4 && ok; ++k) {
        char comma = 0;
        ok = (in >> section[k][0] >> section[k][1] >> section[k][2]) && (k == 3 || ((in >> comma) && comma == ','));
      }
      ok = ok && (in >> std::ws).eof();
      for (const auto& x : section)
        for (double v : x) ok = ok && std::isfinite(v);
      if (!ok)
        throw InputError(name, entry + ": expected two sections 'x y z, x y z, x y z, x y z' separated by ';', found '" +
                                   item + "'");
      try {
        check_section(section);
      } catch (const std::invalid_argument& e) {
        throw InputError(name, entry + ": section '" + item + "': " + e.what());
      }
      const std::size_t first = p.output.probe_points.size();
      for (const auto& x : section) p.output.probe_points.push_back({{x[0] * 1e-3, x[1] * 1e-3, x[2] * 1e-3}});
      p.output.link_sections.push_back({{first, first + 1, first + 2, first + 3}});
    }
    if (!p.output.link_sections.empty() && p.output.link_sections.size() != 2)
      throw InputError(name, entry + ": expected exactly two sections (bottom; top), found " +
                                 std::to_string(p.output.link_sections.size()));
    if (p.output.extensometer_as_displacement && p.output.extensometer.empty())
      throw InputError(name, "'Curve displacement = extensometer' needs 'Extensometer (mm)'");
  }
  prm.leave_subsection();
}

Parameters read_and_convert(const std::filesystem::path& file, const std::vector<std::string>& settings) {
  const std::string name = file.string();
  if (!std::filesystem::is_regular_file(file)) throw InputError(name, "cannot open the parameter file");
  ParameterHandler prm;
  declare(prm);
  const EntryLines lines = check_prm_names(prm, name);
  try {
    prm.parse_input(name, "", false);  // undeclared names are errors, never skipped
  } catch (const std::exception& e) {
    const std::string message = deal_ii_message(e.what());
    std::smatch m;
    if (std::regex_search(message, m, std::regex("[Ll]ine <(\\d+)>")))
      throw InputError(name, std::stoi(m[1]), 0, message);
    throw InputError(name, message);
  }
  std::set<std::string> set_on_command_line;
  for (const auto& setting : settings) {
    apply_setting(prm, setting);
    set_on_command_line.insert(setting.substr(0, setting.find('=')));
  }

  Source source{prm, file, name, lines, set_on_command_line};
  Parameters p;
  read_geometry(source, p);
  read_material(source, p);
  read_formulation(source, p);
  read_forming(source, p);
  read_boundary_conditions(source, p);
  read_load_stepping(source, p);
  read_newton(source, p);
  read_output(source, p);
  std::vector<double> knots;  // contact (issue 5)
  for (const auto& k : p.load.path) knots.push_back(k.first);
  p.contact = contact::parse_contact_parameters(prm, name, knots);
  p.wire_contact = contact::parse_wire_contact_parameters(prm, name);
  if (!p.geometry.quarter && p.load.bottom != EndCondition::clamped && p.load.top != EndCondition::clamped &&
      !p.contact.enabled())
    throw InputError(name, "a full cross-section needs at least one clamped end or contact tools (rigid-body modes)");
  return p;
}
}  // namespace

std::string parameter_listing(bool documented) {
  ParameterHandler prm;
  declare(prm);
  std::ostringstream listing;
  prm.print_parameters(listing, documented ? ParameterHandler::PRM : ParameterHandler::ShortPRM);
  return listing.str();
}

Parameters read_parameters(const std::filesystem::path& file, const std::vector<std::string>& settings) {
  try {
    return read_and_convert(file, settings);
  } catch (const dealii::ExceptionBase& e) {  // a value deal.II could not convert (e.g. an unfilled {placeholder})
    throw InputError(file.string(), deal_ii_message(e.what()));
  }
}

namespace {
double piecewise_linear(const std::vector<std::pair<double, double>>& path, double t) {
  if (t <= path.front().first) return path.front().second;
  for (std::size_t i = 1; i < path.size(); ++i)
    if (t <= path[i].first) {
      const double s = (t - path[i - 1].first) / (path[i].first - path[i - 1].first);
      return path[i - 1].second + s * (path[i].second - path[i - 1].second);
    }
  return path.back().second;
}
}  // namespace

double path_displacement(const LoadParameters& load, double t) { return piecewise_linear(load.path, t); }

double path_rotation(const LoadParameters& load, double t) {
  return load.rotation_path.empty() ? 0.0 : piecewise_linear(load.rotation_path, t);
}

double path_force(const LoadParameters& load, double t) {
  return load.force_control ? piecewise_linear(load.force_path, t) : 0.0;
}

}  // namespace dtwire::fem
