#pragma once
// Loading modes of laboratory curves (wire tests: tension, compression, bending, shear, cyclic;
// mesh tests: punch, panel_tension): how a
// curve's mode is found, and which catalogue effects apply to which mode. Test-setup effects
// (the measurement chain) take one parameter set per mode (each mode has its own fixtures);
// specimen effects (material, geometry) share one set over every mode.
#include <string>
#include <vector>

#include "dtwire/core/curve.hpp"
#include "dtwire/gap/effects.hpp"

namespace dtwire::gap {

const std::vector<std::string>& loading_mode_names();
std::string loading_mode_list();  // "tension, compression, ..."

// Throws InputError naming `field` when `text` is not a mode name.
std::string parse_loading_mode(const std::string& text, const std::string& field);

struct ModeGuess {
  std::string mode;
  std::string basis;  // how it was found, for the report
};

// In order: metadata `loading_mode` (must be a mode name, else InputError naming `file`);
// metadata `tool` of a DEM run (platter -> punch, strip_tension -> panel_tension);
// metadata `experiment` containing a mode name; channels (moment, rotation or deflection -> bending,
// shear_* -> shear); the force (both signs beyond 20 % of the peak -> cyclic; dominant force
// negative -> compression; else tension).
ModeGuess detect_loading_mode(const Curve& curve, const ForceCurve& force_curve, const std::string& file);

// Warnings that a laboratory curve may not be the test its simulation runs (flagged, not refused:
// the user may know better), each naming both curves:
// - their dominant forces are of opposite sign (a compression test against a tension simulation,
//   or opposite sign conventions): each curve is oriented by its own sign, so they would be
//   compared by magnitude alone;
// - the laboratory curve's own mode, stated by its metadata or channels, is not the mode it is
//   compared in (not checked when `compared` comes from --mode: the user chose it);
// - its largest force or displacement lies more than kScaleWarningDecades decades from the
//   simulation's (x 31.6): beyond what any effect does within its plausible range (docs/gap.md,
//   the range table: the largest, a grip slip of 10 mm/kN, stretches a wire test's displacement
//   a few times; none moves the largest force by 2 x), so more likely a unit read wrongly (a kN
//   column labelled N reads 1000 times too small) or a curve of another specimen.
std::vector<std::string> comparison_warnings(const ForceCurve& lab, const ModeGuess& lab_own, const ForceCurve& sim,
                                             const ModeGuess& compared);
inline constexpr double kScaleWarningDecades = 1.5;

// A test of a panel of mesh (the DEM runs' tests), not of a wire or twist specimen.
bool mesh_mode(const std::string& mode);
// Whether `effect` can act in `mode`: wire effects in wire tests, mesh effects in mesh tests
// (each's plausible range is its test's); among wire effects, grip_slip and gauge_length need
// tensile grips and an extensometer (tension and cyclic), ductile_damage tensile strain (not
// compression).
bool effect_applies(const EffectSpec& effect, const std::string& mode);
// Why `effect` is not tested on a curve of `mode` whose displacements reach `largest_displacement_m`
// ("" when it is): it does not act in the mode, or the curve is far outside its test's range (a
// wire test's displacements stay below kWireTestLargestDisplacement).
std::string effect_inapplicable(const EffectSpec& effect, const std::string& mode, double largest_displacement_m);
inline constexpr double kWireTestLargestDisplacement = 0.2;  // m
// Test-setup effects: one parameter set per loading mode.
bool effect_per_mode(const EffectSpec& effect);

}  // namespace dtwire::gap
