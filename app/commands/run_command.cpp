#include <CLI/CLI.hpp>

#include "../cli.hpp"
#include "../commands.hpp"

namespace dtwire::app {

void add_run_command(CLI::App& root, CommandSet& commands) {
  commands.add_unavailable(root, "run", "Run a virtual FE experiment from a .prm file", "the FE solver (issues #4, #5)");
}

}  // namespace dtwire::app
