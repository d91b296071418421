#pragma once
// The `dtwire` command line: a root CLI::App with one subcommand per module. Each module's
// command lives in app/commands/<name>_command.cpp and registers itself through CommandSet.
#include <functional>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace dtwire::app {

class CommandSet {
 public:
  // `run` is called after a successful parse when `command` (or one of its subcommands) was
  // selected; it returns the process exit code.
  void add(CLI::App* command, std::function<int()> run, bool available = true);
  // A command whose module is not built yet: --help works, running it says so and exits 1.
  void add_unavailable(CLI::App& root, const std::string& name, const std::string& description,
                       const std::string& missing_part);
  bool available(const std::string& name) const;
  int run_selected() const;

 private:
  struct Entry {
    CLI::App* command;
    std::function<int()> run;
    bool available;
  };
  std::vector<Entry> entries_;
};

// Parses `args` (without the program name) and runs the selected command. Maps errors to exit
// codes: 0 success, 1 computation failure, 2 bad usage or bad input (one-line reason on stderr).
int run_command_line(const std::vector<std::string>& args);

// Which top-level commands this build can run (for `campaign` to report compiled-out steps).
bool command_available(const std::string& name);

// Every top-level command name, available or compiled out (for `campaign` to refuse typos).
std::vector<std::string> command_names();

std::string version_string();

}  // namespace dtwire::app
