#pragma once
// The campaign summary's bands (issue 54): for the recommended set, each mesh-scale figure as
// its value with the 5-95 % band that `dtwire dem propagate` steps carried from the fits'
// uncertainty (sampled where a step sampled, else linearised), beside the standard's figures
// (50 kN/m, about 500 kN/m) and the thesis's published sets' run, then which fitted parameter
// each figure hangs on (the propagation's sensitivity table).
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace dtwire::app {

struct BandEvidence {
  std::string step;          // the `dem propagate` step
  std::string label;         // its --label (the set)
  std::string status;        // the step's status
  nlohmann::json summary;    // its summary.json; null when absent
  std::vector<std::vector<std::string>> sensitivity;  // sensitivity.csv rows (header first); empty when absent
};

// One figure's 5-95 % band as a propagation step reported it, in the figure's unit (kN, mm, kN/m).
struct FigureBand {
  double q05 = 0.0, q95 = 0.0;
  bool sampled = false;  // the sampled quantiles; false: the linearised value -+ 1.645 sd
  bool emulated = false;  // the converged band of the emulator trained on the sampled runs
  bool valid = true;     // false: a linearised band that reaches 0 (propagate's "not_valid")
  std::string step;      // the `dem propagate` step that gave it
};

// The band of `key` (a headline figure of propagation_runs.hpp, e.g. "peak_force_N") for set
// `label` from the band steps whose run is `tool` ("platter" or "strip_tension": both report a
// displacement_at_peak_mm): a converged sampled band, else a converged emulated one, else a
// sampled one, else a linearised one (a sampled band carries the response's curvature);
// nullopt when no step bands the figure.
std::optional<FigureBand> figure_band(const std::vector<BandEvidence>& bands, const std::string& label,
                                      const std::string& tool, const std::string& key);

// Reads sensitivity.csv as rows of cells (no quoted commas in it); empty if absent.
std::vector<std::vector<std::string>> read_sensitivity_rows(const std::string& file);

// "#### Mesh-scale figures with their band" for `label`: one row per figure of every band step
// of the set, then a row per headline figure of the set's own strip and punch (`own_strip`,
// `own_punch`: their summary.json, null when absent) that no step bands, said to be unbanded;
// its references (`thesis_strip`, `thesis_punch`: the thesis's published sets' runs, null when
// absent), then the sensitivities. Empty when no step bands the set.
std::string band_markdown(const std::string& label, const std::vector<BandEvidence>& bands,
                          const nlohmann::json& thesis_strip, const nlohmann::json& thesis_punch,
                          const nlohmann::json& own_strip = nullptr, const nlohmann::json& own_punch = nullptr);

}  // namespace dtwire::app
