// `dtwire gap features --model DT.prm`: the DT tension model against what the laboratory shows
// besides its curve (issue 17): the tightening toe and where the specimen fails. The model runs
// as it is and with each model-only effect at the end of its plausible range farthest from
// neutral; the report says how far each moved the toe (gap/dt_features.hpp: toe compensation of
// ISO 527-1 / ASTM D638), the force at 0.5 mm and the failure's place and mode.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <cmath>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>

#include "../cli.hpp"
#include "../commands.hpp"
#include "dtwire/core/axis_csv.hpp"
#include "dtwire/core/error.hpp"
#include "dtwire/core/prm_document.hpp"
#include "dtwire/gap/curve_metrics.hpp"
#include "dtwire/gap/dt_features.hpp"
#include "dtwire/gap/effects.hpp"
#include "gap_model_runner.hpp"
#include "text_output.hpp"

namespace dtwire::app {
namespace {

struct FeaturesOptions {
  std::string model, effects, lab_failure, axis, json, report;
  bool lab_toe = false;
};

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

std::string fixed(double value, int digits) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(digits) << value;
  return s.str();
}

std::string markdown(const std::vector<RunFeatures>& runs, const FeaturesOptions& o) {
  std::ostringstream md;
  md << "# DT tension against the laboratory's features\n\n"
     << "Model: `" << o.model << "`. The laboratory shows"
     << (o.lab_toe ? " a tightening toe (soft initial branch)" : " no stated toe")
     << (o.lab_failure.empty() ? "" : (o.lab_toe ? " and" : ";") + std::string(" failure in the ") + o.lab_failure)
     << ". Each model-only effect at the end of its plausible range farthest from neutral; toe by the "
        "toe compensation of ISO 527-1 / ASTM D638 (steepest chord below half the peak, extended to zero force).\n\n"
     << "| effect | strength | toe (mm) | force at 0.5 mm (N) | peak (kN) | failure at (mm) | failure z (mm) | zone | mode |\n"
     << "|---|---|---|---|---|---|---|---|---|\n";
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
       << (r.failure ? r.failure->mode : "-") << " |\n";
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
  return md.str();
}

nlohmann::json to_json(const std::vector<RunFeatures>& runs, const FeaturesOptions& o) {
  nlohmann::json j;
  j["model"] = o.model;
  j["laboratory"] = {{"toe", o.lab_toe}, {"failure_zone", o.lab_failure}};
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
  return j;
}

}  // namespace

void add_gap_features_command(CLI::App& gap_command, CommandSet& commands) {
  auto o = std::make_shared<FeaturesOptions>();
  CLI::App* c = gap_command.add_subcommand(
      "features", "DT tension model against the laboratory's toe and failure zone, with each model-only effect");
  c->add_option("--model", o->model, "The DT tension experiment (.prm)")->required()->check(CLI::ExistingFile);
  c->add_option("--effects", o->effects, "Model-only effects to try (default: every one the .prm supports)");
  c->add_option("--lab-failure", o->lab_failure, "Where the laboratory specimens fail")
      ->check(CLI::IsMember({"twist", "junction", "arm"}));
  c->add_flag("--lab-toe", o->lab_toe, "The laboratory curves show a tightening toe");
  c->add_option("--axis", o->axis, "The mesh's axis file (default: the .prm's mesh file with .axis.csv)");
  c->add_option("--json", o->json, "Write the figures as JSON");
  c->add_option("--report", o->report, "Write a Markdown report");
  commands.add(c, [o] {
    SimulationModel model = make_fe_model(o->model);
    std::filesystem::path axis = o->axis;
    if (axis.empty()) {
      const auto mesh = PrmDocument::read(o->model).get("Geometry/Mesh file");
      if (!mesh || mesh->empty()) throw InputError(o->model, "no 'Geometry/Mesh file': give --axis");
      axis = (std::filesystem::absolute(o->model).parent_path() / *mesh).replace_extension(".axis.csv");
    }
    const auto stations = read_axis_stations(axis);
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
