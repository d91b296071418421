#pragma once
// One registration function per subcommand (app/commands/*.cpp).
namespace CLI {
class App;
}

namespace dtwire::app {
class CommandSet;

void add_mesh_command(CLI::App& root, CommandSet& commands);
void add_run_command(CLI::App& root, CommandSet& commands);
void add_parameters_command(CLI::App& root, CommandSet& commands);
void add_fit_command(CLI::App& root, CommandSet& commands);
void add_export_command(CLI::App& root, CommandSet& commands);
void add_dem_command(CLI::App& root, CommandSet& commands);
void add_gap_command(CLI::App& root, CommandSet& commands);
void add_gap_features_command(CLI::App& gap_command, CommandSet& commands);  // `dtwire gap features`
void add_gap_mesh_selfcheck_command(CLI::App& gap_command, CommandSet& commands);  // `dtwire gap mesh-selfcheck`
void add_campaign_command(CLI::App& root, CommandSet& commands);

}  // namespace dtwire::app
