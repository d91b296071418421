// `dtwire gap mesh-selfcheck --model F.toml` (issue 35): the mesh-scale diagnosis checked on
// DEM runs whose effect is known and withheld. Each trial runs the model with one mesh-level
// effect put in by the run's own input, mostly in a form the diagnosis does not fit (a
// distortion drawn per link, fitted as one uniform slack; a DT weakening that is not the same
// factor on N0 and Nult; a crimp that also softens bending), takes its summary figures (onset,
// peak force, its displacement; on request the force at a fraction of the base run's peak
// displacement) as the laboratory's with a 5 % scatter, and asks
// `gap --model F.toml --lab-summary` for the cause. One trial has no effect (its figures moved
// by half a standard deviation): the answer must be none. The runs share one cache folder.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <memory>
#include <sstream>

#include "../cli.hpp"
#include "../commands.hpp"
#include "dtwire/core/error.hpp"
#include "dtwire/gap/gap_report.hpp"
#include "dtwire/gap/loading_mode.hpp"
#include "dtwire/gap/summary_lab.hpp"
#include "gap_dem_model.hpp"
#include "text_output.hpp"
#include "option_checks.hpp"

namespace dtwire::app {
namespace {

struct MeshTrial {
  std::string name;
  std::string truth;  // the effect the diagnosis should find, or "none"
  std::string form;   // how it was put in, against what the diagnosis fits
  std::vector<std::string> set;  // `dem run --set` entries of the trial's "laboratory" run
  // Catalogue effects that are another side of the same change (a crimp softens the wire both
  // axially and in bending): naming one of them names the change too.
  std::vector<std::string> also_right = {};
};

bool named(const MeshTrial& trial, const std::string& cause) {
  return cause == trial.truth ||
         std::find(trial.also_right.begin(), trial.also_right.end(), cause) != trial.also_right.end();
}

// Laboratory scatter of each figure, as a fraction of its value.
constexpr double kScatter = 0.05;

std::vector<MeshTrial> mesh_trials() {
  const auto both = [](const std::string& key, const std::string& value) {
    return std::vector<std::string>{"links.sw." + key + "=" + value, "links.dt." + key + "=" + value};
  };
  std::vector<std::string> distortion = both("distortion", "\"random\"");
  for (const auto& e : both("distortion_lambda_u", "0.1")) distortion.push_back(e);
  distortion.push_back("links.sw.distortion_seed=11");
  distortion.push_back("links.dt.distortion_seed=12");
  std::vector<std::string> mild_distortion = both("distortion", "\"random\"");
  for (const auto& e : both("distortion_lambda_u", "0.05")) mild_distortion.push_back(e);
  mild_distortion.push_back("links.sw.distortion_seed=21");
  mild_distortion.push_back("links.dt.distortion_seed=22");
  // Magnitudes across each effect's plausible range (docs/gap.md, the range table): distortion at
  // its upper edge (0.1) and mid-range (0.05), the DT at its range's lower edge (0.5), the SW's
  // bending within its (0.05-1), so that a range drawn too narrow shows up as missed trials.
  return {
      {"distortion_random", "mesh_distortion",
       "lambda_u 0.1 drawn per link (triangular on [0, 1], seeds 11/12); fitted as one uniform slack", distortion},
      {"distortion_random_mid", "mesh_distortion",
       "lambda_u 0.05 drawn per link (triangular on [0, 1], seeds 21/22); fitted as one uniform slack",
       mild_distortion},
      {"edges_sliding", "edge_sliding", "slider supports (the fitted form itself: a two-valued effect)",
       {"boundary.support=\"slider\""}},
      {"slack_120mm", "slack_state", "wall 120 mm below, between the fitted runs",
       {"boundary.pretension_strain=0.0", "boundary.wall_below_m=0.12", "dynamics.settle_s=40.0"}},
      {"dt_unravelling", "dt_weakening", "DT N0 x 0.75, Nult x 0.6, W2 x 0.6; fitted as one factor on N0, Nult, W1 and W2",
       {"links.dt.scale.N0_N=0.75", "links.dt.scale.Nult_N=0.6", "links.dt.scale.W2_J=0.6"}},
      {"dt_weak_edge", "dt_weakening",
       "DT N0 x 0.5, Nult x 0.55, W1 and W2 x 0.5 (near the fitted form at its range's lower edge); fitted as "
       "one factor on N0, Nult, W1 and W2",
       {"links.dt.scale.N0_N=0.5", "links.dt.scale.Nult_N=0.55", "links.dt.scale.W1_J=0.5",
        "links.dt.scale.W2_J=0.5"}},
      {"sw_bending_soft", "sw_bending", "SW EI x 0.2 (the fitted form, inside its range)",
       {"links.sw.scale.EI_Nm2_per_deg_convention=0.2"}},
      {"sw_crimp", "sw_softening", "SW EA x 0.15 and EI x 0.5; fitted as a factor on EA or on EI alone",
       {"links.sw.scale.EA_N=0.15", "links.sw.scale.EI_Nm2_per_deg_convention=0.5"}, {"sw_bending"}},
      {"none", "none", "the model itself, its figures moved by half a standard deviation", {}}};
}

struct MeshOptions {
  std::string model, cache, json, report;
  std::vector<std::string> model_set, model_set_params;
  std::size_t model_runs = 4;  // a DEM response is far from linear in a mesh effect
  unsigned jobs = 1;
  // 0: onset, peak and its displacement only. A force on the steep loading branch with a 5 %
  // scatter outweighs the other figures (z up to 176 for a distortion) and, measured, lowers
  // the top-1 rate (docs/gap.md), so it is a study option.
  double force_at_fraction = 0.0;
};

}  // namespace

void add_gap_mesh_selfcheck_command(CLI::App& gap_command, CommandSet& commands) {
  auto o = std::make_shared<MeshOptions>();
  CLI::App* command = gap_command.add_subcommand(
      "mesh-selfcheck", "Check the mesh-scale diagnosis on DEM runs with a known effect withheld");
  command->footer("");  // the parent's footer is about --lab, --sim and --mode, which this has not
  command->add_option("--model", o->model, "DEM run (.toml, punch or strip tension): the base model")->required();
  command->add_option("--model-set", o->model_set, "A `dem run --set` entry of the base model (repeat)");
  command->add_option("--model-set-params", o->model_set_params, "A `dem run --set-params TAG=FILE` of the base model");
  command->add_option("--model-cache", o->cache, "Folder keeping the DEM runs (an interrupted check resumes)");
  command->add_option("--model-runs", o->model_runs, "Runs per effect (and search points per pair)")
      ->capture_default_str()
      ->check(CLI::Range(1, 20));
  command->add_option("--jobs", o->jobs, "Mesh effects searched side by side (one DEM run each)")
      ->capture_default_str()
      ->check(CLI::Range(1, 1024));
  command->add_option("--force-at-fraction", o->force_at_fraction,
                      "Fourth figure: the force at this fraction of the base run's peak displacement (0: none)")
      ->capture_default_str()
      ->check(finite_in(0.0, 0.99));
  command->add_option("--json", o->json, "Write every trial as JSON");
  command->add_option("--report", o->report, "Write a Markdown summary");
  commands.add(command, [o] {
    check_output_files({{"--json", o->json}, {"--report", o->report}});
    check_output_folders({{"--model-cache", o->cache}});
    const auto started = std::chrono::steady_clock::now();
    const std::filesystem::path cache =
        o->cache.empty() ? std::filesystem::temp_directory_path() / ("dtwire_mesh_selfcheck_" + std::to_string(::getpid()))
                         : std::filesystem::path(o->cache);
    const DemModelOptions base_options{o->model_set, o->model_set_params, cache};
    SimulationModel model = make_dem_model(o->model, base_options);
    const gap::ForceCurve base = model.run({});
    const std::string mode = gap::detect_loading_mode(model.run_curve({}), base, o->model).mode;
    // A punch: onset, peak and its displacement; a strip tension: the standard's figures
    // (strength per metre, secant stiffness) and the peak's displacement.
    std::vector<std::string> figures = mode == "panel_tension"
        ? std::vector<std::string>{"strength_N_per_m", "secant_stiffness_N_per_m", "peak_displacement_mm"}
        : std::vector<std::string>{"onset_displacement_mm", "peak_force_N", "peak_displacement_mm"};
    if (o->force_at_fraction > 0.0) {
      const double at_mm = std::round(o->force_at_fraction * gap::curve_feature(base, "peak_displacement_mm"));
      if (at_mm >= 1.0) figures.push_back(gap::force_at_feature_name(at_mm));
    }

    nlohmann::json trials = nlohmann::json::array();
    std::ostringstream table;
    table << "| trial | put in | truth | diagnosed | gap before (sd) | shrink |\n|---|---|---|---|---|---|\n";
    // As the wire-scale selfcheck: an effect whose figures move by less than the laboratory's
    // scatter is rightly read as none, so the rate that judges attribution counts the trials
    // above the floor; the rate over every trial is reported beside it.
    int singles = 0, found = 0, spurious_pairs = 0, none_right = 0, none_trials = 0;
    int singles_above = 0, found_above = 0, below_read_none = 0;
    std::vector<std::string> skipped;
    for (const MeshTrial& trial : mesh_trials()) {
      // An effect the model cannot show (a strip has no edges to slide, no sag to lose).
      if (const auto why = model.unsupported.find(trial.truth); why != model.unsupported.end()) {
        skipped.push_back(trial.name + " (" + why->second + ")");
        continue;
      }
      std::cout << "trial " << trial.name << "\n";
      DemModelOptions lab_options = base_options;
      for (const std::string& entry : trial.set) lab_options.set.push_back(entry);
      const gap::ForceCurve lab_curve = make_dem_model(o->model, lab_options).run({});
      std::vector<gap::SummaryFeature> lab;
      for (const std::string& name : figures) {
        double value = gap::curve_feature(lab_curve, name);
        if (trial.truth == "none") value *= 1.0 + 0.5 * kScatter;
        lab.push_back({name, value, kScatter * std::abs(value)});
      }
      gap::SummaryOptions options;
      for (const gap::EffectSpec& e : gap::effect_catalogue())
        if (const std::string why = gap::effect_inapplicable(e, mode, gap::curve_scale(base).max_displacement_m); !why.empty())
          options.inapplicable[e.name] = why;
      options.model = model.run;
      options.model_unsupported = model.unsupported;
      options.model_runs = o->model_runs;
      options.jobs = o->jobs;
      const gap::SummaryDiagnosis d = gap::diagnose_summary(base, lab, options);
      const double shrink = d.cause == "none" || d.ranking.empty() ? 0.0 : d.ranking.front().shrink;
      if (trial.truth == "none") {
        ++none_trials;
        none_right += d.cause == "none";
      } else {
        ++singles;
        found += named(trial, d.cause);
        spurious_pairs += d.cause.find('+') != std::string::npos;
        if (d.gap_before > d.noise_floor) {
          ++singles_above;
          found_above += named(trial, d.cause);
        } else {
          below_read_none += d.cause == "none";
        }
      }
      std::string truth = trial.truth;
      for (const std::string& also : trial.also_right) truth += " or " + also;
      table << "| " << trial.name << " | " << trial.form << " | " << truth << " | " << d.cause << " | "
            << d.gap_before << " | " << shrink << " |\n";
      trials.push_back({{"trial", trial.name}, {"truth", trial.truth}, {"also_right", trial.also_right},
                        {"form", trial.form}, {"set", trial.set}, {"diagnosed", d.cause}, {"reason", d.reason},
                        {"gap_before", d.gap_before}, {"shrink", shrink}, {"diagnosis", gap::summary_json(d)}});
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    const double top1 = singles ? static_cast<double>(found) / singles : 0.0;
    const double spurious = singles ? static_cast<double>(spurious_pairs) / singles : 0.0;
    const double top1_above = singles_above ? static_cast<double>(found_above) / singles_above : 0.0;
    std::ostringstream md;
    md << "### Mesh-scale selfcheck (`gap mesh-selfcheck`)\n\nModel `" << o->model << "` (" << mode
       << "); laboratory figures of each trial's run:";
    for (const std::string& name : figures) md << " " << name;
    md << ", scatter " << kScatter * 100 << " %. new DEM runs of the diagnoses: " << *model.runs << ", wall time " << seconds << " s.\n\n"
       << table.str() << "\n- top-1 rate, trials whose gap is above the scatter: " << found_above << "/"
       << singles_above << " = " << top1_above << "\n- top-1 rate, every trial with an effect: " << found << "/"
       << singles << " = " << top1 << "\n- right verdicts (the effect found above the scatter, none below it and "
       << "on the effect-free trials): " << found_above + below_read_none + none_right << "/" << singles + none_trials
       << "\n- spurious pairs "
       << spurious_pairs << "/" << singles << "\n- effect-free trials read as none " << none_right << "/" << none_trials
       << "\n";
    for (const std::string& why : skipped) md << "- not run, the model cannot show it: " << why << "\n";
    const nlohmann::json json = {{"model", o->model},     {"mode", mode},         {"scatter", kScatter},
                                 {"figures", figures},     {"top1_rate", top1},      {"spurious_pair_rate", spurious},
                                 {"top1_rate_above_scatter", top1_above}, {"trials_above_scatter", singles_above},
                                 {"right_verdicts", found_above + below_read_none + none_right},
                                 {"trials_run", singles + none_trials},
                                 {"none_right", none_right}, {"none_trials", none_trials},
                                 {"seconds", seconds},     {"trials", trials}, {"skipped", skipped}};
    gap::require_finite(json);
    write_text(o->json, json.dump(2) + "\n");
    write_text(o->report, md.str());
    std::cout << md.str();
    if (o->cache.empty()) std::filesystem::remove_all(cache);
    return 0;
  });
}

}  // namespace dtwire::app
