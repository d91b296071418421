#include "dtwire/meshes/parameter_file.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <sstream>
#include <vector>

#include "dtwire/core/closest_name.hpp"
#include "dtwire/core/error.hpp"

namespace dtwire::meshes {
namespace {

std::string canonical_name(std::string name) {
  for (char& c : name) {
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (c == ' ' || c == '_' || c == '\t') c = '-';
  }
  return name;
}

std::size_t skip_space(const std::string& line, std::size_t at) {
  while (at < line.size() && std::isspace(static_cast<unsigned char>(line[at]))) ++at;
  return at;
}

std::size_t trim_end(const std::string& line, std::size_t end) {
  while (end > 0 && std::isspace(static_cast<unsigned char>(line[end - 1]))) --end;
  return end;
}

}  // namespace

void parse_parameter_text(const std::string& text, const std::string& source,
                          MeshParameters& parameters, FieldLocations& locations) {
  std::istringstream lines(text);
  std::string line;
  int number = 0;
  FieldLocations seen;
  while (std::getline(lines, line)) {
    ++number;
    line = line.substr(0, line.find('#'));
    const std::size_t start = skip_space(line, 0);
    if (start == line.size()) continue;
    auto fail = [&](std::size_t column, const std::string& message) {
      throw InputError(source, number, static_cast<int>(column) + 1, message);
    };
    if (line.compare(start, 4, "set ") != 0 && line.compare(start, 4, "set\t") != 0)
      fail(start, "expected 'set <name> = <value>', found '" + line.substr(start, trim_end(line, line.size()) - start) + "'");
    const std::size_t name_start = skip_space(line, start + 4);
    const std::size_t equals = line.find('=', name_start);
    if (equals == std::string::npos) fail(name_start, "expected '=' after the parameter name");
    const std::string written = line.substr(name_start, trim_end(line, equals) - name_start);
    const std::string name = canonical_name(written);
    const ParameterField* field = find_parameter_field(name);
    if (!field) {
      std::string known;
      std::vector<std::string> names;
      for (const auto& f : parameter_fields())
        if (used_by(f, parameters.kind)) {
          known += (known.empty() ? "" : ", ") + f.name;
          names.push_back(f.name);
        }
      fail(name_start, "unknown parameter '" + written + "'" + did_you_mean(name, names) + ", expected one of: " + known);
    }
    if (!used_by(*field, parameters.kind))
      fail(name_start, "parameter '" + written + "' is not used by mesh " + kind_name(parameters.kind));
    if (seen.count(name)) fail(name_start, "parameter '" + written + "' is set twice (first on line " +
                                               std::to_string(seen[name].line) + ")");
    const std::size_t value_start = skip_space(line, equals + 1);
    const std::string value_text = line.substr(value_start, trim_end(line, line.size()) - std::min(value_start, line.size()));
    double value = 0;
    std::size_t used = 0;
    try {
      value = std::stod(value_text, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (value_text.empty() || used != value_text.size() || !std::isfinite(value))
      fail(value_start, "expected a number (" + field->unit + ") for '" + field->name + "', found '" + value_text + "'");
    if (field->integer && value != std::floor(value))
      fail(value_start, "expected a whole number for '" + field->name + "', found '" + value_text + "'");
    set_user_value(parameters, *field, value);
    const FieldLocation where{source, number, static_cast<int>(value_start) + 1};
    seen[name] = where;
    locations[name] = where;
  }
  // An empty file would mesh on the defaults without a word, like a file of typos.
  if (seen.empty()) throw InputError(source, "no 'set <name> = <value>' line: an empty parameter file");
}

void read_parameter_file(const std::filesystem::path& path, MeshParameters& parameters,
                         FieldLocations& locations) {
  std::ifstream in(path);
  if (!in) throw InputError(path.string(), "cannot open the parameter file");
  std::ostringstream text;
  text << in.rdbuf();
  parse_parameter_text(text.str(), path.string(), parameters, locations);
}

}  // namespace dtwire::meshes
