#include <CLI/CLI.hpp>

#include "../cli.hpp"
#include "../commands.hpp"

namespace dtwire::app {

void add_export_command(CLI::App& root, CommandSet& commands) {
  commands.add_unavailable(root, "export", "Export calibrated parameter sets for DEM codes", "the dem_export module (issue #6)");
}

}  // namespace dtwire::app
