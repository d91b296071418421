#include "cli.hpp"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <iostream>

#include "commands.hpp"
#include "dtwire/core/error.hpp"
#include "dtwire/core/provenance.hpp"

namespace dtwire::app {
namespace {

std::string first_line(const std::string& text) { return text.substr(0, text.find('\n')); }

bool selected(const CLI::App* command) { return command->parsed(); }

void build(CLI::App& root, CommandSet& commands) {
  root.require_subcommand(1);
  root.set_version_flag("--version", version_string());
  root.footer("Run 'dtwire <command> --help' for a command's options.");
  add_mesh_command(root, commands);
  add_run_command(root, commands);
  add_parameters_command(root, commands);
  add_fit_command(root, commands);
  add_export_command(root, commands);
  add_dem_command(root, commands);
  add_gap_command(root, commands);
  add_campaign_command(root, commands);
}

}  // namespace

void CommandSet::add(CLI::App* command, std::function<int()> run, bool available) {
  entries_.push_back({command, std::move(run), available});
}

void CommandSet::add_unavailable(CLI::App& root, const std::string& name,
                                 const std::string& description, const std::string& missing_part) {
  CLI::App* command = root.add_subcommand(name, description + " [not in this build yet]");
  command->allow_extras();
  add(
      command,
      [name, missing_part] {
        std::cerr << "dtwire " << name << ": not available yet: " << missing_part
                  << " is not implemented in this version\n";
        return kExitFailure;
      },
      false);
}

bool CommandSet::available(const std::string& name) const {
  return std::any_of(entries_.begin(), entries_.end(), [&](const Entry& e) {
    return e.command->get_name() == name && e.available;
  });
}

int CommandSet::run_selected() const {
  // The deepest selected command wins, so nested commands (e.g. `dem driver`) can register
  // their own runner next to their parent's.
  const Entry* chosen = nullptr;
  for (const Entry& e : entries_)
    if (selected(e.command)) chosen = &e;
  if (!chosen) throw std::logic_error("no runner for the selected command");
  return chosen->run();
}

std::string version_string() {
  return std::string("dtwire ") + tool_version() + " (git " + git_hash() + ")";
}

bool command_available(const std::string& name) {
  CLI::App root;
  CommandSet commands;
  build(root, commands);
  return commands.available(name);
}

std::vector<std::string> command_names() {
  CLI::App root;
  CommandSet commands;
  build(root, commands);
  std::vector<std::string> names;
  for (const CLI::App* sub : root.get_subcommands({})) names.push_back(sub->get_name());
  return names;
}

int run_command_line(const std::vector<std::string>& args) {
  CLI::App root{"dtwire: calibrated DEM contact parameters for double-twisted wire mesh from FE "
                "experiments and laboratory curves",
                "dtwire"};
  CommandSet commands;
  build(root, commands);
  // CLI11 reports "A subcommand is required" for most mistakes at the top level; say what is
  // actually wrong instead.
  std::string names;
  for (const CLI::App* sub : root.get_subcommands({}))
    names += (names.empty() ? "" : ", ") + sub->get_name();
  const std::string& first = args.empty() ? std::string() : args.front();
  const auto subcommands = root.get_subcommands({});
  const bool is_command = std::any_of(subcommands.begin(), subcommands.end(),
                                      [&](const CLI::App* sub) { return sub->get_name() == first; });
  if (!is_command && first != "-h" && first != "--help" && first != "--version") {
    if (first.empty())
      std::cerr << "dtwire: error: missing command, expected one of: " << names << "\n";
    else if (first.front() == '-')
      std::cerr << "dtwire: error: unknown option '" << first << "' (try 'dtwire --help')\n";
    else
      std::cerr << "dtwire: error: unknown command '" << first << "', expected one of: " << names
                << "\n";
    return kExitBadInput;
  }
  try {
    std::vector<std::string> reversed(args.rbegin(), args.rend());
    root.parse(reversed);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return root.exit(e);  // --help, --version
    std::cerr << "dtwire: error: " << first_line(e.what()) << "\n";
    return kExitBadInput;
  }
  try {
    return commands.run_selected();
  } catch (const InputError& e) {
    std::cerr << "dtwire: error: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const ComputationError& e) {
    std::cerr << "dtwire: failed: " << e.what() << "\n";
    return kExitFailure;
  } catch (const std::exception& e) {
    std::cerr << "dtwire: failed: " << e.what() << "\n";
    return kExitFailure;
  }
}

}  // namespace dtwire::app
