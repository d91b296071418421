#pragma once
// The parameter set the campaign report recommends, first in its summary (issue 52), chosen by
// stated rules among the SW/DT set combinations the campaign calibrates itself (docs/campaign.md,
// "The recommended set"):
//
// 1. Candidates: the sets the campaign's DEM runs name (`dem run --label`) with at least one `fit`
//    step of the campaign upstream of their runs (the fits behind the set). A set without one (the
//    thesis's and WirePM's published sets) is a reference, never recommended.
// 2. A candidate is judged only if every fit behind it wrote its parameters.json, and its punch
//    and its strip tension both ran to the end with their checks passed and apply to the set-up
//    (punch_applies); else it is listed with the reason.
// 3. Mesh scale: its distance is the geometric mean of the factors, each taken either way (>= 1),
//    between its four figures and their references: strip strength per metre against 50 kN/m and
//    strip secant stiffness (10-50 % of the peak) against 500 kN/m (8x10 / 2.7 mm mesh, EN 15381
//    Annex D and the manufacturer); punch peak force and its displacement against the thesis's
//    published sets run by the same campaign in the same set-up (so the set-up's factor common to
//    every set cancels) and the same model variant (the label's part after its first ", ", e.g.
//    "section + N-M fit, beam shear spring" against "thesis published, beam shear spring"), or
//    the thesis DEM punch (25 kN at 0.53 m) when that run is absent. Every
//    figure counts alike, so a factor every set shares (the strip's, set by the common DT set)
//    shifts them all and does not decide.
// 4. The smallest distance wins. Distances within a factor 1.05 of the smallest are a tie at mesh
//    scale (5 %: the tolerance to which the engine's punch reproduces YADE's, docs/dem_engine.md);
//    the tie goes to the better wire-scale fit: fewer fitted curves beyond the model-form NRMSE
//    0.10, then a larger share of identified parameters, then the smaller worst NRMSE.
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace dtwire::app {

// Whether a punch run applies to its set-up: a punch whose force never reaches the onset force
// (1 kN) or still rises when the platter's travel ends (its largest force in the last 1 % of the
// travel) has not loaded the net to failure, so its peak is no figure of the test (the WirePM sets
// in the slack state: 1.8 kN at the end of 0.75 m, a net without bending that never takes a shape,
// docs/dem_engine.md). Returns the reason it does not apply, or nothing.
std::optional<std::string> punch_not_applicable(const std::vector<double>& displacement_m,
                                                const std::vector<double>& force_N);
// Whether a punch started from the state its set-up asks for: a run told to settle to rest
// (dynamics.settle_rest_ratio) whose net was still moving when the settle's time ran out
// (summary.json `settled_at_rest` false) measures that motion as much as the net, so its
// figures are not the test's. Returns the reason, or nothing (also for a run that settled for
// a fixed time: `settled_at_rest` null).
std::optional<std::string> punch_not_at_rest(const nlohmann::json& summary);

// The published sets' label with the same model variant as `label` (its part after the first
// ", "): "thesis published, beam shear spring" for "section + N-M fit, beam shear spring",
// "thesis published" for a label without one. Rule 3's punch reference, and the band table's.
std::string published_counterpart(const std::string& label);

struct FitEvidence {
  std::string step;           // the fit step
  nlohmann::json parameters;  // its parameters.json; null if the step did not write it
};

struct SetEvidence {
  std::string label;
  std::vector<FitEvidence> fits;          // the campaign's fits behind the set; empty: a published set
  std::vector<std::string> files;         // the parameter files its runs read (relative to the output folder)
  nlohmann::json punch, strip;            // the runs' summary.json; null when absent
  std::string punch_step, strip_step;     // empty when the campaign has no such run
  std::string punch_status, strip_status; // the steps' status ("done", "failed", ...)
  std::optional<std::string> punch_not_applicable;  // from the punch's curve
};

struct SetJudgement {
  std::string label;
  bool candidate = false;      // rule 1
  std::string not_judged;      // rule 2's reason; empty when judged
  double distance = 0.0;       // rule 3: the geometric mean of the figures' factors, >= 1
  std::string farthest;        // the figure farthest from its reference, "strip stiffness 1165 kN/m against 500 (x 2.33)"
  std::string punch_reference; // what its punch figures are compared with (rule 3)
  std::vector<std::string> figures;  // the four figures against their references
  int curves = 0, curves_beyond = 0;  // fitted curves, and those beyond NRMSE 0.10
  double worst_nrmse = 0.0;
  std::string worst_curve;
  int parameters = 0, identified = 0;
};

struct Recommendation {
  std::vector<SetJudgement> sets;   // in the order given
  int chosen = -1;                  // index into sets; -1: no candidate could be judged
  std::string tie_note;             // the sets tied at mesh scale and how the tie was broken
  std::string punch_reference;      // what the chosen set's punch figures were compared with
};

Recommendation recommend_set(const std::vector<SetEvidence>& sets);

// "### Recommended parameter set": the set, why, the table of every set; empty if `sets` is empty.
std::string recommendation_markdown(const Recommendation& recommendation, const std::vector<SetEvidence>& sets);

}  // namespace dtwire::app
