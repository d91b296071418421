#include "dtwire/calibrate/initial_values.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include "dtwire/core/error.hpp"

namespace dtwire::calibrate {

std::size_t apply_initial_values(std::vector<ParameterDefinition>& parameters, const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw InputError(file.string(), "cannot open the file with the initial values");
  nlohmann::json json;
  try {
    json = nlohmann::json::parse(in);
  } catch (const nlohmann::json::parse_error& e) {
    throw InputError(file.string(), std::string("not valid JSON: ") + e.what());
  }
  if (!json.is_object() || !json.contains("parameters") || !json.at("parameters").is_array())
    throw InputError(file.string(), "expected a 'parameters' list of {name, value} (a parameters.json of dtwire fit)");
  std::map<std::string, double> values;
  for (const auto& entry : json.at("parameters")) {
    if (!entry.is_object() || !entry.contains("name") || !entry.at("name").is_string() || !entry.contains("value") ||
        !entry.at("value").is_number())
      throw InputError(file.string(), "field 'parameters': every entry needs a string 'name' and a number 'value'");
    values[entry.at("name").get<std::string>()] = entry.at("value").get<double>();
  }
  // The file holds the parameters' own values; an offset parameter starts at its value minus its
  // base's (the base's value from the file if it names it, else the base's initial value).
  const std::vector<int> base = offset_bases(parameters);
  std::vector<double> initial;
  for (const ParameterDefinition& p : parameters) initial.push_back(p.initial);
  std::vector<double> resolved = resolve_offsets(parameters, initial);
  std::vector<bool> named(parameters.size(), false);
  for (std::size_t i = 0; i < parameters.size(); ++i) {
    const auto found = values.find(parameters[i].name);
    if (found == values.end()) continue;
    if (!std::isfinite(found->second))
      throw InputError(file.string(), "parameter '" + parameters[i].name + "': initial value is not finite");
    resolved[i] = found->second;
    named[i] = true;
  }
  std::size_t set = 0;
  for (std::size_t i = 0; i < parameters.size(); ++i) {
    if (!named[i]) continue;
    ParameterDefinition& p = parameters[i];
    const double v = base[i] < 0 ? resolved[i] : resolved[i] - resolved[static_cast<std::size_t>(base[i])];
    if (v < p.lower || v > p.upper) {
      std::ostringstream message;
      message << "parameter '" << p.name << "': initial value " << resolved[i];
      if (base[i] >= 0) message << " gives its offset " << coordinate_name(p) << " = " << v << ",";
      message << " outside the fit's bounds [" << p.lower << ", " << p.upper << "]";
      throw InputError(file.string(), message.str());
    }
    p.initial = v;
    ++set;
  }
  // A file of another fit (other names, or prefixes missing) would silently change nothing.
  if (set == 0 && !parameters.empty())
    throw InputError(file.string(), "names none of the fit's parameters (e.g. '" + parameters.front().name + "')");
  return set;
}

}  // namespace dtwire::calibrate
