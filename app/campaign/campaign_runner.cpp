#include "campaign_runner.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <iostream>

#include "../cli.hpp"
#include "dtwire/core/atomic_file.hpp"
#include "dtwire/core/error.hpp"
#include "dtwire/core/provenance.hpp"
#include "dtwire/version.hpp"

namespace dtwire::app {
namespace {

using nlohmann::json;

std::filesystem::path state_path(const std::filesystem::path& out) {
  return out / "campaign_state.json";
}

json load_state(const std::filesystem::path& out) {
  const auto path = state_path(out);
  if (!std::filesystem::exists(path)) return json::object();
  std::ifstream in(path);
  try {
    return json::parse(in);
  } catch (const json::exception& e) {
    std::cerr << "campaign: ignoring unreadable state " << path << " (" << e.what() << ")\n";
    return json::object();
  }
}

void save_state(const std::filesystem::path& out, const json& state) {
  write_file_atomically(state_path(out), [&](std::ostream& stream) { stream << state.dump(2) << "\n"; });
}

std::string fingerprint(const std::vector<std::string>& command, const std::vector<std::string>& inputs) {
  std::string text = std::string("dtwire ") + kVersion + "\n";
  for (const auto& arg : command) text += arg + '\0';
  for (const auto& input : inputs) text += "\n" + input + " " + sha256_file(input);
  return sha256_text(text);
}

// True if `path` lies inside `folder` (both made absolute, lexically normalised).
bool is_within(const std::filesystem::path& path, const std::filesystem::path& folder) {
  const auto p = std::filesystem::absolute(path).lexically_normal().string();
  const auto f = std::filesystem::absolute(folder).lexically_normal().string();
  return p.compare(0, f.size(), f) == 0;
}

bool outputs_exist(const std::vector<std::string>& outputs) {
  return std::all_of(outputs.begin(), outputs.end(),
                     [](const std::string& o) { return std::filesystem::exists(o); });
}

}  // namespace

std::string status_name(StepStatus status) {
  switch (status) {
    case StepStatus::Done: return "done";
    case StepStatus::Skipped: return "up to date";
    case StepStatus::Failed: return "failed";
    case StepStatus::Unavailable: return "not available yet";
    case StepStatus::Blocked: return "blocked";
  }
  return "unknown";
}

std::vector<StepOutcome> run_campaign(const Campaign& campaign, const CampaignOptions& options) {
  std::filesystem::create_directories(options.out);
  const auto campaign_dir = std::filesystem::absolute(campaign.file).parent_path();
  json state = load_state(options.out);
  std::vector<StepOutcome> outcomes;
  std::size_t index = 0;
  for (const CampaignStep& step : campaign.steps) {
    ++index;
    if (!options.only.empty() &&
        std::find(options.only.begin(), options.only.end(), step.name) == options.only.end())
      continue;
    const std::string progress = "[" + std::to_string(index) + "/" +
                                 std::to_string(campaign.steps.size()) + "] " + step.name;
    StepOutcome outcome{step.name, StepStatus::Done, 0.0, 0, {}};
    if (!command_available(step.command.front())) {
      outcome.status = StepStatus::Unavailable;
      outcome.message = "'dtwire " + step.command.front() + "' is not in this build yet";
      std::cerr << progress << ": " << outcome.message << "\n";
      outcomes.push_back(outcome);
      continue;
    }
    std::vector<std::string> command, inputs, outputs;
    for (const auto& a : step.command) command.push_back(expand(a, options.out, campaign_dir));
    for (const auto& a : step.inputs) inputs.push_back(expand(a, options.out, campaign_dir));
    for (const auto& a : step.outputs) outputs.push_back(expand(a, options.out, campaign_dir));
    const auto missing = std::find_if(inputs.begin(), inputs.end(), [](const std::string& input) {
      return !std::filesystem::exists(input);
    });
    if (missing != inputs.end()) {
      if (!is_within(*missing, options.out))
        throw InputError(campaign.file.string(), "step '" + step.name + "': input " + *missing +
                                                     " does not exist");
      outcome.status = StepStatus::Blocked;
      outcome.message = "input " + *missing + " was not produced by an earlier step";
      std::cerr << progress << ": blocked, " << outcome.message << "\n";
      outcomes.push_back(outcome);
      continue;
    }
    for (const auto& output : outputs)
      std::filesystem::create_directories(std::filesystem::path(output).parent_path());
    const std::string hash = fingerprint(command, inputs);
    const json& previous = state.value(step.name, json::object());
    if (!options.force && previous.value("status", "") == "done" &&
        previous.value("fingerprint", "") == hash && outputs_exist(outputs)) {
      outcome.status = StepStatus::Skipped;
      outcome.seconds = previous.value("seconds", 0.0);
      std::cerr << progress << ": up to date, skipped\n";
      outcomes.push_back(outcome);
      continue;
    }
    std::cerr << progress << ": running dtwire";
    for (const auto& a : command) std::cerr << " " << a;
    std::cerr << "\n";
    const auto start = std::chrono::steady_clock::now();
    outcome.exit_code = run_command_line(command);
    outcome.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (outcome.exit_code != 0) {
      outcome.status = StepStatus::Failed;
      outcome.message = "exit code " + std::to_string(outcome.exit_code);
    } else if (!outputs_exist(outputs)) {
      outcome.status = StepStatus::Failed;
      outcome.message = "finished but did not write all of its outputs";
    }
    std::cerr << progress << ": " << status_name(outcome.status) << " in " << outcome.seconds
              << " s" << (outcome.message.empty() ? "" : " (" + outcome.message + ")") << "\n";
    state[step.name] = {{"status", outcome.status == StepStatus::Done ? "done" : "failed"},
                        {"fingerprint", hash},
                        {"seconds", outcome.seconds},
                        {"finished_utc", utc_now_iso8601()}};
    save_state(options.out, state);
    outcomes.push_back(outcome);
  }
  return outcomes;
}

}  // namespace dtwire::app
