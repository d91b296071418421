#include <CLI/CLI.hpp>

#include "../cli.hpp"
#include "../commands.hpp"

namespace dtwire::app {

void add_gap_command(CLI::App& root, CommandSet& commands) {
  commands.add_unavailable(root, "gap", "Diagnose the gap between simulation and laboratory curves", "the gap module (issue #8)");
}

}  // namespace dtwire::app
