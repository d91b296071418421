// Reading a `dtwire dem run` TOML input (format: docs/dem_engine.md). Every error names
// file:line and the field.
#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include "dtwire/core/error.hpp"
#include "dtwire/dem/export_params.hpp"
#include "dtwire/dem/law_schema.hpp"
#include "dtwire/dem/run.hpp"

namespace dtwire::dem {
namespace {

constexpr double kHuge = std::numeric_limits<double>::max();  // no upper bound

class Reader {
 public:
  explicit Reader(std::filesystem::path file) : file_(std::move(file)) {}

  [[noreturn]] void fail(const toml::node* node, const std::string& field, const std::string& message) const {
    if (node) {
      const auto& where = node->source().begin;
      if (where.line == 0) throw InputError("--set", field + ": " + message);  // no source: given on the command line
      throw InputError(file_.string(), static_cast<int>(where.line), static_cast<int>(where.column), field + ": " + message);
    }
    throw InputError(file_.string(), field + ": " + message);
  }

  void check_keys(const toml::table& table, const std::string& prefix, const std::set<std::string>& allowed) const {
    for (const auto& [key, node] : table)
      if (!allowed.count(std::string(key.str())))
        fail(&node, prefix + std::string(key.str()), "unknown key");
  }

  double number(const toml::table& table, const std::string& prefix, const std::string& key, double fallback,
                bool positive = false) const {
    const toml::node* node = table.get(key);
    if (!node) return fallback;
    const auto value = node->value<double>();
    if (!value || !std::isfinite(*value)) fail(node, prefix + key, "expected a number");
    if (positive && !(*value > 0.0)) fail(node, prefix + key, "expected a positive number");
    return *value;
  }
  // A number in [low, high]; `expected` says so in the error ("a mass >= 0 kg").
  double ranged(const toml::table& table, const std::string& prefix, const std::string& key, double fallback,
                double low, double high, const std::string& expected) const {
    const double value = number(table, prefix, key, fallback);
    if (!(value >= low && value <= high)) fail(table.get(key), prefix + key, "expected " + expected);
    return value;
  }
  // A whole number in [low, high] (1.5 or 1e12 are refused, not truncated).
  long integer(const toml::table& table, const std::string& prefix, const std::string& key, long fallback, long low,
               long high) const {
    const toml::node* node = table.get(key);
    if (!node) return fallback;
    const auto value = node->value_exact<std::int64_t>();
    if (!value || *value < low || *value > high)
      fail(node, prefix + key, "expected an integer in [" + std::to_string(low) + ", " + std::to_string(high) + "]");
    return static_cast<long>(*value);
  }
  double required_number(const toml::table& table, const std::string& prefix, const std::string& key, bool positive) const {
    if (!table.get(key)) fail(&table, prefix + key, "missing");
    return number(table, prefix, key, 0.0, positive);
  }
  std::string text(const toml::table& table, const std::string& prefix, const std::string& key,
                   const std::string& fallback) const {
    const toml::node* node = table.get(key);
    if (!node) return fallback;
    const auto value = node->value<std::string>();
    if (!value) fail(node, prefix + key, "expected a string");
    return *value;
  }
  bool boolean(const toml::table& table, const std::string& prefix, const std::string& key, bool fallback) const {
    const toml::node* node = table.get(key);
    if (!node) return fallback;
    const auto value = node->value<bool>();
    if (!value) fail(node, prefix + key, "expected true or false");
    return *value;
  }
  const toml::table* table(const toml::table& parent, const std::string& key) const {
    const toml::node* node = parent.get(key);
    if (!node) return nullptr;
    if (!node->is_table()) fail(node, key, "expected a table");
    return node->as_table();
  }
  std::filesystem::path path(const std::string& relative) const {
    const std::filesystem::path p(relative);
    return p.is_absolute() ? p : file_.parent_path() / p;
  }
  const std::filesystem::path& file() const { return file_; }

 private:
  std::filesystem::path file_;
};

// Thoeni et al. 2013 initial slack (distortion.hpp): mode, lambda_u in [0, 1), integer seed.
Distortion read_distortion(const Reader& r, const toml::table& table, const std::string& prefix, const LinkSetInput& set) {
  Distortion d;
  try {
    d.mode = distortion_mode_from_name(r.text(table, prefix, "distortion", "none"));
  } catch (const std::invalid_argument& e) {
    r.fail(table.get("distortion"), prefix + "distortion", e.what());
  }
  const toml::node* lambda = table.get("distortion_lambda_u");
  const toml::node* seed = table.get("distortion_seed");
  if (d.mode == DistortionMode::None) {
    if (lambda || seed) r.fail(lambda ? lambda : seed, prefix + (lambda ? "distortion_lambda_u" : "distortion_seed"),
                               "has no effect without distortion = \"constant\" or \"random\"");
    return d;
  }
  if (!lambda) r.fail(&table, prefix + "distortion_lambda_u", "missing: the slack as a fraction of the link length, in [0, 1)");
  d.lambda_u = r.number(table, prefix, "distortion_lambda_u", 0.0);
  if (!(d.lambda_u >= 0.0 && d.lambda_u < 1.0)) r.fail(lambda, prefix + "distortion_lambda_u", "expected a value in [0, 1)");
  if (d.mode == DistortionMode::Constant && seed)
    r.fail(seed, prefix + "distortion_seed", "has no effect with distortion = \"constant\" (every link gets lambda_u l0)");
  if (d.mode == DistortionMode::Random) {
    if (!seed) r.fail(&table, prefix + "distortion_seed", "missing: an integer in [1, 2147483646]");
    const auto value = seed->value_exact<std::int64_t>();
    if (!value || *value < 1 || *value > kLargestDistortionSeed)
      r.fail(seed, prefix + "distortion_seed", "expected an integer in [1, 2147483646]");
    d.seed = *value;
  }
  if (set.law == "wirepm" && set.parameters.count("lambda_u") && set.parameters.at("lambda_u") != 0.0)
    r.fail(table.get("distortion"), prefix + "distortion",
           "the parameter file already sets lambda_u; give the distortion in one place");
  return d;
}

void apply_scales(LinkSetInput& set) {
  for (const auto& [name, factor] : set.scales) set.parameters[name] *= factor;
}

LinkSetInput read_link_set(const Reader& r, const toml::table& table, const std::string& prefix) {
  r.check_keys(table, prefix, {"law", "params", "wire_type", "backbone", "parameters", "scale", "length",
                               "distortion", "distortion_lambda_u", "distortion_seed"});
  LinkSetInput set;
  const std::string params = r.text(table, prefix, "params", "");
  if (params.empty()) r.fail(&table, prefix + "params", "missing: the parameter file (.json) of this link type");
  const std::filesystem::path params_path = r.path(params);
  if (!std::filesystem::exists(params_path)) r.fail(table.get("params"), prefix + "params", "no such file " + params_path.string());
  const std::vector<ParameterSet> sets = read_parameter_file(params_path);
  ParameterSet chosen = select_wire_type(sets, r.text(table, prefix, "wire_type", ""), params_path);
  set.files.push_back(params_path);
  const std::string backbone = r.text(table, prefix, "backbone", "");
  if (!backbone.empty()) {
    const std::filesystem::path backbone_path = r.path(backbone);
    if (!std::filesystem::exists(backbone_path))
      r.fail(table.get("backbone"), prefix + "backbone", "no such file " + backbone_path.string());
    add_backbone(chosen, read_backbone_csv(backbone_path));
    set.files.push_back(backbone_path);
  }
  set.law = r.text(table, prefix, "law", chosen.law);
  if (set.law.empty()) r.fail(&table, prefix + "law", "missing (the parameter file names no law)");
  if (!chosen.law.empty() && chosen.law != set.law)
    r.fail(table.get("law"), prefix + "law", "'" + set.law + "' but the parameter file says '" + chosen.law + "'");
  set.parameters = chosen.map();
  set.length = r.text(table, prefix, "length", "set");
  if (set.length != "set" && set.length != "link")
    r.fail(table.get("length"), prefix + "length", "expected \"set\" (the set as calibrated, as the PFC7 plugin) or \"link\" (rescaled to the link's length)");
  if (set.length == "link" && set.law == "wirepm")
    r.fail(table.get("length"), prefix + "length", "WirePM links always take the link's own length (a strain law, as YADE); remove the key");
  if (set.length == "link" && !(chosen.map().count("reference_length_m")))
    r.fail(table.get("length"), prefix + "length", "\"link\" needs the set's reference_length_m (the length it was calibrated on)");
  // Values that replace or add to the file's set for this run only (set-up studies, e.g. the
  // PFC7 plugin's damage mode: parameters = { damage_scales_forces = 0 }).
  if (const toml::table* overrides = r.table(table, "parameters")) {
    for (const auto& [key, node] : *overrides) {
      const std::string name(key.str());
      if (!is_law_parameter(set.law, name))
        r.fail(&node, prefix + "parameters." + name, "not a parameter of the " + set.law + " law");
      const auto value = node.value<double>();
      if (!value || !std::isfinite(*value)) r.fail(&node, prefix + "parameters." + name, "expected a number");
      set.parameters[name] = *value;
      set.overrides[name] = *value;
    }
  }
  // Factors on the set's values for this run only (sensitivity studies, `gap --model` on a DEM
  // run: scale = { N0_N = 0.8, Nult_N = 0.8 } weakens the links by 20 %).
  if (const toml::table* scales = r.table(table, "scale")) {
    for (const auto& [key, node] : *scales) {
      const std::string name(key.str());
      if (!set.parameters.count(name))
        r.fail(&node, prefix + "scale." + name, "not a value of this link set (" + set.law + " law)");
      const auto factor = node.value<double>();
      if (!factor || !std::isfinite(*factor) || !(*factor > 0.0))
        r.fail(&node, prefix + "scale." + name, "expected a factor > 0");
      set.scales[name] = *factor;
    }
  }
  apply_scales(set);
  try {
    check_parameter_names(chosen, set.law, params_path);
    ParameterMap probe = set.parameters;
    if (set.law == "wirepm" && !probe.count("reference_length_m")) probe["reference_length_m"] = 0.05;
    make_contact_law(set.law, probe);  // validates names and values now, not in the middle of a run
  } catch (const std::invalid_argument& e) {
    r.fail(&table, prefix + "params", e.what());
  }
  set.distortion = read_distortion(r, table, prefix, set);
  return set;
}

// `--set table.key=value`: the value is TOML ("slider" with its quotes, 0.01, [1, 2]); the
// entry replaces or adds to the file's, and is then checked as the file's are.
void apply_override(toml::table& root, const std::string& entry) {
  const auto equals = entry.find('=');
  if (equals == std::string::npos || equals == 0)
    throw InputError("--set", "expected TABLE.KEY=VALUE (e.g. boundary.support=\"slider\"), found '" + entry + "'");
  const std::string path = entry.substr(0, equals);
  toml::table parsed;
  try {
    parsed = toml::parse("value = " + entry.substr(equals + 1));
  } catch (const toml::parse_error& e) {
    throw InputError("--set", path + ": the value is not TOML (" + std::string(e.description()) +
                                  "); strings need quotes: " + path + "=\"text\"");
  }
  toml::table* table = &root;
  std::size_t start = 0;
  for (std::size_t dot = path.find('.'); dot != std::string::npos; dot = path.find('.', start)) {
    const std::string key = path.substr(start, dot - start);
    if (!table->contains(key)) table->insert(key, toml::table{});
    table = (*table)[key].as_table();
    if (!table) throw InputError("--set", path + ": '" + key + "' is not a table");
    start = dot + 1;
  }
  table->insert_or_assign(path.substr(start), *parsed.get("value"));
}

// `[tool] kind = "strip_tension"` (strip_tension.hpp): the clamps replace the boundary; the
// platter and boulder keys do not apply.
void read_strip_tension(const Reader& r, const toml::table& root, const toml::table& tool, RunInput& in) {
  const std::set<std::string> strip_keys = {"kind", "direction", "clamp_depth_m", "speed_m_per_s", "travel_m"};
  for (const auto& [key, node] : tool)
    if (!strip_keys.count(std::string(key.str())))
      r.fail(&node, "tool." + std::string(key.str()),
             "not a strip_tension key (expected direction, clamp_depth_m, speed_m_per_s, travel_m)");
  if (const toml::table* boundary = root.get_as<toml::table>("boundary"))
    for (const auto& [key, node] : *boundary)
      r.fail(&node, "boundary." + std::string(key.str()),
             "not used by strip_tension: the clamps hold the strip's ends and its edges along the pull are free");
  in.pinned_sides = 0;
  const std::string direction = r.text(tool, "tool.", "direction", "along_twists");
  if (direction != "along_twists" && direction != "across_twists")
    r.fail(tool.get("direction"), "tool.direction", "expected along_twists or across_twists");
  const bool along = direction == "along_twists";
  in.strip.direction = along ? PullDirection::AlongTwists : PullDirection::AcrossTwists;
  in.speed = r.required_number(tool, "tool.", "speed_m_per_s", true);
  in.travel = r.required_number(tool, "tool.", "travel_m", true);
  in.strip.clamp_depth = r.required_number(tool, "tool.", "clamp_depth_m", true);
  // The panel checks above already refuse a strip narrower than one opening across the pull.
  const double length = along ? in.mesh.height : in.mesh.width;
  if (in.strip.clamp_depth >= 0.5 * length)
    r.fail(tool.get("clamp_depth_m"), "tool.clamp_depth_m",
           "the two clamps leave no free length: the strip is " + std::to_string(length) + " m long along the pull (mesh." +
               (along ? "height_m" : "width_m") + "); expected a depth below half of it");
}

}  // namespace

RunInput read_run_input(const std::filesystem::path& file, const std::vector<std::string>& overrides) {
  toml::table root;
  try {
    root = toml::parse_file(file.string());
  } catch (const toml::parse_error& e) {
    throw InputError(file.string(), static_cast<int>(e.source().begin.line), static_cast<int>(e.source().begin.column),
                     std::string(e.description()));
  }
  for (const std::string& entry : overrides) apply_override(root, entry);
  Reader r(file);
  RunInput in;
  in.file = file;
  r.check_keys(root, "", {"title", "mesh", "links", "boundary", "dynamics", "tool", "output", "checks"});
  in.title = r.text(root, "", "title", file.stem().string());

  const toml::table* mesh = r.table(root, "mesh");
  if (!mesh) r.fail(nullptr, "mesh", "missing table");
  r.check_keys(*mesh, "mesh.", {"pattern", "width_m", "height_m", "selvedge", "node_mass_kg", "node_radius_m", "nodes_per_wire"});
  in.pattern = r.text(*mesh, "mesh.", "pattern", in.pattern);
  try {
    in.mesh = hex_pattern(in.pattern);
  } catch (const std::invalid_argument& e) {
    r.fail(mesh->get("pattern"), "mesh.pattern", e.what());
  }
  in.mesh.width = r.required_number(*mesh, "mesh.", "width_m", true);
  in.mesh.height = r.required_number(*mesh, "mesh.", "height_m", true);
  in.mesh.selvedge = r.boolean(*mesh, "mesh.", "selvedge", false);
  in.mesh.node_mass = r.ranged(*mesh, "mesh.", "node_mass_kg", 0.0, 0.0, kHuge, "a mass >= 0 kg (0: from the wire)");
  in.mesh.node_radius = r.number(*mesh, "mesh.", "node_radius_m", in.mesh.node_radius, true);
  in.mesh.nodes_per_wire = static_cast<int>(r.integer(*mesh, "mesh.", "nodes_per_wire", 2, 2, 3));
  if (in.mesh.width < in.mesh.opening_width)
    r.fail(mesh->get("width_m"), "mesh.width_m", "the panel is narrower than one mesh opening (" +
                                                      std::to_string(in.mesh.opening_width) + " m)");
  if (in.mesh.height < in.mesh.opening_height)
    r.fail(mesh->get("height_m"), "mesh.height_m", "the panel is shorter than one mesh opening (" +
                                                        std::to_string(in.mesh.opening_height) + " m)");

  const toml::table* links = r.table(root, "links");
  if (!links) r.fail(nullptr, "links", "missing table: a law set for each link type (links.sw, links.dt)");
  r.check_keys(*links, "links.", {"sw", "dt", "selvedge"});
  const std::vector<std::pair<LinkTag, std::string>> tags = {
      {LinkTag::SingleWire, "sw"}, {LinkTag::DoubleTwist, "dt"}, {LinkTag::Selvedge, "selvedge"}};
  for (const auto& [tag, name] : tags) {
    const toml::table* set = r.table(*links, name);
    if (!set) {
      if (tag == LinkTag::Selvedge && !in.mesh.selvedge) continue;
      r.fail(links, "links." + name, "missing: no law set for the " + name + " links");
    }
    in.link_sets[tag] = read_link_set(r, *set, "links." + name + ".");
    if (in.mesh.nodes_per_wire == 3 && tag != LinkTag::Selvedge && in.link_sets[tag].law == "wirepm")
      r.fail(mesh->get("nodes_per_wire"), "mesh.nodes_per_wire",
             "3 needs links with bending stiffness (thesis, macro3d, parallel_bond); the wirepm " + name +
                 " links carry axial force only, so each middle node would be a hinge");
  }

  if (const toml::table* boundary = r.table(root, "boundary")) {
    r.check_keys(*boundary, "boundary.", {"pinned", "support", "pretension_strain", "presag_m", "wall_below_m"});
    if (const toml::node* pinned = boundary->get("pinned")) {
      const toml::array* sides = pinned->as_array();
      if (!sides) r.fail(pinned, "boundary.pinned", "expected an array of sides");
      in.pinned_sides = 0;
      for (const toml::node& side : *sides) {
        const auto name = side.value<std::string>();
        const std::map<std::string, unsigned> known = {{"left", kLeft}, {"right", kRight}, {"bottom", kBottom}, {"top", kTop}};
        if (!name || !known.count(*name)) r.fail(&side, "boundary.pinned", "expected left, right, bottom or top");
        in.pinned_sides |= known.at(*name);
      }
    }
    try {
      in.support = parse_edge_support(r.text(*boundary, "boundary.", "support", "pinned"));
    } catch (const std::invalid_argument& e) {
      r.fail(boundary->get("support"), "boundary.support", e.what());
    }
    in.pretension_strain = r.number(*boundary, "boundary.", "pretension_strain", 0.0);
    if (in.pretension_strain < 0.0 || in.pretension_strain > 0.05)
      r.fail(boundary->get("pretension_strain"), "boundary.pretension_strain", "expected a value in [0, 0.05]");
    in.presag = r.number(*boundary, "boundary.", "presag_m", 0.0);
    if (in.presag < 0.0 || in.presag > 0.5)
      r.fail(boundary->get("presag_m"), "boundary.presag_m", "expected a sag in [0, 0.5] m (0: none)");
    in.wall_below = r.number(*boundary, "boundary.", "wall_below_m", 0.0);
    if (in.wall_below < 0.0 || in.wall_below > 2.0)
      r.fail(boundary->get("wall_below_m"), "boundary.wall_below_m", "expected a depth in [0, 2] m (0: no wall)");
    if (in.presag > 0.0 && in.pretension_strain > 0.0)
      r.fail(boundary->get("presag_m"), "boundary.presag_m",
             "given with pretension_strain: the pre-load searches the pre-tension that gives this sag; give one of the two");
    if (in.presag > 0.0 && in.wall_below > 0.0)
      r.fail(boundary->get("wall_below_m"), "boundary.wall_below_m",
             "given with presag_m: the net either is pre-loaded taut or settles slack onto the wall; give one of the two");
    if (in.wall_below > 0.0 && in.pretension_strain > 0.0)
      r.fail(boundary->get("wall_below_m"), "boundary.wall_below_m",
             "given with pretension_strain: a net settling slack onto the wall has no pre-tension");
  }

  if (const toml::table* dynamics = r.table(root, "dynamics")) {
    r.check_keys(*dynamics, "dynamics.", {"gravity_m_per_s2", "local_damping", "mass_scale", "rotational_inertia_scale",
                                          "safety", "time_step_s", "threads", "settle_s",
                                          "settle_rest_ratio"});
    in.engine.gravity = Vector3(0.0, 0.0, -r.ranged(*dynamics, "dynamics.", "gravity_m_per_s2", 9.81, 0.0, kHuge,
                                                    "an acceleration >= 0 (it acts along -z)"));
    in.engine.local_damping = r.number(*dynamics, "dynamics.", "local_damping", 0.0);
    if (in.engine.local_damping < 0.0 || in.engine.local_damping >= 1.0)
      r.fail(dynamics->get("local_damping"), "dynamics.local_damping", "expected a value in [0, 1)");
    in.engine.mass_scale = r.number(*dynamics, "dynamics.", "mass_scale", 1.0, true);
    in.engine.rotational_inertia_scale = r.number(*dynamics, "dynamics.", "rotational_inertia_scale", 1.0, true);
    in.engine.safety = r.number(*dynamics, "dynamics.", "safety", 0.5, true);
    if (in.engine.safety > 1.0) r.fail(dynamics->get("safety"), "dynamics.safety", "expected a value in (0, 1]");
    in.engine.time_step = r.number(*dynamics, "dynamics.", "time_step_s", 0.0, true);
    in.engine.threads = static_cast<int>(r.integer(*dynamics, "dynamics.", "threads", 1, 1, 256));
    in.settle_time = r.ranged(*dynamics, "dynamics.", "settle_s", 0.0, 0.0, kHuge, "a time >= 0 s");
    in.settle_rest_ratio = r.ranged(*dynamics, "dynamics.", "settle_rest_ratio", 0.0, 0.0, 1.0,
                                    "an unbalanced-force ratio in [0, 1] (0: settle for settle_s)");
    if (in.settle_rest_ratio > 0.0 && !(in.settle_time > 0.0))
      r.fail(dynamics->get("settle_rest_ratio"), "dynamics.settle_rest_ratio",
             "needs dynamics.settle_s > 0: the longest the net may take to come to rest");
  }

  if ((in.presag > 0.0 || in.wall_below > 0.0) && !(in.settle_time > 0.0))
    r.fail(root.get("boundary"), in.presag > 0.0 ? "boundary.presag_m" : "boundary.wall_below_m",
           "needs dynamics.settle_s > 0: the net reaches this state while it settles under gravity");

  const toml::table* tool = r.table(root, "tool");
  if (!tool) r.fail(nullptr, "tool", "missing table");
  r.check_keys(*tool, "tool.", {"kind", "base_radius_m", "height_m", "gap_m", "speed_m_per_s", "travel_m",
                                "force_levels_N", "unload_force_N", "side_m", "corner_plane_m", "mass_kg",
                                "duration_s", "kn_N_per_m", "ks_N_per_m", "friction", "direction", "clamp_depth_m",
                                "stop_below_peak_fraction"});
  in.tool = r.text(*tool, "tool.", "kind", "platter");
  if (in.tool == "strip_tension") read_strip_tension(r, root, *tool, in);
  else if (in.tool != "platter" && in.tool != "boulder" && in.tool != "none")
    r.fail(tool->get("kind"), "tool.kind", "expected platter, boulder, none or strip_tension");
  for (const char* key : {"direction", "clamp_depth_m"})
    if (in.tool != "strip_tension" && tool->get(key)) r.fail(tool->get(key), std::string("tool.") + key, "only for kind = \"strip_tension\"");
  in.platter_base_radius = r.number(*tool, "tool.", "base_radius_m", in.platter_base_radius, true);
  in.platter_height = r.number(*tool, "tool.", "height_m", in.platter_height, true);
  in.start_gap = r.number(*tool, "tool.", "gap_m", in.start_gap);
  if (in.start_gap < 0.0)
    r.fail(tool->get("gap_m"), "tool.gap_m", "negative: the tool would start inside the mesh");
  in.speed = r.number(*tool, "tool.", "speed_m_per_s", in.speed, true);
  in.travel = r.number(*tool, "tool.", "travel_m", in.travel, true);
  if (const toml::node* levels = tool->get("force_levels_N")) {
    const toml::array* array = levels->as_array();
    if (!array) r.fail(levels, "tool.force_levels_N", "expected an array of forces");
    for (const toml::node& level : *array) {
      const auto value = level.value<double>();
      if (!value || !(*value > 0.0)) r.fail(&level, "tool.force_levels_N", "expected positive forces");
      in.force_levels.push_back(*value);
    }
  }
  in.unload_force = r.number(*tool, "tool.", "unload_force_N", in.unload_force, true);
  in.stop_below_peak_fraction =
      r.ranged(*tool, "tool.", "stop_below_peak_fraction", 0.0, 0.0, 0.99, "a fraction of the peak force in [0, 0.99] (0: the whole travel)");
  if (in.stop_below_peak_fraction > 0.0 && (in.tool != "platter" || !in.force_levels.empty()))
    r.fail(tool->get("stop_below_peak_fraction"), "tool.stop_below_peak_fraction",
           "only for a monotonic punch (kind = \"platter\" without force_levels_N)");
  if (!in.force_levels.empty() && in.unload_force >= *std::min_element(in.force_levels.begin(), in.force_levels.end()))
    r.fail(tool->get("unload_force_N") ? tool->get("unload_force_N") : tool->get("force_levels_N"), "tool.unload_force_N",
           "expected a force below the smallest of force_levels_N (the platter reloads below it)");
  in.boulder_side = r.number(*tool, "tool.", "side_m", in.boulder_side, true);
  in.boulder_corner_plane = r.number(*tool, "tool.", "corner_plane_m", 0.625 * in.boulder_side, true);
  if (!(in.boulder_corner_plane > 0.5 * in.boulder_side && in.boulder_corner_plane <= 1.5 * in.boulder_side))
    r.fail(tool->get("corner_plane_m"), "tool.corner_plane_m", "expected a distance in (side_m / 2, 3 side_m / 2]");
  in.boulder_mass = r.number(*tool, "tool.", "mass_kg", in.boulder_mass, true);
  in.duration = r.ranged(*tool, "tool.", "duration_s", 0.0, 0.0, kHuge, "a time >= 0 s");
  in.contact.normal_stiffness = r.number(*tool, "tool.", "kn_N_per_m", 1e9, true);
  in.contact.shear_stiffness = r.number(*tool, "tool.", "ks_N_per_m", 1e8, true);
  in.contact.friction = r.ranged(*tool, "tool.", "friction", 0.2, 0.0, kHuge, "a Coulomb coefficient >= 0");
  if (in.tool == "boulder" && !(in.duration > 0.0))
    r.fail(tool, "tool.duration_s", "missing: an impact runs for a given time");

  if (const toml::table* output = r.table(root, "output")) {
    r.check_keys(*output, "output.", {"interval_s", "frames"});
    in.output_interval = r.number(*output, "output.", "interval_s", in.output_interval, true);
    in.frames = static_cast<int>(r.integer(*output, "output.", "frames", in.frames, 0, 100000));
  }
  // The self-checks' bounds (run_checks.hpp), in percent; studies loosen them per run.
  if (const toml::table* checks = r.table(root, "checks")) {
    r.check_keys(*checks, "checks.", {"max_balance_error_percent", "max_kinetic_share_percent"});
    in.checks.max_balance_error = 0.01 * r.ranged(*checks, "checks.", "max_balance_error_percent",
                                                  100.0 * in.checks.max_balance_error, 0.0, kHuge, "a percentage >= 0");
    in.checks.max_kinetic_share = 0.01 * r.ranged(*checks, "checks.", "max_kinetic_share_percent",
                                                  100.0 * in.checks.max_kinetic_share, 0.0, kHuge, "a percentage >= 0");
  }
  return in;
}

void override_link_set(RunInput& input, const std::string& tag, const std::filesystem::path& params,
                       const std::string& option) {
  const std::map<std::string, LinkTag> tags = {{"sw", LinkTag::SingleWire}, {"dt", LinkTag::DoubleTwist}, {"selvedge", LinkTag::Selvedge}};
  if (!tags.count(tag)) throw InputError(option, "expected sw, dt or selvedge before '=', found '" + tag + "'");
  LinkSetInput& set = input.link_sets[tags.at(tag)];
  const std::vector<ParameterSet> sets = read_parameter_file(params);
  const ParameterSet chosen = select_wire_type(sets, sets.size() == 1 ? "" : (tag == "dt" ? "double_twist" : "single_wire"), params);
  if (!chosen.law.empty()) set.law = chosen.law;
  if (set.law.empty()) throw InputError(option, params.string() + " names no law and the input has none for " + tag);
  set.parameters = chosen.map();
  for (const auto& [name, value] : set.overrides) set.parameters[name] = value;
  for (const auto& [name, factor] : set.scales)
    if (!set.parameters.count(name))
      throw InputError(option, params.string() + " has no " + name + " for the input's " + tag + ".scale");
  apply_scales(set);
  set.files = {params};
  try {
    check_parameter_names(chosen, set.law, params);
    make_contact_law(set.law, set.parameters);
  } catch (const std::invalid_argument& e) {
    throw InputError(option, e.what());
  }
}

}  // namespace dtwire::dem
