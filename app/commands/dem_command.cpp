#include <CLI/CLI.hpp>

#include "../cli.hpp"
#include "../commands.hpp"

namespace dtwire::app {

void add_dem_command(CLI::App& root, CommandSet& commands) {
  commands.add_unavailable(root, "dem", "DEM contact laws", " two-node driver:the dem_export module (issue #6)");
}

}  // namespace dtwire::app
