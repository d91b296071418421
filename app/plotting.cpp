#include "plotting.hpp"

#include <cstdlib>
#include <filesystem>

#include "dtwire/core/error.hpp"
#include "data_path.hpp"

namespace dtwire::app {
namespace {
std::string quoted(const std::string& text) {
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}
}  // namespace

std::string find_python_with_matplotlib() {
  if (const char* chosen = std::getenv("DTWIRE_PYTHON")) return chosen;
  for (const char* candidate : {"/usr/bin/python3", "python3"}) {
    const std::string probe = std::string(candidate) + " -c 'import matplotlib' >/dev/null 2>&1";
    if (std::system(probe.c_str()) == 0) return candidate;
  }
  return "";
}

void require_plotting(const std::string& script, const std::string& flag) {
  if (find_python_with_matplotlib().empty())
    throw InputError(flag, "plotting needs python3 with matplotlib (Debian: python3-matplotlib); none found. "
                           "Install it, or run without the plot");
  const std::filesystem::path path = data_path("scripts/" + script);
  if (!std::filesystem::is_regular_file(path))
    throw InputError(flag, "the plot script " + path.string() +
                               " is missing (dtwire reads its scripts from share/dtwire beside its binary, or from "
                               "$DTWIRE_DATA_DIR: set it to the source tree), or run without the plot");
}

void run_plot_script(const std::string& script, const std::vector<std::string>& arguments) {
  const std::string python = find_python_with_matplotlib();
  if (python.empty())
    throw ComputationError("plotting needs python3 with matplotlib (Debian: python3-matplotlib); "
                           "none found");
  std::string command = python + " " + quoted(data_path("scripts/" + script).string());
  for (const auto& argument : arguments) command += " " + quoted(argument);
  if (std::system(command.c_str()) != 0) throw ComputationError("plotting failed: " + command);
}

}  // namespace dtwire::app
