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
//
// {out} is the output directory, {campaign} the folder of the campaign file.
#include <filesystem>
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
};

struct Campaign {
  std::filesystem::path file;
  std::string name;
  std::string title;
  std::vector<CampaignStep> steps;
};

// Throws InputError naming file:line:column and the field at fault.
Campaign read_campaign(const std::filesystem::path& file);

// Replaces {out} and {campaign} in `text`.
std::string expand(const std::string& text, const std::filesystem::path& out,
                   const std::filesystem::path& campaign_dir);

}  // namespace dtwire::app
