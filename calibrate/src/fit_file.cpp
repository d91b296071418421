#include "dtwire/calibrate/fit_file.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>
#include <tuple>
#include <toml++/toml.h>

#include <nlohmann/json.hpp>

#include "dtwire/calibrate/command_simulator.hpp"
#include "dtwire/calibrate/dem_specimen.hpp"
#include "dtwire/calibrate/law_replay.hpp"
#include "dtwire/calibrate/voce_bar.hpp"
#include "dtwire/core/closest_name.hpp"
#include "dtwire/core/csv.hpp"
#include "dtwire/core/error.hpp"
#include "dtwire/core/provenance.hpp"
#include "dtwire/core/units.hpp"
#include "dtwire/dem/law_schema.hpp"
#include "command_input.hpp"
#include "fit_file_checks.hpp"
#include "toml_table.hpp"

namespace dtwire::calibrate {
namespace {

// The paths count their increments in an int; the memory check (check_path_memory) is the limit
// that matters.
constexpr long long kMostIncrementsPerLeg = std::numeric_limits<int>::max();

const toml::table& table_at(const toml::table& root, const std::string& key, const std::string& file) {
  const toml::node* node = root.get(key);
  if (!node || !node->is_table())
    throw InputError(file, node ? static_cast<int>(node->source().begin.line) : 0, 0,
                     "field '" + key + "': expected a table [" + key + "]");
  return *node->as_table();
}

// Waypoints from keys <prefix><unit> (e.g. path_displacement_mm), converted to SI.
std::vector<double> waypoints(const Table& t, const std::string& prefix, Dimension dimension,
                              const toml::table& raw) {
  std::vector<double> out;
  std::string found;
  for (const auto& [key, node] : raw) {
    const std::string name(key.str());
    if (name.rfind(prefix, 0) != 0) continue;
    const auto unit = find_unit(name.substr(prefix.size()));
    if (!unit || unit->dimension != dimension)
      t.fail(&node, name, "unknown unit suffix '" + name.substr(prefix.size()) + "' (expected " +
                              std::string(dimension_name(dimension)) + " unit, e.g. " + prefix +
                              si_unit(dimension).symbol + ")");
    if (!found.empty()) t.fail(&node, name, "given twice (also as " + found + ")");
    found = name;
    out = t.numbers(name);
    for (double& v : out) v *= unit->to_si;
  }
  return out;
}

dem::ParameterMap read_fixed_json(const std::filesystem::path& path, const std::string& section,
                                  const Table& t, const std::string& section_key = "fixed_parameters_section") {
  std::ifstream in(path);
  if (!in) t.fail(t.get("fixed_parameters_file"), "fixed_parameters_file", "cannot open " + path.string());
  nlohmann::json root;
  try {
    root = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& error) {
    throw InputError(path.string(), std::string("not valid JSON: ") + error.what());
  }
  const nlohmann::json* object = &root;
  if (!section.empty()) {
    if (!root.contains(section) || !root[section].is_object())
      t.fail(t.get(section_key), section_key, "no object '" + section + "' in " + path.string());
    object = &root[section];
  }
  dem::ParameterMap out;
  for (const auto& [name, value] : object->items())
    if (value.is_number()) out[name] = value.get<double>();
  return out;
}

// [experiment.target_columns]: simulated quantity = "target column" or {column, factor}. The
// nodes are returned too, so that a missing column is reported at its own line.
std::vector<ColumnMapping> column_mapping(const Table& x, const std::string& file,
                                          std::vector<const toml::node*>& nodes) {
  std::vector<ColumnMapping> out;
  const toml::node* node = x.get("target_columns");
  if (!node) return out;
  if (!node->is_table())
    x.fail(node, "target_columns",
           "expected a table of quantity = \"column\" or quantity = {column = \"...\", factor = ...}");
  const Table t(*node->as_table(), x.field("target_columns"), file);
  for (const auto& [key, value] : *node->as_table()) {
    ColumnMapping m;
    m.quantity = std::string(key.str());
    if (value.is_string()) {
      m.column = value.as_string()->get();
    } else if (value.is_table()) {
      const Table entry(*value.as_table(), t.field(m.quantity), file);
      entry.only({"column", "factor"});
      m.column = entry.text("column");
      m.factor = entry.number("factor", 1.0);
      if (m.factor == 0.0) entry.fail(entry.get("factor"), "factor", "expected a number other than 0");
    } else {
      t.fail(&value, m.quantity, "expected the target column's quantity (a string) or {column = \"...\", factor = ...}");
    }
    out.push_back(m);
    nodes.push_back(&value);
  }
  return out;
}

// `target`: relative to the fit file, or below the targets directory when it starts with
// {targets}/. Also gives the name --synthesize writes it under.
std::pair<std::filesystem::path, std::filesystem::path> target_path(const Table& x, const std::filesystem::path& folder,
                                                                    const FitReadOptions& options) {
  static const std::string placeholder = "{targets}";
  const std::string text = x.text("target");
  if (text.empty()) x.fail(x.get("target"), "target", "empty: expected the path of the target CSV");
  if (text.rfind(placeholder, 0) != 0) {
    if (text.find(placeholder) != std::string::npos)
      x.fail(x.get("target"), "target", "{targets} must begin the path, as in \"{targets}/run/curve.csv\"");
    const std::filesystem::path p(text);
    const std::filesystem::path path = p.is_absolute() ? p : folder / p;
    return {path, path.filename()};
  }
  const std::filesystem::path rest = std::filesystem::path(text.substr(placeholder.size())).relative_path();
  if (text.size() == placeholder.size() || text[placeholder.size()] != '/' || rest.empty())
    x.fail(x.get("target"), "target", "expected {targets}/<path of the CSV below the targets directory>");
  if (options.targets_directory.empty() && options.read_targets)
    x.fail(x.get("target"), "target",
           "uses {targets}, but no targets directory was given (dtwire fit --targets DIR)");
  return {options.targets_directory / rest, rest};
}

// [simulator.specimen] and [simulator.quasi_static] (optional tables).
void read_specimen_tables(const Table& sim, const std::string& file, SpecimenGeometry& geometry,
                          QuasiStaticOptions& quasi_static, bool& scale, RollerRig& rig) {
  constexpr double degree = 3.14159265358979323846 / 180.0;
  if (const toml::node* node = sim.get("specimen")) {
    if (!node->is_table()) sim.fail(node, "specimen", "expected a table [simulator.specimen]");
    const Table t(*node->as_table(), "simulator.specimen", file);
    t.only({"twist_length_mm", "arm_length_mm", "arm_angle_deg", "arm_links", "scale_to_link_length", "roller_radius_mm",
            "support_z_mm", "loading_z_mm", "support_tilt_deg", "roller_friction", "roller_stiffness_N_per_m",
            "sw_contact_radius_mm", "dt_contact_radius_mm"});
    geometry.twist_length_m = t.number("twist_length_mm", geometry.twist_length_m * 1e3) * 1e-3;
    if (!(geometry.twist_length_m > 0)) t.fail(t.get("twist_length_mm"), "twist_length_mm", "expected a number > 0");
    geometry.arm_length_m = t.number("arm_length_mm", geometry.arm_length_m * 1e3) * 1e-3;
    if (!(geometry.arm_length_m > 0)) t.fail(t.get("arm_length_mm"), "arm_length_mm", "expected a number > 0");
    geometry.arm_angle_rad = t.number("arm_angle_deg", geometry.arm_angle_rad / degree) * degree;
    if (!(geometry.arm_angle_rad > 0 && geometry.arm_angle_rad < 90 * degree))
      t.fail(t.get("arm_angle_deg"), "arm_angle_deg", "expected an angle in (0, 90) deg");
    geometry.arm_links = static_cast<int>(t.integer("arm_links", 1, 1));
    scale = t.boolean("scale_to_link_length", true);
    // The bending rig (three_point_bending experiments; dem_specimen.hpp, RollerRig).
    const auto positive_mm = [&](const char* key, double& metres) {
      metres = t.number(key, metres * 1e3) * 1e-3;
      if (!(metres > 0)) t.fail(t.get(key), key, "expected a number > 0 (mm)");
    };
    positive_mm("roller_radius_mm", rig.radius_m);
    positive_mm("sw_contact_radius_mm", rig.sw_contact_radius_m);
    positive_mm("dt_contact_radius_mm", rig.dt_contact_radius_m);
    if (t.has("support_z_mm")) {
      const std::vector<double> z = t.numbers("support_z_mm");
      if (z.size() != 2 || !(z[0] < z[1]))
        t.fail(t.get("support_z_mm"), "support_z_mm", "expected two increasing z positions [lower, upper] (mm)");
      rig.support_z_m = {z[0] * 1e-3, z[1] * 1e-3};
    }
    rig.loading_z_m = t.number("loading_z_mm", rig.loading_z_m * 1e3) * 1e-3;
    if (!(rig.support_z_m[0] < rig.loading_z_m && rig.loading_z_m < rig.support_z_m[1]))
      t.fail(t.get("loading_z_mm"), "loading_z_mm", "expected a z between the supports' (support_z_mm)");
    rig.support_tilt_rad = t.number("support_tilt_deg", rig.support_tilt_rad / degree) * degree;
    if (!(std::abs(rig.support_tilt_rad) < 45 * degree))
      t.fail(t.get("support_tilt_deg"), "support_tilt_deg", "expected an angle within (-45, 45) deg");
    rig.friction = t.number("roller_friction", rig.friction);
    if (!(rig.friction >= 0)) t.fail(t.get("roller_friction"), "roller_friction", "expected a number >= 0");
    rig.normal_stiffness_N_per_m = t.number("roller_stiffness_N_per_m", rig.normal_stiffness_N_per_m);
    if (!(rig.normal_stiffness_N_per_m > 0))
      t.fail(t.get("roller_stiffness_N_per_m"), "roller_stiffness_N_per_m", "expected a number > 0");
  }
  if (const toml::node* node = sim.get("quasi_static")) {
    if (!node->is_table()) sim.fail(node, "quasi_static", "expected a table [simulator.quasi_static]");
    const Table t(*node->as_table(), "simulator.quasi_static", file);
    t.only({"local_damping", "move_steps", "tolerance", "max_relax_steps", "safety"});
    quasi_static.local_damping = t.number("local_damping", quasi_static.local_damping);
    if (!(quasi_static.local_damping >= 0 && quasi_static.local_damping < 1))
      t.fail(t.get("local_damping"), "local_damping", "expected a number in [0, 1)");
    quasi_static.move_steps = static_cast<int>(t.integer("move_steps", quasi_static.move_steps, 1));
    quasi_static.tolerance = t.number("tolerance", quasi_static.tolerance);
    if (!(quasi_static.tolerance > 0)) t.fail(t.get("tolerance"), "tolerance", "expected a number > 0");
    quasi_static.max_relax_steps = static_cast<long>(t.integer("max_relax_steps", quasi_static.max_relax_steps, 1));
    quasi_static.safety = t.number("safety", quasi_static.safety);
    if (!(quasi_static.safety > 0 && quasi_static.safety <= 1)) t.fail(t.get("safety"), "safety", "expected a number in (0, 1]");
  }
}

LossKind loss_kind(const Table& t) {
  const std::string loss = t.text("loss", "squared");
  if (loss == "squared") return LossKind::Squared;
  if (loss == "huber") return LossKind::Huber;
  if (loss == "cauchy") return LossKind::Cauchy;
  t.fail(t.get("loss"), "loss", "expected squared, huber or cauchy, found '" + loss + "'");
}

// [fit] screening_iterations = [k1, k2, ...] and screening_cost_ratio = [r1, r2, ...]: the
// multi-start's screening stages (fitter.hpp), one ratio per iteration count.
void read_screening(const Table& fit, FitOptions& options) {
  if (!fit.has("screening_iterations") && !fit.has("screening_cost_ratio")) return;
  if (!fit.has("screening_iterations") || !fit.has("screening_cost_ratio"))
    fit.fail(fit.get(fit.has("screening_iterations") ? "screening_iterations" : "screening_cost_ratio"),
             fit.has("screening_iterations") ? "screening_iterations" : "screening_cost_ratio",
             "give screening_iterations and screening_cost_ratio together (one ratio per stage)");
  const std::vector<double> iterations = fit.numbers("screening_iterations");
  const std::vector<double> ratios = fit.numbers("screening_cost_ratio");
  if (iterations.empty() || iterations.size() != ratios.size())
    fit.fail(fit.get("screening_cost_ratio"), "screening_cost_ratio",
             "expected one ratio per entry of screening_iterations (" + std::to_string(iterations.size()) + ")");
  for (std::size_t k = 0; k < iterations.size(); ++k) {
    const double i = iterations[k];
    if (!(i >= 1 && i == std::floor(i)) || (k > 0 && !(i > iterations[k - 1])))
      fit.fail(fit.get("screening_iterations"), "screening_iterations",
               "expected increasing whole numbers of iterations >= 1");
    if (!(ratios[k] > 1.0))
      fit.fail(fit.get("screening_cost_ratio"), "screening_cost_ratio", "expected cost ratios > 1");
    options.screening.push_back({static_cast<int>(i), ratios[k]});
  }
}

}  // namespace

FitDefinition read_fit_file(const std::filesystem::path& file, const FitReadOptions& options) {
  const bool read_targets = options.read_targets;
  const std::string name = file.string();
  toml::table root;
  try {
    root = toml::parse_file(name);
  } catch (const toml::parse_error& error) {
    const auto& where = error.source().begin;
    throw InputError(name, static_cast<int>(where.line), static_cast<int>(where.column),
                     std::string(error.description()));
  }
  const std::filesystem::path folder = file.parent_path();
  const auto resolve = [&](const std::string& relative) {
    const std::filesystem::path p(relative);
    return p.is_absolute() ? p : folder / p;
  };
  FitDefinition def;
  def.file = file;
  def.inputs.push_back(file);
  const Table top(root, "", name);
  top.only({"title", "wire_type", "simulator", "fit", "parameter", "experiment"});
  def.title = top.text("title", "");
  def.wire_type = top.text("wire_type", "default");

  const toml::table& sim_table = table_at(root, "simulator", name);
  const Table sim(sim_table, "simulator", name);
  sim.only({"kind", "law", "fixed_parameters_file", "fixed_parameters_section", "fixed", "program",
            "arguments", "result", "work_directory", "sw_section", "dt_section", "specimen", "quasi_static"});
  def.simulator = sim.text("kind");
  if (def.simulator != "law_replay" && def.simulator != "voce_bar" && def.simulator != "command" &&
      def.simulator != "dem_specimen")
    sim.fail(sim.get("kind"), "kind",
             "expected law_replay, dem_specimen, command or voce_bar, found '" + def.simulator + "'");
  const bool specimen = def.simulator == "dem_specimen";
  for (const char* key : {"sw_section", "dt_section", "specimen", "quasi_static"})
    if (!specimen && sim.has(key)) sim.fail(sim.get(key), key, "only for kind = \"dem_specimen\"");
  if (specimen && sim.has("fixed_parameters_section"))
    sim.fail(sim.get("fixed_parameters_section"), "fixed_parameters_section",
             "dem_specimen reads two sections: give sw_section and dt_section (defaults single_wire, double_twist)");
  if (specimen && sim.has("fixed_parameters_file")) {
    // Both sets from one file, prefixed with their wire type.
    const auto path = resolve(sim.text("fixed_parameters_file"));
    for (const auto& [prefix, key, fallback] : {std::tuple<std::string, std::string, std::string>{kSwPrefix, "sw_section", "single_wire"},
                                                {kDtPrefix, "dt_section", "double_twist"}})
      for (const auto& [parameter, value] : read_fixed_json(path, sim.text(key, fallback), sim, key))
        def.fixed[prefix + parameter] = value;
    def.inputs.push_back(path);
  } else if (sim.has("fixed_parameters_file")) {
    const auto path = resolve(sim.text("fixed_parameters_file"));
    def.fixed = read_fixed_json(path, sim.text("fixed_parameters_section", ""), sim);
    def.inputs.push_back(path);
  }
  if (const toml::node* fixed = sim.get("fixed")) {
    if (!fixed->is_table()) sim.fail(fixed, "fixed", "expected a table of name = number");
    const Table fixed_table(*fixed->as_table(), "simulator.fixed", name);
    for (const auto& [key, value] : *fixed->as_table())
      def.fixed[std::string(key.str())] = fixed_table.number_of(&value, std::string(key.str()));
  }
  CommandSpecification command;
  SpecimenGeometry geometry;
  QuasiStaticOptions quasi_static;
  bool scale_to_link = true;
  RollerRig rig;
  if (def.simulator == "law_replay") {
    def.law = sim.text("law");
    check_fixed_law_parameters(def, sim);
  } else if (specimen) {
    def.law = sim.text("law");
    check_fixed_specimen_parameters(def, sim);
    read_specimen_tables(sim, name, geometry, quasi_static, scale_to_link, rig);
  } else if (def.simulator == "command") {
    def.law = sim.text("law", "command");
    const std::string program = sim.text("program", "dtwire");
    command.program = program == "dtwire" ? dtwire_executable() : std::filesystem::path(program);
    const toml::node* arguments = sim.get("arguments");
    if (!arguments || !arguments->is_array())
      sim.fail(arguments, "arguments", "expected an array of strings, e.g. [\"run\", \"{input}\", \"--out\", \"{output}\", \"-q\"]");
    for (const toml::node& a : *arguments->as_array()) {
      if (!a.is_string()) sim.fail(&a, "arguments", "expected strings");
      command.arguments.push_back(a.as_string()->get());
    }
    command.result = sim.text("result", "curve.csv");
    command.work_directory =
        sim.has("work_directory")
            ? resolve(sim.text("work_directory"))
            : std::filesystem::temp_directory_path() / "dtwire-fit-runs" /
                  sha256_text(std::filesystem::absolute(file).string()).substr(0, 16);
    command.fixed = def.fixed;
  } else {
    def.law = "voce_bar";
  }

  bool log_parameters = false;  // [fit] log_parameters: applied to the parameters read below
  if (root.contains("fit")) {
    const Table fit(table_at(root, "fit", name), "fit", name);
    fit.only({"loss", "loss_scale", "starts", "log_parameters", "seed", "max_iterations", "relative_step",
              "central_differences", "threads", "function_tolerance", "parameter_tolerance",
              "gradient_tolerance", "disk_cache", "identification_tolerance", "screening_iterations",
              "screening_cost_ratio", "line_search", "polish_relative_step"});
    def.disk_cache = fit.boolean("disk_cache", false);
    def.fit.loss = loss_kind(fit);
    def.fit.loss_scale = fit.number("loss_scale", 1.0);
    if (!(def.fit.loss_scale > 0)) fit.fail(fit.get("loss_scale"), "loss_scale", "expected a number > 0");
    def.fit.starts = static_cast<int>(fit.integer("starts", 1, 1));
    log_parameters = fit.boolean("log_parameters", false);
    def.fit.seed = static_cast<std::uint64_t>(fit.integer("seed", 1, 0));
    def.fit.max_iterations = static_cast<int>(fit.integer("max_iterations", 50, 1));
    def.fit.identification_tolerance = fit.number("identification_tolerance", def.fit.identification_tolerance);
    if (!(def.fit.identification_tolerance > 0))
      fit.fail(fit.get("identification_tolerance"), "identification_tolerance", "expected a number > 0");
    def.fit.function_tolerance = fit.number("function_tolerance", def.fit.function_tolerance);
    def.fit.parameter_tolerance = fit.number("parameter_tolerance", def.fit.parameter_tolerance);
    def.fit.gradient_tolerance = fit.number("gradient_tolerance", def.fit.gradient_tolerance);
    def.evaluation.relative_step = fit.number("relative_step", def.evaluation.relative_step);
    if (!(def.evaluation.relative_step > 0 && def.evaluation.relative_step < 1))
      fit.fail(fit.get("relative_step"), "relative_step", "expected a number in (0, 1)");
    if (fit.has("polish_relative_step")) {
      def.fit.polish_relative_step = fit.number("polish_relative_step", 0.0);
      if (!(def.fit.polish_relative_step > def.evaluation.relative_step && def.fit.polish_relative_step < 1))
        fit.fail(fit.get("polish_relative_step"), "polish_relative_step",
                 "expected a number above relative_step (" + std::to_string(def.evaluation.relative_step) + ") and below 1");
    }
    def.evaluation.central_differences = fit.boolean("central_differences", false);
    def.evaluation.threads = static_cast<unsigned>(fit.integer("threads", 0, 0));
    read_screening(fit, def.fit);
    const std::string line_search = fit.text("line_search", "gradients");
    if (line_search != "gradients" && line_search != "values")
      fit.fail(fit.get("line_search"), "line_search", "expected gradients or values, found '" + line_search + "'");
    def.fit.value_only_line_search = line_search == "values";
  }

  const toml::node* parameters = root.get("parameter");
  if (!parameters || !parameters->is_array_of_tables())
    throw InputError(name, parameters ? static_cast<int>(parameters->source().begin.line) : 0, 0,
                     "field 'parameter': expected at least one [[parameter]] table");
  std::size_t index = 0;
  std::vector<Table> parameter_tables;
  for (const toml::node& node : *parameters->as_array()) {
    const Table p(*node.as_table(), "parameter[" + std::to_string(++index) + "]", name);
    parameter_tables.push_back(p);
    p.only({"name", "unit", "initial", "lower", "upper", "scale", "reference", "offset_from"});
    ParameterDefinition d;
    d.name = p.text("name");
    d.unit = p.text("unit", "1");
    d.offset_from = p.text("offset_from", "");
    if (p.has("offset_from") && d.offset_from.empty())
      p.fail(p.get("offset_from"), "offset_from", "expected the name of another fitted parameter");
    d.initial = p.number("initial");
    d.lower = p.number("lower");
    d.upper = p.number("upper");
    d.scale = p.number("scale", 0.0);
    if (p.has("reference")) d.reference = p.number("reference");
    // An offset parameter's numbers are those of its offset: say so where they are refused.
    const std::string of_offset = d.offset_from.empty() ? "" : " (of the offset " + coordinate_name(d) + ")";
    if (!(d.lower < d.upper)) p.fail(p.get("upper"), "upper", "expected upper > lower" + of_offset);
    if (d.initial < d.lower || d.initial > d.upper)
      p.fail(p.get("initial"), "initial", "expected a value within [lower, upper]" + of_offset);
    if (d.scale < 0) p.fail(p.get("scale"), "scale", "expected a number > 0");
    d.logarithmic = log_parameters && d.lower > 0 && d.upper >= 10 * d.lower;
    for (const auto& other : def.parameters)
      if (other.name == d.name) p.fail(p.get("name"), "name", "parameter '" + d.name + "' defined twice");
    def.parameters.push_back(d);
  }
  check_offsets(def.parameters, parameter_tables);

  const toml::node* experiments = root.get("experiment");
  if (!experiments || !experiments->is_array_of_tables())
    throw InputError(name, experiments ? static_cast<int>(experiments->source().begin.line) : 0, 0,
                     "field 'experiment': expected at least one [[experiment]] table");
  index = 0;
  std::vector<std::string> names_in_file;
  for (const toml::node& node : *experiments->as_array()) {
    const toml::table& raw = *node.as_table();
    const Table x(raw, "experiment[" + std::to_string(++index) + "]", name);
    x.only({"name", "target", "target_columns", "abscissa", "arc_length", "channels", "weight",
            "branch_tolerance", "increments_per_leg", "input_template", "input_prm", "prm_set",
            "pull_angle_deg", "pull_angle_rad", "path_from_target", "test", "peak"},
           "path_");
    for (const char* key : {"pull_angle_deg", "pull_angle_rad", "test"})
      if (x.has(key) && def.simulator != "dem_specimen") x.fail(x.get(key), key, "only for kind = \"dem_specimen\"");
    Experiment e;
    e.name = x.text("name");
    if (std::find(names_in_file.begin(), names_in_file.end(), e.name) != names_in_file.end())
      x.fail(x.get("name"), "name", "experiment '" + e.name + "' defined twice");
    names_in_file.push_back(e.name);
    const auto& only = options.only_experiments;
    if (!only.empty() && std::find(only.begin(), only.end(), e.name) == only.end()) continue;
    const auto [target, synthesized_name] = target_path(x, folder, options);
    std::vector<const toml::node*> mapping_nodes;
    const std::vector<ColumnMapping> mapping = column_mapping(x, name, mapping_nodes);
    if (read_targets) {
      const Curve curve = read_csv(target);  // InputError with the CSV's own file:line:column
      for (std::size_t m = 0; m < mapping.size(); ++m)
        if (!curve.has(mapping[m].column)) {
          std::string columns;
          for (const Channel& c : curve.channels()) columns += (columns.empty() ? "" : ", ") + c.column_name();
          x.fail(mapping_nodes[m], "target_columns." + mapping[m].quantity,
                 "the target " + target.string() + " has no column '" + mapping[m].column +
                     "_<unit>' (columns: " + columns + ")");
        }
      e.target = map_columns(curve, mapping);
      def.inputs.push_back(target);
    }
    // path_from_target: the replayed path is the target's own kinematics; it also gives the
    // target its pseudo-time column, so it is built before the abscissa is checked.
    std::optional<LoadPath> followed_path;
    if (x.has("path_from_target") && def.simulator != "law_replay")
      x.fail(x.get("path_from_target"), "path_from_target", "only for kind = \"law_replay\"");
    if (def.simulator == "law_replay" && x.has("path_from_target")) {
      if (!x.boolean("path_from_target", false))
        x.fail(x.get("path_from_target"), "path_from_target", "expected true or no field");
      for (const auto& [key, item] : raw)
        if (std::string(key.str()).rfind("path_", 0) == 0 && std::string(key.str()) != "path_from_target")
          x.fail(&item, std::string(key.str()), "give either path_from_target or path waypoints, not both");
      if (!read_targets)
        x.fail(x.get("path_from_target"), "path_from_target", "needs the target curve (not available with --synthesize)");
      try {
        const long long increments = x.integer("increments_per_leg", 100, 1, kMostIncrementsPerLeg);
        check_path_memory(x, static_cast<double>(increments) * static_cast<double>(std::max<std::size_t>(e.target.size(), 1)));
        followed_path = path_from_target(e.target, static_cast<int>(increments));
      } catch (const std::invalid_argument& error) {
        x.fail(x.get("path_from_target"), "path_from_target", "the target " + target.string() + ": " + error.what());
      }
    }
    def.experiment_targets.push_back(target);
    def.experiment_target_names.push_back(synthesized_name);
    def.experiment_columns.push_back(mapping);
    e.abscissa = x.text("abscissa", "displacement");
    e.kind = x.boolean("arc_length", false) ? AbscissaKind::NormalizedArcLength : AbscissaKind::Channel;
    e.weight = x.number("weight", 1.0);
    if (!(e.weight > 0)) x.fail(x.get("weight"), "weight", "expected a number > 0");
    e.branch_tolerance = x.number("branch_tolerance", e.branch_tolerance);
    if (e.branch_tolerance < 0) x.fail(x.get("branch_tolerance"), "branch_tolerance", "expected >= 0");
    std::vector<Compared> compared{{e.abscissa, "abscissa", x.get("abscissa")}};
    // `key` = ["force"] or [{quantity, weight, scale}], each a channel of the target.
    const auto weighted_quantities = [&](const char* key) {
      const toml::node* list = x.get(key);
      if (!list || !list->is_array() || list->as_array()->empty())
        x.fail(list, key, "expected a non-empty array, e.g. [\"force\"] or [{quantity = \"force\", weight = 1}]");
      std::vector<ChannelWeight> out;
      for (const toml::node& c : *list->as_array()) {
        ChannelWeight w;
        if (c.is_string()) {
          w.quantity = c.as_string()->get();
        } else if (c.is_table()) {
          const Table ct(*c.as_table(), x.field(key), name);
          ct.only({"quantity", "weight", "scale"});
          w.quantity = ct.text("quantity");
          w.weight = ct.number("weight", 1.0);
          w.scale = ct.number("scale", 0.0);
          if (!(w.weight > 0)) ct.fail(ct.get("weight"), "weight", "expected a number > 0");
          if (w.scale < 0) ct.fail(ct.get("scale"), "scale", "expected a number > 0 (or no field: the target's range)");
        } else {
          x.fail(&c, key, "expected a quantity name or a {quantity, weight, scale} table");
        }
        if (read_targets && !e.target.has(w.quantity))
          x.fail(&c, key, "the target " + target.string() + " has no channel '" + w.quantity + "'");
        if (std::any_of(out.begin(), out.end(), [&](const ChannelWeight& o) { return o.quantity == w.quantity; }))
          x.fail(&c, key, "'" + w.quantity + "' given twice");
        out.push_back(w);
        compared.push_back({w.quantity, key, &c});
      }
      return out;
    };
    e.channels = weighted_quantities("channels");
    if (x.has("peak")) e.peaks = weighted_quantities("peak");
    if (read_targets && !e.target.has(e.abscissa))
      x.fail(x.get("abscissa"), "abscissa", "the target " + target.string() + " has no channel '" + e.abscissa + "'");
    const int increments = static_cast<int>(x.integer("increments_per_leg", 100, 1, kMostIncrementsPerLeg));
    if (followed_path) {
      e.simulator = std::make_shared<LawReplaySimulator>(def.law, def.fixed, *followed_path);
    } else if (def.simulator == "law_replay") {
      LoadPath path;
      path.displacement_m = waypoints(x, "path_displacement_", Dimension::Length, raw);
      path.rotation_rad = waypoints(x, "path_rotation_", Dimension::Angle, raw);
      if (path.displacement_m.empty() && path.rotation_rad.empty())
        x.fail(nullptr, "path_displacement_mm", "missing: give path_displacement_<unit> and/or path_rotation_<unit>");
      if (path.displacement_m.empty()) path.displacement_m.assign(path.rotation_rad.size(), 0.0);
      if (path.rotation_rad.empty()) path.rotation_rad.assign(path.displacement_m.size(), 0.0);
      if (path.displacement_m.size() != path.rotation_rad.size())
        x.fail(nullptr, "path_rotation", "displacement and rotation waypoints must have the same length");
      if (path.displacement_m.size() < 2)
        x.fail(x.get("path_displacement_mm"), x.has("path_displacement_mm") ? "path_displacement_mm" : "path_displacement",
               "expected >= 2 waypoints (a leg runs from one to the next)");
      path.increments_per_leg = increments;
      check_path_memory(x, static_cast<double>(increments) * static_cast<double>(path.displacement_m.size() - 1));
      e.simulator = std::make_shared<LawReplaySimulator>(def.law, def.fixed, path);
    } else if (specimen) {
      SpecimenPath path;
      path.displacement_m = waypoints(x, "path_displacement_", Dimension::Length, raw);
      const std::string test = x.text("test", "pull");
      if (test != "pull" && test != "three_point_bending")
        x.fail(x.get("test"), "test", "expected pull or three_point_bending, found '" + test + "'");
      if (test == "three_point_bending") {
        path.test = SpecimenTest::ThreePointBending;
        for (const char* key : {"pull_angle_deg", "pull_angle_rad"})
          if (x.has(key)) x.fail(x.get(key), key, "a three_point_bending experiment has no pull angle");
      }
      if (path.displacement_m.empty())
        x.fail(nullptr, "path_displacement_mm",
               "missing: the upper grips' displacement waypoints along the pull direction (three_point_bending: the "
               "loading roller's along -y)");
      for (const auto& [key, item] : raw)
        if (std::string(key.str()).rfind("path_", 0) == 0 && std::string(key.str()).rfind("path_displacement_", 0) != 0)
          x.fail(&item, std::string(key.str()), "dem_specimen paths have grip displacements only (path_displacement_<unit>) "
                                                "and a pull angle (pull_angle_deg)");
      const toml::node* first = x.get("path_displacement_mm");
      if (path.displacement_m.size() < 2 || path.displacement_m.front() != 0.0)
        x.fail(first, first ? "path_displacement_mm" : "path_displacement", "expected >= 2 waypoints starting at 0");
      if (x.has("pull_angle_deg") && x.has("pull_angle_rad"))
        x.fail(x.get("pull_angle_rad"), "pull_angle_rad", "given twice (also as pull_angle_deg)");
      path.pull_angle_rad = x.has("pull_angle_rad") ? x.number("pull_angle_rad")
                                                    : x.number("pull_angle_deg", 0.0) * 3.14159265358979323846 / 180.0;
      if (std::abs(path.pull_angle_rad) > 0.5 * 3.14159265358979323846 + 1e-12)
        x.fail(x.get(x.has("pull_angle_rad") ? "pull_angle_rad" : "pull_angle_deg"),
               x.has("pull_angle_rad") ? "pull_angle_rad" : "pull_angle_deg", "expected an angle within [-90, 90] deg");
      path.increments_per_leg = increments;
      check_path_memory(x, static_cast<double>(increments) * static_cast<double>(path.displacement_m.size() - 1));
      try {
        e.simulator =
            std::make_shared<DemSpecimenSimulator>(def.law, def.fixed, geometry, quasi_static, path, scale_to_link, rig);
      } catch (const std::invalid_argument& error) {
        x.fail(nullptr, "path_displacement_mm", error.what());
      }
    } else if (def.simulator == "command") {
      const CommandSpecification spec = command_experiment(x, command, resolve, def.inputs);
      auto simulator = std::make_shared<CommandSimulator>(spec);
      // Every placeholder must have a value (a parameter or a fixed value).
      std::vector<double> initial;
      for (const auto& p : def.parameters) initial.push_back(p.initial);
      const ParameterValues probe = to_values(def.parameters, initial);
      try {
        simulator->instantiate(probe);
      } catch (const ComputationError& error) {
        const std::string key = x.has("input_prm") ? "input_prm" : "input_template";
        x.fail(x.get(key), key, x.text(key) + ": " + error.what());
      }
      e.simulator = simulator;
    } else {
      std::vector<double> strain;
      if (x.has("path_strain_1")) strain = x.numbers("path_strain_1");
      else x.fail(nullptr, "path_strain_1", "missing (the voce_bar path: strain waypoints)");
      if (strain.size() < 2) x.fail(x.get("path_strain_1"), "path_strain_1", "expected >= 2 waypoints");
      e.simulator = std::make_shared<VoceBarSimulator>(strain, increments);
    }
    check_simulated_channels(e, compared, def.simulator, x);
    try {
      if (read_targets) validate(e);
    } catch (const std::invalid_argument& error) {
      x.fail(nullptr, "target", error.what());
    }
    def.experiments.push_back(std::move(e));
  }
  for (const std::string& wanted : options.only_experiments)
    if (std::find(names_in_file.begin(), names_in_file.end(), wanted) == names_in_file.end()) {
      std::string held;
      for (const std::string& n : names_in_file) held += (held.empty() ? "" : ", ") + n;
      throw InputError(name, "--experiments: no experiment '" + wanted + "' in the file (it has: " + held + ")");
    }
  check_parameters_are_read(def, parameter_tables);
  return def;
}

}  // namespace dtwire::calibrate
