#include "campaign_graph.hpp"

#include <algorithm>

namespace dtwire::app {
namespace {

bool within(const std::string& path, const std::string& folder) {
  return path == folder || path.rfind(folder + "/", 0) == 0;
}

bool outputs_overlap(const CampaignStep& a, const CampaignStep& b) {
  for (const auto& x : a.outputs)
    for (const auto& y : b.outputs)
      if (within(x, y) || within(y, x)) return true;
  return false;
}

// The {out} paths an argument names: "sw={out}/a.json" -> {out}/a.json; a list "x,{out}/b" and
// a section suffix "{out}/p.json#double_twist" are cut at ',' and '#'.
std::vector<std::string> named_paths(const std::string& argument) {
  std::vector<std::string> paths;
  for (auto at = argument.find("{out}"); at != std::string::npos; at = argument.find("{out}", at + 5))
    paths.push_back(argument.substr(at, argument.find_first_of(",#", at) - at));
  return paths;
}

bool command_reads(const CampaignStep& step, const CampaignStep& earlier) {
  for (const auto& argument : step.command)
    for (const auto& path : named_paths(argument))
      for (const auto& output : earlier.outputs)
        if (within(path, output) || within(output, path)) return true;
  return false;
}

}  // namespace

bool step_writes(const CampaignStep& step, const std::string& path) {
  return std::any_of(step.outputs.begin(), step.outputs.end(),
                     [&](const std::string& output) { return within(path, output); });
}

std::vector<std::vector<std::size_t>> step_dependencies(const Campaign& campaign) {
  const auto& steps = campaign.steps;
  std::vector<std::vector<std::size_t>> waits(steps.size());
  for (std::size_t i = 0; i < steps.size(); ++i)
    for (std::size_t j = 0; j < i; ++j) {
      const bool reads = std::any_of(steps[i].inputs.begin(), steps[i].inputs.end(),
                                     [&](const std::string& input) { return step_writes(steps[j], input); });
      if (reads || command_reads(steps[i], steps[j]) || outputs_overlap(steps[i], steps[j]))
        waits[i].push_back(j);
    }
  return waits;
}

}  // namespace dtwire::app
