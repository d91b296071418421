#pragma once
// `dtwire dem propagate FILE --params-fit TAG=FIT.json`: a fit's uncertainty carried to the
// mesh-scale strip or punch (bands, convergence, linearised band, sensitivities).
namespace CLI {
class App;
}

namespace dtwire::app {
class CommandSet;
void add_dem_propagate_command(CLI::App& dem, CommandSet& commands);
}  // namespace dtwire::app
