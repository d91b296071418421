#pragma once
// Runs a campaign's steps, each as a child dtwire process whose console output goes to
// {out}/steps/<step>/output.log; stderr gets one progress line per step (step_console.hpp).
// With jobs = 1 the steps run one after another in the file's order; with more, a step starts
// as soon as the steps it waits for (campaign_graph.hpp) are finished and its cores (`threads`)
// fit in the `jobs` cores left. State is saved after every step (out/campaign_state.json), so an
// interrupted campaign resumes where it stopped: a step is skipped when it finished before with
// the same command, inputs and tool version and its outputs still exist. A step whose producer
// failed is blocked; the steps already running finish.
//
// Before a step starts, the stale temporaries of a killed writer (atomic_file.hpp) go from the
// folders of its outputs. A `fit` step that was interrupted (its folder holds checkpoint.json and
// steps/<step>/fingerprint shows the same command and inputs) runs with --resume, so it goes on
// from its last iteration and ends where an uninterrupted fit ends; --force starts it afresh.
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

class CampaignLock;

struct CampaignOptions {
  std::filesystem::path out;
  bool force = false;  // re-run every step
  std::vector<std::string> only;  // run just these steps (empty: all)
  std::filesystem::path executable;  // the dtwire binary that runs the steps
  int jobs = 1;  // cores for steps side by side; a step wider than this runs alone
  CampaignLock* lock = nullptr;  // records the running steps' process groups (campaign_lock.hpp)
};

// {out}/steps/<step>: the step's console log (output.log).
std::filesystem::path step_folder(const std::filesystem::path& out, const std::string& step);

// Inputs from outside the output folder must all exist before anything runs: throws InputError
// naming the step and the file:line of its inputs.
void check_external_inputs(const Campaign& campaign, const std::filesystem::path& out);

// The outcomes in the campaign's step order (steps not selected by --only and never run are
// left out).
std::vector<StepOutcome> run_campaign(const Campaign& campaign, const CampaignOptions& options);

std::string status_name(StepStatus status);

}  // namespace dtwire::app
