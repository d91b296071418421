#include "dtwire/gap/gap_report.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "dtwire/core/error.hpp"
#include "dtwire/gap/loading_mode.hpp"

namespace dtwire::gap {
namespace {

// `<parameter>`, `<effect>.<parameter>` for a pair; in the combined ranking of several loading
// modes a test-setup effect's parameters are per mode: `<mode>.<parameter>`.
nlohmann::json params_json(const RankedEffect& r, const CurveScale& scale) {
  nlohmann::json out = nlohmann::json::object();
  auto add = [&](const std::vector<AppliedEffect>& fitted, const std::string& mode) {
    for (const AppliedEffect& a : fitted) {
      const auto specs = a.effect->parameters(scale);
      const std::string prefix = (r.fitted.size() > 1 ? a.effect->name + "." : std::string()) +
                                 (!mode.empty() && effect_per_mode(*a.effect) ? mode + "." : std::string());
      for (std::size_t i = 0; i < specs.size(); ++i) out[prefix + specs[i].name] = a.params[i];
    }
  };
  if (r.fitted_by_mode.empty()) add(r.fitted, "");
  for (const auto& [mode, fitted] : r.fitted_by_mode) add(fitted, mode);
  return out;
}

nlohmann::json curve_json(const ForceCurve& c) {
  std::vector<double> u, f;
  for (std::size_t i = 0; i < c.size(); ++i) {
    u.push_back(c.u[i] * 1e3);
    f.push_back(c.f[i]);
  }
  return {{"source", c.source}, {"displacement_mm", u}, {"force_N", f}};
}

}  // namespace

void require_finite(const nlohmann::json& value, const std::string& path) {
  if (value.is_number_float() && !std::isfinite(value.get<double>()))
    throw ComputationError("gap: the result " + path + " is not a finite number");
  if (value.is_object())
    for (const auto& [key, item] : value.items()) require_finite(item, path + "/" + key);
  if (value.is_array())
    for (std::size_t i = 0; i < value.size(); ++i) require_finite(value[i], path + "/" + std::to_string(i));
}

namespace {

bool uses_model(const RankedEffect& r) {
  return std::any_of(r.fitted.begin(), r.fitted.end(), [](const AppliedEffect& a) { return a.effect->needs_model; });
}

// Values run by the searches of the model-only candidates (each at most one model run) and
// their wall time.
std::pair<int, double> model_cost(const Diagnosis& d) {
  int runs = 0;
  double seconds = 0.0;
  for (const RankedEffect& r : d.ranking) {
    runs += r.model_runs;
    seconds += r.model_seconds;
  }
  return {runs, seconds};
}

}  // namespace

nlohmann::json beyond_range_json(const std::vector<BeyondRange>& beyond) {
  nlohmann::json out = nlohmann::json::array();
  for (const BeyondRange& b : beyond)
    out.push_back({{"effect", b.effect}, {"parameter", b.parameter}, {"value", b.value},
                   {"plausible", {b.plausible_lower, b.plausible_upper}}});
  return out;
}

nlohmann::json diagnosis_json(const Diagnosis& d) {
  const CurveScale scale = curve_scale(d.sim);
  nlohmann::json where = nlohmann::json::array();
  for (const GapSegment& g : d.where) {
    where.push_back({{"region", g.region},
                     {"from_mm", g.from_m * 1e3},
                     {"to_mm", g.to_m * 1e3},
                     {"share", g.share},
                     {"direction", g.direction},
                     {"gap", g.gap}});
    if (!g.mode.empty()) where.back()["mode"] = g.mode;
  }
  nlohmann::json ranking = nlohmann::json::array();
  for (const RankedEffect& r : d.ranking) {
    ranking.push_back({{"effect", r.effect},
                       {"params", params_json(r, scale)},
                       {"gap_after", r.gap_after},
                       {"shrink", r.shrink},
                       {"score", r.score},
                       {"aicc", r.aicc},
                       {"delta_aicc", r.delta_aicc},
                       {"bic", r.bic},
                       {"plausibility", r.plausibility},
                       {"region_match", r.region_match},
                       {"frechet_after", r.frechet_after},
                       {"pcm_after", r.pcm_after},
                       {"gap_after_by_region", r.gap_after_by_segment},
                       {"parameters", r.parameters},
                       {"qualifies", r.qualifies},
                       {"implausible", r.implausible}});
    if (r.search_points > 0) ranking.back()["search_points"] = r.search_points;
    if (uses_model(r)) {
      ranking.back()["model_runs"] = r.model_runs;
      ranking.back()["model_seconds"] = r.model_seconds;
    }
    if (!r.at_range_edge.empty()) ranking.back()["at_plausible_edge"] = beyond_range_json(r.at_range_edge);
    if (r.implausible) {
      ranking.back()["beyond_plausible_range"] = beyond_range_json(r.beyond_range);
      ranking.back()["qualifies_but_implausible"] = r.qualifies_but_implausible;
    }
    if (r.against_single.done) {
      const PairEvidence& e = r.against_single;
      nlohmann::json j = {{"single", e.single}, {"lag1_autocorrelation", e.lag1},
                          {"effective_sample_size", e.n_eff}, {"bic_single", e.bic_single},
                          {"bic_pair", e.bic_pair}, {"information_ok", e.information_ok},
                          {"heldout_done", e.heldout_done}};
      if (e.heldout_done) {
        j["heldout_error_single"] = e.heldout_error_single;
        j["heldout_error_pair"] = e.heldout_error_pair;
        j["heldout_ok"] = e.heldout_ok;
      }
      ranking.back()["against_single"] = j;
      ranking.back()["also_possible"] = r.also_possible;
    }
    if (!r.fitted_by_mode.empty()) {
      std::vector<std::string> modes;
      for (const auto& [mode, fitted] : r.fitted_by_mode) modes.push_back(mode);
      ranking.back()["modes"] = modes;
    }
  }
  nlohmann::json labs = nlohmann::json::array();
  for (const ForceCurve& lab : d.labs) labs.push_back(lab.source);
  nlohmann::json predictive = {{"done", d.predictive.done}};
  if (d.predictive.done) {
    predictive["effect"] = d.predictive.effect;
    predictive["fitted_on"] = d.predictive.fitted_on;
    predictive["predicted"] = d.predictive.predicted;
    predictive["gap_before"] = d.predictive.gap_before;
    predictive["gap_after"] = d.predictive.gap_after;
    predictive["shrink"] = d.predictive.shrink;
  } else {
    predictive["note"] = d.predictive.note;
  }
  nlohmann::json out = {{"metric", d.metric},
                        {"noise_floor", d.noise_floor},
                        {"gap_before", d.gap_before},
                        {"where", where},
                        {"ranking", ranking},
                        {"cause", d.cause},
                        {"cause_reason", d.reason},
                        {"also_closes", d.also_closes},
                        {"noise_sigma_N", d.noise_sigma_N},
                        {"frechet_before", d.frechet_before},
                        {"pcm_before", d.pcm_before},
                        {"effective_sample_size", d.effective_sample_size},
                        {"lag1_autocorrelation", d.lag1_autocorrelation},
                        {"compression", d.compression},
                        {"not_tested", d.not_tested},
                        {"not_tested_reason", d.not_tested_reason},
                        {"predictive_check", predictive},
                        {"lab", labs},
                        {"sim", d.sim.source}};
  if (d.scatter_gap >= 0) out["scatter_gap"] = d.scatter_gap;
  if (d.aligned_scatter_gap >= 0) {
    out["aligned_scatter_gap"] = d.aligned_scatter_gap;
    out["gap_before_unadjusted"] = d.gap_before_unadjusted;
    out["specimen_scale_bounds"] = {{"force_1", d.specimen_force_bound},
                                    {"displacement_1", d.specimen_length_bound}};
  }
  // Per laboratory curve (in "lab" order): where it broke, 0 when it ended without a fracture's
  // drop (its damage on the law's own clock).
  out["lab_fracture_m"] = d.fracture_m;
  out["verdict"] = d.verdict;
  const auto [runs, seconds] = model_cost(d);
  out["model_runs"] = runs;
  out["model_seconds"] = seconds;
  std::vector<std::string> also_possible;
  for (const RankedEffect& r : d.ranking) {
    if (r.also_possible) also_possible.push_back(r.effect);
    if (r.effect == d.refused_effect)
      out["refused_for_magnitude"] = {{"effect", r.effect}, {"shrink", r.shrink}, {"gap_after", r.gap_after},
                                      {"beyond_plausible_range", beyond_range_json(r.beyond_range)}};
  }
  out["also_possible"] = also_possible;
  require_finite(out);
  return out;
}

std::string diagnosis_markdown(const Diagnosis& d) {
  std::ostringstream s;
  s.precision(3);
  s << "### Gap diagnosis\n\n"
    << "Simulation `" << d.sim.source << "` against " << d.labs.size() << " laboratory curve(s)";
  for (const ForceCurve& lab : d.labs) s << " `" << lab.source << "`";
  s << ".\n\n"
    << "- gap before (area between curves on normalised axes): " << d.gap_before
    << "; discrete Frechet distance " << d.frechet_before << "; partial curve mapping "
    << d.pcm_before << "\n"
    << "- noise floor: " << d.noise_floor << " (load noise " << d.noise_sigma_N << " N"
    << (d.scatter_gap >= 0 ? ", scatter between the laboratory curves " + std::to_string(d.scatter_gap) +
                                 ", " + std::to_string(d.aligned_scatter_gap) + " once aligned by scale" : std::string())
    << ")\n"
    << "- **cause: " << d.cause << "** (" << d.reason << ")\n";
  for (const RankedEffect& r : d.ranking)
    if (r.also_possible)
      s << "- also possible: " << r.effect << " (fits better than " << r.against_single.single
        << " but fails the parsimony rule: BIC " << r.against_single.bic_pair << " against "
        << r.against_single.bic_single << " on " << r.against_single.n_eff << " effective points"
        << (r.against_single.heldout_done ? ", held-out error " + std::to_string(r.against_single.heldout_error_pair) +
                                                " against " + std::to_string(r.against_single.heldout_error_single)
                                          : std::string())
        << ")\n";
  if (!d.not_tested.empty()) {
    s << "- not tested:";
    for (const auto& n : d.not_tested) {
      const auto why = d.not_tested_reason.find(n);
      s << " " << n << (why != d.not_tested_reason.end() ? " (" + why->second + ")" : std::string()) << ";";
    }
    s << "\n";
  }
  if (const auto [runs, seconds] = model_cost(d); runs > 0) {
    s << "- model runs of the searches (each value at most one run, cached runs free): " << runs << ", "
      << seconds << " s:";
    for (const RankedEffect& r : d.ranking)
      if (uses_model(r)) s << " " << r.effect << " " << r.model_runs << " (" << r.model_seconds << " s);";
    s << "\n";
  }
  if (d.predictive.done)
    s << "- predictive check: " << d.predictive.effect << " fitted on `" << d.predictive.fitted_on
      << "` shrinks the gap of `" << d.predictive.predicted << "` from " << d.predictive.gap_before
      << " to " << d.predictive.gap_after << " (shrink " << d.predictive.shrink << ")\n";
  else
    s << "- predictive check: not done (" << d.predictive.note << ")\n";
  const bool modes = !d.where.empty() && !d.where.front().mode.empty();  // combined over modes
  s << "\n|" << (modes ? " mode |" : "") << " region | from mm | to mm | share | direction |\n|"
    << (modes ? "---|" : "") << "---|---|---|---|---|\n";
  for (const GapSegment& g : d.where)
    s << "| " << (modes ? g.mode + " | " : std::string()) << g.region << " | " << g.from_m * 1e3 << " | "
      << g.to_m * 1e3 << " | " << g.share << " | " << g.direction << " |\n";
  s << "\n| effect | gap after | shrink | score | dAICc | plausibility | region match |\n"
    << "|---|---|---|---|---|---|---|\n";
  constexpr std::size_t kShown = 10;  // the JSON has them all
  for (std::size_t k = 0; k < d.ranking.size() && k < kShown; ++k) {
    const RankedEffect& r = d.ranking[k];
    s << "| " << r.effect << (r.implausible ? " (implausible)" : "") << " | " << r.gap_after << " | " << r.shrink << " | " << r.score << " | "
      << r.delta_aicc << " | " << r.plausibility << " | " << r.region_match << " |\n";
  }
  if (d.ranking.size() > kShown)
    s << "\n(" << d.ranking.size() - kShown << " more candidates in the JSON)\n";
  return s.str();
}

nlohmann::json plot_data_json(const Diagnosis& d) {
  nlohmann::json labs = nlohmann::json::array();
  for (const ForceCurve& lab : d.labs) labs.push_back(curve_json(lab));
  nlohmann::json regions = nlohmann::json::array();
  for (const GapSegment& g : d.where)
    regions.push_back({{"region", g.region}, {"from_mm", g.from_m * 1e3}, {"to_mm", g.to_m * 1e3},
                       {"share", g.share}, {"direction", g.direction}});
  const std::string best = d.cause != "none" ? d.cause
                           : d.ranking.empty() ? std::string("simulation")
                                               : d.ranking.front().effect + " (not significant)";
  nlohmann::json out = {{"labs", labs},
                        {"sim", curve_json(d.sim)},
                        {"best", curve_json(d.best_model)},
                        {"best_label", "simulation + " + best},
                        {"regions", regions},
                        {"cause", d.cause},
                        {"gap_before", d.gap_before},
                        {"noise_floor", d.noise_floor}};
  require_finite(out);
  return out;
}

}  // namespace dtwire::gap
