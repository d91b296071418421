#include "parameters.hpp"

#include <deal.II/base/parameter_handler.h>

#include <algorithm>
#include <regex>
#include <set>
#include <sstream>

#include "dtwire/core/closest_name.hpp"
#include "dtwire/core/error.hpp"
#include "parameters/parameters_reading.hpp"
#include "prm_check.hpp"

namespace dtwire::fem {
namespace {

using namespace prm_reading;
using dealii::ParameterHandler;

void declare(ParameterHandler& prm) {
  declare_geometry(prm);
  declare_material(prm);
  declare_formulation(prm);
  declare_forming(prm);
  declare_boundary_conditions(prm);
  declare_load_stepping(prm);
  declare_newton(prm);
  declare_output(prm);
  contact::declare_contact_parameters(prm);  // contact (issue 5)
  declare_check_parameters(prm);
}

// `Section/Sub/Entry=value` from the command line, set on top of the file; a relative
// file (Mesh file, Axis file, State file) given this way is taken from the working directory,
// where the user typed it.
void apply_setting(ParameterHandler& prm, const std::string& setting) {
  const auto equals = setting.find('=');
  if (equals == std::string::npos || equals == 0)
    throw InputError("--set", "'" + setting + "': expected Section/Entry=value");
  std::string path = setting.substr(0, equals), value = setting.substr(equals + 1);
  std::vector<std::string> sections;
  for (auto slash = path.find('/'); slash != std::string::npos; slash = path.find('/')) {
    sections.push_back(path.substr(0, slash));
    path.erase(0, slash + 1);
  }
  const bool file_entry =
      path == "Mesh file" || path == "Axis file" || path == "State file" || path == "Twisted pair state";
  if (file_entry && !value.empty()) value = std::filesystem::absolute(value).string();
  // A misspelled name gets the closest declared one, as in the file (deal.II would only say
  // that the entry is not declared).
  std::string full_path;
  for (const auto& s : sections) full_path += s + "/";
  full_path += path;
  const PrmDocument declared_document = declared_parameters(prm);
  std::vector<std::string> declared;
  for (const auto& entry : declared_document.entries()) declared.push_back(entry.path);
  if (std::find(declared.begin(), declared.end(), full_path) == declared.end())
    throw InputError("--set", "'" + setting + "': unknown entry '" + full_path + "'" + did_you_mean(full_path, declared));
  for (const auto& s : sections) prm.enter_subsection(s);
  try {
    prm.set(path, value);
  } catch (const std::exception& e) {
    for (std::size_t i = 0; i < sections.size(); ++i) prm.leave_subsection();
    throw InputError("--set", "'" + setting + "': " + deal_ii_message(e.what()));
  }
  for (std::size_t i = 0; i < sections.size(); ++i) prm.leave_subsection();
}

}  // namespace

// deal.II's exception text is long; keep its "Additional information" on one line.
std::string deal_ii_message(const std::string& what) {
  std::string text = what;
  const auto pos = text.find("Additional information:");
  if (pos != std::string::npos) text = text.substr(pos + 23);
  const auto stack = text.find("Stacktrace:");
  if (stack != std::string::npos) text = text.substr(0, stack);
  text = std::regex_replace(text, std::regex("[\\s-]+\\n|\\s+"), " ");
  return std::regex_replace(text, std::regex("^ +| +$"), "");
}

namespace {
Parameters read_and_convert(const std::filesystem::path& file, const std::vector<std::string>& settings) {
  const std::string name = file.string();
  if (!std::filesystem::is_regular_file(file)) throw InputError(name, "cannot open the parameter file");
  ParameterHandler prm;
  declare(prm);
  const EntryLines lines = check_prm_names(prm, name);
  try {
    prm.parse_input(name, "", false);  // undeclared names are errors, never skipped
  } catch (const std::exception& e) {
    const std::string message = deal_ii_message(e.what());
    std::smatch m;
    if (std::regex_search(message, m, std::regex("[Ll]ine <(\\d+)>")))
      throw InputError(name, std::stoi(m[1]), 0, message);
    throw InputError(name, message);
  }
  std::set<std::string> set_on_command_line;
  for (const auto& setting : settings) {
    apply_setting(prm, setting);
    set_on_command_line.insert(setting.substr(0, setting.find('=')));
  }

  Source source{prm, file, name, lines, set_on_command_line};
  Parameters p;
  read_geometry(source, p);
  read_material(source, p);
  read_formulation(source, p);
  read_forming(source, p);
  read_boundary_conditions(source, p);
  read_load_stepping(source, p);
  read_newton(source, p);
  read_output(source, p);
  std::vector<double> knots;  // contact (issue 5)
  for (const auto& k : p.load.path) knots.push_back(k.first);
  p.contact = contact::parse_contact_parameters(prm, name, knots);
  p.wire_contact = contact::parse_wire_contact_parameters(prm, name);
  p.checks = parse_check_parameters(prm);
  if (!p.geometry.quarter && p.load.bottom != EndCondition::clamped && p.load.top != EndCondition::clamped &&
      !p.contact.enabled())
    throw InputError(name, "a full cross-section needs at least one clamped end or contact tools (rigid-body modes)");
  return p;
}
}  // namespace

std::string parameter_listing(bool documented) {
  ParameterHandler prm;
  declare(prm);
  std::ostringstream listing;
  prm.print_parameters(listing, documented ? ParameterHandler::PRM : ParameterHandler::ShortPRM);
  return listing.str();
}

Parameters read_parameters(const std::filesystem::path& file, const std::vector<std::string>& settings) {
  try {
    return read_and_convert(file, settings);
  } catch (const dealii::ExceptionBase& e) {  // a value deal.II could not convert (e.g. an unfilled {placeholder})
    throw InputError(file.string(), deal_ii_message(e.what()));
  }
}

namespace {
double piecewise_linear(const std::vector<std::pair<double, double>>& path, double t) {
  if (t <= path.front().first) return path.front().second;
  for (std::size_t i = 1; i < path.size(); ++i)
    if (t <= path[i].first) {
      const double s = (t - path[i - 1].first) / (path[i].first - path[i - 1].first);
      return path[i - 1].second + s * (path[i].second - path[i - 1].second);
    }
  return path.back().second;
}
}  // namespace

double path_displacement(const LoadParameters& load, double t) { return piecewise_linear(load.path, t); }

double path_rotation(const LoadParameters& load, double t) {
  return load.rotation_path.empty() ? 0.0 : piecewise_linear(load.rotation_path, t);
}

double path_force(const LoadParameters& load, double t) {
  return load.force_control ? piecewise_linear(load.force_path, t) : 0.0;
}

}  // namespace dtwire::fem