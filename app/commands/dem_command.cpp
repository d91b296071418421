#include <CLI/CLI.hpp>

#include <iostream>
#include <optional>
#include <stdexcept>

#include "../cli.hpp"
#include "../commands.hpp"
#include "../data_path.hpp"
#include "dem_plot_command.hpp"
#include "dem_propagate_command.hpp"
#include "dem_run_command.hpp"
#include "dem_surface_command.hpp"
#include "dtwire/core/error.hpp"
#include "dtwire/core/resources.hpp"
#include "dtwire/core/provenance.hpp"
#include "dtwire/dem/driver.hpp"
#include "dtwire/dem/export_params.hpp"
#include "option_checks.hpp"

namespace dtwire::app {
namespace {

struct DriverOptions {
  std::string law;
  std::string params = data_path("experiments/data/macroelement_thesis_params.json").string();
  std::string wire_type;
  std::string backbone;
  std::string path = "all";
  std::size_t steps = 2000;
  std::optional<double> max_strain;
  double max_rotation = 0.5;
  std::string out;
  std::string max_memory;
};

// Per sample: 18 history channels, held about four times (growing vectors, the curve, the
// writers), and the path's six increments; 1.2 times the peak RSS of 2e5 and 1e6 steps
// (docs/dem_engine.md, "Resources"). On disk: the CSV and driver.h5, 270 B per sample.
constexpr double kDriverBytesPerSample = 18 * 8 * 4 + 6 * 8, kDriverProgramBytes = 80e6, kDriverDiskPerSample = 300.0;

// Refuses, before any path is replayed, a --steps the memory or the disk cannot hold (exit 2).
void check_driver_resources(const DriverOptions& o, std::size_t sets) {
  const double paths = o.path == "all" ? 6.0 : 1.0;
  const double samples = paths * static_cast<double>(sets) * static_cast<double>(o.steps);
  std::optional<std::uint64_t> max_memory;
  if (!o.max_memory.empty()) max_memory = parse_byte_size(o.max_memory, "--max-memory");
  const std::string what = std::to_string(o.steps) + " steps x " + std::to_string(static_cast<long>(paths * sets)) + " path runs";
  check_memory(kDriverProgramBytes + kDriverBytesPerSample * samples, max_memory, "--steps", what);
  check_disk(kDriverDiskPerSample * samples, o.out, "--steps", what);
}

// One parameter set on the chosen path(s), written to `out`.
void drive_set(const DriverOptions& o, dem::ParameterSet set, const std::filesystem::path& out,
               const std::string& command_line) {
  if (!o.backbone.empty()) dem::add_backbone(set, dem::read_backbone_csv(o.backbone));
  if (!o.law.empty() && !set.law.empty() && o.law != set.law)
    throw InputError(o.params, "field 'law': the file says '" + set.law + "' but --law is '" + o.law + "'");
  const std::string law = o.law.empty() ? set.law : o.law;
  if (law.empty()) throw InputError("--law", "no law given and the parameter file has no 'law' field");
  const dem::ParameterMap parameters = set.map();

  std::vector<dem::DriverRun> runs;
  try {
    dem::check_parameter_names(set, law, o.params);
    dem::PathOptions path_options = dem::default_path_options(law, parameters);
    path_options.steps = o.steps;
    if (o.max_strain) path_options.max_axial_strain = *o.max_strain;
    path_options.max_rotation = o.max_rotation;
    dem::FreeOscillationOptions oscillation;
    oscillation.steps = o.steps;
    runs = dem::run_driver(law, parameters, o.path, path_options, oscillation);
  } catch (const InputError&) {
    throw;
  } catch (const std::invalid_argument& e) {
    // Unknown law, bad law parameters or an unknown path name.
    const std::string message = e.what();
    throw InputError(message.rfind("unknown path", 0) == 0 ? "--path" : o.params,
                     (set.wire_type == "default" ? "" : set.wire_type + ": ") + message);
  }
  std::vector<std::filesystem::path> inputs{o.params};
  if (!o.backbone.empty()) inputs.emplace_back(o.backbone);
  if (std::filesystem::path(o.path).extension() == ".csv") inputs.emplace_back(o.path);
  dem::write_driver_results(runs, law, parameters, out, make_provenance(command_line, inputs));
  for (const dem::DriverRun& run : runs) {
    const auto& broken = run.history.channel("broken").values;
    std::cout << set.wire_type << " " << run.path_name << ": " << run.history.size() << " samples"
              << (broken.back() > 0.5 ? ", bond broken" : "") << " -> " << (out / (run.path_name + ".csv")).string()
              << "\n";
  }
  std::cout << "all histories: " << (out / "driver.h5").string() << "\n";
}

int run_driver_command(const DriverOptions& o, const std::string& command_line) {
  check_output_folders({{"--out", o.out}});
  const std::vector<dem::ParameterSet> sets = dem::read_parameter_file(o.params);
  check_driver_resources(o, o.wire_type.empty() ? sets.size() : 1);
  if (!o.wire_type.empty() || sets.size() == 1) {
    drive_set(o, dem::select_wire_type(sets, o.wire_type, o.params), o.out, command_line);
    return 0;
  }
  // Several sets and none chosen: every set, each in its own folder.
  for (const dem::ParameterSet& set : sets)
    drive_set(o, set, std::filesystem::path(o.out) / set.wire_type, command_line);
  return 0;
}

}  // namespace

void add_dem_command(CLI::App& root, CommandSet& commands) {
  CLI::App* dem = root.add_subcommand("dem", "DEM contact laws: the two-node driver; mesh-scale runs of the wire net");
  dem->require_subcommand(1);
  commands.add(dem, [] { return kExitBadInput; });  // never runs: a subcommand is required
  add_dem_run_command(*dem, commands);
  add_dem_plot_command(*dem, commands);
  add_dem_surface_command(*dem, commands);
  add_dem_propagate_command(*dem, commands);

  auto options = std::make_shared<DriverOptions>();
  CLI::App* driver = dem->add_subcommand(
      "driver", "Replay load paths on a contact law between two nodes; write force, moment and energy histories");
  driver->add_option("--law", options->law, "Contact law: thesis, macro3d, wirepm, parallel_bond (default: the file's 'law')");
  driver->add_option("--params", options->params, "Parameter file (.json; thesis, flat or calibrate format)")
      ->capture_default_str()
      ->check(CLI::ExistingFile);
  driver->add_option("--wire-type", options->wire_type,
                     "Which set of a multi-set file (e.g. single_wire); default: every set, in <out>/<wire type>/");
  driver->add_option("--backbone", options->backbone, "WirePM backbone CSV (strain_1,stress_Pa)")->check(CLI::ExistingFile);
  driver->add_option("--path", options->path,
                     "axial_pull, compression, bending_spin, pull_spin, cycles, free_oscillation, all, or FILE.csv")
      ->capture_default_str();
  driver->add_option("--steps", options->steps, "Increments per path")->capture_default_str()->check(CLI::Range(1, 100000000));
  driver->add_option("--max-strain", options->max_strain,
                     "Peak elongation / reference length of the pulls (default 0.4; wirepm: 1.1 x its break)")
      ->check(finite_in(0.0));
  driver->add_option("--max-rotation", options->max_rotation, "Peak bending rotation theta_y [rad]")
      ->capture_default_str()
      ->check(finite_in(0.0));
  driver->add_option("--out", options->out, "Output directory")->required();
  driver->add_option("--max-memory", options->max_memory,
                     "Refuse a run whose memory estimate exceeds SIZE (4G, 512M; default: the available memory)");
  commands.add(driver, [options] {
    return run_driver_command(*options, "dtwire dem driver --path " + options->path + " --params " + options->params);
  });
}

}  // namespace dtwire::app
