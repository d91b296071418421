#include "report_mesh_scale.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "report_summary.hpp"

namespace dtwire::app {
namespace {

using nlohmann::json;

// The references (docs/dem_engine.md; ../shared/data/wire_2.7mm_literature.md).
constexpr double kThesisOnsetM = 0.20, kThesisPeakKN = 25.0, kThesisPeakM = 0.53;
constexpr double kMeshStrengthKNPerM = 50.0, kMeshStiffnessKNPerM = 500.0;

// "57.0 (+128 %)": the value and its deviation from the reference.
std::string against(double value, double reference, int decimals) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(decimals) << value << " (" << std::showpos << std::setprecision(0)
    << 100.0 * (value / reference - 1.0) << " %)";
  return s.str();
}

// The figure `key` of a summary in `scale` units, against `reference`; "n/a" if absent.
std::string cell(const json& summary, const char* key, double scale, double reference, int decimals, const char* absent = "n/a") {
  if (!summary.is_object() || !summary.contains(key)) return "n/a";
  if (!summary[key].is_number()) return absent;
  return against(summary[key].get<double>() * scale, reference, decimals);
}

// "34.2 / 48.5, 20.8": the punch's membrane at the platter's rim at the peak (mean and largest
// sector tension, slope), "n/a" for a run without it.
std::string rim_cell(const json& summary) {
  for (const char* key : {"rim_tension_at_peak_kN_per_m", "rim_largest_sector_tension_at_peak_kN_per_m", "rim_slope_at_peak_deg"})
    if (!summary.contains(key) || !summary[key].is_number()) return "n/a";
  std::ostringstream s;
  s << std::fixed << std::setprecision(1) << summary["rim_tension_at_peak_kN_per_m"].get<double>() << " / "
    << summary["rim_largest_sector_tension_at_peak_kN_per_m"].get<double>() << ", "
    << summary["rim_slope_at_peak_deg"].get<double>();
  return s.str();
}

// " [5-95 %: 45.1 - 60.2]": the band of a figure, `scale` from the band's unit to the table's;
// "" when no step bands it.
std::string band_suffix(const std::vector<BandEvidence>& bands, const std::string& label, const std::string& tool,
                        const std::string& key, double scale, int decimals) {
  const std::optional<FigureBand> band = figure_band(bands, label, tool, key);
  if (!band) return {};
  std::ostringstream s;
  if (!band->valid) return " [5-95 %: linearised band not valid (reaches 0): sample it]";
  s << std::fixed << std::setprecision(decimals) << " [5-95 %: " << band->q05 * scale << " - " << band->q95 * scale
    << (band->sampled ? "" : band->emulated ? ", emulated" : ", linearised") << "]";
  return s.str();
}

std::string step_link(const MeshScaleRun& run) { return "[" + run.step + "](#" + heading_anchor(run.step) + ")"; }

}  // namespace

const std::vector<std::string>& expected_mesh_scale_sets() {
  static const std::vector<std::string> sets = {"thesis published", "WirePM published", "straight-wire fit", "as-made fit"};
  return sets;
}

std::string label_of_command(const std::vector<std::string>& command) {
  const auto at = std::find(command.begin(), command.end(), "--label");
  return at != command.end() && at + 1 != command.end() ? *(at + 1) : std::string();
}

std::string mesh_scale_table(const std::vector<MeshScaleRun>& runs, const std::vector<BandEvidence>& bands) {
  if (runs.empty()) return {};
  std::vector<std::string> labels = expected_mesh_scale_sets();
  for (const MeshScaleRun& run : runs)
    if (std::find(labels.begin(), labels.end(), run.label) == labels.end()) labels.push_back(run.label);

  std::ostringstream md;
  md << "Every set at mesh scale (deviation from the reference in brackets): the punch as its steps run it, "
        "the strip tension along the twists. The rim column is the punch's membrane just outside the "
        "platter at the peak (membrane_at_peak.csv): the mean radial tension per metre of circumference, "
        "that of the most loaded eighth, and the net's slope there; the peak is 2 pi r x mean x "
        "tan(slope), so a set's peak moves with its strength (against the strip's) and with how far "
        "the net is pushed before it fails (the slope). Where a `dem propagate` step carries the set's fits' "
        "uncertainty to a figure, its 5-95 % band follows in square brackets (sampled where the step sampled, "
        "else linearised; counts and convergence in the band section of the summary).\n\n"
     << "| set | punch onset (m) | punch peak (kN) | displacement at peak (m) | sag settled (mm) | "
        "rim at peak: tension mean / largest eighth (kN/m), slope (deg) | "
        "strip strength (kN/m) | strip secant stiffness, 10-50 % of peak (kN/m) | steps |\n"
     << "|---|---|---|---|---|---|---|---|---|\n"
     << "| *thesis DEM punch (Previtali; validated against laboratory punches)* | 0.20 | 25 | 0.53 | | | | | |\n"
     << "| *published mesh, 8x10 / 2.7 mm (EN 15381 Annex D; manufacturer)* | | | | | | 50 | about 500 | |\n";
  for (const std::string& label : labels) {
    const MeshScaleRun* punch = nullptr;
    const MeshScaleRun* strip = nullptr;
    std::vector<std::string> steps;
    for (const MeshScaleRun& run : runs) {
      if (run.label != label) continue;
      steps.push_back(step_link(run) + (run.summary.is_object() ? "" : " (" + run.status + ")"));
      const std::string tool = run.summary.is_object() ? run.summary.value("tool", "") : "";
      if (tool == "platter") punch = &run;
      if (tool == "strip_tension") strip = &run;
    }
    md << "| " << label << " | ";
    if (steps.empty()) {
      md << "not yet run | | | | | | | |\n";
      continue;
    }
    if (punch && !punch->not_applicable.empty()) {
      md << "not applicable: " << punch->not_applicable << " | | | | | ";
    } else if (punch) {
      const json& s = punch->summary;
      // The band's units (propagation_runs.hpp): kN and mm; the table's: kN and m.
      md << cell(s, "onset_displacement_mm", 1e-3, kThesisOnsetM, 3, "no onset")
         << band_suffix(bands, label, "platter", "onset_displacement_mm", 1e-3, 3) << " | " << cell(s, "peak_force_N", 1e-3, kThesisPeakKN, 1)
         << band_suffix(bands, label, "platter", "peak_force_N", 1.0, 1) << " | "
         << cell(s, "displacement_at_peak_mm", 1e-3, kThesisPeakM, 3)
         << band_suffix(bands, label, "platter", "displacement_at_peak_mm", 1e-3, 3) << " | " << (s.contains("sag_after_settling_mm") && s["sag_after_settling_mm"].is_number()
                          ? std::to_string(static_cast<long>(std::lround(s["sag_after_settling_mm"].get<double>())))
                          : std::string("n/a"))
         << " | " << rim_cell(s) << " | ";
    } else {
      md << "not run | | | | | ";
    }
    if (strip) {
      md << cell(strip->summary, "strength_per_width_kN_per_m", 1.0, kMeshStrengthKNPerM, 1)
         << band_suffix(bands, label, "strip_tension", "strength_per_width_kN_per_m", 1.0, 1) << " | "
         << cell(strip->summary, "secant_EA_10_50_kN_per_m", 1.0, kMeshStiffnessKNPerM, 0, "undefined")
         << band_suffix(bands, label, "strip_tension", "secant_EA_10_50_kN_per_m", 1.0, 0) << " | ";
    } else {
      md << "not run | | ";
    }
    for (std::size_t i = 0; i < steps.size(); ++i) md << (i ? ", " : "") << steps[i];
    md << " |\n";
  }
  md << "\n";
  return md.str();
}

}  // namespace dtwire::app
