#pragma once
// Runs a campaign's steps in order, each as a child dtwire process whose console output goes to
// {out}/steps/<step>/output.log; stderr gets one progress line per step (updated in place on a
// terminal). State is saved after every step (out/campaign_state.json), so an interrupted
// campaign resumes where it stopped: a step is skipped when it finished before with the same
// command, inputs and tool version and its outputs still exist.
#include <filesystem>
#include <string>
#include <vector>

#include "campaign_file.hpp"

namespace dtwire::app {

// Unavailable: the command is compiled out of this build. Blocked: an input that an earlier step
// should have written is missing (that step failed).
enum class StepStatus { Done, Skipped, Failed, Unavailable, Blocked };

struct StepOutcome {
  std::string name;
  StepStatus status;
  double seconds = 0.0;
  int exit_code = 0;
  std::string message;
};

struct CampaignOptions {
  std::filesystem::path out;
  bool force = false;  // re-run every step
  std::vector<std::string> only;  // run just these steps (empty: all)
  std::filesystem::path executable;  // the dtwire binary that runs the steps
};

// {out}/steps/<step>: the step's console log (output.log).
std::filesystem::path step_folder(const std::filesystem::path& out, const std::string& step);

std::vector<StepOutcome> run_campaign(const Campaign& campaign, const CampaignOptions& options);

std::string status_name(StepStatus status);

}  // namespace dtwire::app
