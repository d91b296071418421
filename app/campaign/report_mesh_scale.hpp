#pragma once
// The campaign summary's mesh-scale judgement of every parameter set (issue 36): per set, the
// punch's onset, peak force and its displacement and the strip's tension strength and secant
// stiffness per metre, against the thesis's validated DEM punch (onset 0.20 m, 25 kN at 0.53 m)
// and the published mesh figures for 8x10 / 2.7 mm (50 kN/m, about 500 kN/m).
//
// A set is named by its runs' label (`dem run --label`, written to summary.json); the punch
// figures come from a run whose summary says tool "platter", the strip's from "strip_tension".
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "report_band.hpp"

namespace dtwire::app {

struct MeshScaleRun {
  std::string label;     // the set, e.g. "thesis published"
  std::string step;      // the campaign step that runs it
  std::string status;    // "done", "blocked", "failed", ... (a run without summary shows it)
  nlohmann::json summary;  // the run's summary.json; null when the step has not produced it
  std::string not_applicable = {};  // a punch that does not apply to its set-up: why (report_recommendation.hpp)
};

// The sets issue 36 judges, in table order; one of them without any run gets a 'not yet run'
// row (the as-made fit is planned, its steps do not exist yet).
const std::vector<std::string>& expected_mesh_scale_sets();

// The label a `dem run` command gives its runs (--label VALUE), empty if none.
std::string label_of_command(const std::vector<std::string>& command);

// Markdown table (with its reference rows), then a blank line; empty if `runs` is empty. A
// figure that a `dem propagate` step of the same set bands (`bands`, report_band.hpp) is followed
// by its 5-95 % band.
std::string mesh_scale_table(const std::vector<MeshScaleRun>& runs, const std::vector<BandEvidence>& bands = {});

}  // namespace dtwire::app
