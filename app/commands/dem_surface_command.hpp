#pragma once
// `dtwire dem surface`: the N-M yield surfaces of a macro-element parameter set, as CSV.
namespace CLI {
class App;
}

namespace dtwire::app {
class CommandSet;
void add_dem_surface_command(CLI::App& dem, CommandSet& commands);
}  // namespace dtwire::app
