// Parameter files (thesis, flat and calibrate JSON formats) and backbone CSVs.
#include "dtwire/dem/export_params.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "dtwire/core/closest_name.hpp"
#include "dtwire/core/csv.hpp"
#include "dtwire/core/error.hpp"
#include "dtwire/core/units.hpp"
#include "dtwire/dem/law_schema.hpp"

namespace dtwire::dem {
namespace {

using nlohmann::json;

// Thesis parameters whose names carry no SI suffix (Previtali's PFC7 plugin conventions).
const std::pair<const char*, const char*> kKnownUnits[] = {
    {"k_F", "1/m"}, {"k_M", "1/deg"}, {"EI_Nm2_per_deg_convention", "N m^2/deg"}};

bool ends_with(const std::string& text, const std::string& suffix) {
  return text.size() >= suffix.size() && text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

double number_field(const json& value, const std::filesystem::path& file, const std::string& field) {
  if (!value.is_number()) throw InputError(file.string(), "field '" + field + "': expected a number");
  const double number = value.get<double>();
  if (!std::isfinite(number)) throw InputError(file.string(), "field '" + field + "': not a finite number");
  return number;
}

std::string string_field(const json& object, const char* key, const std::filesystem::path& file,
                         const std::string& fallback) {
  if (!object.contains(key)) return fallback;
  if (!object[key].is_string()) throw InputError(file.string(), std::string("field '") + key + "': expected a string");
  return object[key].get<std::string>();
}

void read_backbone_object(const json& backbone, const std::filesystem::path& file, ParameterSet& set) {
  if (!backbone.is_object() || !backbone.contains("strain_1") || !backbone.contains("stress_Pa") ||
      !backbone["strain_1"].is_array() || !backbone["stress_Pa"].is_array())
    throw InputError(file.string(), "field 'backbone': expected {\"strain_1\": [...], \"stress_Pa\": [...]}");
  const json& strain = backbone["strain_1"];
  const json& stress = backbone["stress_Pa"];
  if (strain.size() != stress.size())
    throw InputError(file.string(), "field 'backbone': strain_1 and stress_Pa differ in length");
  Curve curve;
  std::vector<double> strains, stresses;
  for (std::size_t i = 0; i < strain.size(); ++i) {
    strains.push_back(number_field(strain[i], file, "backbone.strain_1[" + std::to_string(i) + "]"));
    stresses.push_back(number_field(stress[i], file, "backbone.stress_Pa[" + std::to_string(i) + "]"));
  }
  curve.add_channel("strain", *find_unit("1"), strains);
  curve.add_channel("stress", *find_unit("Pa"), stresses);
  add_backbone(set, curve);
}

ParameterSet read_numeric_object(const json& object, const std::filesystem::path& file,
                                 const std::string& prefix, std::string wire_type, std::string law) {
  ParameterSet set{std::move(wire_type), std::move(law), {}};
  for (const auto& [name, value] : object.items())
    set.set(name, number_field(value, file, prefix + name));
  return set;
}

ParameterSet read_calibrate_array(const json& array, const std::filesystem::path& file,
                                  std::string wire_type, std::string law) {
  ParameterSet set{std::move(wire_type), std::move(law), {}};
  for (std::size_t i = 0; i < array.size(); ++i) {
    const json& item = array[i];
    const std::string field = "parameters[" + std::to_string(i) + "]";
    if (!item.is_object()) throw InputError(file.string(), "field '" + field + "': expected an object");
    if (!item.contains("name") || !item["name"].is_string() || item["name"].get<std::string>().empty())
      throw InputError(file.string(), "field '" + field + ".name': expected a non-empty string");
    if (!item.contains("value")) throw InputError(file.string(), "field '" + field + ".value': missing");
    ParameterEntry entry;
    entry.name = item["name"].get<std::string>();
    entry.value = number_field(item["value"], file, field + ".value");
    entry.unit = string_field(item, "unit", file, "1");
    if (entry.unit.empty()) entry.unit = "1";
    // Column-style unit symbols become the name suffix; other unit texts ("1/m") stay beside it.
    if (entry.unit != "1" && find_unit(entry.unit) && !ends_with(entry.name, "_" + entry.unit))
      entry.name += "_" + entry.unit;
    if (item.contains("sigma") && !item["sigma"].is_null())
      entry.sigma = number_field(item["sigma"], file, field + ".sigma");
    if (set.has(entry.name)) throw InputError(file.string(), "field '" + field + ".name': duplicate '" + entry.name + "'");
    set.entries.push_back(entry);
  }
  return set;
}

// A joint fit of a DT specimen (calibrate's dem_specimen) names its parameters sw.<name> and
// dt.<name>: its file holds the single-wire and the double-twist set, which are split here.
std::vector<ParameterSet> split_specimen_set(ParameterSet joint) {
  const auto prefixed = [](const ParameterEntry& e) { return e.name.rfind("sw.", 0) == 0 || e.name.rfind("dt.", 0) == 0; };
  if (joint.entries.empty() || !std::all_of(joint.entries.begin(), joint.entries.end(), prefixed)) return {std::move(joint)};
  ParameterSet sw{"single_wire", joint.law, {}}, dt{"double_twist", joint.law, {}};
  for (ParameterEntry& e : joint.entries) {
    ParameterSet& target = e.name.rfind("sw.", 0) == 0 ? sw : dt;
    e.name = e.name.substr(3);
    target.entries.push_back(std::move(e));
  }
  std::vector<ParameterSet> sets;
  for (ParameterSet* set : {&sw, &dt})
    if (!set->entries.empty()) sets.push_back(std::move(*set));
  return sets;
}

}  // namespace

ParameterMap ParameterSet::map() const {
  ParameterMap result;
  for (const ParameterEntry& e : entries) result[e.name] = e.value;
  return result;
}

bool ParameterSet::has(const std::string& name) const {
  return std::any_of(entries.begin(), entries.end(), [&](const ParameterEntry& e) { return e.name == name; });
}

void ParameterSet::set(const std::string& name, double value, const std::string& unit) {
  const std::string resolved = unit.empty() ? parameter_unit(name) : unit;
  for (ParameterEntry& e : entries) {
    if (e.name == name) {
      e = ParameterEntry{name, value, resolved, std::nullopt};
      return;
    }
  }
  entries.push_back(ParameterEntry{name, value, resolved, std::nullopt});
}

std::string parameter_unit(const std::string& name) {
  for (const auto& [known, unit] : kKnownUnits)
    if (name == known) return unit;
  const auto underscore = name.rfind('_');
  if (underscore == std::string::npos) return "1";
  const std::string suffix = name.substr(underscore + 1);
  if (const auto unit = find_unit(suffix)) return unit->symbol;
  return "1";
}

std::vector<ParameterSet> read_parameter_file(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw InputError(file.string(), "cannot open the parameter file");
  std::stringstream text;
  text << in.rdbuf();
  json root;
  try {
    root = json::parse(text.str());
  } catch (const json::exception& e) {  // syntax, or a number out of range (1e999)
    throw InputError(file.string(), std::string("not valid JSON: ") + e.what());
  }
  if (!root.is_object()) throw InputError(file.string(), "expected a JSON object at the top level");
  const std::string law = string_field(root, "law", file, "");
  const std::string wire_type = string_field(root, "wire_type", file, "default");

  std::vector<ParameterSet> sets;
  if (root.contains("parameters")) {
    const json& parameters = root["parameters"];
    if (parameters.is_object())
      sets.push_back(read_numeric_object(parameters, file, "parameters.", wire_type, law));
    else if (parameters.is_array())
      for (ParameterSet& set : split_specimen_set(read_calibrate_array(parameters, file, wire_type, law)))
        sets.push_back(std::move(set));
    else
      throw InputError(file.string(), "field 'parameters': expected an object {name: value} or an array of "
                                      "{name, value, unit, sigma}");
    if (root.contains("backbone")) read_backbone_object(root["backbone"], file, sets.back());
  } else {
    // Text fields are the file's notes (source, units, law); anything else that is not a wire
    // type's object would be dropped without a word.
    for (const auto& [name, value] : root.items()) {
      if (value.is_object())
        sets.push_back(read_numeric_object(value, file, name + ".", name, law));
      else if (!value.is_string())
        throw InputError(file.string(), "field '" + name + "': expected an object {name: value} of a wire type's "
                                        "parameters (e.g. 'single_wire'), or a text note, found " + value.type_name());
    }
  }
  if (sets.empty())
    throw InputError(file.string(), "no parameters: expected a 'parameters' field or wire-type objects "
                                    "(e.g. 'single_wire')");
  for (const ParameterSet& set : sets)
    if (set.entries.empty()) throw InputError(file.string(), "field '" + set.wire_type + "': no parameters");
  return sets;
}

ParameterSet select_wire_type(const std::vector<ParameterSet>& sets, const std::string& wire_type,
                              const std::filesystem::path& file) {
  std::string known;
  for (const ParameterSet& s : sets) {
    if (s.wire_type == wire_type || (wire_type.empty() && sets.size() == 1)) return s;
    known += (known.empty() ? "" : ", ") + s.wire_type;
  }
  throw InputError(file.string(), (wire_type.empty() ? std::string("the file holds several wire types")
                                                     : "no wire type '" + wire_type + "'") +
                                      "; choose one of: " + known + " (--wire-type)");
}

void check_parameter_names(const ParameterSet& set, const std::string& law, const std::filesystem::path& file) {
  const std::vector<std::string> unknown = unknown_law_parameters(law, set.map());
  if (unknown.empty()) return;
  const std::string& name = unknown.front();
  // The line of the quoted name, so the user lands on the typo.
  int line = 0;
  std::ifstream in(file);
  std::string text;
  for (int number = 1; std::getline(in, text); ++number)
    if (text.find('"' + name + '"') != std::string::npos) {
      line = number;
      break;
    }
  const std::string message = "wire type '" + set.wire_type + "': unknown parameter '" + name + "' for law " + law +
                              did_you_mean(name, law_parameter_names(law));
  if (line > 0) throw InputError(file.string(), line, 0, message);
  throw InputError(file.string(), message);
}

Curve read_backbone_csv(const std::filesystem::path& file) {
  Curve curve = read_csv(file);
  const Channel* strain = curve.find("strain");
  const Channel* stress = curve.find("stress");
  if (!strain || strain->unit.dimension != Dimension::Dimensionless)
    throw InputError(file.string(), 1, 1, "backbone CSV needs a dimensionless strain column (strain_1)");
  if (!stress || stress->unit.dimension != Dimension::Stress)
    throw InputError(file.string(), 1, 1, "backbone CSV needs a stress column (e.g. stress_Pa, stress_MPa)");
  return curve;
}

void add_backbone(ParameterSet& set, const Curve& backbone) {
  set.entries.erase(std::remove_if(set.entries.begin(), set.entries.end(),
                                   [](const ParameterEntry& e) { return e.name.rfind("backbone_", 0) == 0; }),
                    set.entries.end());
  const std::vector<double> strain = backbone.si("strain");
  const std::vector<double> stress = backbone.si("stress");
  for (std::size_t i = 0; i < strain.size(); ++i) {
    set.set("backbone_" + std::to_string(i) + "_strain_1", strain[i], "1");
    set.set("backbone_" + std::to_string(i) + "_stress_Pa", stress[i], "Pa");
  }
}

}  // namespace dtwire::dem
