#pragma once
// Figures are drawn by small python3-matplotlib scripts in scripts/; this finds an interpreter
// that has matplotlib and runs one of them.
#include <string>
#include <vector>

namespace dtwire::app {

// $DTWIRE_PYTHON, else Debian's /usr/bin/python3, else the first python3 on PATH, whichever
// imports matplotlib first; empty if none does.
std::string find_python_with_matplotlib();

// Refuses, before any work, a plot that cannot be drawn: no interpreter with matplotlib, or no
// scripts/<script> in the data folder (a binary copied out of its build or install tree). Throws
// InputError naming `flag` (the option that asks for the plot) and how to go on.
void require_plotting(const std::string& script, const std::string& flag);

// Runs scripts/<script> with the arguments. Throws ComputationError if no interpreter has
// matplotlib or the script fails.
void run_plot_script(const std::string& script, const std::vector<std::string>& arguments);

}  // namespace dtwire::app
