#include <CLI/CLI.hpp>

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <stdexcept>

#include "../cli.hpp"
#include "../commands.hpp"
#include "../data_path.hpp"
#include "dtwire/core/atomic_file.hpp"
#include "dtwire/core/error.hpp"
#include "dtwire/core/provenance.hpp"
#include "dtwire/dem/contact_law.hpp"
#include "dtwire/dem/driver.hpp"
#include "dtwire/dem/export.hpp"
#include "dtwire/dem/export_params.hpp"

namespace dtwire::app {
namespace {

struct ExportOptions {
  std::vector<std::string> params;  // one or more files; their sets are exported together
  std::string backbone;
  std::string wire_type;
  std::size_t steps = 2000;
  std::string out;
  bool beam_shear = false;  // every macro-element set gets beam_shear = 1 (docs/dem_laws.md, "Shear spring")
};

bool is_wirepm_set(const dem::ParameterSet& set) {
  return set.law == "wirepm" ||
         (set.has("diameter_m") && set.has("reference_length_m") && set.has("backbone_0_strain_1"));
}

// The names an export writes (so an earlier export's folder may be replaced).
bool is_export_output(const std::string& name) {
  const auto ends_with = [&](const std::string& suffix) {
    return name.size() > suffix.size() && name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0;
  };
  return name == "c_abi" || name == "macroelement_pfc7.dat" || ends_with("_parameters.h5") ||
         ends_with("_parameters.json") || ends_with("_parameters.csv") || ends_with("_wirepm_yade.py");
}

int run_export_command(const ExportOptions& o) {
  // The sets of every --params file, each with the file it came from (for the messages); a wire
  // type given by two files is refused, so the SW and DT fits of one campaign export together.
  std::vector<dem::ParameterSet> sets;
  std::vector<std::string> source;
  std::string types_present;
  for (const std::string& given : o.params) {
    // FILE#TYPE takes only that wire type's set from FILE (e.g. the DT set of a specimen fit).
    const auto hash = given.rfind('#');
    const std::string file = hash == std::string::npos ? given : given.substr(0, hash);
    const std::string only = hash == std::string::npos ? "" : given.substr(hash + 1);
    if (!std::filesystem::is_regular_file(file)) throw InputError(file, "cannot open the parameter file (--params)");
    std::vector<dem::ParameterSet> file_sets = dem::read_parameter_file(file);
    if (!only.empty()) file_sets = {dem::select_wire_type(file_sets, only, file)};
    for (dem::ParameterSet& set : file_sets) {
      if (types_present.find(set.wire_type) == std::string::npos)
        types_present += (types_present.empty() ? "" : ", ") + set.wire_type;
      if (!o.wire_type.empty() && set.wire_type != o.wire_type) continue;
      for (std::size_t k = 0; k < sets.size(); ++k)
        if (sets[k].wire_type == set.wire_type)
          throw InputError(file, "wire type '" + set.wire_type + "' is also in " + source[k] +
                                     " (one set per wire type: export them apart, or choose one with --wire-type)");
      sets.push_back(std::move(set));
      source.push_back(file);
    }
  }
  if (sets.empty())
    throw InputError(o.params.front(), "no wire type '" + o.wire_type + "' in the --params files; choose one of: " +
                                           types_present + " (--wire-type)");
  if (!o.backbone.empty()) {
    const Curve backbone = dem::read_backbone_csv(o.backbone);
    for (dem::ParameterSet& set : sets) dem::add_backbone(set, backbone);
  }
  if (o.beam_shear)
    for (std::size_t index = 0; index < sets.size(); ++index) {
      dem::ParameterSet& set = sets[index];
      if (is_wirepm_set(set) || !(set.has("EA_N") || set.has("axial_stiffness_N_per_m")))
        throw InputError(source[index], "wire type '" + set.wire_type +
                                            "': --beam-shear applies to macro-element sets (thesis, macro3d), and this "
                                            "one has no bending spring");
      if (set.has("shear_stiffness_N_per_m"))
        throw InputError(source[index], "wire type '" + set.wire_type +
                                            "': the set gives shear_stiffness_N_per_m; --beam-shear would replace it");
      set.set("beam_shear", 1.0);
    }
  // Every set is checked by the law the DEM driver would build from it (the same checks as
  // `dtwire dem driver` and the C ABI) before anything is written: a refused set leaves no export.
  for (std::size_t index = 0; index < sets.size(); ++index) {
    const dem::ParameterSet& set = sets[index];
    const dem::ParameterMap values = set.map();
    for (const char* length : {"reference_length_m", "diameter_m", "D_m"})
      if (values.count(length) && !(values.at(length) > 0.0))
        throw InputError(source[index], "wire type '" + set.wire_type + "': '" + length + "': expected a length > 0, found " +
                                       std::to_string(values.at(length)));
    const std::string law = !set.law.empty() ? set.law
                            : is_wirepm_set(set)                       ? "wirepm"
                            : set.has("N0_N") || set.has("Nult_N")     ? "thesis"
                                                                       : "";
    if (law.empty()) continue;
    try {
      dem::check_parameter_names(set, law, source[index]);
      dem::make_contact_law(law, values);
    } catch (const std::invalid_argument& e) {
      throw InputError(source[index], "wire type '" + set.wire_type + "' (law " + law + "): " + e.what());
    }
  }
  std::vector<std::filesystem::path> inputs;
  for (const std::string& file : source)
    if (std::find(inputs.begin(), inputs.end(), std::filesystem::path(file)) == inputs.end()) inputs.emplace_back(file);
  if (!o.backbone.empty()) inputs.emplace_back(o.backbone);
  std::string command_line = "dtwire export";
  for (const std::string& file : o.params) command_line += " --params " + file;
  if (o.beam_shear) command_line += " --beam-shear";
  const Provenance provenance = make_provenance(command_line, inputs);
  // Everything goes to a fresh folder moved into place at the end: an earlier export's files
  // (e.g. a set this parameter file no longer has) never sit beside this one's.
  PendingFolder folder(o.out, is_export_output);
  const std::filesystem::path& out = folder.temporary();

  std::vector<std::filesystem::path> written = dem::export_parameter_tables(sets, out, provenance);
  for (std::size_t index = 0; index < sets.size(); ++index) {
    const dem::ParameterSet& set = sets[index];
    if (!is_wirepm_set(set)) {
      std::cout << set.wire_type << ": no YADE script (needs diameter_m, reference_length_m and a backbone)\n";
      continue;
    }
    const dem::ParameterMap parameters = set.map();
    const std::filesystem::path script = out / (set.wire_type + "_wirepm_yade.py");
    try {
      dem::PathOptions path = dem::default_path_options("wirepm", parameters);  // as `dem driver`
      path.steps = o.steps;
      dem::write_yade_script(parameters, path, script);
    } catch (const std::invalid_argument& e) {
      throw InputError(source[index], std::string("wire type '") + set.wire_type + "': " + e.what());
    }
    written.push_back(script);
  }
  if (std::any_of(sets.begin(), sets.end(), dem::is_pfc7_macroelement_set)) {
    const std::filesystem::path pfc7 = out / "macroelement_pfc7.dat";
    try {
      const std::string commands = dem::pfc7_macroelement_commands(sets, provenance);
      write_file_atomically(pfc7, [&](std::ostream& os) { os << commands; });
    } catch (const std::invalid_argument& e) {
      throw InputError(o.params.front(), e.what());
    }
    written.push_back(pfc7);
  }
  for (const auto& file : dem::export_c_abi(out / "c_abi", data_path("c_abi/include"), data_path("c_abi/examples"))) written.push_back(file);
  folder.commit();
  for (const auto& file : written)
    std::cout << "wrote " << (folder.target() / std::filesystem::relative(file, out)).string() << "\n";
  return 0;
}

}  // namespace

void add_export_command(CLI::App& root, CommandSet& commands) {
  auto options = std::make_shared<ExportOptions>();
  CLI::App* command = root.add_subcommand(
      "export", "Export calibrated parameter sets for DEM codes (tables, YADE WirePM script, C ABI)");
  command->add_option("--params", options->params,
                      "Parameter file (.json; thesis, flat or calibrate format); repeat it to export the sets of "
                      "several files together (e.g. the SW and the DT fit), one set per wire type; FILE#TYPE takes "
                      "only that wire type's set from FILE")
      ->required();
  command->add_option("--backbone", options->backbone, "WirePM backbone CSV (strain_1,stress_Pa) added to every set")
      ->check(CLI::ExistingFile);
  command->add_option("--wire-type", options->wire_type, "Export only this set (e.g. single_wire)");
  command->add_option("--steps", options->steps, "Increments of the YADE script's path")
      ->capture_default_str()
      ->check(CLI::Range(1, 100000000));
  command->add_option("--out", options->out, "Output directory")->required();
  command->add_flag("--beam-shear", options->beam_shear,
                    "Give every macro-element set the slender beam's shear spring, 12 EI / L^3 (beam_shear = 1), "
                    "instead of the PFC7 plugin's EA / 2.6");
  commands.add(command, [options] { return run_export_command(*options); });
}

}  // namespace dtwire::app
