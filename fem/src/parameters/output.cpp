// The .prm reader of one concern (parameters_reading.hpp): Output: fields, probes, extensometer, link sections, checkpoints.
#include <deal.II/base/parameter_handler.h>

#include <cmath>
#include <sstream>

#include "dtwire/core/error.hpp"
#include "../link_kinematics.hpp"
#include "parameters_reading.hpp"

namespace dtwire::fem::prm_reading {

using dealii::ParameterHandler;
namespace Patterns = dealii::Patterns;

void declare_output(ParameterHandler& prm) {
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
}

void read_output(const Source& source, Parameters& p) {
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

}  // namespace dtwire::fem::prm_reading
