#include <CLI/CLI.hpp>

#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <sstream>

#include "../cli.hpp"
#include "../plotting.hpp"
#include "../commands.hpp"
#include "dtwire/core/atomic_file.hpp"
#include "dtwire/core/error.hpp"
#include "dtwire/gap/diagnosis.hpp"
#include "dtwire/gap/gap_report.hpp"
#include "dtwire/gap/selfcheck.hpp"
#include "dtwire/gap/summary_lab.hpp"
#include "gap_model_runner.hpp"
#include "dtwire/version.hpp"

namespace dtwire::app {
namespace {

std::vector<std::string> split_names(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream s(text);
  std::string part;
  while (std::getline(s, part, ','))
    if (!part.empty()) out.push_back(part);
  return out;
}

void write_text(const std::string& path, const std::string& text) {
  if (path.empty()) return;
  const std::filesystem::path target(path);
  if (target.has_parent_path()) std::filesystem::create_directories(target.parent_path());
  write_file_atomically(target, [&](std::ostream& out) { out << text; });
}

void render_plot(const nlohmann::json& data, const std::string& png) {
  const std::filesystem::path target(png);
  if (target.has_parent_path()) std::filesystem::create_directories(target.parent_path());
  std::filesystem::path data_file = target;
  data_file.replace_extension(".plot.json");
  write_text(data_file.string(), data.dump());
  try {
    run_plot_script("plot_gap.py", {data_file.string(), target.string()});
  } catch (const ComputationError& e) {
    throw ComputationError(std::string(e.what()) + "; the plot data is in " + data_file.string());
  }
}

}  // namespace

void add_gap_command(CLI::App& root, CommandSet& commands) {
  struct Options {
    std::vector<std::string> labs;
    std::string sim, model, lab_summary, effects, json, plot, report;
    std::size_t model_runs = 3;
    double gauge_mm = 0.0, area_mm2 = 0.0;
    bool no_pairs = false;
    unsigned seed = 1;
  };
  auto options = std::make_shared<Options>();
  CLI::App* command = root.add_subcommand(
      "gap", "Diagnose the gap between simulation and laboratory curves (where, which effect, how far)");
  command->add_option("--lab", options->labs, "Laboratory curve CSV (repeat for several)");
  command->add_option("--sim", options->sim, "Simulated curve CSV (curve-only mode)");
  command->add_option("--model", options->model,
                      "FE experiment (.prm) re-run through `dtwire run` with model-only effects "
                      "switched on (the base run is the simulation unless --sim is given)");
  command->add_option("--lab-summary", options->lab_summary,
                      "Laboratory summary figures instead of curves, name=mean:sd,...: " +
                          gap::summary_feature_names() + " (e.g. peak_force_N=1510:196)");
  command->add_option("--model-runs", options->model_runs,
                      "FE runs per model-only effect with --lab-summary")->capture_default_str();
  command->add_option("--effects", options->effects,
                      "Comma-separated effects to test (default: all that apply): " +
                          gap::effect_names());
  command->add_option("--json", options->json, "Write the diagnosis as JSON");
  command->add_option("--plot", options->plot, "Write a PNG of the curves, gap regions and best model");
  command->add_option("--report", options->report, "Write a Markdown summary");
  command->add_option("--gauge-mm", options->gauge_mm,
                      "Gauge length turning strain_1 columns into displacement");
  command->add_option("--area-mm2", options->area_mm2,
                      "Cross-section turning stress columns into force");
  command->add_flag("--no-pairs", options->no_pairs, "Do not try pairs of effects");
  command->add_option("--seed", options->seed, "Seed of the multi-start fits")->capture_default_str();

  commands.add(command, [options] {
    if (options->labs.empty() && options->lab_summary.empty())
      throw InputError("--lab", "give at least one laboratory curve (or --lab-summary)");
    if (!options->labs.empty() && !options->lab_summary.empty())
      throw InputError("--lab-summary", "give either --lab curves or --lab-summary figures, not both");
    if (options->sim.empty() && options->model.empty())
      throw InputError("--sim", "give the simulated curve (or --model)");
    std::vector<gap::SummaryFeature> summary;
    if (!options->lab_summary.empty()) summary = gap::parse_lab_summary(options->lab_summary);
    std::vector<std::string> effects;
    try {
      for (const auto& name : split_names(options->effects)) {
        gap::find_effect(name);
        effects.push_back(name);
      }
    } catch (const std::invalid_argument& e) {
      throw InputError("--effects", e.what());
    }
    gap::CurveConversion conversion;
    if (options->gauge_mm > 0) conversion.gauge_length_m = options->gauge_mm * 1e-3;
    if (options->area_mm2 > 0) conversion.area_m2 = options->area_mm2 * 1e-6;
    std::vector<gap::ForceCurve> labs;
    for (const auto& lab : options->labs) labs.push_back(gap::load_force_curve(lab, conversion));
    FeModel fe;
    if (!options->model.empty()) fe = make_fe_model(options->model);
    // The run directory goes when empty (a failed run's directory is kept for diagnosis).
    struct RemoveWhenEmpty {
      std::filesystem::path dir;
      ~RemoveWhenEmpty() {
        std::error_code ignored;
        if (!dir.empty()) std::filesystem::remove(dir, ignored);
      }
    } cleanup{fe.work};
    const gap::ForceCurve sim = !options->sim.empty() ? gap::load_force_curve(options->sim, conversion)
                                                      : fe.run({});
    if (!summary.empty()) {
      gap::SummaryOptions summary_options;
      summary_options.effects = effects;
      summary_options.model = fe.run;
      summary_options.model_unsupported = fe.unsupported;
      summary_options.model_runs = options->model_runs;
      summary_options.seed = options->seed;
      const gap::SummaryDiagnosis d = gap::diagnose_summary(sim, summary, summary_options);
      write_text(options->json, gap::summary_json(d).dump(2) + "\n");
      write_text(options->report, gap::summary_markdown(d));
      std::cout << "gap " << d.gap_before << " lab sd (noise floor " << d.noise_floor << "), cause: "
                << d.cause << " (" << d.reason << ")";
      if (!d.ranking.empty())
        std::cout << "; best: " << d.ranking.front().effect << ", shrink " << d.ranking.front().shrink;
      std::cout << "\n";
      if (fe.runs) std::cout << "FE runs: " << *fe.runs << "\n";
      if (!options->plot.empty())
        throw InputError("--plot", "not available with --lab-summary (no laboratory curve to draw)");
      return 0;
    }
    gap::DiagnosisOptions diagnosis_options;
    diagnosis_options.effects = effects;
    diagnosis_options.model = fe.run;
    diagnosis_options.model_unsupported = fe.unsupported;
    diagnosis_options.try_pairs = !options->no_pairs;
    diagnosis_options.seed = options->seed;
    const gap::Diagnosis d = gap::diagnose(labs, sim, diagnosis_options);
    const nlohmann::json json = gap::diagnosis_json(d);
    write_text(options->json, json.dump(2) + "\n");
    write_text(options->report, gap::diagnosis_markdown(d));
    std::cout << "gap " << d.gap_before << " (noise floor " << d.noise_floor << "), cause: " << d.cause
              << " (" << d.reason << ")";
    if (!d.ranking.empty())
      std::cout << "; best: " << d.ranking.front().effect << ", shrink " << d.ranking.front().shrink;
    std::cout << "\n";
    if (!d.not_tested.empty()) {
      std::cout << "not tested:";
      for (const auto& n : d.not_tested) std::cout << " " << n << " (" << d.not_tested_reason.at(n) << ")";
      std::cout << "\n";
    }
    if (!options->plot.empty()) render_plot(gap::plot_data_json(d), options->plot);
    return 0;
  });

  struct SelfcheckOptions {
    gap::SelfcheckOptions run;
    std::string json, report;
    bool require_goals = false;
  };
  auto self = std::make_shared<SelfcheckOptions>();
  self->run.backbone_csv = std::string(kSourceDir) + "/experiments/data/sw_2.7mm_dem_backbone.csv";
  CLI::App* selfcheck = command->add_subcommand(
      "selfcheck", "Inject effects into model curves, withhold them, and check the diagnosis");
  selfcheck->add_option("--trials", self->run.trials, "Trials per single effect")->capture_default_str();
  selfcheck->add_option("--pair-trials", self->run.pair_trials, "Trials with two effects")->capture_default_str();
  selfcheck->add_option("--none-trials", self->run.none_trials, "Effect-free trials")->capture_default_str();
  selfcheck->add_option("--seed", self->run.seed, "Random seed")->capture_default_str();
  selfcheck->add_option("--backbone", self->run.backbone_csv, "DEM backbone CSV used as a base model")
      ->capture_default_str();
  selfcheck->add_option("--json", self->json, "Write the figures and every trial as JSON");
  selfcheck->add_option("--report", self->report, "Write a Markdown summary");
  selfcheck->add_flag("--require-goals", self->require_goals, "Exit 1 when a goal is missed");
  commands.add(selfcheck, [self] {
    const gap::SelfcheckResult result = gap::run_selfcheck(self->run);
    const nlohmann::json json = gap::selfcheck_json(result);
    gap::require_finite(json);
    write_text(self->json, json.dump(2) + "\n");
    const std::string markdown = gap::selfcheck_markdown(result);
    write_text(self->report, markdown);
    std::cout << markdown;
    return self->require_goals && !result.goals_met ? kExitFailure : 0;
  });
}

}  // namespace dtwire::app
