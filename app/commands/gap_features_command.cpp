// `dtwire gap features --model DT.prm`: the DT tension model against what the laboratory shows
// besides its curve (issues 17, 50): the tightening toe, where the specimen fails and its peak.
// The model runs as it is and with each model-only effect at the end of its plausible range
// farthest from neutral; the report says how far each moved the toe (gap/dt_features.hpp: toe
// compensation of ISO 527-1 / ASTM D638), the force at 0.5 mm, the failure's place and mode and
// the peak, and which effect puts the failure where the laboratory's is, nearest its peak
// (gap::explain_features).
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <cmath>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>
#include <tuple>

#include "../cli.hpp"
#include "../commands.hpp"
#include "dtwire/core/axis_csv.hpp"
#include "dtwire/core/csv.hpp"
#include "dtwire/core/error.hpp"
#include "dtwire/core/prm_document.hpp"
#include "dtwire/gap/curve_metrics.hpp"
#include "dtwire/gap/dt_features.hpp"
#include "dtwire/gap/effects.hpp"
#include "gap_model_runner.hpp"
#include "text_output.hpp"
#include "option_checks.hpp"

namespace dtwire::app {
namespace {

struct FeaturesOptions {
  std::string model, effects, lab_failure, lab_peak, lab_curve, axis, json, report, model_cache;
  double lab_peak_sd = 0.0;
  std::vector<std::string> model_set;
  bool lab_toe = false;
  gap::LabFeatures lab;  // the stated failure zone and peak, parsed
};

// --lab-peak F:SD (N): the laboratory's peak force and its standard deviation.
std::pair<double, double> parse_lab_peak(const std::string& text) {
  const auto colon = text.find(':');
  double peak = 0.0, sd = 0.0;
  try {
    if (colon == std::string::npos) throw std::invalid_argument(text);
    std::size_t used = 0;
    peak = std::stod(text.substr(0, colon), &used);
    if (used != colon) throw std::invalid_argument(text);
    sd = std::stod(text.substr(colon + 1), &used);
    if (used != text.size() - colon - 1) throw std::invalid_argument(text);
  } catch (const std::exception&) {
    throw InputError("--lab-peak", "'" + text + "': expected PEAK_N:SD_N, e.g. 5000:500");
  }
  if (!(peak > 0.0) || !(sd > 0.0) || !std::isfinite(peak) || !std::isfinite(sd))
    throw InputError("--lab-peak", "'" + text + "': the peak and its standard deviation must be positive (N)");
  return {peak, sd};
}

struct RunFeatures {
  std::string effect = "none";
  double strength = 0.0;
  std::string error;  // the run failed: why
  double toe_m = 0.0, force_at_half_mm = 0.0, peak_force = 0.0;
  std::optional<gap::ReportedFailure> failure;
  gap::FailureZone zone = gap::FailureZone::unknown;
};

// (height, curvature magnitude) of every station of the mesh's axis file.
std::vector<std::pair<double, double>> read_axis_stations(const std::filesystem::path& file) {
  std::vector<std::pair<double, double>> stations;
  for (const auto& wire : read_axis_csv(file))
    for (const AxisStation& s : wire)
      stations.emplace_back(s.point[2], std::hypot(s.curvature[0], s.curvature[1], s.curvature[2]));
  return stations;
}

RunFeatures features_of(const Curve& curve, const std::vector<std::pair<double, double>>& stations) {
  RunFeatures r;
  gap::ForceCurve c;
  c.u = curve.si("displacement");
  c.f = curve.si("force");
  r.toe_m = gap::toe_length(c);
  r.force_at_half_mm = gap::interpolate_clamped(c.u, c.f, 0.5e-3);
  for (const double f : c.f) r.peak_force = std::max(r.peak_force, f);
  r.failure = gap::parse_reported_failure(curve.metadata("failure"));
  if (r.failure) r.zone = gap::failure_zone(r.failure->z, stations);
  return r;
}

bool peak_stated(const FeaturesOptions& o) { return o.lab.peak_sd > 0.0; }

gap::FeatureRun feature_run(const RunFeatures& r) {
  return {r.effect, !r.error.empty(), r.peak_force, r.zone};
}

gap::FeatureVerdict verdict_of(const std::vector<RunFeatures>& runs, const FeaturesOptions& o) {
  std::vector<gap::FeatureRun> read;
  for (const auto& r : runs) read.push_back(feature_run(r));
  return gap::explain_features(read, o.lab);
}

double peak_gap_sd(const RunFeatures& r, const FeaturesOptions& o) {
  return std::abs(r.peak_force - o.lab.peak_force) / o.lab.peak_sd;
}

std::string fixed(double value, int digits) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(digits) << value;
  return s.str();
}

std::string joined(const std::vector<std::string>& parts, const std::string& separator) {
  std::string text;
  for (const std::string& part : parts) text += (text.empty() ? "" : separator) + part;
  return text;
}

std::string markdown(const std::vector<RunFeatures>& runs, const FeaturesOptions& o) {
  std::ostringstream md;
  md << "# DT tension against the laboratory's features\n\n"
     << "Model: `" << o.model << "`. The laboratory shows"
     << (o.lab_toe ? " a tightening toe (soft initial branch)" : " no stated toe")
     << (o.lab_failure.empty() ? "" : (o.lab_toe ? " and" : ";") + std::string(" failure in the ") + o.lab_failure)
     << (o.lab_curve.empty() ? "" : " (read from `" + o.lab_curve + "`)")
     << (!peak_stated(o) ? "" : "; a peak of " + fixed(1e-3 * o.lab.peak_force, 2) + " kN (sd " +
                                       fixed(1e-3 * o.lab.peak_sd, 2) + " kN)")
     << (o.model_set.empty() ? "" : ". The model with `" + joined(o.model_set, "`, `") + "`")
     << ". Each model-only effect at the end of its plausible range farthest from neutral; toe by the "
        "toe compensation of ISO 527-1 / ASTM D638 (steepest chord below half the peak, extended to zero force).\n\n"
     << "| effect | strength | toe (mm) | force at 0.5 mm (N) | peak (kN) | failure at (mm) | failure z (mm) | zone | mode |"
     << (!peak_stated(o) ? "" : " peak gap (sd) |") << "\n"
     << "|---|---|---|---|---|---|---|---|---|" << (!peak_stated(o) ? "" : "---|") << "\n";
  const RunFeatures& base = runs.front();
  for (const auto& r : runs) {
    if (!r.error.empty()) {
      md << "| " << r.effect << " | " << r.strength << " | run failed: " << r.error << " ||||||\n";
      continue;
    }
    md << "| " << r.effect << " | " << (r.effect == "none" ? "-" : fixed(r.strength, 3)) << " | " << fixed(1e3 * r.toe_m, 3)
       << " | " << fixed(r.force_at_half_mm, 0) << " | " << fixed(1e-3 * r.peak_force, 3) << " | "
       << (r.failure ? fixed(1e3 * r.failure->displacement, 2) : "no failure") << " | "
       << (r.failure ? fixed(1e3 * r.failure->z, 1) : "-") << " | " << gap::zone_name(r.zone) << " | "
       << (r.failure ? r.failure->mode : "-") << " |"
       << (!peak_stated(o) ? "" : " " + fixed(peak_gap_sd(r, o), 2) + " |") << "\n";
  }
  md << "\n## Diagnosis\n\n";
  bool toe_found = false, zone_found = false;
  for (std::size_t k = 1; k < runs.size(); ++k) {
    const auto& r = runs[k];
    if (!r.error.empty() || !base.error.empty()) continue;
    const double toe_change = 1e3 * (r.toe_m - base.toe_m);
    const bool moves_zone = !o.lab_failure.empty() && r.zone != base.zone && gap::zone_name(r.zone) == o.lab_failure;
    toe_found = toe_found || (o.lab_toe && toe_change > 0.1);
    zone_found = zone_found || moves_zone;
    md << "- `" << r.effect << "`: toe " << (toe_change >= 0 ? "+" : "") << fixed(toe_change, 3) << " mm, force at 0.5 mm "
       << (r.force_at_half_mm >= base.force_at_half_mm ? "+" : "") << fixed(r.force_at_half_mm - base.force_at_half_mm, 0)
       << " N; failure " << (r.failure && base.failure
                                 ? "moved by " + fixed(1e3 * (r.failure->z - base.failure->z), 1) + " mm in z (" +
                                       gap::zone_name(base.zone) + " -> " + gap::zone_name(r.zone) + ")"
                                 : std::string("not comparable (no failure in one of the runs)"))
       << ".\n";
  }
  md << "\n";
  if (o.lab_toe)
    md << (toe_found ? "A toe of more than 0.1 mm appears with at least one effect above.\n"
                     : "No effect tried produces a toe of more than 0.1 mm: the laboratory's toe is not explained by "
                       "these effects at their plausible strengths.\n");
  if (!o.lab_failure.empty())
    md << (zone_found ? "At least one effect moves the failure into the laboratory's zone (" + o.lab_failure + ").\n"
                      : "No effect tried moves the failure into the laboratory's zone (" + o.lab_failure +
                            "): the cause is outside these model effects (e.g. the resolution of the junction's "
                            "contact, the twisting of each wire about its own axis, a clamp at the junction).\n");
  if (!o.lab_failure.empty() || peak_stated(o)) {
    const gap::FeatureVerdict v = verdict_of(runs, o);
    md << "\n**Which:** ";
    if (v.effect == "none") {
      md << "no effect tried " << (o.lab_failure.empty() ? "" : "puts the failure in the " + o.lab_failure)
         << (!o.lab_failure.empty() && peak_stated(o) ? " and " : "")
         << (!peak_stated(o) ? "" : "brings the peak nearer the laboratory's") << ".\n";
    } else {
      md << "`" << v.effect << "`" << (o.lab_failure.empty() ? "" : " puts the failure in the " + o.lab_failure);
      if (peak_stated(o))
        md << (o.lab_failure.empty() ? "" : " and") << " takes the peak's gap from " << fixed(v.gap_before_sd, 2) << " to "
           << fixed(v.gap_after_sd, 2) << " sd (shrink " << fixed(v.shrink, 2) << "; "
           << (v.within_scatter ? "within the laboratory's scatter" : "not to the laboratory's scatter") << ")";
      md << (v.candidates.size() > 1 ? "; the other effects that do so: " : ".");
      for (std::size_t k = 0, shown = 0; k < v.candidates.size(); ++k)
        if (v.candidates[k] != v.effect) md << (shown++ ? ", `" : "`") << v.candidates[k] << "`";
      md << (v.candidates.size() > 1 ? ".\n" : "\n");
    }
  }
  return md.str();
}

nlohmann::json to_json(const std::vector<RunFeatures>& runs, const FeaturesOptions& o) {
  nlohmann::json j;
  j["model"] = o.model;
  j["laboratory"] = {{"toe", o.lab_toe}, {"failure_zone", o.lab_failure}};
  if (peak_stated(o)) j["laboratory"]["peak"] = {{"force_N", o.lab.peak_force}, {"sd_N", o.lab.peak_sd}};
  j["model_set"] = o.model_set;
  for (const auto& r : runs) {
    nlohmann::json e = {{"effect", r.effect}, {"strength", r.strength}};
    if (!r.error.empty()) {
      e["error"] = r.error;
    } else {
      e["toe_mm"] = 1e3 * r.toe_m;
      e["force_at_0_5_mm_N"] = r.force_at_half_mm;
      e["peak_force_N"] = r.peak_force;
      e["failure_zone"] = gap::zone_name(r.zone);
      if (r.failure)
        e["failure"] = {{"mode", r.failure->mode}, {"displacement_mm", 1e3 * r.failure->displacement},
                        {"z_mm", 1e3 * r.failure->z}};
    }
    j["runs"].push_back(e);
  }
  if (!o.lab_failure.empty() || peak_stated(o)) {
    const gap::FeatureVerdict v = verdict_of(runs, o);
    j["verdict"] = {{"effect", v.effect}, {"candidates", v.candidates}};
    if (peak_stated(o))
      j["verdict"].update({{"peak_gap_before_sd", v.gap_before_sd}, {"peak_gap_after_sd", v.gap_after_sd},
                           {"shrink", v.shrink}, {"within_scatter", v.within_scatter}});
  }
  return j;
}

}  // namespace

void add_gap_features_command(CLI::App& gap_command, CommandSet& commands) {
  auto o = std::make_shared<FeaturesOptions>();
  CLI::App* c = gap_command.add_subcommand(
      "features", "DT tension model against the laboratory's toe and failure zone, with each model-only effect");
  c->footer("");  // the parent's footer is about --lab, --sim and --mode, which this has not
  c->add_option("--model", o->model, "The DT tension experiment (.prm)")->required()->check(CLI::ExistingFile);
  c->add_option("--effects", o->effects, "Model-only effects to try (default: every one the .prm supports)");
  c->add_option("--lab-failure", o->lab_failure, "Where the laboratory specimens fail")
      ->check(CLI::IsMember({"twist", "junction", "arm"}));
  c->add_flag("--lab-toe", o->lab_toe, "The laboratory curves show a tightening toe");
  c->add_option("--lab-peak", o->lab_peak, "The laboratory's peak force and its standard deviation, PEAK_N:SD_N");
  c->add_option("--lab-curve", o->lab_curve,
                "A DT tension curve in the laboratory's role (CSV): its peak, and its failure's zone when the curve "
                "reports one (`# failure:`, an FE run) and --lab-failure is not given")
      ->check(CLI::ExistingFile);
  c->add_option("--lab-peak-sd", o->lab_peak_sd, "The standard deviation of --lab-curve's peak (N)")
      ->check(finite_positive());
  c->add_option("--model-cache", o->model_cache,
                "Keep every FE run's curve in this folder and take it from there next time (resume, share runs)");
  c->add_option("--model-set", o->model_set,
                "Section/Entry=value: change the model itself before any effect (repeatable), e.g. "
                "'Material/Failure locus=johnson-cook'");
  c->add_option("--axis", o->axis, "The mesh's axis file (default: the .prm's mesh file with .axis.csv)");
  c->add_option("--json", o->json, "Write the figures as JSON");
  c->add_option("--report", o->report, "Write a Markdown report");
  commands.add(c, [o] {
    check_output_files({{"--json", o->json}, {"--report", o->report}});
    check_output_folders({{"--model-cache", o->model_cache}});
    if (!o->lab_peak.empty()) std::tie(o->lab.peak_force, o->lab.peak_sd) = parse_lab_peak(o->lab_peak);
    for (const gap::FailureZone zone : {gap::FailureZone::twist, gap::FailureZone::junction, gap::FailureZone::arm})
      if (gap::zone_name(zone) == o->lab_failure) o->lab.zone = zone;
    if (!o->lab_curve.empty() && !o->lab_peak.empty())
      throw InputError("--lab-curve", "give the laboratory's peak either as --lab-peak or from --lab-curve, not both");
    if (o->lab_curve.empty() != !(o->lab_peak_sd > 0.0))
      throw InputError(o->lab_curve.empty() ? "--lab-peak-sd" : "--lab-curve",
                       "--lab-curve and --lab-peak-sd go together (the curve's peak and its standard deviation)");
    SimulationModel model = make_fe_model(o->model, {}, o->model_set, o->model_cache);
    std::filesystem::path axis = o->axis;
    if (axis.empty()) {
      const auto mesh = PrmDocument::read(o->model).get("Geometry/Mesh file");
      if (!mesh || mesh->empty()) throw InputError(o->model, "no 'Geometry/Mesh file': give --axis");
      axis = (std::filesystem::absolute(o->model).parent_path() / *mesh).replace_extension(".axis.csv");
    }
    const auto stations = read_axis_stations(axis);
    if (!o->lab_curve.empty()) {
      const Curve lab_curve = read_csv(o->lab_curve);
      if (!lab_curve.has("displacement") || !lab_curve.has("force"))
        throw InputError(o->lab_curve, "expected displacement_<length unit> and force_<force unit> columns (a DT tension curve)");
      const RunFeatures lab = features_of(lab_curve, stations);
      o->lab.peak_force = lab.peak_force;
      o->lab.peak_sd = o->lab_peak_sd;
      if (!(lab.peak_force > 0.0)) throw InputError(o->lab_curve, "no positive force: no peak to hold the model to");
      if (o->lab_failure.empty() && lab.failure && lab.zone != gap::FailureZone::unknown) {
        o->lab.zone = lab.zone;
        o->lab_failure = gap::zone_name(lab.zone);
      }
    }
    std::vector<std::string> names;
    if (o->effects.empty()) {
      for (const auto& e : gap::effect_catalogue())
        if (e.needs_model && !model.unsupported.count(e.name) && e.name != "coating_slip") names.push_back(e.name);
    } else {
      std::stringstream s(o->effects);
      for (std::string name; std::getline(s, name, ',');) {
        try {
          if (!gap::find_effect(name).needs_model)
            throw InputError("--effects", name + " acts on a curve; `gap features` re-runs the FE model with model-only effects");
        } catch (const std::invalid_argument& e) {
          throw InputError("--effects", e.what());
        }
        if (const auto why = model.unsupported.find(name); why != model.unsupported.end())
          throw InputError("--effects", name + ": " + why->second);
        names.push_back(name);
      }
    }
    std::vector<RunFeatures> runs;
    const auto run = [&](const std::vector<gap::AppliedEffect>& effects, const std::string& name, double p) {
      RunFeatures r;
      try {
        r = features_of(model.run_curve(effects), stations);
      } catch (const ComputationError& e) {
        r.error = e.what();
      }
      r.effect = name;
      r.strength = p;
      runs.push_back(r);
    };
    run({}, "none", 0.0);
    // Without the model's own run there is nothing to hold the effects against (and a value the
    // solver refuses, e.g. from --model-set, would fail every run the same way).
    if (!runs.front().error.empty())
      throw ComputationError("the model as it is did not run (" + runs.front().error +
                             "); no effect was tried");
    for (const auto& name : names) {
      const gap::EffectSpec& effect = gap::find_effect(name);
      const gap::ParameterSpec spec = effect.parameters(gap::CurveScale{}).at(effect.magnitude);
      const double p = std::abs(spec.plausible_upper - effect.neutral) >= std::abs(spec.plausible_lower - effect.neutral)
                           ? spec.plausible_upper
                           : spec.plausible_lower;
      run({{&effect, {p}}}, name, p);
    }
    const nlohmann::json json = to_json(runs, *o);
    write_text(o->json, json.dump(2) + "\n");
    const std::string md = markdown(runs, *o);
    write_text(o->report, md);
    std::cout << md;
    return 0;
  });
}

}  // namespace dtwire::app
