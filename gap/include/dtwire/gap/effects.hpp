#pragma once
// The catalogue of candidate unmodelled effects. Each is a parametrised augmentation of a
// simulated force-displacement curve with bounds (for the fit) and a plausible range (for the
// ranking). Effects that need the FE model re-run (`needs_model`) are declared here with their
// FE-level parameters, so that the --model mode plugs in through a ModelRunner; in --sim mode
// they are listed as not tested.
#include <algorithm>
#include <cmath>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "dtwire/gap/force_curve.hpp"

namespace dtwire::gap {

// Scales of the simulated curve that set the bounds of the effect parameters.
struct CurveScale {
  double peak_force_N = 1.0;
  double max_displacement_m = 1.0;
  double initial_stiffness_N_per_m = 1.0;
  // Where the force first peaks (a tension test's neck starts there, Considere); at most
  // max_displacement_m, equal to it when the force rises to the end.
  double peak_displacement_m = 1.0;
  // Where the laboratory test ends (its largest displacement; 0: the simulation's end). An
  // effect whose size grows along the test (ductile damage) is judged by what the test shows.
  double test_end_m = 0.0;
  // The damage's clock on the record the curve is compared with (Comparison::damage_clock):
  // an effect that runs to fracture (`runs_to_fracture`) reads the displacement times it.
  double damage_clock = 1.0;
};
CurveScale curve_scale(const ForceCurve& sim);

struct ParameterSpec {
  std::string name;  // with its unit, e.g. compliance_mm_per_kN
  double lower = 0.0, upper = 1.0;                      // fit bounds
  double plausible_lower = 0.0, plausible_upper = 1.0;  // realistic range
  // Fitted by a search over `grid` (piecewise-constant effect on the curve, no gradient).
  std::vector<double> grid;
  // A shape parameter (issue 17): its value for the effect's basic form. Held there where a
  // few summary figures cannot tell shapes apart.
  std::optional<double> shape_neutral;
  // Further values the fit starts from (the rest of the start at the basic form): for a
  // parameter whose misfit has a basin per value, such as where a change sets in.
  std::vector<double> scan_starts;

  // The fits' coordinate x = (p - plausible_lower) / plausible width: every unknown O(1).
  double width() const {
    const double w = plausible_upper - plausible_lower;
    return w > 0 ? w : std::max(upper - lower, 1e-12);
  }
  double to_scaled(double value) const { return (value - plausible_lower) / width(); }
  double from_scaled(double x) const { return std::clamp(plausible_lower + x * width(), lower, upper); }
  // The grid value nearest to `value` (the value itself for a continuous parameter).
  double snapped(double value) const {
    if (grid.empty()) return value;
    double best = grid.front();
    for (double g : grid)
      if (std::abs(g - value) < std::abs(best - value)) best = g;
    return best;
  }
};

struct EffectSpec {
  std::string name;
  std::string description;
  bool needs_model = false;  // only in --model mode
  // The kind of test the effect belongs to, which its plausible range is stated for: "wire" (a
  // wire or twist specimen in a testing machine, displacements of millimetres) or "mesh" (a panel
  // of mesh: punch, panel tension; displacements of decimetres; the model is a DEM run).
  std::string test = "wire";
  int order = 0;             // composition order: material first, then the measurement chain
  std::size_t magnitude = 0; // index of the parameter that measures the effect's size
  double neutral = 0.0;      // value of that parameter for which the effect vanishes
  // The effect runs on each fractured record's own clock to that record's fracture
  // (CurveScale::damage_clock): one law, shared parameters, a model curve per record.
  bool runs_to_fracture = false;
  // A model-only effect's run time over the model's own (the side-by-side searches start the
  // costliest first, so that it does not run alone at the end).
  double relative_run_cost = 1.0;
  std::function<std::vector<ParameterSpec>(const CurveScale&)> parameters;
  std::function<ForceCurve(const ForceCurve&, const std::vector<double>&, const CurveScale&)> apply;
};

const std::vector<EffectSpec>& effect_catalogue();
// Throws std::invalid_argument listing the known names.
const EffectSpec& find_effect(const std::string& name);
std::string effect_names();

struct AppliedEffect {
  const EffectSpec* effect;
  std::vector<double> params;
};

// --model mode: re-runs the FE experiment with the given model-only effects (`needs_model`)
// switched on at the given parameters and returns its curve (oriented like the simulation).
// Curve-mode effects are applied by gap on top of it.
using ModelRunner = std::function<ForceCurve(const std::vector<AppliedEffect>&)>;

// The simulation with `effects`: model-only ones through `runner` (which must be set when there
// are any), then the curve-mode ones by apply_effects.
ForceCurve augment(const ForceCurve& sim, const std::vector<AppliedEffect>& effects,
                   const CurveScale& scale, const ModelRunner& runner);

// Applies the effects in catalogue order (strain_rate, ductile_damage, gauge_length,
// machine_compliance, grip_slip, initial_slack).
ForceCurve apply_effects(const ForceCurve& sim, std::vector<AppliedEffect> effects,
                         const CurveScale& scale);

// Whether no effect's magnitude is stronger than its plausible range (beyond it, away from the
// neutral value): such an effect is reported as implausible and is never the cause (issue 37).
// A magnitude between the neutral value and the range is a weak effect, not an implausible one.
bool magnitudes_plausible(const std::vector<AppliedEffect>& effects, const CurveScale& scale);

// An effect's magnitude stronger than its plausible range: which effect, which parameter (or the
// shown magnitude), the value and the range, for the verdict ("needs a scale_1 of 0.64, outside
// [0.85, 1.3]").
struct BeyondRange {
  std::string effect, parameter;
  double value = 0.0, plausible_lower = 0.0, plausible_upper = 0.0;
  std::string text() const;  // "a <parameter> of <value>, outside [<lower>, <upper>]"
};
// The magnitudes of `effects` that lie beyond their plausible range (empty when none).
std::vector<BeyondRange> magnitudes_beyond_range(const std::vector<AppliedEffect>& effects, const CurveScale& scale);

// 1 inside the plausible range, falling linearly to 0.2 at the fit bounds; product over params.
double plausibility(const EffectSpec& effect, const std::vector<double>& params,
                    const CurveScale& scale);

}  // namespace dtwire::gap
