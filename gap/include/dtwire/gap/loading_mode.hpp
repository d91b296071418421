#pragma once
// Loading modes of laboratory curves (tension, compression, bending, shear, cyclic): how a
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
// metadata `experiment` containing a mode name; channels (moment, rotation or deflection -> bending,
// shear_* -> shear); the force (both signs beyond 20 % of the peak -> cyclic; dominant force
// negative -> compression; else tension).
ModeGuess detect_loading_mode(const Curve& curve, const ForceCurve& force_curve, const std::string& file);

// Whether `effect` can act in `mode` (grip_slip and gauge_length need tensile grips and an
// extensometer: tension and cyclic; ductile_damage needs tensile strain: not compression).
bool effect_applies(const EffectSpec& effect, const std::string& mode);
// Test-setup effects: one parameter set per loading mode.
bool effect_per_mode(const EffectSpec& effect);

}  // namespace dtwire::gap
