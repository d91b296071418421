#include "campaign_runner.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <fstream>
#include <map>
#include <mutex>
#include <optional>
#include <set>
#include <thread>

#include "../cli.hpp"
#include "campaign_graph.hpp"
#include "campaign_lock.hpp"
#include "campaign_state.hpp"
#include "interruption.hpp"
#include "dtwire/core/atomic_file.hpp"
#include "dtwire/core/error.hpp"
#include "dtwire/core/provenance.hpp"
#include "start_order.hpp"
#include "step_console.hpp"
#include "step_process.hpp"

namespace dtwire::app {
namespace {

using nlohmann::json;
using Clock = std::chrono::steady_clock;

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

// The --out folder a `fit` command names, or "" (another command, or the fit's default folder).
std::filesystem::path fit_folder(const std::vector<std::string>& command) {
  if (command.empty() || command.front() != "fit") return {};
  for (std::size_t i = 1; i < command.size(); ++i) {
    if ((command[i] == "--out" || command[i] == "-o") && i + 1 < command.size()) return command[i + 1];
    if (command[i].rfind("--out=", 0) == 0) return command[i].substr(6);
  }
  return {};
}

std::string file_text(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::string text;
  std::getline(in, text);
  return text;
}

// A step that has to run: its expanded command, inputs, outputs and fingerprint.
struct Launch {
  std::vector<std::string> command, inputs, outputs;
  std::string hash;
  int cores = 1;
};

// What a step's turn gives before anything runs: an outcome (skipped, blocked, ...), a launch,
// or nothing (not selected by --only and never run).
struct Decision {
  std::optional<StepOutcome> outcome;
  std::optional<Launch> launch;
  std::string note;  // the console's line for a step that does not run
};

class Runner {
 public:
  Runner(const Campaign& campaign, const CampaignOptions& options)
      : campaign_(campaign),
        options_(options),
        campaign_dir_(std::filesystem::absolute(campaign.file).parent_path()),
        waits_(step_dependencies(campaign)),
        state_(load_state(options.out)),
        console_(options.jobs > 1),
        phase_(campaign.steps.size(), Phase::Waiting),
        outcomes_(campaign.steps.size()),
        workers_(campaign.steps.size()),
        earlier_seconds_(earlier_seconds()),
        order_(offer_order()) {}

  ~Runner() {  // after an error: the running steps finish first
    for (auto& worker : workers_)
      if (worker.joinable()) worker.join();
  }

  std::vector<StepOutcome> run() {
    for (;;) {
      start_ready_steps();
      if (cores_in_use_ == 0) break;  // nothing running: every step has had its turn
      collect_one_finished_step();
    }
    std::vector<StepOutcome> outcomes;
    for (auto& outcome : outcomes_)
      if (outcome) outcomes.push_back(*outcome);
    return outcomes;
  }

 private:
  enum class Phase { Waiting, Running, Finished };

  std::string expand_text(const std::string& text) const { return expand(text, options_.out, campaign_dir_); }
  std::vector<std::string> expand_all(const std::vector<std::string>& texts) const {
    std::vector<std::string> out;
    for (const auto& t : texts) out.push_back(expand_text(t));
    return out;
  }
  std::string label(std::size_t i) const {
    return "[" + std::to_string(i + 1) + "/" + std::to_string(campaign_.steps.size()) + "] " + campaign_.steps[i].name;
  }

  bool ready(std::size_t i) const {
    // One at a time, the steps keep the file's order.
    if (options_.jobs == 1 && std::any_of(phase_.begin(), phase_.begin() + static_cast<std::ptrdiff_t>(i),
                                          [](Phase p) { return p != Phase::Finished; }))
      return false;
    return std::all_of(waits_[i].begin(), waits_[i].end(), [&](std::size_t j) { return phase_[j] == Phase::Finished; });
  }

  // Each step's time in this folder's earlier run, if it ran to the end there.
  std::vector<std::optional<double>> earlier_seconds() const {
    std::vector<std::optional<double>> earlier;
    for (const CampaignStep& step : campaign_.steps) {
      // This folder's earlier run of the step, else the time its campaign file states.
      const json& previous = state_.value(step.name, json::object());
      earlier.push_back(previous.value("status", "") == "done" && previous.contains("seconds") &&
                                previous["seconds"].is_number()
                            ? std::optional<double>(previous["seconds"].get<double>())
                            : step.expected_seconds);
    }
    return earlier;
  }

  // One at a time: the file's order. Side by side: highest level first (start_order.hpp).
  std::vector<std::size_t> offer_order() const {
    if (options_.jobs > 1) return start_order(waits_, earlier_seconds_);
    std::vector<std::size_t> order(campaign_.steps.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    return order;
  }

  // Settles every waiting step whose producers are finished and that does not run (up to date,
  // blocked, not selected), then starts the ready ones as their cores allow (steps_to_start).
  void start_ready_steps() {
    if (interruption_signal() != 0) return;  // interrupted: the running steps stop, nothing new starts
    for (bool settled = true; settled;) {
      settled = false;
      for (const std::size_t i : order_) {
        if (phase_[i] != Phase::Waiting || !ready(i)) continue;
        if (!decisions_.count(i)) decisions_[i] = decide(i);
        const Decision& decision = decisions_[i];
        if (decision.launch) continue;
        if (!decision.note.empty()) console_.finished(label(i), decision.note);
        outcomes_[i] = decision.outcome;
        phase_[i] = Phase::Finished;
        settled = true;
      }
    }
    std::vector<ReadyStep> ready_steps;
    for (const std::size_t i : order_)
      if (phase_[i] == Phase::Waiting && ready(i))
        ready_steps.push_back({i, decisions_.at(i).launch->cores, earlier_seconds_[i]});
    const double now = std::chrono::duration<double>(Clock::now() - campaign_start_).count();
    std::vector<RunningStep> running;
    for (std::size_t i = 0; i < phase_.size(); ++i) {
      if (phase_[i] != Phase::Running) continue;
      std::optional<double> remaining;
      if (earlier_seconds_[i] && started_at_.at(i) + *earlier_seconds_[i] > now)
        remaining = started_at_.at(i) + *earlier_seconds_[i] - now;
      running.push_back({decisions_.at(i).launch->cores, remaining});
    }
    for (const std::size_t i : steps_to_start(ready_steps, running, options_.jobs)) start(i, *decisions_.at(i).launch);
  }

  Decision decide(std::size_t i) {
    const CampaignStep& step = campaign_.steps[i];
    const auto outputs = expand_all(step.outputs);
    const json& previous = state_.value(step.name, json::object());
    if (!options_.only.empty() && std::find(options_.only.begin(), options_.only.end(), step.name) == options_.only.end()) {
      // Not selected: its earlier results, if any, still belong in the report.
      if (previous.value("status", "") == "done" && outputs_exist(outputs))
        return {StepOutcome{step.name, StepStatus::Skipped, previous.value("seconds", 0.0), 0,
                            "not selected by --only; results of an earlier run"},
                std::nullopt, {}};
      return {};
    }
    StepOutcome outcome{step.name, StepStatus::Done, 0.0, 0, {}};
    if (!command_available(step.command.front())) {
      outcome.status = StepStatus::Unavailable;
      outcome.message = "'dtwire " + step.command.front() + "' is compiled out of this build";
      return {outcome, std::nullopt, outcome.message};
    }
    for (std::size_t j : waits_[i])
      if (outcomes_[j] && (outcomes_[j]->status == StepStatus::Failed || outcomes_[j]->status == StepStatus::Blocked)) {
        // Its earlier outputs may still be on disk: never run on what a failed step left.
        const auto read = std::find_if(step.inputs.begin(), step.inputs.end(), [&](const std::string& input) {
          return step_writes(campaign_.steps[j], input);
        });
        outcome.status = StepStatus::Blocked;
        outcome.message = (read != step.inputs.end()
                               ? "input " + std::filesystem::relative(expand_text(*read), options_.out).string() +
                                     " was not produced"
                               : std::string("it waits for step '") + campaign_.steps[j].name + "'") +
                          " (step '" + campaign_.steps[j].name + "' " + status_name(outcomes_[j]->status) + ")";
        return {outcome, std::nullopt, "blocked, " + outcome.message};
      }
    Launch launch{expand_all(step.command), expand_all(step.inputs), outputs, {}, std::min(step.threads, options_.jobs)};
    const auto missing = std::find_if(launch.inputs.begin(), launch.inputs.end(),
                                      [](const std::string& input) { return !std::filesystem::exists(input); });
    if (missing != launch.inputs.end()) {
      outcome.status = StepStatus::Blocked;
      outcome.message = "input " + std::filesystem::relative(*missing, options_.out).string() +
                        " was not produced (an earlier step failed)";
      return {outcome, std::nullopt, "blocked, " + outcome.message};
    }
    launch.hash = step_fingerprint(launch.command, launch.inputs);
    if (!options_.force && previous.value("status", "") == "done" && previous.value("fingerprint", "") == launch.hash &&
        outputs_exist(outputs)) {
      outcome.status = StepStatus::Skipped;
      outcome.seconds = previous.value("seconds", 0.0);
      remove_stale_temporaries_below(step_folder(options_.out, step.name), outputs);
      return {outcome, std::nullopt, "up to date, skipped"};
    }
    return {std::nullopt, launch, {}};
  }

  // An up-to-date step is not run again, but a writer killed after it finished (or a later
  // command into its folders) may have left temporaries there: they never outlive the next
  // campaign (issue 53). Its folder and its outputs' folders, with everything below them.
  static void remove_stale_temporaries_below(const std::filesystem::path& step_folder,
                                             const std::vector<std::string>& outputs) {
    std::set<std::filesystem::path> folders{step_folder};
    for (const auto& output : outputs) folders.insert(std::filesystem::path(output).parent_path());
    for (const auto& folder : folders) {
      std::error_code error;
      if (!std::filesystem::is_directory(folder, error)) continue;
      remove_stale_temporaries(folder);
      for (std::filesystem::recursive_directory_iterator it(folder, error), end; !error && it != end; it.increment(error))
        if (it->is_directory(error)) remove_stale_temporaries(it->path());
    }
  }

  void start(std::size_t i, const Launch& launch) {
    phase_[i] = Phase::Running;
    cores_in_use_ += launch.cores;
    started_at_[i] = std::chrono::duration<double>(Clock::now() - campaign_start_).count();
    console_.started(label(i), campaign_.steps[i].name);
    workers_[i] = std::thread([this, i, launch] {
      StepOutcome outcome = execute(i, launch);
      const std::lock_guard<std::mutex> lock(mutex_);
      finished_.push_back({i, std::move(outcome)});
      wake_.notify_one();
    });
  }

  // On a worker thread: runs the step's process and judges it. Never throws.
  StepOutcome execute(std::size_t i, const Launch& launch) {
    const CampaignStep& step = campaign_.steps[i];
    StepOutcome outcome{step.name, StepStatus::Done, 0.0, 0, {}};
    const auto folder = step_folder(options_.out, step.name);
    const auto log = folder / "output.log";
    const auto start = Clock::now();
    try {
      std::filesystem::create_directories(folder);
      // Only now, when the step starts: a step still waiting for cores must not put its folders
      // into another step's output folder while that one runs (`export` replaces its own whole).
      for (const auto& output : launch.outputs)
        std::filesystem::create_directories(std::filesystem::path(output).parent_path());
      // A killed writer's temporaries never outlive the step that writes the same outputs.
      std::set<std::filesystem::path> output_folders{folder};
      for (const auto& output : launch.outputs) output_folders.insert(std::filesystem::path(output).parent_path());
      for (const auto& output_folder : output_folders) remove_stale_temporaries(output_folder);
      std::vector<std::string> command = launch.command;
      const auto fit_out = fit_folder(command);
      if (!options_.force && !fit_out.empty() && std::filesystem::exists(fit_out / "checkpoint.json") &&
          file_text(folder / "fingerprint") == launch.hash)
        command.push_back("--resume");  // the same fit was interrupted: it goes on from its checkpoint
      write_file_atomically(folder / "fingerprint", [&](std::ostream& os) { os << launch.hash << "\n"; });
      write_file_atomically(folder / "command.txt", [&](std::ostream& header) {
        header << "dtwire";
        for (const auto& a : command) header << " " << a;
        header << "\n";
      });
      const auto track = [this](int group, bool running) {
        if (!options_.lock) return;
        if (running) options_.lock->add_step_group(group);
        else options_.lock->remove_step_group(group);
      };
      outcome.exit_code = run_step_process(options_.executable, command, log, [&](double seconds) {
        console_.progress(label(i), seconds, step_progress(progress_logs(log, launch.outputs)));
      }, track);
      if (outcome.exit_code != 0 || !outputs_exist(launch.outputs)) {
        outcome.status = StepStatus::Failed;
        // An interrupted fit saves its checkpoint and may exit 0 without its outputs.
        if (interruption_signal() != 0)
          outcome.message = "interrupted (signal " + std::to_string(interruption_signal()) + "), exit code " +
                            std::to_string(outcome.exit_code);
        else if (outcome.exit_code != 0)
          outcome.message = "exit code " + std::to_string(outcome.exit_code) + ": " + last_line(log);
        else
          outcome.message = "finished but did not write all of its outputs";
      }
    } catch (const std::exception& e) {  // the step could not be started: it fails, the others run
      outcome.status = StepStatus::Failed;
      outcome.exit_code = 1;
      outcome.message = e.what();
    }
    outcome.seconds = std::chrono::duration<double>(Clock::now() - start).count();
    return outcome;
  }

  void collect_one_finished_step() {
    std::pair<std::size_t, StepOutcome> done;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      wake_.wait(lock, [&] { return !finished_.empty(); });
      done = std::move(finished_.front());
      finished_.erase(finished_.begin());
    }
    const auto& [i, outcome] = done;
    workers_[i].join();
    const Launch& launch = *decisions_[i].launch;
    cores_in_use_ -= launch.cores;
    const std::string log_name =
        std::filesystem::relative(step_folder(options_.out, outcome.name) / "output.log", options_.out).string();
    console_.finished(label(i), status_name(outcome.status) + " in " + StepConsole::seconds_text(outcome.seconds) +
                                    (outcome.message.empty() ? "" : " (" + outcome.message + "; log " + log_name + ")"));
    state_[outcome.name] = {{"status", outcome.status == StepStatus::Done ? "done" : "failed"},
                            {"fingerprint", launch.hash},
                            {"seconds", outcome.seconds},
                            {"started_s", started_at_[i]},
                            {"log", log_name},
                            {"finished_utc", utc_now_iso8601()}};
    save_state(options_.out, state_);
    outcomes_[i] = outcome;
    phase_[i] = Phase::Finished;
  }

  const Campaign& campaign_;
  const CampaignOptions& options_;
  const std::filesystem::path campaign_dir_;
  const std::vector<std::vector<std::size_t>> waits_;
  json state_;
  StepConsole console_;
  std::vector<Phase> phase_;
  std::vector<std::optional<StepOutcome>> outcomes_;
  std::map<std::size_t, Decision> decisions_;
  std::map<std::size_t, double> started_at_;  // seconds after the campaign started
  const Clock::time_point campaign_start_ = Clock::now();
  int cores_in_use_ = 0;
  std::vector<std::thread> workers_;
  const std::vector<std::optional<double>> earlier_seconds_;  // step times of this folder's earlier run
  const std::vector<std::size_t> order_;  // the order in which ready steps are offered cores
  std::mutex mutex_;
  std::condition_variable wake_;
  std::vector<std::pair<std::size_t, StepOutcome>> finished_;  // reported by workers, not yet collected
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

void check_external_inputs(const Campaign& campaign, const std::filesystem::path& out) {
  const auto campaign_dir = std::filesystem::absolute(campaign.file).parent_path();
  for (const CampaignStep& step : campaign.steps)
    for (const auto& raw : step.inputs) {
      const std::string input = expand(raw, out, campaign_dir);
      if (!is_within(input, out) && !std::filesystem::exists(input))
        throw InputError((step.file.empty() ? campaign.file : step.file).string(), step.field_lines.count("inputs") ? step.field_lines.at("inputs") : step.line,
                         0, "step '" + step.name + "': input " + input + " does not exist");
    }
}

std::vector<StepOutcome> run_campaign(const Campaign& campaign, const CampaignOptions& options) {
  if (options.jobs < 1) throw InputError("--jobs", "must be at least 1, got " + std::to_string(options.jobs));
  check_commands(campaign, command_names());
  std::filesystem::create_directories(options.out);
  check_external_inputs(campaign, options.out);
  return Runner(campaign, options).run();
}

}  // namespace dtwire::app
