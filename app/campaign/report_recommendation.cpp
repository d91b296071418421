#include "report_recommendation.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <tuple>

#include "dtwire/gap/force_curve.hpp"
#include "dtwire/gap/summary_lab.hpp"
#include "report_summary.hpp"

namespace dtwire::app {
namespace {

using nlohmann::json;

// The references (report_mesh_scale.hpp names their sources).
constexpr double kStripStrengthKNPerM = 50.0, kStripStiffnessKNPerM = 500.0;
constexpr double kThesisPeakN = 25000.0, kThesisPeakMm = 530.0;
constexpr double kOnsetForceN = 1000.0;     // dem run's punch onset: the force first at 1 kN
constexpr double kMeshScaleTie = 1.05;      // the punch's agreement with YADE (5 %)
constexpr double kModelFormNrmse = 0.10;    // report_summary.cpp's model-form threshold
const char* const kReferenceSet = "thesis published";

std::string fixed(double value, int decimals) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(decimals) << value;
  return s.str();
}

bool finished(const std::string& status) { return status == "done" || status == "up to date"; }

bool has_number(const json& object, const char* key) {
  return object.is_object() && object.contains(key) && object[key].is_number();
}

// A figure against its reference: the factor either way (>= 1) and how it reads.
struct Figure {
  double factor;
  std::string text;
};

Figure against(const std::string& name, double value, double reference, const std::string& unit, int decimals) {
  const double ratio = value / reference;
  const double factor = ratio >= 1.0 ? ratio : 1.0 / ratio;
  return {factor, name + " " + fixed(value, decimals) + " " + unit + " against " + fixed(reference, decimals) + " (x " +
                      fixed(ratio, 2) + ")"};
}

// Rule 2: why a candidate cannot be judged, empty if it can.
std::string why_not_judged(const SetEvidence& set) {
  for (const FitEvidence& fit : set.fits)
    if (!fit.parameters.is_object()) return "fit `" + fit.step + "` wrote no parameters.json";
  if (set.punch_step.empty()) return "no punch run in this campaign";
  if (set.strip_step.empty()) return "no strip tension run in this campaign";
  for (const auto& [step, status, summary] : {std::tie(set.punch_step, set.punch_status, set.punch),
                                              std::tie(set.strip_step, set.strip_status, set.strip)}) {
    if (!finished(status)) return "`" + step + "` " + status;
    if (!summary.is_object()) return "`" + step + "` wrote no summary.json";
    if (summary.value("status", "ok") == "failed") return "`" + step + "` stopped at a failed check";
  }
  if (set.punch_not_applicable) return "its punch does not apply: " + *set.punch_not_applicable;
  for (const char* key : {"peak_force_N", "displacement_at_peak_mm"})
    if (!has_number(set.punch, key)) return "its punch gives no " + std::string(key);
  for (const char* key : {"strength_per_width_kN_per_m", "secant_EA_10_50_kN_per_m"})
    if (!has_number(set.strip, key)) return "its strip gives no " + std::string(key);
  return {};
}

// The wire-scale figures of the fits behind a set.
void wire_scale(const SetEvidence& set, SetJudgement& judged) {
  for (const FitEvidence& fit : set.fits) {
    if (!fit.parameters.is_object()) continue;
    for (const json& q : fit.parameters.value("fit_quality", json::array())) {
      if (!has_number(q, "nrmse")) continue;
      const double nrmse = q["nrmse"].get<double>();
      ++judged.curves;
      judged.curves_beyond += nrmse > kModelFormNrmse;
      if (nrmse > judged.worst_nrmse) {
        judged.worst_nrmse = nrmse;
        judged.worst_curve = fit.step + ": " + q.value("experiment", "") + " " + q.value("quantity", "");
      }
    }
    for (const json& p : fit.parameters.value("parameters", json::array()))
      if (p.value("fitted", false)) {
        ++judged.parameters;
        judged.identified += p.value("identified", true);
      }
  }
}

// Rule 4's wire-scale order: true if `a` is the better fit.
bool better_wire_fit(const SetJudgement& a, const SetJudgement& b) {
  if (a.curves_beyond != b.curves_beyond) return a.curves_beyond < b.curves_beyond;
  const double share_a = a.parameters ? double(a.identified) / a.parameters : 0.0;
  const double share_b = b.parameters ? double(b.identified) / b.parameters : 0.0;
  if (share_a != share_b) return share_a > share_b;
  return a.worst_nrmse < b.worst_nrmse;
}

std::string wire_text(const SetJudgement& s) {
  std::ostringstream t;
  t << s.curves_beyond << " of " << s.curves << " fitted curves beyond NRMSE " << fixed(kModelFormNrmse, 2)
    << " (worst " << fixed(s.worst_nrmse, 2) << (s.worst_curve.empty() ? "" : ", " + s.worst_curve) << "); "
    << s.identified << " of " << s.parameters << " parameters identified";
  return t.str();
}

std::string fits_text(const SetEvidence& set) {
  std::string text;
  for (const FitEvidence& fit : set.fits)
    text += (text.empty() ? "" : ", ") + ("[" + fit.step + "](#" + heading_anchor(fit.step) + ")");
  return text.empty() ? "published (no fit)" : text;
}

struct PunchReference {
  double peak_N = 0.0, position_mm = 0.0;
  std::string text;
};

// A label's model variant: its part after the first ", " ("beam shear spring"), empty if none.
std::string model_variant(const std::string& label) {
  const auto comma = label.find(", ");
  return comma == std::string::npos ? std::string() : label.substr(comma + 2);
}

// A set's punch reference: the published sets' run with its model variant, or the thesis DEM.
PunchReference punch_reference_for(const std::string& label, const std::vector<SetEvidence>& sets) {
  const std::string reference_label = published_counterpart(label), variant = model_variant(label);
  for (const SetEvidence& set : sets)
    if (set.label == reference_label && finished(set.punch_status) && !set.punch_not_applicable &&
        has_number(set.punch, "peak_force_N") && has_number(set.punch, "displacement_at_peak_mm") &&
        set.punch.value("status", "ok") != "failed") {
      const double peak = set.punch["peak_force_N"].get<double>(), position = set.punch["displacement_at_peak_mm"].get<double>();
      return {peak, position,
              "the thesis's published sets in the same set-up" + (variant.empty() ? "" : " with the same " + variant) +
                  " (`" + set.punch_step + "`: " + fixed(peak / 1000.0, 1) +
                  " kN at " + fixed(position, 0) + " mm)"};
    }
  return {kThesisPeakN, kThesisPeakMm,
          "the thesis DEM punch (25 kN at 530 mm; no run of the thesis's published sets" +
              (variant.empty() ? std::string() : ", " + variant + ",") + " in this campaign)"};
}

}  // namespace

std::string published_counterpart(const std::string& label) {
  const std::string variant = model_variant(label);
  return variant.empty() ? std::string(kReferenceSet) : std::string(kReferenceSet) + ", " + variant;
}

std::optional<std::string> punch_not_applicable(const std::vector<double>& displacement_m,
                                                const std::vector<double>& force_N) {
  if (displacement_m.empty() || displacement_m.size() != force_N.size()) return "no punch curve";
  const auto peak = std::max_element(force_N.begin(), force_N.end()) - force_N.begin();
  const double travel = *std::max_element(displacement_m.begin(), displacement_m.end());
  // A peak in the last 1 % of the travel is no peak: gap's rule for a run that ended first.
  const std::string at_peak = fixed(force_N[peak] / 1000.0, 1) + " kN at " + fixed(displacement_m[peak], 2) + " m";
  if (force_N[peak] < kOnsetForceN) return "the net never carries the onset force of 1 kN (" + at_peak + ")";
  if (gap::peak_at_curve_end(gap::ForceCurve{displacement_m, force_N, "punch", 0.0, 0.0}))
    return "no peak within the travel: the force still rises when the platter stops (" + at_peak + " of " +
           fixed(travel, 2) + " m), so the net has not failed";
  return std::nullopt;
}

std::optional<std::string> punch_not_at_rest(const nlohmann::json& summary) {
  const auto rest = summary.find("settled_at_rest");
  if (rest == summary.end() || !rest->is_boolean() || rest->get<bool>()) return std::nullopt;
  std::vector<std::string> details;
  if (summary.contains("settle_s") && summary["settle_s"].is_number())
    details.push_back("after " + fixed(summary["settle_s"].get<double>(), 1) + " s of settling");
  if (summary.contains("settle_unbalanced_force_ratio") && summary["settle_unbalanced_force_ratio"].is_number())
    details.push_back("unbalanced-force ratio " + fixed(summary["settle_unbalanced_force_ratio"].get<double>(), 6));
  std::string why = "the net was not at rest when the platter started";
  for (std::size_t i = 0; i < details.size(); ++i) why += (i == 0 ? " (" : ", ") + details[i];
  return details.empty() ? why : why + ")";
}

Recommendation recommend_set(const std::vector<SetEvidence>& sets) {
  Recommendation r;
  for (const SetEvidence& set : sets) {
    SetJudgement j;
    j.label = set.label;
    j.candidate = !set.fits.empty();
    wire_scale(set, j);
    j.not_judged = j.candidate ? why_not_judged(set) : "published set: a reference, not a candidate";
    const PunchReference reference = punch_reference_for(set.label, sets);
    j.punch_reference = reference.text;
    if (j.not_judged.empty()) {
      const std::vector<Figure> figures = {
          against("strip strength", set.strip["strength_per_width_kN_per_m"].get<double>(), kStripStrengthKNPerM, "kN/m", 1),
          against("strip stiffness", set.strip["secant_EA_10_50_kN_per_m"].get<double>(), kStripStiffnessKNPerM, "kN/m", 0),
          against("punch peak", set.punch["peak_force_N"].get<double>() / 1000.0, reference.peak_N / 1000.0, "kN", 1),
          against("punch peak position", set.punch["displacement_at_peak_mm"].get<double>(), reference.position_mm, "mm", 0)};
      double log_sum = 0.0, farthest = 0.0;
      for (const Figure& f : figures) {
        j.figures.push_back(f.text);
        log_sum += std::log(f.factor);
        if (f.factor > farthest) {
          farthest = f.factor;
          j.farthest = f.text;
        }
      }
      j.distance = std::exp(log_sum / static_cast<double>(figures.size()));
    }
    r.sets.push_back(j);
  }
  // Rule 4: the smallest distance; a tie within kMeshScaleTie goes to the better wire-scale fit.
  double smallest = 0.0;
  for (const SetJudgement& s : r.sets)
    if (s.candidate && s.not_judged.empty() && (smallest == 0.0 || s.distance < smallest)) smallest = s.distance;
  if (smallest == 0.0) {
    r.punch_reference = punch_reference_for(kReferenceSet, sets).text;
    return r;
  }
  std::vector<int> tied;
  for (std::size_t i = 0; i < r.sets.size(); ++i)
    if (r.sets[i].candidate && r.sets[i].not_judged.empty() && r.sets[i].distance <= kMeshScaleTie * smallest)
      tied.push_back(static_cast<int>(i));
  r.chosen = tied.front();
  for (const int i : tied)
    if (better_wire_fit(r.sets[i], r.sets[r.chosen])) r.chosen = i;
  r.punch_reference = r.sets[r.chosen].punch_reference;
  if (tied.size() > 1) {
    r.tie_note = "Tied at mesh scale (distances within a factor " + fixed(kMeshScaleTie, 2) + " of the smallest): ";
    for (std::size_t k = 0; k < tied.size(); ++k) r.tie_note += (k ? ", " : "") + r.sets[tied[k]].label;
    r.tie_note += "; the better wire-scale fit decides (rule 4).";
  }
  return r;
}

std::string recommendation_markdown(const Recommendation& r, const std::vector<SetEvidence>& sets) {
  if (sets.empty()) return {};
  std::ostringstream md;
  md << "### Recommended parameter set\n\n";
  int candidates = 0;
  for (const SetJudgement& s : r.sets) candidates += s.candidate;
  if (r.chosen < 0) {
    md << "None: " << (candidates ? "no set this campaign calibrates could be judged (reasons in the table)"
                                  : "this campaign calibrates no set that its DEM runs judge at mesh scale")
       << ".\n\n";
  } else {
    const SetJudgement& s = r.sets[r.chosen];
    const SetEvidence& e = sets[r.chosen];
    md << "**" << s.label << "**: fits " << fits_text(e);
    if (!e.files.empty()) {
      md << "; files";
      for (std::size_t i = 0; i < e.files.size(); ++i) md << (i ? "," : "") << " `" << e.files[i] << "`";
    }
    md << ".\n\n**Why**: of the " << candidates << " set(s) this campaign calibrates, its mesh-scale figures lie "
       << "nearest their references, x " << fixed(s.distance, 2) << " from them on geometric mean (farthest: "
       << s.farthest << "; punch figures against " << r.punch_reference << "). Wire scale: " << wire_text(s) << ". "
       << r.tie_note << (r.tie_note.empty() ? "" : " ")
       << (model_variant(s.label) == "beam shear spring"
               ? "The PFC7 plugin's law has no such spring (the exported `.dat` says so): in PFC7 take the same "
                 "fits with the plugin's spring, the set `" + s.label.substr(0, s.label.find(", ")) + "` below. "
               : std::string())
       << "Rules: the sets with a fit of this campaign behind them are the candidates; each is judged by the "
          "geometric mean of the factors between its strip (strength, 10-50 % secant stiffness) and 50 kN/m, "
          "500 kN/m, and between its punch peak and its position and those of the thesis's published sets; the "
          "smallest wins, a tie within 5 % going to the better wire-scale fit (docs/campaign.md, \"The "
          "recommended set\").\n\n";
  }
  md << "| set | fits behind it | mesh scale: farthest figure (factor) | wire scale | verdict (mesh-scale distance) |\n"
        "|---|---|---|---|---|\n";
  for (std::size_t i = 0; i < r.sets.size(); ++i) {
    const SetJudgement& s = r.sets[i];
    md << "| " << s.label << " | " << fits_text(sets[i]) << " | "
       << (s.not_judged.empty() ? s.farthest : std::string("n/a")) << " | "
       << (s.candidate ? wire_text(s) : std::string("published")) << " | "
       << (static_cast<int>(i) == r.chosen ? "**recommended**, x " + fixed(s.distance, 2)
           : !s.candidate                   ? std::string("reference (published set)")
           : s.not_judged.empty()           ? "judged, x " + fixed(s.distance, 2)
                                            : "not judged: " + s.not_judged)
       << " |\n";
  }
  md << "\n";
  return md.str();
}

}  // namespace dtwire::app
