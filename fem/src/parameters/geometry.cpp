// The .prm reader of one concern (parameters_reading.hpp): Geometry: the wire's size, cross-section, mesh and imperfections.
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/utilities.h>

#include <cmath>
#include <sstream>

#include "dtwire/core/error.hpp"
#include "parameters_reading.hpp"

namespace dtwire::fem::prm_reading {

using dealii::ParameterHandler;
namespace Patterns = dealii::Patterns;

void declare_geometry(ParameterHandler& prm) {
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
  prm.declare_entry("Junction refinement cycles", "0", Patterns::Integer(0, 3),
                    "Refinements of the cells near the junction planes (0: none; docs/fem_dt.md, Junction refinement)");
  prm.declare_entry("Junction refinement half-width (mm)", "4", Patterns::Double(0.0),
                    "Cells whose centre lies this close to a junction plane are refined");
  prm.declare_entry("Junction planes (mm)", "", Patterns::List(Patterns::Double()),
                    "z of the junction planes (the DT's twist ends, e.g. 0, 40); needed with cycles > 0");
  prm.leave_subsection();
}

void read_geometry(const Source& source, Parameters& p) {
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
  p.geometry.junction_cycles = prm.get_integer("Junction refinement cycles");
  p.geometry.junction_half_width = prm.get_double("Junction refinement half-width (mm)") * 1e-3;
  p.geometry.junction_planes.clear();
  for (const auto& z : dealii::Utilities::split_string_list(prm.get("Junction planes (mm)")))
    p.geometry.junction_planes.push_back(std::stod(z) * 1e-3);
  source.require(p.geometry.junction_cycles == 0 || !p.geometry.junction_planes.empty(), "Geometry",
                 "Junction planes (mm)", "the z of at least one junction plane when 'Junction refinement cycles' > 0");
  source.require(p.geometry.junction_cycles == 0 || p.geometry.junction_half_width > 0.0, "Geometry",
                 "Junction refinement half-width (mm)", "a half-width > 0 when 'Junction refinement cycles' > 0");
  if (p.geometry.bow != 0.0 && p.geometry.quarter)
    throw InputError(name, "'Bow imperfection (mm)' needs Cross section = full");
  prm.leave_subsection();
}

}  // namespace dtwire::fem::prm_reading
