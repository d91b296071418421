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
    std::string sim, model, effects, json, plot, report;
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
                      "FE experiment (.prm) to re-run with effects switched on (needs fem)");
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
    if (!options->model.empty())
      throw ComputationError("gap --model: re-running FE experiments needs the fem module, "
                             "not in this build yet; use --sim with a finished curve");
    if (options->labs.empty()) throw InputError("--lab", "give at least one laboratory curve");
    if (options->sim.empty()) throw InputError("--sim", "give the simulated curve (or --model)");
    gap::CurveConversion conversion;
    if (options->gauge_mm > 0) conversion.gauge_length_m = options->gauge_mm * 1e-3;
    if (options->area_mm2 > 0) conversion.area_m2 = options->area_mm2 * 1e-6;
    std::vector<gap::ForceCurve> labs;
    for (const auto& lab : options->labs) labs.push_back(gap::load_force_curve(lab, conversion));
    const gap::ForceCurve sim = gap::load_force_curve(options->sim, conversion);
    gap::DiagnosisOptions diagnosis_options;
    try {
      for (const auto& name : split_names(options->effects)) {
        gap::find_effect(name);
        diagnosis_options.effects.push_back(name);
      }
    } catch (const std::invalid_argument& e) {
      throw InputError("--effects", e.what());
    }
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
      std::cout << "not tested (need --model):";
      for (const auto& n : d.not_tested) std::cout << " " << n;
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
