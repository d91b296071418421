#include <CLI/CLI.hpp>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <sstream>

#include "../cli.hpp"
#include "../commands.hpp"
#include "dtwire/core/atomic_file.hpp"
#include "dtwire/core/error.hpp"
#include "dtwire/core/resources.hpp"
#include "dtwire/meshes/axis_io.hpp"
#include "dtwire/meshes/cross_section.hpp"
#include "dtwire/meshes/mesh_check.hpp"
#include "dtwire/meshes/mesh_io.hpp"
#include "dtwire/meshes/parameter_file.hpp"
#include "dtwire/meshes/wire_geometry.hpp"
#include "option_checks.hpp"

namespace dtwire::app {
namespace {

struct MeshOptions {
  meshes::WireKind kind;
  std::string prm;
  std::string msh;
  std::string vtu;
  std::string report;
  bool check = false;
  std::map<std::string, double> values;  // option name -> value in mm / deg / count
  std::map<std::string, CLI::Option*> given;
  std::string max_memory;
};

// Per hexahedron: its 8 node indices, about one node's coordinates, the material and the writers'
// copies; fitted to the peak RSS of SW and DT meshes (docs/meshes.md, "Resources").
constexpr double kBytesPerCell = 500.0, kMeshProgramBytes = 80e6;

// The hexahedra build_wire_mesh would make, before it makes them: the O-grid section's quads
// times the stations along each wire axis (a twist's axis at most its length plus one turn of the
// pair per half turn, and a station per max_section_turn of the section's spin).
double estimated_cells(const meshes::MeshParameters& p) {
  constexpr double kPi = 3.14159265358979323846;
  const meshes::Resolution r = meshes::resolution(p.level, p.diameter);
  const double n = r.block_cells;
  const double quads = n * n + 4.0 * n * (r.radial_cells + (p.coating > 0.0 ? r.coating_cells : 0));
  if (p.kind == meshes::WireKind::Single) return quads * std::ceil(p.length / r.axial_cell_length);
  if (p.kind == meshes::WireKind::Segment)  // five pieces, each rounding its layers up once
    return quads * (std::ceil((p.length + 2.0 * p.grip_length) / r.axial_cell_length) + 4.0);
  const double axis = p.twist_length + kPi * (p.diameter + 2.0 * p.coating + p.gap) * p.half_turns + 2.0 * p.arm_length;
  const double stations = std::ceil(axis / r.axial_cell_length) + std::ceil(kPi * p.half_turns / r.max_section_turn);
  return 2.0 * quads * stations;
}

// Refuses, before anything is built, a mesh the memory cannot hold (a length typed in m as mm).
void check_mesh_memory(const MeshOptions& options, const meshes::MeshParameters& p) {
  const double cells = estimated_cells(p);
  if (!std::isfinite(cells)) return;  // a zero diameter: build_wire_mesh names the field
  std::optional<std::uint64_t> max_memory;
  if (!options.max_memory.empty()) max_memory = parse_byte_size(options.max_memory, "--max-memory");
  std::ostringstream what;
  what << "about " << std::setprecision(3) << cells << " hexahedra at level " << p.level
       << (p.kind != meshes::WireKind::DoubleTwist ? ", length " : ", twist-length and arm-length ")
       << (p.kind != meshes::WireKind::DoubleTwist ? 1000.0 * p.length : 1000.0 * p.twist_length) << " mm";
  if (p.kind == meshes::WireKind::DoubleTwist) what << ", " << 1000.0 * p.arm_length << " mm";
  check_memory(kMeshProgramBytes + kBytesPerCell * cells, max_memory, options.prm.empty() ? "mesh" : options.prm, what.str());
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

int run_mesh(const MeshOptions& options) {
  using namespace meshes;
  MeshParameters parameters = default_parameters(options.kind);
  FieldLocations locations;
  if (!options.prm.empty()) read_parameter_file(options.prm, parameters, locations);
  // Command-line values override the file.
  for (const auto& [name, option] : options.given) {
    if (option->count() == 0) continue;
    const ParameterField& field = *find_parameter_field(name);
    const double value = options.values.at(name);
    if (field.integer && value != static_cast<double>(static_cast<long>(value)))
      throw InputError("--" + name, "expected a whole number, got " + option->as<std::string>());
    set_user_value(parameters, field, value);
    locations[name] = FieldLocation{"--" + name, 0, 0};
  }
  if (options.msh.empty() && options.vtu.empty() && !options.check && options.report.empty())
    throw InputError("mesh", "nothing to do: give -o FILE.msh, --vtu FILE.vtu, --check or --report FILE.md");

  check_output_files({{"-o", options.msh}, {"--vtu", options.vtu}, {"--report", options.report}});
  check_mesh_memory(options, parameters);
  const auto start = std::chrono::steady_clock::now();
  const WireMesh mesh = build_wire_mesh(parameters, locations);
  const double build_seconds = seconds_since(start);
  // Output folders are made as the other commands make theirs (checked above: no file in the way).
  for (const std::string& file : {options.msh, options.vtu, options.report})
    if (!file.empty() && std::filesystem::path(file).has_parent_path())
      std::filesystem::create_directories(std::filesystem::path(file).parent_path());
  if (!options.msh.empty()) {
    write_msh(mesh.mesh, options.msh);
    write_axis_csv(mesh, axis_file_for(options.msh));
  }
  if (!options.vtu.empty()) write_vtu(mesh.mesh, options.vtu);
  const double total_seconds = seconds_since(start);
  std::cerr << "mesh: " << mesh.mesh.hexes.size() << " hexahedra, built in " << build_seconds
            << " s, written in " << total_seconds - build_seconds << " s\n";
  if (options.check || !options.report.empty()) {
    MeshCheck check = check_mesh(mesh);
    check.seconds_to_build = total_seconds;
    const std::string markdown = format_check_markdown(parameters, mesh, check);
    if (options.check) std::cout << markdown;
    if (!options.report.empty())
      write_file_atomically(options.report, [&](std::ostream& out) { out << markdown; });
  }
  return 0;
}

const char* kind_description(meshes::WireKind kind) {
  switch (kind) {
    case meshes::WireKind::Single: return "Single wire of diameter d and length L with grips at both ends";
    case meshes::WireKind::DoubleTwist: return "Double twist: two wires twisted through n half turns, with four SW arms";
    case meshes::WireKind::Segment:
      return "One SW segment as the mesh has it: out of a twist, a bend, the slanted run, a bend into the next "
             "twist; grips inside the twists, the chord along z";
  }
  return "";
}

void add_kind(CLI::App& mesh, CommandSet& commands, meshes::WireKind kind) {
  auto options = std::make_shared<MeshOptions>();
  options->kind = kind;
  CLI::App* command = mesh.add_subcommand(meshes::kind_name(kind), kind_description(kind));
  const meshes::MeshParameters defaults = meshes::default_parameters(kind);
  command->add_option("--prm", options->prm, "Parameter file (set name = value; same names and units as the options)");
  for (const meshes::ParameterField& field : meshes::parameter_fields()) {
    if (!meshes::used_by(field, kind)) continue;
    options->values[field.name] = meshes::user_value(defaults, field);
    const std::string unit = field.unit == "1" ? "" : " (" + field.unit + ")";
    CLI::Option* option = command->add_option("--" + field.name, options->values[field.name], field.help + unit);
    option->capture_default_str()->type_name(field.integer ? "INT" : "FLOAT");
    options->given[field.name] = option;
  }
  command->add_option("-o,--out", options->msh, "Mesh file to write (gmsh MSH 2.2, coordinates in m); its wire axes go to FILE.axis.csv beside it");
  command->add_option("--vtu", options->vtu, "VTU preview for ParaView");
  command->add_flag("--check", options->check,
                    "Print cell count, scaled Jacobian, aspect ratio, wire-wire distance, lay angle and volume");
  command->add_option("--report", options->report, "Write the --check figures as Markdown to this file");
  command->add_option("--max-memory", options->max_memory,
                      "Refuse a mesh whose memory estimate exceeds SIZE (4G, 512M; default: the available memory)");
  commands.add(command, [options] { return run_mesh(*options); });
}

}  // namespace

void add_mesh_command(CLI::App& root, CommandSet& commands) {
  CLI::App* mesh = root.add_subcommand("mesh", "Build parametric hexahedral meshes of single wires and double twists");
  mesh->require_subcommand(1);
  // Registered before sw/dt so the campaign sees `mesh` as available; the deepest selected
  // command runs, and require_subcommand means this runner is never reached.
  commands.add(mesh, [] { return kExitBadInput; });
  add_kind(*mesh, commands, meshes::WireKind::Single);
  add_kind(*mesh, commands, meshes::WireKind::DoubleTwist);
  add_kind(*mesh, commands, meshes::WireKind::Segment);
}

}  // namespace dtwire::app
