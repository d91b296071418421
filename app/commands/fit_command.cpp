#include <CLI/CLI.hpp>

#include "../cli.hpp"
#include "../commands.hpp"

namespace dtwire::app {

void add_fit_command(CLI::App& root, CommandSet& commands) {
  commands.add_unavailable(root, "fit", "Calibrate parameters with Ceres from a .prm fit definition", "the calibrate module (issue #7)");
}

}  // namespace dtwire::app
