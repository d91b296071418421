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
  std::size_t set = 0;
  for (ParameterDefinition& p : parameters) {
    const auto found = values.find(p.name);
    if (found == values.end()) continue;
    const double v = found->second;
    if (!std::isfinite(v) || v < p.lower || v > p.upper) {
      std::ostringstream message;
      message << "parameter '" << p.name << "': initial value " << v << " is outside the fit's bounds [" << p.lower
              << ", " << p.upper << "]";
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
