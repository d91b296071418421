#include "dem_plot_command.hpp"

#include <CLI/CLI.hpp>

#include <iostream>
#include <memory>

#include "../cli.hpp"
#include "../plotting.hpp"

namespace dtwire::app {

void add_dem_plot_command(CLI::App& dem, CommandSet& commands) {
  struct Options {
    std::string out;
    std::vector<std::string> curves;
  };
  auto o = std::make_shared<Options>();
  CLI::App* plot = dem.add_subcommand(
      "plot-punch", "Punch curves of several dem runs on one figure, with the thesis's punch figures as markers");
  plot->add_option("out", o->out, "Figure (PNG)")->required();
  plot->add_option("curves", o->curves, "curve.csv files of dem run punches (legend: their labels, dem run --label)")
      ->required()
      ->check(CLI::ExistingFile);
  commands.add(plot, [o] {
    std::vector<std::string> arguments{o->out};
    arguments.insert(arguments.end(), o->curves.begin(), o->curves.end());
    run_plot_script("plot_punch.py", arguments);
    std::cout << "plot: " << o->out << "\n";
    return 0;
  });
}

}  // namespace dtwire::app
