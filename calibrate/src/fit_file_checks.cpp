// The fit file's cross-field checks (fit_file_checks.hpp).
#include "fit_file_checks.hpp"

#include <algorithm>
#include <stdexcept>

#include "dtwire/calibrate/dem_specimen.hpp"
#include "dtwire/core/closest_name.hpp"
#include "dtwire/core/csv.hpp"
#include "dtwire/core/resources.hpp"
#include "dtwire/core/units.hpp"
#include "dtwire/dem/law_schema.hpp"

namespace dtwire::calibrate {

void check_fixed_law_parameters(const FitDefinition& def, const Table& sim) {
  try {
    dem::law_parameter_names(def.law);
  } catch (const std::invalid_argument& error) {
    sim.fail(sim.get("law"), "law", error.what());
  }
  for (const auto& [parameter, value] : def.fixed)
    if (!dem::is_law_parameter(def.law, parameter)) {
      const toml::node* fixed = sim.get("fixed");
      const bool inline_value = fixed && fixed->is_table() && fixed->as_table()->contains(parameter);
      sim.fail(inline_value ? fixed->as_table()->get(parameter) : sim.get("fixed_parameters_file"),
               inline_value ? "fixed." + parameter : "fixed_parameters_file",
               "the " + def.law + " law reads no parameter '" + parameter + "'" +
                   did_you_mean(parameter, dem::law_parameter_names(def.law)));
    }
}

void check_parameters_are_read(const FitDefinition& def, const std::vector<Table>& tables) {
  for (std::size_t i = 0; i < def.parameters.size(); ++i) {
    std::vector<std::string> known;
    bool read = false;
    for (const Experiment& e : def.experiments) {
      const std::vector<std::string> names = e.simulator->parameter_names();
      if (names.empty() || std::find(names.begin(), names.end(), def.parameters[i].name) != names.end()) read = true;
      known.insert(known.end(), names.begin(), names.end());
    }
    if (read) continue;
    const std::string what =
        def.simulator == "command"        ? "no experiment's input template has a placeholder {" + def.parameters[i].name + "}"
        : def.simulator == "dem_specimen" ? "the dem_specimen simulator (law " + def.law + ") reads no parameter '" +
                                                def.parameters[i].name + "' (names are sw.<law parameter> or dt.<law parameter>)"
                                          : "the " + def.law + " simulator reads no parameter '" + def.parameters[i].name + "'";
    tables[i].fail(tables[i].get("name"), "name", what + did_you_mean(def.parameters[i].name, known));
  }
}

void check_offsets(const std::vector<ParameterDefinition>& parameters, const std::vector<Table>& tables) {
  std::vector<std::string> names;
  for (const auto& p : parameters) names.push_back(p.name);
  for (std::size_t i = 0; i < parameters.size(); ++i) {
    const ParameterDefinition& p = parameters[i];
    if (p.offset_from.empty()) continue;
    const Table& t = tables[i];
    if (p.offset_from == p.name)
      t.fail(t.get("offset_from"), "offset_from", "names the parameter itself (expected another fitted parameter)");
    const auto base = std::find(names.begin(), names.end(), p.offset_from);
    if (base == names.end())
      t.fail(t.get("offset_from"), "offset_from",
             "'" + p.offset_from + "' names no other [[parameter]] of this file" + did_you_mean(p.offset_from, names));
    if (p.reference) {
      if (*p.reference < p.lower || *p.reference > p.upper)
        t.fail(t.get("reference"), "reference",
               "expected the reference of the offset " + coordinate_name(p) + ", within [lower, upper]");
      if (!parameters[static_cast<std::size_t>(base - names.begin())].reference)
        t.fail(t.get("reference"), "reference",
               "the offset's reference needs one of '" + p.offset_from + "' too (the reference of " + p.name + " is theirs summed)");
    }
  }
  try {
    offset_bases(parameters);
  } catch (const std::invalid_argument& error) {  // only a cycle is left
    for (std::size_t i = 0; i < parameters.size(); ++i)
      if (std::string(error.what()).rfind("parameter '" + parameters[i].name + "'", 0) == 0)
        tables[i].fail(tables[i].get("offset_from"), "offset_from", error.what());
    tables.front().fail(nullptr, "offset_from", error.what());
  }
}

void check_simulated_channels(const Experiment& e, const std::vector<Compared>& compared, const std::string& kind,
                              const Table& x) {
  const auto declared = e.simulator->channels();
  if (declared.empty()) return;
  for (const auto& [quantity, key, node] : compared) {
    const auto it = std::find_if(declared.begin(), declared.end(),
                                 [&, q = quantity](const auto& d) { return d.first == q; });
    if (it == declared.end()) {
      std::string list;
      for (const auto& d : declared) list += (list.empty() ? "" : ", ") + d.first;
      x.fail(node, key, "the " + kind + " simulator has no channel '" + quantity + "' (it gives " + list + ")");
    }
    const Channel* target = e.target.find(quantity);
    if (target && target->unit.dimension != it->second)
      x.fail(node, key,
             "the target's '" + quantity + "' is a " + std::string(dimension_name(target->unit.dimension)) + " (" +
                 target->unit.symbol + "), the simulated '" + quantity + "' a " +
                 std::string(dimension_name(it->second)) + " (map the right column with target_columns)");
  }
}

void check_fixed_specimen_parameters(const FitDefinition& def, const Table& sim) {
  if (def.law != "thesis" && def.law != "macro3d")
    sim.fail(sim.get("law"), "law", "the dem_specimen simulator takes the thesis or macro3d law, found '" + def.law + "'");
  const toml::node* fixed = sim.get("fixed");
  for (const auto& [parameter, value] : def.fixed) {
    const bool inline_value = fixed && fixed->is_table() && fixed->as_table()->contains(parameter);
    const toml::node* node = inline_value ? fixed->as_table()->get(parameter) : sim.get("fixed_parameters_file");
    const std::string key = inline_value ? "fixed." + parameter : "fixed_parameters_file";
    const bool prefixed = parameter.rfind(kSwPrefix, 0) == 0 || parameter.rfind(kDtPrefix, 0) == 0;
    if (!prefixed)
      sim.fail(node, key, "'" + parameter + "' names no wire type: write sw." + parameter + " or dt." + parameter);
    if (!dem::is_law_parameter(def.law, parameter.substr(3))) {
      std::vector<std::string> known;
      for (const std::string& name : dem::law_parameter_names(def.law)) known.push_back(parameter.substr(0, 3) + name);
      sim.fail(node, key, "the " + def.law + " law reads no parameter '" + parameter.substr(3) + "'" +
                              did_you_mean(parameter, known));
    }
  }
  for (const char* prefix : {kSwPrefix, kDtPrefix})
    if (!def.fixed.count(std::string(prefix) + "reference_length_m"))
      sim.fail(sim.has("fixed_parameters_file") ? sim.get("fixed_parameters_file") : sim.get("kind"),
               sim.has("fixed_parameters_file") ? "fixed_parameters_file" : "kind",
               std::string("no ") + prefix +
                   "reference_length_m (the length the set was calibrated for; give it in the set's section or "
                   "[simulator.fixed])");
}

void check_path_memory(const Table& experiment, double increments) {
  constexpr double kBytesPerIncrement = 48 * sizeof(double);
  const double bytes = kBytesPerIncrement * increments;
  const std::optional<std::uint64_t> available = available_memory();
  if (!available || bytes <= static_cast<double>(*available)) return;
  experiment.fail(experiment.get("increments_per_leg"), "increments_per_leg",
                  "the path's " + format_number(increments) + " increments need about " + format_bytes(bytes) +
                      " of memory for one evaluation, above the " + format_bytes(static_cast<double>(*available)) +
                      " available (MemAvailable, /proc/meminfo); expected fewer increments per leg");
}

}  // namespace dtwire::calibrate
