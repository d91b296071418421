// `dtwire dem surface`: the N-M yield surfaces (initial and fully hardened) of the thesis or
// macro3d macro-element for each set of a parameter file, as CSV for plots against FE envelopes
// (scripts/dt_envelope --params).
#include "dem_surface_command.hpp"

#include <CLI/CLI.hpp>

#include <filesystem>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "../cli.hpp"
#include "../commands.hpp"
#include "dtwire/core/csv.hpp"
#include "dtwire/core/error.hpp"
#include "dtwire/core/provenance.hpp"
#include "dtwire/dem/export_params.hpp"
#include "dtwire/dem/yield_surface.hpp"
#include "option_checks.hpp"

namespace dtwire::app {
namespace {

struct SurfaceOptions {
  std::string params;
  std::string wire_type;
  std::string law;
  int points = 201;
  std::string out;
};

struct SetSurfaces {
  std::string wire_type, law;
  std::vector<dem::YieldSurfaceCurve> curves;  // N0, then Nult
};

// Every curve is computed before anything is written, so bad input leaves no file behind.
SetSurfaces compute_surfaces(const SurfaceOptions& o, const dem::ParameterSet& set) {
  if (!o.law.empty() && !set.law.empty() && o.law != set.law)
    throw InputError(o.params, "field 'law': the file says '" + set.law + "' but --law is '" + o.law + "'");
  SetSurfaces out{set.wire_type, o.law.empty() ? (set.law.empty() ? "thesis" : set.law) : o.law, {}};
  try {
    out.curves = dem::initial_and_ultimate_yield_surfaces(out.law, set.map(), o.points);
  } catch (const std::invalid_argument& e) {
    throw InputError(o.params, (set.wire_type == "default" ? "" : set.wire_type + ": ") + e.what());
  }
  return out;
}

// One set: both curves in one file, told apart by yield_strength_N (N0, then Nult).
void write_surfaces(const SurfaceOptions& o, const SetSurfaces& set, const Provenance& provenance) {
  std::vector<double> strength, force, moment;
  for (const dem::YieldSurfaceCurve& curve : set.curves)
    for (std::size_t i = 0; i < curve.axial_force_N.size(); ++i) {
      strength.push_back(curve.yield_strength_N);
      force.push_back(curve.axial_force_N[i]);
      moment.push_back(curve.moment_Nm[i]);
    }
  Curve table;
  table.add_channel("yield_strength", si_unit(Dimension::Force), strength);
  table.add_channel("axial_force", si_unit(Dimension::Force), force);
  table.add_channel("moment", si_unit(Dimension::Moment), moment);
  table.set_metadata("content", "yield surface M >= 0 of the " + set.law +
                                    " macro-element at yield_strength_N = N0 (initial) and Nult (fully hardened)");
  table.set_metadata("law", set.law);
  table.set_metadata("wire_type", set.wire_type);
  table.set_metadata("tool", provenance.tool_version + " (git " + provenance.git_hash + ")");
  table.set_metadata("created_utc", provenance.created_utc);
  table.set_metadata("command", provenance.command);
  for (const auto& [path, digest] : provenance.input_sha256) table.set_metadata("input_sha256 " + path, digest);
  const std::filesystem::path file = std::filesystem::path(o.out) / (set.wire_type + "_yield_surface.csv");
  write_csv(table, file);
  std::cout << set.wire_type << " (" << set.law << "): N0 " << set.curves[0].yield_strength_N << " N, Nult "
            << set.curves[1].yield_strength_N << " N -> " << file.string() << "\n";
}

int run_surface_command(const SurfaceOptions& o) {
  check_output_folders({{"--out", o.out}});
  const std::vector<dem::ParameterSet> sets = dem::read_parameter_file(o.params);
  std::vector<SetSurfaces> surfaces;
  if (!o.wire_type.empty() || sets.size() == 1)
    surfaces.push_back(compute_surfaces(o, dem::select_wire_type(sets, o.wire_type, o.params)));
  else
    for (const dem::ParameterSet& set : sets) surfaces.push_back(compute_surfaces(o, set));
  const Provenance provenance = make_provenance("dtwire dem surface --params " + o.params, {o.params});
  // A rerun into the same folder never leaves an earlier run's curves beside the new ones.
  std::filesystem::create_directories(o.out);
  for (const auto& entry : std::filesystem::directory_iterator(o.out)) {
    const std::string name = entry.path().filename().string();
    const std::string suffix = "_yield_surface.csv";
    if (name.size() > suffix.size() && name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0)
      std::filesystem::remove(entry.path());
  }
  for (const SetSurfaces& set : surfaces) write_surfaces(o, set, provenance);
  return 0;
}

}  // namespace

void add_dem_surface_command(CLI::App& dem, CommandSet& commands) {
  auto options = std::make_shared<SurfaceOptions>();
  CLI::App* surface = dem.add_subcommand(
      "surface", "N-M yield surfaces (initial and fully hardened) of the thesis or macro3d element, as CSV");
  surface->add_option("--params", options->params, "Parameter file (.json; thesis, flat or calibrate format)")
      ->required()
      ->check(CLI::ExistingFile);
  surface->add_option("--wire-type", options->wire_type,
                      "Which set of a multi-set file (e.g. double_twist); default: every set");
  surface->add_option("--law", options->law, "thesis or macro3d (default: the file's 'law', else thesis)");
  surface->add_option("--points", options->points, "Points per curve")->capture_default_str()->check(CLI::Range(3, 100000));
  surface->add_option("--out", options->out, "Output directory: <wire type>_yield_surface.csv per set")->required();
  commands.add(surface, [options] { return run_surface_command(*options); });
}

}  // namespace dtwire::app
