#include <CLI/CLI.hpp>

#include <iostream>
#include <memory>

#include "../cli.hpp"
#include "../commands.hpp"
#ifdef DTWIRE_HAVE_FEM
#include "dtwire/fem/run.hpp"
#endif

namespace dtwire::app {

// `dtwire parameters [--describe]`: every entry of an FE experiment .prm with its default, the
// listing `dtwire gap --model` reads the solver's defaults from.
void add_parameters_command(CLI::App& root, CommandSet& commands) {
  const std::string description = "List every entry of an FE experiment .prm (`dtwire run`) with its default";
#ifndef DTWIRE_HAVE_FEM
  commands.add_unavailable(root, "parameters", description, "the FE solver (DTWIRE_WITH_FEM=OFF)");
#else
  auto describe = std::make_shared<bool>(false);
  CLI::App* command = root.add_subcommand("parameters", description);
  command->add_flag("--describe", *describe, "Add each entry's documentation and allowed values");
  commands.add(command, [describe] {
    std::cout << fem::parameter_listing(*describe);
    return 0;
  });
#endif
}

}  // namespace dtwire::app
