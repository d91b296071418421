#include "recorded_outcomes.hpp"

#include <algorithm>
#include <fstream>
#include <string>

#include "../cli.hpp"
#include "campaign_state.hpp"
#include "dtwire/core/provenance.hpp"

namespace dtwire::app {
namespace {

// The "s" column of a Snakemake benchmark file (header line, then one line per repeat), or 0.
double benchmark_seconds(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::string header, row;
  if (!std::getline(in, header) || !std::getline(in, row) || header.rfind("s\t", 0) != 0) return 0.0;
  try {
    return std::stod(row.substr(0, row.find('\t')));
  } catch (const std::exception&) {
    return 0.0;
  }
}

}  // namespace

std::vector<StepOutcome> recorded_outcomes(const Campaign& campaign, const std::filesystem::path& out) {
  const auto campaign_dir = std::filesystem::absolute(campaign.file).parent_path();
  nlohmann::json state = load_state(out);
  bool recorded = false;
  std::vector<StepOutcome> outcomes;
  for (const CampaignStep& step : campaign.steps) {
    std::vector<std::string> command, inputs, outputs;
    for (const auto& a : step.command) command.push_back(expand(a, out, campaign_dir));
    for (const auto& a : step.inputs) inputs.push_back(expand(a, out, campaign_dir));
    for (const auto& a : step.outputs) outputs.push_back(expand(a, out, campaign_dir));
    StepOutcome outcome{step.name, StepStatus::Done, 0.0, 0, {}};
    const auto missing = std::find_if(outputs.begin(), outputs.end(),
                                      [](const std::string& o) { return !std::filesystem::exists(o); });
    if (missing != outputs.end()) {
      const bool compiled_out = !command_available(step.command.front());
      outcome.status = compiled_out ? StepStatus::Unavailable : StepStatus::Blocked;
      outcome.message = compiled_out ? "'dtwire " + step.command.front() + "' is compiled out of this build"
                                     : "output " + std::filesystem::relative(*missing, out).string() + " is missing";
      outcomes.push_back(outcome);
      continue;
    }
    const bool inputs_exist = outputs_exist(inputs);
    const std::string hash = inputs_exist ? step_fingerprint(command, inputs) : std::string();
    const nlohmann::json& previous = state.value(step.name, nlohmann::json::object());
    if (previous.value("status", "") == "done" && previous.value("fingerprint", "") == hash) {
      outcome.seconds = previous.value("seconds", 0.0);
    } else {
      const auto folder = step_folder(out, step.name);
      // A step whose inputs changed since its record (a step Snakemake ran, or an earlier build's
      // run) keeps its recorded time unless Snakemake timed it: 0 would hide it from the
      // report's critical path.
      const double timed = benchmark_seconds(folder / "benchmark.tsv");
      outcome.seconds = timed > 0.0 ? timed : previous.value("seconds", 0.0);
      if (inputs_exist) {
        state[step.name] = {{"status", "done"},
                            {"fingerprint", hash},
                            {"seconds", outcome.seconds},
                            {"log", std::filesystem::relative(folder / "output.log", out).string()},
                            {"finished_utc", utc_now_iso8601()}};
        recorded = true;
      }
    }
    outcomes.push_back(outcome);
  }
  if (recorded) save_state(out, state);
  return outcomes;
}

}  // namespace dtwire::app
