#include <CLI/CLI.hpp>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <map>
#include <optional>
#include <sstream>

#include <unistd.h>

#include "../cli.hpp"
#include "../plotting.hpp"
#include "../commands.hpp"
#include "text_output.hpp"
#include "../data_path.hpp"
#include "dtwire/core/error.hpp"
#include "dtwire/gap/diagnosis.hpp"
#include "dtwire/core/csv.hpp"
#include "dtwire/gap/gap_report.hpp"
#include "dtwire/gap/loading_mode.hpp"
#include "dtwire/gap/modes.hpp"
#include "dtwire/gap/selfcheck.hpp"
#include "dtwire/gap/summary_lab.hpp"
#include "gap_dem_model.hpp"
#include "gap_model_runner.hpp"
#include "option_checks.hpp"

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

// The run directory goes when empty (a failed run's directory is kept for diagnosis).
struct RemoveWhenEmpty {
  std::filesystem::path dir;
  ~RemoveWhenEmpty() {
    std::error_code ignored;
    if (!dir.empty()) std::filesystem::remove(dir, ignored);
  }
};

// `values` given once for all laboratory curves, or once per curve (in the order of --lab).
std::vector<std::string> per_lab(const std::vector<std::string>& values, std::size_t labs,
                                 const std::string& option, const std::string& what) {
  if (values.empty() || values.size() == labs) return values;
  if (values.size() == 1) return std::vector<std::string>(labs, values.front());
  throw InputError(option, std::to_string(values.size()) + " " + what + " for " + std::to_string(labs) +
                               " laboratory curves: give one " + option + " for all, or one per --lab in "
                               "the same order");
}

bool is_dem_model(const std::string& file) { return std::filesystem::path(file).extension() == ".toml"; }

// The loading mode a DEM model implies: its tool (a punch or a strip tension), read from the
// input without a run.
gap::ModeGuess dem_model_mode(const std::string& file, const DemModelOptions& options) {
  const std::string tool = read_dem_model(file, options).tool;
  return {tool == "platter" ? "punch" : "panel_tension", "--model " + file + " (tool.kind = \"" + tool + "\")"};
}

// A --mode that contradicts its --model is refused naming both: a DEM model is its tool's mesh
// test, an FE .prm a wire test (its wire mode is the user's to give).
void check_mode_against_model(const std::string& mode, const std::string& model, const DemModelOptions& dem) {
  if (model.empty()) return;
  if (is_dem_model(model)) {
    const gap::ModeGuess implied = dem_model_mode(model, dem);
    if (implied.mode != mode)
      throw InputError("--mode", "'" + mode + "' contradicts " + implied.basis + ", which is a " + implied.mode +
                                     " test: give --mode " + implied.mode + " or leave --mode out");
  } else if (gap::mesh_mode(mode)) {
    throw InputError("--mode", "'" + mode + "' is a mesh test, but --model " + model +
                                   " is an FE wire experiment (.prm): give a wire mode or a DEM --model (.toml)");
  }
}

// Writes the diagnosis's JSON and report, the input warnings (flagged, not refused) in both:
// `input_warnings` in the JSON, a warning line each at the report's head.
void write_diagnosis(const std::string& json_path, const std::string& report_path, nlohmann::json document,
                     std::string markdown, const std::vector<std::string>& warnings) {
  if (!warnings.empty()) {
    document["input_warnings"] = warnings;
    std::string flagged;
    for (const std::string& w : warnings) flagged += "> **Warning**: " + w + "\n\n";
    markdown = flagged + markdown;
  }
  write_text(json_path, document.dump(2) + "\n");
  write_text(report_path, markdown);
}

std::string png_for_mode(const std::string& png, const std::string& mode) {
  std::filesystem::path p(png);
  const std::string extension = p.extension().string();
  p.replace_extension();
  return p.string() + "_" + mode + (extension.empty() ? ".png" : extension);
}

}  // namespace

void add_gap_command(CLI::App& root, CommandSet& commands) {
  struct Options {
    std::vector<std::string> labs, sims, models, modes;
    std::string lab_summary, effects, columns, json, plot, report;
    std::vector<std::string> model_set, model_set_params;
    std::string model_cache;
    std::size_t model_runs = 3;
    unsigned jobs = 1;
    double gauge_mm = 0.0, area_mm2 = 0.0;
    bool no_pairs = false;
    unsigned seed = 1;
  };
  auto options = std::make_shared<Options>();
  CLI::App* command = root.add_subcommand(
      "gap", "Diagnose the gap between simulation and laboratory curves (where, which effect, how far)");
  command->footer(
      "Several loading modes: each --lab curve's mode is its CSV metadata `# loading_mode: ...`, "
      "else a mode name inside `# experiment: ...`, else its channels (moment/rotation/deflection "
      "-> bending, shear_* -> shear), else its force (both signs -> cyclic, mostly negative -> "
      "compression, else tension); --mode overrides. Curves are diagnosed per mode, and jointly: "
      "the JSON top level is the combined diagnosis (test-setup effects with one parameter set per "
      "mode, specimen effects shared over all modes) and \"modes\" lists each mode's diagnosis "
      "(mode, curves, gap_before, where, ranking, cause, ...). Give --sim (or --model) once for all "
      "curves of one mode, or once per --lab in the same order; curves of one mode must share their "
      "simulation. With several modes --plot OUT.png writes OUT_<mode>.png per mode.");
  command->add_option("--lab", options->labs, "Laboratory curve CSV (repeat for several)");
  command->add_option("--sim", options->sims,
                      "Simulated curve CSV (curve-only mode): once, or once per --lab");
  command->add_option("--model", options->models,
                      "FE experiment (.prm) re-run through `dtwire run`, or DEM run (.toml: punch or "
                      "strip tension) re-run through `dtwire dem run`, with model-only effects "
                      "switched on (the base run is the simulation unless --sim is given): once, or "
                      "once per --lab");
  command->add_option("--model-set", options->model_set,
                      "A `dem run --set TABLE.KEY=VALUE` entry of a DEM --model (repeat for several)");
  command->add_option("--model-set-params", options->model_set_params,
                      "A `dem run --set-params TAG=FILE` of a DEM --model (repeat for several)");
  command->add_option("--model-cache", options->model_cache,
                      "Folder keeping the DEM --model runs (reused by a later gap with the same inputs; "
                      "default: a temporary folder removed at the end)");
  command->add_option("--mode", options->modes,
                      "Loading mode of each --lab in order (comma-separated or repeated; one name "
                      "for all): " + gap::loading_mode_list() + " (default: from each curve)")
      ->delimiter(',');
  command->add_option("--lab-summary", options->lab_summary,
                      "Laboratory summary figures instead of curves, name=mean:sd,...: " +
                          gap::summary_feature_names() + " (e.g. peak_force_N=1510:196)");
  command->add_option("--model-runs", options->model_runs,
                      "FE runs per model-only effect with --lab-summary, and search points per pair "
                      "with a model-only effect (each at most one FE run)")->capture_default_str();
  command->add_option("--jobs", options->jobs,
                      "With --lab-summary: model-only effects searched side by side, each run a "
                      "process of its own (the diagnosis is the serial one); a DEM model's base run "
                      "takes this many threads")
      ->capture_default_str()
      ->check(CLI::Range(1, 1024));
  command->add_option("--effects", options->effects,
                      "Comma-separated effects to test (default: all that apply): " +
                          gap::effect_names());
  command->add_option("--json", options->json, "Write the diagnosis as JSON");
  command->add_option("--plot", options->plot, "Write a PNG of the curves, gap regions and best model");
  command->add_option("--report", options->report, "Write a Markdown summary");
  command->add_option("--gauge-mm", options->gauge_mm,
                      "Gauge length turning strain_1 columns into displacement")
      ->check(finite_positive());
  command->add_option("--area-mm2", options->area_mm2,
                      "Cross-section turning stress columns into force")
      ->check(finite_positive());
  command->add_option("--columns", options->columns,
                      "Displacement and force channels of every curve, names without unit "
                      "(e.g. tool_displacement,tool_force of a DEM run); default displacement,force");
  command->add_flag("--no-pairs", options->no_pairs, "Do not try pairs of effects");
  command->add_option("--seed", options->seed, "Seed of the multi-start fits")->capture_default_str()->check(unsigned_whole());

  commands.add(command, [options] {
    if (options->labs.empty() && options->lab_summary.empty())
      throw InputError("--lab", "give at least one laboratory curve (or --lab-summary)");
    if (!options->labs.empty() && !options->lab_summary.empty())
      throw InputError("--lab-summary", "give either --lab curves or --lab-summary figures, not both");
    if (options->sims.empty() && options->models.empty())
      throw InputError("--sim", "give the simulated curve (or --model)");
    if (!options->plot.empty() && options->lab_summary.empty()) require_plotting("plot_gap.py", "--plot");
    check_output_files({{"--json", options->json}, {"--report", options->report}});
    check_output_folders({{"--model-cache", options->model_cache}});
    check_plot_file(options->plot, "--plot");
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
    if (!options->columns.empty()) {
      const auto names = split_names(options->columns);
      if (names.size() != 2)
        throw InputError("--columns", "expected two channel names, displacement,force; found '" + options->columns + "'");
      conversion.displacement_channel = names[0];
      conversion.force_channel = names[1];
    }
    const bool dem_options_given = !options->model_set.empty() || !options->model_set_params.empty() ||
                                   !options->model_cache.empty();
    if (dem_options_given && std::none_of(options->models.begin(), options->models.end(), is_dem_model))
      throw InputError(!options->model_set.empty() ? "--model-set"
                       : !options->model_set_params.empty() ? "--model-set-params" : "--model-cache",
                       "applies to a DEM --model (.toml); give one");
    // One model per file (its runs cached across the modes that use it): FE for a .prm, DEM for a .toml.
    std::map<std::string, SimulationModel> fe_models;
    std::vector<RemoveWhenEmpty> cleanup;
    std::vector<std::filesystem::path> temporary_caches;  // removed after a diagnosis that ends well
    cleanup.reserve(options->models.size());
    const DemModelOptions dem_options{options->model_set, options->model_set_params, options->model_cache,
                                      options->jobs};
    const auto fe_model = [&](const std::string& file) -> SimulationModel& {
      auto found = fe_models.find(file);
      if (found == fe_models.end()) {
        if (is_dem_model(file)) {
          found = fe_models.emplace(file, make_dem_model(file, dem_options)).first;
          if (options->model_cache.empty()) temporary_caches.push_back(found->second.work);
        } else {
          const std::filesystem::path work = std::filesystem::temp_directory_path() /
              ("dtwire_gap_model_" + std::to_string(::getpid()) + "_" + std::to_string(fe_models.size()));
          found = fe_models.emplace(file, make_fe_model(file, work)).first;
          cleanup.push_back({found->second.work});
        }
      }
      return found->second;
    };
    const auto remove_temporary_caches = [&] {
      std::error_code ignored;
      for (const auto& dir : temporary_caches) std::filesystem::remove_all(dir, ignored);
    };
    const auto report_runs = [&] {
      for (const auto& [prm, fe] : fe_models)
        if (fe.runs) std::cout << (is_dem_model(prm) ? "DEM" : "FE") << " runs (" << prm << "): " << *fe.runs << "\n";
    };

    if (!options->lab_summary.empty()) {
      const std::vector<gap::SummaryFeature> summary = gap::parse_lab_summary(options->lab_summary);
      if (options->sims.size() > 1 || options->models.size() > 1)
        throw InputError(options->sims.size() > 1 ? "--sim" : "--model",
                         "--lab-summary compares one simulation: give --sim and --model at most once");
      if (!options->plot.empty())
        throw InputError("--plot", "not available with --lab-summary (no laboratory curve to draw)");
      if (options->modes.size() > 1)
        throw InputError("--mode", "--lab-summary compares one simulation: give one loading mode");
      if (!options->modes.empty() && !options->models.empty())
        check_mode_against_model(gap::parse_loading_mode(options->modes.front(), "--mode"), options->models.front(),
                                 dem_options);
      SimulationModel none;
      SimulationModel& fe = options->models.empty() ? none : fe_model(options->models.front());
      const gap::ForceCurve sim = !options->sims.empty() ? gap::load_force_curve(options->sims.front(), conversion)
                                                         : fe.run({});
      // The loading mode: --mode, else a DEM model's tool, else the simulated curve's (metadata,
      // channels, sign).
      const gap::ModeGuess mode =
          !options->modes.empty() ? gap::ModeGuess{gap::parse_loading_mode(options->modes.front(), "--mode"), "--mode"}
          : !options->models.empty() && is_dem_model(options->models.front())
              ? dem_model_mode(options->models.front(), dem_options)
          : !options->sims.empty() ? gap::detect_loading_mode(read_csv(options->sims.front()), sim, options->sims.front())
                                   : gap::detect_loading_mode(fe.run_curve({}), sim, options->models.front());
      gap::SummaryOptions summary_options;
      for (const gap::EffectSpec& e : gap::effect_catalogue())
        if (const std::string why = gap::effect_inapplicable(e, mode.mode, gap::curve_scale(sim).max_displacement_m);
            !why.empty())
          summary_options.inapplicable[e.name] = why;
      summary_options.effects = effects;
      summary_options.model = fe.run;
      summary_options.model_unsupported = fe.unsupported;
      summary_options.model_runs = options->model_runs;
      summary_options.jobs = options->jobs;
      summary_options.try_pairs = !options->no_pairs;
      summary_options.seed = options->seed;
      const std::vector<std::string> warnings = gap::summary_scale_warnings(summary, sim);
      for (const std::string& w : warnings) std::cerr << "warning: " << w << "\n";
      const gap::SummaryDiagnosis d = gap::diagnose_summary(sim, summary, summary_options);
      write_diagnosis(options->json, options->report, gap::summary_json(d), gap::summary_markdown(d), warnings);
      std::cout << "gap " << d.gap_before << " lab sd (noise floor " << d.noise_floor << "), cause: "
                << d.cause << " (" << d.reason << ")";
      if (!d.ranking.empty())
        std::cout << "; best: " << d.ranking.front().effect << ", shrink " << d.ranking.front().shrink;
      std::cout << "\n";
      report_runs();
      remove_temporary_caches();
      return 0;
    }

    const std::size_t n = options->labs.size();
    const auto sims = per_lab(options->sims, n, "--sim", "simulations");
    const auto models = per_lab(options->models, n, "--model", "models");
    const auto given_modes = per_lab(options->modes, n, "--mode", "loading modes");
    // Each laboratory curve's mode, then the curves grouped by mode (in order of appearance).
    std::vector<gap::ModeInput> inputs;
    std::vector<std::string> input_sim, input_model, input_first_lab;
    std::vector<std::string> input_warnings;  // flagged, not refused: the user may know better
    struct LabModes {
      std::size_t input = 0, index = 0;  // inputs[input].labs[index]
      std::optional<gap::ModeGuess> own;  // the curve's own (none if its metadata names no mode we know)
      gap::ModeGuess compared;
    };
    std::vector<LabModes> lab_modes;
    for (std::size_t k = 0; k < n; ++k) {
      const std::string& path = options->labs[k];
      const gap::ForceCurve lab = gap::load_force_curve(path, conversion);
      if (const std::string warning = gap::row_order_warning(lab); !warning.empty()) {
        std::cerr << "warning: " << warning << "\n";
        input_warnings.push_back(warning);
      }
      const std::string sim = sims.empty() ? "" : sims[k];
      const std::string model = models.empty() ? "" : models[k];
      // The mode: --mode (checked against the model); else the model's (a DEM input's tool; an
      // FE model's simulated curve: --sim, else its base run); else the laboratory curve's.
      gap::ModeGuess guess;
      if (!given_modes.empty()) {
        guess = {gap::parse_loading_mode(given_modes[k], "--mode"), "--mode"};
        check_mode_against_model(guess.mode, model, dem_options);
      } else if (!model.empty() && is_dem_model(model)) {
        guess = dem_model_mode(model, dem_options);
      } else if (!model.empty() && !sim.empty()) {
        const gap::ModeGuess of_sim = gap::detect_loading_mode(read_csv(sim), gap::load_force_curve(sim, conversion), sim);
        guess = {of_sim.mode, "--sim " + sim + " of --model " + model + " (" + of_sim.basis + ")"};
      } else if (!model.empty()) {
        SimulationModel& fe = fe_model(model);
        const Curve base = fe.run_curve({});
        const gap::ModeGuess of_run = gap::detect_loading_mode(base, fe.run({}), model);
        guess = {of_run.mode, "--model " + model + " (its run: " + of_run.basis + ")"};
      } else {
        guess = gap::detect_loading_mode(read_csv(path), lab, path);
      }
      auto in = std::find_if(inputs.begin(), inputs.end(), [&](const gap::ModeInput& i) { return i.mode == guess.mode; });
      if (in == inputs.end()) {
        inputs.push_back({guess.mode, guess.basis, {}, {}, {}, {}});
        input_sim.push_back(sim);
        input_model.push_back(model);
        input_first_lab.push_back(path);
        in = inputs.end() - 1;
      }
      const auto m = static_cast<std::size_t>(in - inputs.begin());
      if (input_sim[m] != sim || input_model[m] != model)
        throw InputError(input_sim[m] != sim ? "--sim" : "--model",
                         "laboratory curves " + input_first_lab[m] + " and " + path + " are both " + guess.mode +
                             " (" + guess.basis + ") but name different simulations: curves of one loading "
                             "mode share one simulation (or set their modes with --mode)");
      if (in->basis != guess.basis && in->basis.find(guess.basis) == std::string::npos)
        in->basis += "; " + guess.basis;
      in->labs.push_back(lab);
      LabModes modes{m, in->labs.size() - 1, std::nullopt, guess};
      try {
        modes.own = gap::detect_loading_mode(read_csv(path), lab, path);
      } catch (const InputError&) {
        // A mode name we do not know in the curve's metadata: the mode given or inferred stands.
      }
      lab_modes.push_back(modes);
    }
    if (inputs.size() > 1 && options->sims.size() <= 1 && options->models.size() <= 1)
      throw InputError("--sim", "the laboratory curves are of " + std::to_string(inputs.size()) +
                                    " loading modes (" + [&] {
                                      std::string list;
                                      for (const auto& i : inputs) list += (list.empty() ? "" : ", ") + i.mode;
                                      return list;
                                    }() + ") but one simulation was given: give one --sim (or --model) per --lab, "
                                          "in the same order");
    for (std::size_t m = 0; m < inputs.size(); ++m) {
      if (!input_model[m].empty()) {
        SimulationModel& fe = fe_model(input_model[m]);
        inputs[m].model = fe.run;
        inputs[m].model_unsupported = fe.unsupported;
      }
      inputs[m].sim = !input_sim[m].empty() ? gap::load_force_curve(input_sim[m], conversion) : inputs[m].model({});
    }
    for (const LabModes& l : lab_modes)
      for (const std::string& warning :
           gap::comparison_warnings(inputs[l.input].labs[l.index], l.own.value_or(l.compared), inputs[l.input].sim,
                                    l.compared)) {
        std::cerr << "warning: " << warning << "\n";
        input_warnings.push_back(warning);
      }
    gap::DiagnosisOptions diagnosis_options;
    diagnosis_options.effects = effects;
    diagnosis_options.try_pairs = !options->no_pairs;
    diagnosis_options.seed = options->seed;
    diagnosis_options.model_runs = options->model_runs;
    const gap::MultiModeDiagnosis result = gap::diagnose_modes(inputs, diagnosis_options);
    write_diagnosis(options->json, options->report, gap::multimode_json(result), gap::multimode_markdown(result),
                    input_warnings);
    const auto summary_line = [](const gap::Diagnosis& d) {
      std::ostringstream line;
      line << "gap " << d.gap_before << " (noise floor " << d.noise_floor << "), cause: " << d.cause << " ("
           << d.reason << ")";
      if (!d.ranking.empty())
        line << "; best: " << d.ranking.front().effect << ", shrink " << d.ranking.front().shrink;
      return line.str();
    };
    std::cout << (result.modes.size() > 1 ? "combined: " : "") << summary_line(result.combined) << "\n";
    if (result.modes.size() > 1)
      for (const gap::ModeDiagnosis& m : result.modes)
        std::cout << m.mode << " (" << m.diagnosis.labs.size() << " curves): " << summary_line(m.diagnosis) << "\n";
    const gap::Diagnosis& d = result.combined;
    if (!d.not_tested.empty()) {
      std::cout << "not tested:";
      for (const auto& name : d.not_tested) std::cout << " " << name << " (" << d.not_tested_reason.at(name) << ")";
      std::cout << "\n";
    }
    report_runs();
    if (!options->plot.empty()) {
      if (result.modes.size() == 1)
        render_plot(gap::plot_data_json(result.modes.front().diagnosis), options->plot);
      else
        for (const gap::ModeDiagnosis& m : result.modes)
          render_plot(gap::plot_data_json(m.diagnosis), png_for_mode(options->plot, m.mode));
    }
    remove_temporary_caches();
    return 0;
  });

  add_gap_features_command(*command, commands);
  add_gap_mesh_selfcheck_command(*command, commands);

  struct SelfcheckOptions {
    gap::SelfcheckOptions run;
    std::string json, report;
    bool require_goals = false;
  };
  auto self = std::make_shared<SelfcheckOptions>();
  self->run.backbone_csv = data_path("experiments/data/sw_2.7mm_dem_backbone.csv").string();
  CLI::App* selfcheck = command->add_subcommand(
      "selfcheck", "Inject effects into model curves, withhold them, and check the diagnosis");
  selfcheck->footer("");  // the parent's footer is about --lab, --sim and --mode, which this has not
  selfcheck->add_option("--trials", self->run.trials, "Trials per single effect")->capture_default_str()->check(CLI::Range(0, 100000));
  selfcheck->add_option("--pair-trials", self->run.pair_trials, "Trials with two effects")->capture_default_str()->check(CLI::Range(0, 100000));
  selfcheck->add_option("--none-trials", self->run.none_trials, "Effect-free trials")->capture_default_str()->check(CLI::Range(0, 100000));
  selfcheck->add_option("--seed", self->run.seed, "Random seed")->capture_default_str()->check(unsigned_whole());
  selfcheck->add_option("--family", self->run.family,
                        "Effect generators: fitted (the fitted augmentations) or independent (other physical forms, "
                        "realistic measurement chain, repeated specimens)")
      ->check(CLI::IsMember({"fitted", "independent"}))
      ->capture_default_str();
  selfcheck->add_option("--repeats", self->run.repeats, "Independent family: laboratory curves (specimens) per trial")
      ->check(CLI::Range(1, 5))
      ->capture_default_str();
  selfcheck->add_option("--backbone", self->run.backbone_csv, "DEM backbone CSV used as a base model")
      ->capture_default_str();
  selfcheck->add_option("--write-curves", self->run.curves_dir,
                        "Write every trial's simulation and laboratory curves to DIR/trial_NNN_<truth>/ (the JSON's "
                        "trial order), to diagnose a miss again with gap --lab ... --sim ...");
  selfcheck->add_option("--effects", self->run.effects,
                        "Comma-separated single effects to trial (and to draw pairs from); default: all of them")
      ->delimiter(',');
  selfcheck->add_option("--json", self->json, "Write the figures and every trial as JSON");
  selfcheck->add_option("--report", self->report, "Write a Markdown summary");
  selfcheck->add_flag("--require-goals", self->require_goals, "Exit 1 when a goal is missed");
  commands.add(selfcheck, [self] {
    check_output_files({{"--json", self->json}, {"--report", self->report}});
    check_output_folders({{"--write-curves", self->run.curves_dir}});
    // A backbone that is not there would leave half the trials out without a word.
    if (!self->run.backbone_csv.empty() && !std::filesystem::is_regular_file(self->run.backbone_csv))
      throw InputError("--backbone", "no such file: '" + self->run.backbone_csv.string() +
                                         "' (expected the DEM backbone CSV; --backbone '' runs the Voce base alone)");
    if (const std::filesystem::path& dir = self->run.curves_dir; !dir.empty() && std::filesystem::exists(dir)) {
      if (!std::filesystem::is_directory(dir))
        throw InputError("--write-curves", "'" + dir.string() + "' is a file; give a folder");
      if (!std::filesystem::is_empty(dir))
        throw InputError("--write-curves", "'" + dir.string() +
                                               "' is not empty (an earlier run's trials would mix with this one's); "
                                               "give a new or empty folder");
    }
    for (const std::string& name : self->run.effects)
      if (std::find(gap::selfcheck_effects().begin(), gap::selfcheck_effects().end(), name) ==
          gap::selfcheck_effects().end()) {
        std::string known;
        for (const std::string& k : gap::selfcheck_effects()) known += (known.empty() ? "" : ", ") + k;
        throw InputError("--effects", "'" + name + "' is no curve-mode effect (expected one of " + known + ")");
      }
    if (self->run.pair_trials > 0 && !self->run.effects.empty() && self->run.effects.size() < 2)
      throw InputError("--pair-trials", "pairs need at least two --effects (give --pair-trials 0 for one effect)");
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
