// The summary diagnosis written out: its JSON (the figures, the ranking with each effect's model
// runs and their wall time) and its Markdown report.
#include <algorithm>
#include <sstream>

#include "dtwire/gap/gap_report.hpp"
#include "dtwire/gap/summary_lab.hpp"

namespace dtwire::gap {
namespace {

// Parameter names with their values; `<effect>.<parameter>` for a pair.
std::vector<std::pair<std::string, double>> named_params(const SummaryCandidate& c, const CurveScale& scale) {
  std::vector<std::pair<std::string, double>> out;
  for (const AppliedEffect& a : c.fitted) {
    const auto specs = a.effect->parameters(scale);
    for (std::size_t j = 0; j < specs.size(); ++j)
      out.emplace_back((c.fitted.size() > 1 ? a.effect->name + "." : std::string()) + specs[j].name, a.params[j]);
  }
  return out;
}

}  // namespace

nlohmann::json summary_json(const SummaryDiagnosis& d) {
  const CurveScale scale = curve_scale(d.sim);
  nlohmann::json where = nlohmann::json::array();
  double total = 0.0;
  std::vector<double> z2;
  for (std::size_t i = 0; i < d.lab.size(); ++i) {
    const double z = (d.sim_features[i] - d.lab[i].mean) / d.lab[i].sd;
    z2.push_back(z * z);
    total += z * z;
  }
  const auto peak = std::max_element(d.sim.f.begin(), d.sim.f.end()) - d.sim.f.begin();
  nlohmann::json lab = nlohmann::json::array();
  for (std::size_t i = 0; i < d.lab.size(); ++i) {
    const std::string& name = d.lab[i].name;
    const auto force_at_mm = force_at_displacement_mm(name);
    // The onsets are read where the simulated force first reaches their level: before the peak.
    const bool onset = name == "onset_displacement_mm" || displacement_at_force_N(name).has_value();
    const bool at_peak = name != "residual_force_N" && !force_at_mm && !onset;
    const double peak_u = d.sim.u[static_cast<std::size_t>(peak)];
    const double at = force_at_mm ? *force_at_mm * 1e-3 : onset ? d.sim_features[i] * 1e-3 : at_peak ? peak_u : d.sim.u.back();
    const double z = (d.sim_features[i] - d.lab[i].mean) / d.lab[i].sd;
    const std::string region = at_peak ? "peak" : (force_at_mm || onset) && at < peak_u ? "pre_peak" : "post_peak";
    const bool displacement = name.size() > 3 && name.compare(name.size() - 3, 3, "_mm") == 0;
    where.push_back({{"region", region},
                     {"from_mm", at * 1e3},
                     {"to_mm", at * 1e3},
                     {"share", total > 0 ? z2[i] / total : 1.0 / static_cast<double>(d.lab.size())},
                     {"direction", displacement                         ? "horizontal offset"
                                   : name == "secant_stiffness_N_per_m" ? "slope"
                                                                        : "vertical offset"},
                     {"feature", d.lab[i].name},
                     {"z", z}});
    lab.push_back({{"feature", d.lab[i].name}, {"mean", d.lab[i].mean}, {"sd", d.lab[i].sd},
                   {"simulated", d.sim_features[i]}});
  }
  nlohmann::json ranking = nlohmann::json::array();
  for (const SummaryCandidate& c : d.ranking) {
    nlohmann::json params = nlohmann::json::object();
    for (const auto& [name, value] : named_params(c, scale)) params[name] = value;
    ranking.push_back({{"effect", c.effect}, {"params", params}, {"gap_after", c.gap_after},
                       {"shrink", c.shrink}, {"score", c.score}, {"plausibility", c.plausibility}, {"implausible", c.implausible},
                       {"aic", c.aic}, {"parameters", c.parameters},
                       {"features_after", c.features}, {"fe_runs", c.runs}, {"model_seconds", c.model_seconds},
                       {"fitted_peak_at_curve_end", fitted_peak_at_end(c)}, {"qualifies", c.qualifies}});
    if (!c.at_range_edge.empty()) ranking.back()["at_plausible_edge"] = beyond_range_json(c.at_range_edge);
    if (c.implausible) {
      ranking.back()["beyond_plausible_range"] = beyond_range_json(c.beyond_range);
      ranking.back()["qualifies_but_implausible"] = c.qualifies_but_implausible;
    }
    if (!c.peak_at_end.empty()) {
      nlohmann::json values = nlohmann::json::array();
      for (const auto& v : c.peak_at_end) values.push_back(v.size() == 1 ? nlohmann::json(v.front()) : nlohmann::json(v));
      ranking.back()["peak_at_curve_end"] = values;
    }
    if (!c.samples.empty()) {
      nlohmann::json samples = nlohmann::json::array();
      for (const auto& [v, f] : c.samples)
        samples.push_back({{"value", v.size() == 1 ? nlohmann::json(v.front()) : nlohmann::json(v)}, {"features", f}});
      ranking.back()["fe_samples"] = samples;
    }
  }
  nlohmann::json out = {{"metric", d.metric},       {"noise_floor", d.noise_floor},
                        {"gap_before", d.gap_before}, {"where", where},
                        {"ranking", ranking},       {"cause", d.cause},
                        {"cause_reason", d.reason}, {"also_closes", d.also_closes},
                        {"compression", d.compression},
                        {"not_tested", d.not_tested}, {"not_tested_reason", d.not_tested_reason},
                        {"lab_summary", lab},       {"sim", d.sim.source}, {"verdict", d.verdict}};
  int runs = 0;
  double seconds = 0.0;
  for (const SummaryCandidate& c : d.ranking) {
    runs += c.runs;
    seconds += c.model_seconds;
  }
  out["model_runs"] = runs;
  out["model_seconds"] = seconds;
  out["model_elapsed_seconds"] = d.model_elapsed_seconds;
  for (const SummaryCandidate& c : d.ranking)
    if (c.effect == d.refused_effect)
      out["refused_for_magnitude"] = {{"effect", c.effect}, {"shrink", c.shrink},
                                      {"beyond_plausible_range", beyond_range_json(c.beyond_range)}};
  require_finite(out);
  return out;
}

std::string summary_markdown(const SummaryDiagnosis& d) {
  std::ostringstream s;
  s.precision(4);
  s << "### Gap diagnosis against laboratory summary figures\n\n"
    << "Simulation `" << d.sim.source << "`; gap = rms of (simulated - laboratory mean) / "
    << "laboratory sd over the features; noise floor " << d.noise_floor << " (one sd).\n\n"
    << "| feature | laboratory mean | sd | simulated | z |\n|---|---|---|---|---|\n";
  for (std::size_t i = 0; i < d.lab.size(); ++i)
    s << "| " << d.lab[i].name << " | " << d.lab[i].mean << " | " << d.lab[i].sd << " | "
      << d.sim_features[i] << " | " << (d.sim_features[i] - d.lab[i].mean) / d.lab[i].sd << " |\n";
  s << "\n- gap before: " << d.gap_before << "\n- **cause: " << d.cause << "** (" << d.reason << ")\n";
  if (!d.not_tested.empty()) {
    s << "- not tested:";
    for (const auto& n : d.not_tested) s << " " << n << " (" << d.not_tested_reason.at(n) << ");";
    s << "\n";
  }
  int runs = 0;
  for (const SummaryCandidate& c : d.ranking) runs += c.runs;
  if (runs > 0)
    s << "- model runs of the searches (each value at most one run, cached runs free): " << runs << " in "
      << d.model_elapsed_seconds << " s of wall time\n";
  s << "\n| effect | fitted | features after | gap after | shrink | plausibility | model runs (s) |\n"
    << "|---|---|---|---|---|---|---|\n";
  const CurveScale scale = curve_scale(d.sim);
  for (const SummaryCandidate& c : d.ranking) {
    s << "| " << c.effect << (c.implausible ? " (implausible)" : !c.at_range_edge.empty() ? " (at its range's edge)" : "")
      << (fitted_peak_at_end(c) ? " (peak at the curve's end)" : "") << " | ";
    for (const auto& [name, value] : named_params(c, scale)) s << name << " " << value << " ";
    s << "| ";
    for (double f : c.features) s << f << " ";
    s << "| " << c.gap_after << " | " << c.shrink << " | " << c.plausibility << " | " << c.runs;
    if (c.runs > 0) s << " (" << c.model_seconds << ")";
    s << " |\n";
  }
  for (const SummaryCandidate& c : d.ranking) {
    if (c.samples.empty()) continue;
    std::string names;
    for (const AppliedEffect& a : c.fitted)
      if (a.effect->needs_model) names += (names.empty() ? "" : ", ") + a.effect->parameters(scale).front().name;
    s << "\nModel runs of " << c.effect << " (" << names << " -> features, rms z):";
    for (const auto& [v, f] : c.samples) {
      for (double x : v) s << " " << x;
      s << " ->";
      for (double x : f) s << " " << x;
      s << " (" << summary_gap(d.lab, f)
        << (std::find(c.peak_at_end.begin(), c.peak_at_end.end(), v) != c.peak_at_end.end() ? ", peak at the curve's end" : "")
        << ");";
    }
    s << "\n";
    if (!c.peak_at_end.empty())
      s << "(peak at the curve's end: the run ended before the specimen failed, so its peak figures are lower bounds "
           "of the failure's.)\n";
  }
  return s.str();
}

}  // namespace dtwire::gap
