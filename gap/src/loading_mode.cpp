#include "dtwire/gap/loading_mode.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>

#include "dtwire/core/error.hpp"

namespace dtwire::gap {
namespace {

std::string lower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return std::tolower(c); });
  return text;
}

std::string trimmed(const std::string& text) {
  const auto first = text.find_first_not_of(" \t");
  if (first == std::string::npos) return "";
  return text.substr(first, text.find_last_not_of(" \t") - first + 1);
}

bool contains(const std::vector<std::string>& list, const std::string& name) {
  return std::find(list.begin(), list.end(), name) != list.end();
}

}  // namespace

const std::vector<std::string>& loading_mode_names() {
  static const std::vector<std::string> names = {"tension", "compression", "bending", "shear", "cyclic",
                                                    "punch", "panel_tension"};
  return names;
}

std::string loading_mode_list() {
  std::string out;
  for (const auto& n : loading_mode_names()) out += (out.empty() ? "" : ", ") + n;
  return out;
}

std::string parse_loading_mode(const std::string& text, const std::string& field) {
  const std::string mode = lower(trimmed(text));
  if (!contains(loading_mode_names(), mode))
    throw InputError(field, "unknown loading mode '" + text + "', expected one of: " + loading_mode_list());
  return mode;
}

ModeGuess detect_loading_mode(const Curve& curve, const ForceCurve& c, const std::string& file) {
  if (const std::string given = curve.metadata("loading_mode"); !given.empty())
    return {parse_loading_mode(given, file + ": metadata loading_mode"), "metadata loading_mode"};
  // A DEM run's curve names its tool (dem/src/run_outputs.cpp).
  if (const std::string tool = lower(curve.metadata("tool")); tool == "platter") return {"punch", "metadata tool"};
  else if (tool == "strip_tension") return {"panel_tension", "metadata tool"};
  const std::string experiment = lower(curve.metadata("experiment"));
  for (const std::string& mode : loading_mode_names())
    if (experiment.find(mode) != std::string::npos) return {mode, "metadata experiment"};
  for (const Channel& channel : curve.channels()) {
    const std::string q = lower(channel.quantity);
    if (q == "moment" || q == "rotation" || q == "deflection") return {"bending", "channel " + channel.column_name()};
    if (q.rfind("shear", 0) == 0) return {"shear", "channel " + channel.column_name()};
  }
  const auto [lo, hi] = std::minmax_element(c.f.begin(), c.f.end());
  const double peak = std::max(std::abs(*lo), std::abs(*hi));
  if (*lo < -0.2 * peak && *hi > 0.2 * peak) return {"cyclic", "force of both signs"};
  if (std::abs(*lo) > std::abs(*hi)) return {"compression", "dominant force negative"};
  return {"tension", "dominant force positive"};
}

bool mesh_mode(const std::string& mode) { return mode == "punch" || mode == "panel_tension"; }

bool effect_applies(const EffectSpec& effect, const std::string& mode) {
  // An effect's plausible range is stated for its own kind of test.
  if ((effect.test == "mesh") != mesh_mode(mode)) return false;
  if (effect.name == "grip_slip" || effect.name == "gauge_length") return mode == "tension" || mode == "cyclic";
  if (effect.name == "ductile_damage") return mode != "compression";
  return true;
}

std::string effect_inapplicable(const EffectSpec& effect, const std::string& mode, double largest_displacement_m) {
  if (!effect_applies(effect, mode)) return "does not apply to " + mode;
  if (effect.test == "wire" && largest_displacement_m > kWireTestLargestDisplacement)
    return "a wire-test effect: the curve's displacement reaches " +
           std::to_string(static_cast<int>(std::lround(largest_displacement_m * 1e3))) + " mm, beyond a wire test's (" +
           std::to_string(static_cast<int>(kWireTestLargestDisplacement * 1e3)) + " mm)";
  return "";
}

bool effect_per_mode(const EffectSpec& effect) {
  return effect.name == "machine_compliance" || effect.name == "grip_slip" ||
         effect.name == "initial_slack" || effect.name == "gauge_length";
}

}  // namespace dtwire::gap
