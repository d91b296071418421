#include <CLI/CLI.hpp>

#include <iostream>
#include <memory>

#include "../cli.hpp"
#include "../plotting.hpp"
#include "../commands.hpp"
#ifdef DTWIRE_HAVE_FEM
#include "dtwire/core/resources.hpp"
#include "dtwire/fem/run.hpp"
#include "option_checks.hpp"
#endif

namespace dtwire::app {

// `dtwire run FILE.prm [--out DIR]`: a virtual FE experiment. Works under mpirun; MPI is
// initialised inside the command (deal.II MPI_InitFinalize).
void add_run_command(CLI::App& root, CommandSet& commands) {
#ifndef DTWIRE_HAVE_FEM
  commands.add_unavailable(root, "run", "Run a virtual FE experiment from a .prm file", "the FE solver (DTWIRE_WITH_FEM=OFF)");
#else
  struct Options {
    std::string file;
    std::vector<std::string> settings;
    std::string out;
    bool quiet = false;
    int restart_step = -1;
    std::string plot;
    std::string plot_x = "displacement";
    std::string plot_y = "force";
    std::string max_memory;
  };
  auto options = std::make_shared<Options>();
  CLI::App* command = root.add_subcommand("run", "Run a virtual FE experiment from a .prm file (MPI-capable)");
  command->add_option("file", options->file, "Experiment parameter file (.prm)")->required();
  command->add_option("--set", options->settings,
                      "Override an entry of the file: 'Section/Entry=value' (repeatable; a relative "
                      "'Geometry/Mesh file' is taken from the working directory)");
  command->add_option("-o,--out", options->out, "Output directory (default: fem-out/<file stem>)");
  command->add_flag("-q,--quiet", options->quiet, "Write progress only to run.log");
  command->add_option("--restart", options->restart_step,
                      "Resume from the checkpoint of this step in the output directory (Checkpoint interval)")
      ->check(CLI::Range(0, 1000000000));
  command->add_option("--max-memory", options->max_memory,
                      "Refuse a run whose memory estimate exceeds SIZE (4G, 512M; default: the available memory)");
  command->add_option("--plot", options->plot,
                      "Also draw a curve of the run to this PNG (python3-matplotlib)");
  command->add_option("--plot-x", options->plot_x, "Quantity on the plot's x axis (a curve.csv column without its unit)")
      ->capture_default_str();
  command->add_option("--plot-y", options->plot_y, "Quantity on the plot's y axis")->capture_default_str();
  commands.add(command, [options] {
    if (!options->plot.empty()) require_plotting("plot_curves.py", "--plot");
    check_output_folders({{"-o", options->out}});
    check_plot_file(options->plot, "--plot");
    fem::RunOptions run;
    run.parameter_file = options->file;
    run.output_directory = options->out.empty()
                               ? std::filesystem::path("fem-out") / std::filesystem::path(options->file).stem()
                               : std::filesystem::path(options->out);
    run.settings = options->settings;
    run.command_line = "dtwire run " + options->file;
    for (const auto& setting : options->settings) run.command_line += " --set '" + setting + "'";
    run.command_line += " --out " + run.output_directory.string();
    run.echo = !options->quiet;
    run.restart_step = options->restart_step;
    if (!options->max_memory.empty()) run.max_memory = parse_byte_size(options->max_memory, "--max-memory");
    const fem::RunSummary s = fem::run_experiment_with_mpi(run);
    if (s.root)
      std::cout << "run: " << s.steps << " steps, " << s.dofs << " dofs on " << s.ranks << " rank(s), peak force "
                << s.peak_force_N << " N at " << s.displacement_at_peak_mm << " mm, " << s.wall_seconds
                << " s; curve: " << s.curve_csv.string() << "\n";
    if (s.root && !options->plot.empty())
      run_plot_script("plot_curves.py", {options->plot, options->plot_x, options->plot_y,
                                         std::filesystem::path(options->file).stem().string(),
                                         s.curve_csv.string()});
    return 0;
  });
#endif
}

}  // namespace dtwire::app
