#pragma once
// `dtwire dem plot-punch OUT.png CURVE...`: the punch curves of several `dem run` folders on one
// figure with the thesis's punch figures as markers (scripts/plot_punch.py), so that a campaign
// step can draw every set's punch once all of them have run.
namespace CLI {
class App;
}

namespace dtwire::app {
class CommandSet;
void add_dem_plot_command(CLI::App& dem, CommandSet& commands);
}  // namespace dtwire::app
