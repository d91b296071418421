#include "propagation_runs.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <atomic>
#include <csignal>
#include <cmath>
#include <exception>
#include <fstream>
#include <iostream>
#include <limits>
#include <thread>

#include "../campaign/report_recommendation.hpp"
#include "../campaign/step_process.hpp"
#include "dtwire/calibrate/command_simulator.hpp"
#include "dtwire/core/atomic_file.hpp"
#include "dtwire/core/csv.hpp"
#include "dtwire/core/error.hpp"
#include "dtwire/core/provenance.hpp"

namespace dtwire::app {

std::vector<HeadlineFigure> headline_figures(const std::string& tool) {
  if (tool == "strip_tension")
    return {{"strength_per_width_kN_per_m", "strength per metre", "kN/m", 1.0, "strength_per_width_kN_per_m"},
            {"secant_EA_10_50_kN_per_m", "secant EA per metre (10-50 % of the peak)", "kN/m", 1.0, "secant_EA_10_50_kN_per_m"},
            {"displacement_at_peak_mm", "elongation at the peak", "mm", 1.0, "displacement_at_peak_mm"}};
  return {{"peak_force_N", "punch peak force", "kN", 1e-3, "peak_force_kN"},
          {"displacement_at_peak_mm", "punch displacement at the peak", "mm", 1.0, "displacement_at_peak_mm"},
          {"onset_displacement_mm", "onset (1 kN) displacement", "mm", 1.0, "onset_displacement_mm"}};
}

CurveAxes band_curve_axes(const std::string& tool) {
  if (tool == "strip_tension") return {"strain", "force_per_width"};
  return {"tool_displacement", "tool_force"};
}

PropagationRunner::PropagationRunner(std::filesystem::path cache, std::vector<std::string> base_arguments,
                                     std::string identity, std::vector<HeadlineFigure> figures)
    : cache_(std::move(cache)), base_arguments_(std::move(base_arguments)), identity_(std::move(identity)),
      figures_(std::move(figures)) {
  std::filesystem::create_directories(cache_);
}

RunOutcome PropagationRunner::run(const std::map<std::string, std::string>& parameter_files, const std::string& label) {
  RunOutcome outcome;
  outcome.folder = cache_ / key(parameter_files);
  const std::filesystem::path& run = outcome.folder;
  // `finished` is written after the run ended (successfully or stopped by its checks): a run
  // cut short is run again.
  if (std::filesystem::exists(run / "finished")) {
    outcome.cached = true;
    const std::lock_guard<std::mutex> lock(mutex_);
    ++cache_hits_;
  } else {
    std::filesystem::remove_all(run);
    std::filesystem::create_directories(run);
    std::vector<std::string> arguments = base_arguments_;
    for (const auto& [tag, text] : parameter_files) {
      const std::filesystem::path file = run / (tag + "_parameters.json");
      write_file_atomically(file, [&](std::ostream& os) { os << text; });
      arguments.insert(arguments.end(), {"--set-params", tag + "=" + file.string()});
    }
    arguments.insert(arguments.end(), {"-o", (run / "out").string()});
    write_file_atomically(run / "command.txt", [&](std::ostream& os) {
      os << calibrate::dtwire_executable().string();
      for (const std::string& a : arguments) os << " '" << a << "'";
      os << "\n";
    });
    const int code = run_step_process(calibrate::dtwire_executable(), arguments, run / "command.log", [](double) {});
    // A run stopped by its own checks (exit 1 with its partial summary), or one the contact law
    // gave up on (exit 1, or an abort: 128 + SIGABRT, e.g. "too many plastic substeps" at a
    // corner of the ranges), is a set that fails: named in the outputs, kept in the cache, left
    // out of the band. Anything else (bad input, a kill) ends the propagation.
    const bool stopped = code == 1 && std::filesystem::exists(run / "out" / "summary.json");
    const bool law_failed = !stopped && (code == 1 || code == 128 + SIGABRT);
    if (code != 0 && !stopped && !law_failed)
      throw ComputationError("DEM run (" + label + ") failed (exit " + std::to_string(code) + "), see " +
                             (run / "command.log").string());
    if (law_failed)
      write_file_atomically(run / "failure", [&](std::ostream& os) {
        os << "failed (exit " << code << "): " << last_line(run / "command.log") << "\n";
      });
    write_file_atomically(run / "finished", [&](std::ostream& os) { os << label << "\n"; });
    const std::lock_guard<std::mutex> lock(mutex_);
    ++runs_done_;
    std::cout << "  DEM run " << label << (stopped ? ": stopped by its checks" : law_failed ? ": failed" : ": done") << "\n"
              << std::flush;
  }
  if (std::filesystem::exists(run / "failure")) {
    std::ifstream in(run / "failure");
    std::getline(in, outcome.status);
    outcome.figures.assign(figures_.size(), std::numeric_limits<double>::quiet_NaN());
    return outcome;
  }
  std::ifstream in(run / "out" / "summary.json");
  const nlohmann::json summary = nlohmann::json::parse(in);
  outcome.status = summary.value("status", "ok");
  if (summary.contains("failed_check") && summary["failed_check"].is_object())
    outcome.status += ": " + summary["failed_check"].value("message", "");
  outcome.ok = outcome.status == "ok";
  for (const HeadlineFigure& f : figures_) {
    const auto found = summary.find(f.key);
    outcome.figures.push_back(found != summary.end() && found->is_number() ? found->get<double>() * f.factor
                                                                           : std::numeric_limits<double>::quiet_NaN());
  }
  outcome.curve = read_csv(run / "out" / "curve.csv");
  // A punch that never carries the onset force, or whose force still rises when the platter's
  // travel ends, has not loaded the net to failure: its "peak" is no figure of the test, and the
  // campaign report never shows it as one (report_recommendation.hpp). It is a set whose figures
  // the test does not measure, named and left out of the band like one its checks stop.
  if (outcome.ok && summary.value("tool", "") == "platter")
    if (const auto why = punch_not_at_rest(summary)) {
      outcome.ok = false;
      outcome.status = "not applicable: " + *why;
    }
  if (outcome.ok && summary.value("tool", "") == "platter" && outcome.curve.has("tool_displacement") &&
      outcome.curve.has("tool_force"))
    if (const auto why = punch_not_applicable(outcome.curve.si("tool_displacement"), outcome.curve.si("tool_force"))) {
      outcome.ok = false;
      outcome.status = "not applicable: " + *why;
    }
  return outcome;
}

std::string PropagationRunner::key(const std::map<std::string, std::string>& parameter_files) const {
  std::string key_text = identity_;
  for (const std::string& a : base_arguments_) key_text += a + "\n";
  for (const auto& [tag, text] : parameter_files) key_text += tag + "\n" + text + "\n";
  return sha256_text(key_text).substr(0, 24);
}

std::vector<RunOutcome> PropagationRunner::run_all(const std::vector<std::map<std::string, std::string>>& sets,
                                                   const std::vector<std::string>& labels, unsigned jobs) {
  // Equal sets share one run folder: only the first of them runs in the parallel pass, the
  // others read its result afterwards (two threads never write one folder).
  std::vector<std::size_t> first;
  std::vector<std::string> keys;
  for (std::size_t k = 0; k < sets.size(); ++k) {
    keys.push_back(key(sets[k]));
    if (std::find(keys.begin(), keys.end() - 1, keys.back()) == keys.end() - 1) first.push_back(k);
  }
  std::vector<RunOutcome> outcomes(sets.size());
  std::atomic<std::size_t> next{0};
  std::exception_ptr error;
  std::mutex error_mutex;
  const auto work = [&] {
    for (std::size_t m = next++; m < first.size(); m = next++) {
      try {
        outcomes[first[m]] = run(sets[first[m]], labels[first[m]]);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(error_mutex);
        if (!error) error = std::current_exception();
        next = first.size();  // start no more runs
      }
    }
  };
  std::vector<std::thread> threads;
  for (unsigned t = 1; t < std::max(1u, jobs); ++t) threads.emplace_back(work);
  work();
  for (std::thread& t : threads) t.join();
  if (error) std::rethrow_exception(error);
  for (std::size_t k = 0; k < sets.size(); ++k)
    if (outcomes[k].folder.empty()) outcomes[k] = run(sets[k], labels[k]);
  return outcomes;
}

}  // namespace dtwire::app
