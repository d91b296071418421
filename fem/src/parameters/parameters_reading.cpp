// The shared pieces of the .prm readers: where a bad value came from, and the small parsers.
#include <deal.II/base/parameter_handler.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "dtwire/core/error.hpp"
#include "parameters_reading.hpp"

namespace dtwire::fem::prm_reading {

void Source::require(bool ok, const std::string& section, const std::string& entry, const std::string& expected) const {
  if (!ok) fail(section, entry, "expected " + expected + ", found '" + prm.get(entry) + "'");
}

void Source::fail(const std::string& section, const std::string& entry, const std::string& message) const {
  const std::string path = section + "/" + entry;
  if (set_on_command_line.count(path)) throw InputError("--set", path + ": '" + entry + "': " + message);
  const auto line = lines.find(path);
  throw InputError(name, line == lines.end() ? 0 : line->second, 0, "subsection " + section + ": '" + entry + "': " + message);
}
std::array<double, 3> Source::vector3(const std::string& entry) const {
  std::istringstream in(prm.get(entry));
  std::array<double, 3> v{};
  for (auto& x : v)
    if (!(in >> x) || !std::isfinite(x)) throw InputError(name, "'" + entry + "': expected three numbers");
  std::string rest;
  if (in >> rest) throw InputError(name, "'" + entry + "': expected three numbers");
  return v;
}
std::array<double, 3> Source::unit(const std::string& entry) const {
  auto v = vector3(entry);
  const double n = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  if (!(n > 0.0)) throw InputError(name, "'" + entry + "': expected a non-zero direction");
  for (auto& x : v) x /= n;
  return v;
}

std::vector<std::pair<double, double>> Source::pairs(const std::string& section, const std::string& entry) const {
  std::vector<std::pair<double, double>> pairs;
  std::stringstream list(prm.get(entry));
  std::string item;
  while (std::getline(list, item, ',')) {
    if (item.find_first_not_of(" \t") == std::string::npos) continue;
    const auto colon = item.find(':');
    try {
      if (colon == std::string::npos) throw std::invalid_argument("no colon");
      std::size_t used = 0;
      const double x = std::stod(item.substr(0, colon), &used);
      const double y = std::stod(item.substr(colon + 1), &used);
      if (!std::isfinite(x) || !std::isfinite(y)) throw std::invalid_argument("not finite");
      pairs.emplace_back(x, y);
    } catch (const std::exception&) {
      fail(section, entry, "expected number:number pairs of finite numbers, found '" + item + "'");
    }
  }
  return pairs;
}

// A gmsh file starts with $MeshFormat ($NOD in format 1); an empty or garbage file would otherwise reach deal.II's
// reader and fail there without naming the file.
bool looks_like_gmsh(const std::filesystem::path& mesh) {
  std::ifstream in(mesh);
  std::string line;
  while (std::getline(in, line) && line.find_first_not_of(" \t\r") == std::string::npos) {
  }
  return line.rfind("$MeshFormat", 0) == 0 || line.rfind("$NOD", 0) == 0;  // gmsh 2-4, gmsh 1
}

EndCondition end_condition(const std::string& s) {
  if (s == "axial") return EndCondition::axial;
  if (s == "symmetry") return EndCondition::symmetry;
  if (s == "guided") return EndCondition::guided;
  if (s == "free") return EndCondition::free;
  return EndCondition::clamped;
}

}  // namespace dtwire::fem::prm_reading
