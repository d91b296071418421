#pragma once
// A campaign file (TOML) lists the steps of a study, each one a dtwire command line:
//
//   name = "default"
//   title = "..."
//   [[step]]
//   name = "sw_mesh"                      # unique, [a-z0-9_]
//   command = ["mesh", "sw", "-o", "{out}/meshes/sw.msh"]
//   inputs = ["{campaign}/sw.prm"]        # hashed: a change re-runs the step on resume
//   outputs = ["{out}/meshes/sw.msh"]     # must exist after the step for it to count as done
//   report = ["{out}/meshes/sw_check.md", "{out}/figures/sw.png"]  # embedded in the report
//   summary = ["{out}/fit/parameters.json"]  # read by the report's summary (optional)
//   threads = 4                           # cores the step uses (its threads or MPI ranks); 1 if absent
//   expected_seconds = 150                # optional: its wall time as measured, for the start order
//   [variables]                           # optional: {name} in any step string, value a string
//   as_made = "false"                     # default; `dtwire campaign --var as_made=true` overrides
//   include = ["../default/campaign.toml"]  # optional, before the tables: another campaign's
//                                         # steps and variables come first, as that file has them
//
// {out} is the output directory, {campaign} the folder of the campaign file (of the included file
// for its steps, resolved when it is read, so a shared step runs the same command in both). The
// file is checked completely before anything runs: unknown fields, unknown placeholders, unknown
// commands, a step name used twice (also across an include), an include cycle and {out} inputs
// that no earlier step writes are errors naming file:line.
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace dtwire::app {

struct CampaignStep {
  std::string name;
  std::string description;
  std::vector<std::string> command;
  std::vector<std::string> inputs;
  std::vector<std::string> outputs;
  std::vector<std::string> report;
  std::vector<std::string> summary;
  int threads = 1;  // cores it occupies while it runs (campaign --jobs, Snakemake threads:)
  std::optional<double> expected_seconds;  // its wall time as measured: the start order's guess in a fresh folder
  std::filesystem::path file;         // the campaign file that declares it (an included one for its steps)
  int line = 0;                       // of the step's [[step]] table
  std::map<std::string, int> field_lines;  // field name -> line of its value
};

struct Campaign {
  std::filesystem::path file;
  std::string name;
  std::string title;
  std::vector<CampaignStep> steps;
  std::map<std::string, std::string> variables;  // name -> value: the file's defaults, then --var
  std::vector<std::string> overridden;           // the variables set by --var
};

// Reads and checks the file (fields, placeholders, graph); throws InputError naming
// file:line:column and the field at fault. Command names are checked by check_commands.
Campaign read_campaign(const std::filesystem::path& file);

// Refuses a step whose command is not one of `known_commands` (a typo), naming file:line and
// the closest known command.
void check_commands(const Campaign& campaign, const std::vector<std::string>& known_commands);

// `settings` (NAME=VALUE, from --var) replace the file's defaults; then every {name} of a
// variable in the steps' strings is replaced by its value. Throws InputError("--var", ...) for
// an unknown name or a setting without '='.
void apply_variables(Campaign& campaign, const std::vector<std::string>& settings);

// Replaces {out} and {campaign} in `text`.
std::string expand(const std::string& text, const std::filesystem::path& out,
                   const std::filesystem::path& campaign_dir);

}  // namespace dtwire::app
