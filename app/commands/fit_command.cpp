#include <CLI/CLI.hpp>

#include <algorithm>
#include <atomic>
#include <csignal>
#include <cstdlib>
#include <iostream>
#include <thread>

#include "../cli.hpp"
#include "../plotting.hpp"
#include "../commands.hpp"
#include "dtwire/calibrate/fit_file.hpp"
#include "dtwire/calibrate/fit_output.hpp"
#include "dtwire/calibrate/initial_values.hpp"
#include "dtwire/calibrate/fitter.hpp"
#include "dtwire/calibrate/synthesize.hpp"
#include "dtwire/core/atomic_file.hpp"
#include "dtwire/core/error.hpp"
#include "dtwire/core/provenance.hpp"
#include "option_checks.hpp"

namespace dtwire::app {
namespace {

std::atomic<bool> stop_requested{false};
extern "C" void request_stop(int) { stop_requested = true; }

// --experiments: keeps the named experiments, in the file's order; an unknown or repeated name
// is an input error naming the file and what it holds.
void keep_only_experiments(calibrate::FitDefinition& def, const std::vector<std::string>& names) {
  std::string held;
  for (const auto& e : def.experiments) held += (held.empty() ? "" : ", ") + e.name;
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (std::count(names.begin(), names.begin() + static_cast<std::ptrdiff_t>(i), names[i]) > 0)
      throw InputError(def.file.string(), "--experiments: '" + names[i] + "' is named twice");
    const bool known = std::any_of(def.experiments.begin(), def.experiments.end(),
                                   [&](const auto& e) { return e.name == names[i]; });
    if (!known)
      throw InputError(def.file.string(),
                       "--experiments: no experiment '" + names[i] + "' in the file (it has: " + held + ")");
  }
  std::vector<calibrate::Experiment> kept;
  for (auto& e : def.experiments)
    if (std::find(names.begin(), names.end(), e.name) != names.end()) kept.push_back(std::move(e));
  def.experiments = std::move(kept);
}

}  // namespace

void add_fit_command(CLI::App& root, CommandSet& commands) {
  struct Options {
    std::string file;
    std::string out;
    std::string targets;
    std::string initial;
    bool resume = false;
    bool plot = false;
    int threads = -1;
    std::string synthesize;
    double noise = 0.0;
    std::uint64_t seed = 1;
    std::size_t points = 81;
    std::vector<std::string> experiments;
  };
  auto options = std::make_shared<Options>();
  CLI::App* command = root.add_subcommand(
      "fit", "Calibrate parameters with Ceres from a fit definition (TOML, see docs/calibrate.md)");
  command->add_option("file", options->file, "Fit definition (.toml)")->required();
  command->add_option("-o,--out", options->out, "Output directory (default: fit-out/<file stem>)");
  command->add_option("--targets", options->targets,
                      "Directory that replaces {targets} at the start of the experiments' target paths "
                      "(e.g. where a campaign wrote its FE curves)")
      ->check(CLI::ExistingDirectory);
  command->add_option("--initial", options->initial,
                      "Start from the values in an earlier fit's parameters.json (parameters it names; "
                      "e.g. a level-1 fit from the level-0 optimum)")
      ->check(CLI::ExistingFile);
  command->add_option("--experiments", options->experiments,
                      "Fit only these experiments of the file (names, comma-separated), e.g. a study "
                      "without some curves; the parameters and settings stay the file's")
      ->delimiter(',');
  command->add_flag("--resume", options->resume,
                    "Continue from <out>/checkpoint.json if present (same fit definition)");
  command->add_flag("--plot", options->plot,
                    "Also draw <out>/fit_curves.png with scripts/plot_fit.py (python3-matplotlib)");
  command->add_option("-j,--jobs,--threads", options->threads,
                      "Simulator runs side by side: the starts, and an iteration's experiments and "
                      "finite-difference columns, each command run in its own folder; the results do "
                      "not depend on it "
                      "(default: the fit file's, else all cores)")
      ->check(CLI::Range(1, 1024));
  command->add_option("--synthesize", options->synthesize,
                      "Instead of fitting: write the targets simulated at the parameters' reference "
                      "values into this directory");
  command->add_option("--noise", options->noise, "With --synthesize: Gaussian noise, fraction of each channel's range")
      ->check(finite_in(0.0, 1.0));
  command->add_option("--seed", options->seed, "With --synthesize: noise seed")->check(unsigned_whole());
  command->add_option("--points", options->points, "With --synthesize: at most this many rows per curve")
      ->check(CLI::Range(3, 100000));
  commands.add(command, [options] {
    if (options->plot && options->synthesize.empty()) require_plotting("plot_fit.py", "--plot");
    check_output_folders({{"-o", options->out}, {"--synthesize", options->synthesize}});
    if (!options->synthesize.empty()) {
      calibrate::FitReadOptions read;
      read.read_targets = false;
      auto def = calibrate::read_fit_file(options->file, read);
      if (!options->experiments.empty()) keep_only_experiments(def, options->experiments);
      for (const auto& file :
           calibrate::write_synthetic_targets(def, options->synthesize, options->noise, options->seed, options->points))
        std::cout << "wrote " << file.string() << "\n";
      return 0;
    }
    calibrate::FitReadOptions read;
    read.targets_directory = options->targets;
    read.only_experiments = options->experiments;
    auto def = calibrate::read_fit_file(options->file, read);
    if (!options->experiments.empty()) keep_only_experiments(def, options->experiments);
    if (!options->initial.empty()) {
      const std::size_t set = calibrate::apply_initial_values(def.parameters, options->initial);
      std::cout << "initial values of " << set << " of " << def.parameters.size() << " parameters from "
                << options->initial << "\n";
      def.inputs.emplace_back(options->initial);
    }
    const std::filesystem::path out =
        options->out.empty() ? std::filesystem::path("fit-out") / def.file.stem() : std::filesystem::path(options->out);
    std::filesystem::create_directories(out);
    // A fit killed while it wrote leaves temporaries (atomic_file.hpp): they go first.
    for (const auto& folder : {out, out / "curves", out / "cache"}) remove_stale_temporaries(folder);
    if (options->threads >= 0) def.evaluation.threads = static_cast<unsigned>(options->threads);
    // The starts go side by side too; the evaluator keeps the runs at `threads` at once.
    def.fit.parallel_starts =
        def.evaluation.threads > 0 ? def.evaluation.threads : std::max(1u, std::thread::hardware_concurrency());
    if (def.disk_cache) def.evaluation.cache_directory = out / "cache";
    def.fit.checkpoint = out / "checkpoint.json";
    // A new fit's folder never shows an earlier fit's results beside its checkpoint.
    if (!options->resume)
      for (const char* stale : {"parameters.json", "parameters.h5", "fit_report.md", "fit_curves.png"})
        std::filesystem::remove(out / stale);
    def.fit.resume = options->resume;
    def.fit.progress = &std::cerr;
    stop_requested = false;
    def.fit.stop_requested = &stop_requested;
    // SIGTERM (a batch system, or the campaign runner's death: step_process.hpp) stops the fit
    // like Ctrl-C: after the running iteration, with its checkpoint saved.
    const auto previous_int = std::signal(SIGINT, request_stop);
    const auto previous_term = std::signal(SIGTERM, request_stop);
    const auto restore_signals = [&] {
      std::signal(SIGINT, previous_int);
      std::signal(SIGTERM, previous_term);
    };
    const std::string resume_command =
        "dtwire fit " + options->file + (options->targets.empty() ? "" : " --targets " + options->targets) +
        (options->initial.empty() ? "" : " --initial " + options->initial) + " --out " + out.string() + " --resume";
    calibrate::ProblemEvaluator evaluator(def.experiments, def.parameters, def.evaluation);
    calibrate::FitResult result;
    try {
      result = calibrate::run_fit(evaluator, def.fit);
    } catch (...) {
      restore_signals();
      throw;
    }
    restore_signals();
    // A stop that arrives during the last iteration lets the solve finish, but the results are
    // still not written: a step whose runner died never writes after it (the checkpoint holds
    // the finished starts, so the resume writes them without new runs).
    if (!result.completed || stop_requested) {
      std::cerr << "fit interrupted; continue with: " << resume_command << "\n";
      return kExitFailure;
    }
    std::string chosen;
    for (const auto& name : options->experiments) chosen += (chosen.empty() ? "" : ",") + name;
    const auto provenance = make_provenance(
        "dtwire fit " + options->file + (options->targets.empty() ? "" : " --targets " + options->targets) +
            (options->initial.empty() ? "" : " --initial " + options->initial) +
            (chosen.empty() ? "" : " --experiments " + chosen),
        def.inputs);
    try {
      calibrate::write_fit_outputs(def, result, provenance, out);
    } catch (const std::runtime_error& e) {
      throw std::runtime_error(std::string(e.what()) + "; no result written, the checkpoint is kept: once the "
                               "cause is fixed, " + resume_command + " writes the results");
    }
    std::cout << "fit " << def.file.filename().string() << ": cost " << result.cost << ", "
              << result.statistics.simulations << " simulation runs, " << result.wall_seconds
              << " s; parameters: " << (out / "parameters.json").string() << "\n";
    for (std::size_t i = 0; i < result.values.size(); ++i)
      std::cout << "  " << result.parameters[i].name << " = " << result.values[i]
                << (result.sigma.empty() ? std::string() : " +- " + std::to_string(result.sigma[i])) << " "
                << result.parameters[i].unit
                << (result.parameters[i].offset_from.empty() || i >= result.fitted_values.size()
                        ? std::string()
                        : " (fitted as " + result.parameters[i].offset_from + " + " +
                              std::to_string(result.fitted_values[i]) +
                              (i < result.fitted_sigma.size() ? " +- " + std::to_string(result.fitted_sigma[i]) : "") + ")")
                << (i < result.identification.size() && !result.identification[i].identified
                        ? "  NOT IDENTIFIED: " + result.identification[i].reason
                        : std::string())
                << "\n";
    if (!result.covariance_status.empty() && result.covariance_status != "positive definite")
      std::cout << "  covariance " << result.covariance_status << ": the +- are not standard errors\n";
    if (options->plot) {
      try {
        run_plot_script("plot_fit.py", {out.string()});
      } catch (const ComputationError& e) {
        std::cerr << "warning: " << e.what() << "; the fit results are written\n";
      }
    }
    return 0;
  });
}

}  // namespace dtwire::app
