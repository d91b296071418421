#pragma once
// `dtwire dem run FILE`: a mesh-scale validation run (punch, cyclic punch, impact) of the wire
// net engine (dem/), and its YADE script.
namespace CLI {
class App;
}

namespace dtwire::app {
class CommandSet;
void add_dem_run_command(CLI::App& dem, CommandSet& commands);
}  // namespace dtwire::app
