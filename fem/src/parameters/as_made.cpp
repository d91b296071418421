// The .prm reader of one concern (parameters_reading.hpp): As made: the forming history of the double twist (issue 19).
#include <deal.II/base/parameter_handler.h>

#include <cmath>
#include <sstream>

#include "dtwire/core/error.hpp"
#include "parameters_reading.hpp"

namespace dtwire::fem::prm_reading {

using dealii::ParameterHandler;
namespace Patterns = dealii::Patterns;

void declare_forming(ParameterHandler& prm) {
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
}

void read_forming(const Source& source, Parameters& p) {
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

}  // namespace dtwire::fem::prm_reading
