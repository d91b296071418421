#include "campaign_runner.hpp"

#include <nlohmann/json.hpp>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <set>
#include <sstream>

#include "../cli.hpp"
#include "dtwire/core/atomic_file.hpp"
#include "dtwire/core/error.hpp"
#include "dtwire/core/provenance.hpp"
#include "dtwire/version.hpp"
#include "step_process.hpp"

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

// The step's console log, then the *.log files a command writes beside its outputs (run.log).
std::vector<std::filesystem::path> progress_logs(const std::filesystem::path& console,
                                                 const std::vector<std::string>& outputs) {
  std::vector<std::filesystem::path> logs{console};
  std::set<std::filesystem::path> folders;
  for (const auto& output : outputs) folders.insert(std::filesystem::path(output).parent_path());
  for (const auto& folder : folders)
    if (std::filesystem::exists(folder / "run.log")) logs.push_back(folder / "run.log");
  return logs;
}

// One line per step: rewritten in place on a terminal, printed once when the step ends otherwise.
class ProgressLine {
 public:
  explicit ProgressLine(std::string prefix) : prefix_(std::move(prefix)), live_(::isatty(2) == 1) {}
  void update(double seconds, const std::string& progress) {
    if (!live_) return;
    std::cerr << "\r\033[K" << text(seconds, progress) << std::flush;
  }
  void finish(const std::string& message) {
    std::cerr << (live_ ? "\r\033[K" : "") << prefix_ << ": " << message << "\n";
  }
  static std::string seconds_text(double seconds) {
    std::ostringstream s;
    s << std::fixed << std::setprecision(seconds < 10 ? 1 : 0) << seconds << " s";
    return s.str();
  }

 private:
  std::string text(double seconds, const std::string& progress) const {
    std::string line = prefix_ + ": running " + seconds_text(seconds) + (progress.empty() ? "" : ", " + progress);
    return line.size() > 118 ? line.substr(0, 115) + "..." : line;
  }
  std::string prefix_;
  bool live_;
};

}  // namespace

std::filesystem::path step_folder(const std::filesystem::path& out, const std::string& step) {
  return out / "steps" / step;
}

std::string status_name(StepStatus status) {
  switch (status) {
    case StepStatus::Done: return "done";
    case StepStatus::Skipped: return "up to date";
    case StepStatus::Failed: return "failed";
    case StepStatus::Unavailable: return "not in this build";
    case StepStatus::Blocked: return "blocked";
  }
  return "unknown";
}

std::vector<StepOutcome> run_campaign(const Campaign& campaign, const CampaignOptions& options) {
  check_commands(campaign, command_names());
  std::filesystem::create_directories(options.out);
  const auto campaign_dir = std::filesystem::absolute(campaign.file).parent_path();
  // Inputs from outside the output folder must all exist before anything runs.
  for (const CampaignStep& step : campaign.steps)
    for (const auto& raw : step.inputs) {
      const std::string input = expand(raw, options.out, campaign_dir);
      if (!is_within(input, options.out) && !std::filesystem::exists(input))
        throw InputError(campaign.file.string(), step.field_lines.count("inputs") ? step.field_lines.at("inputs") : step.line,
                         0, "step '" + step.name + "': input " + input + " does not exist");
    }
  json state = load_state(options.out);
  std::vector<StepOutcome> outcomes;
  std::size_t index = 0;
  for (const CampaignStep& step : campaign.steps) {
    ++index;
    if (!options.only.empty() &&
        std::find(options.only.begin(), options.only.end(), step.name) == options.only.end()) {
      // Not selected: its earlier results, if any, still belong in the report.
      std::vector<std::string> outputs;
      for (const auto& a : step.outputs) outputs.push_back(expand(a, options.out, campaign_dir));
      const json& previous = state.value(step.name, json::object());
      if (previous.value("status", "") == "done" && outputs_exist(outputs))
        outcomes.push_back({step.name, StepStatus::Skipped, previous.value("seconds", 0.0), 0,
                            "not selected by --only; results of an earlier run"});
      continue;
    }
    ProgressLine line("[" + std::to_string(index) + "/" + std::to_string(campaign.steps.size()) + "] " + step.name);
    StepOutcome outcome{step.name, StepStatus::Done, 0.0, 0, {}};
    if (!command_available(step.command.front())) {
      outcome.status = StepStatus::Unavailable;
      outcome.message = "'dtwire " + step.command.front() + "' is compiled out of this build";
      line.finish(outcome.message);
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
      outcome.status = StepStatus::Blocked;
      outcome.message = "input " + std::filesystem::relative(*missing, options.out).string() +
                        " was not produced (an earlier step failed)";
      line.finish("blocked, " + outcome.message);
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
      line.finish("up to date, skipped");
      outcomes.push_back(outcome);
      continue;
    }
    const auto folder = step_folder(options.out, step.name);
    std::filesystem::create_directories(folder);
    const auto log = folder / "output.log";
    {
      std::ofstream header(folder / "command.txt");
      header << "dtwire";
      for (const auto& a : command) header << " " << a;
      header << "\n";
    }
    const auto start = std::chrono::steady_clock::now();
    std::string start_failure;
    try {
      outcome.exit_code = run_step_process(options.executable, command, log, [&](double seconds) {
        line.update(seconds, step_progress(progress_logs(log, outputs)));
      });
    } catch (const ComputationError& e) {  // the step could not be started: it fails, the others run
      start_failure = e.what();
      outcome.exit_code = 1;
    }
    outcome.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!start_failure.empty()) {
      outcome.status = StepStatus::Failed;
      outcome.message = start_failure;
    } else if (outcome.exit_code != 0) {
      outcome.status = StepStatus::Failed;
      outcome.message = "exit code " + std::to_string(outcome.exit_code) + ": " + last_line(log);
    } else if (!outputs_exist(outputs)) {
      outcome.status = StepStatus::Failed;
      outcome.message = "finished but did not write all of its outputs";
    }
    const std::string log_name = std::filesystem::relative(log, options.out).string();
    line.finish(status_name(outcome.status) + " in " + ProgressLine::seconds_text(outcome.seconds) +
                (outcome.message.empty() ? "" : " (" + outcome.message + "; log " + log_name + ")"));
    state[step.name] = {{"status", outcome.status == StepStatus::Done ? "done" : "failed"},
                        {"fingerprint", hash},
                        {"seconds", outcome.seconds},
                        {"log", log_name},
                        {"finished_utc", utc_now_iso8601()}};
    save_state(options.out, state);
    outcomes.push_back(outcome);
  }
  return outcomes;
}

}  // namespace dtwire::app
