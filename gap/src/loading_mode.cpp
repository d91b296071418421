#include "dtwire/gap/loading_mode.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>

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

namespace {

struct Extent {
  double largest_force = 0.0, largest_displacement = 0.0;
  int sign = 0;  // of the dominant force; 0 for a curve loaded both ways (cyclic)
};

Extent extent_of(const ForceCurve& c) {
  Extent e;
  const auto [lo, hi] = std::minmax_element(c.f.begin(), c.f.end());
  e.largest_force = std::max(std::abs(*lo), std::abs(*hi));
  for (const double u : c.u) e.largest_displacement = std::max(e.largest_displacement, std::abs(u));
  const bool both_ways = *lo < -0.2 * e.largest_force && *hi > 0.2 * e.largest_force;  // as detect_loading_mode
  e.sign = both_ways ? 0 : (std::abs(*lo) > std::abs(*hi) ? -1 : 1);
  return e;
}

// "" when a and b (> 0) lie within kScaleWarningDecades decades of each other; else what the
// ratio suggests.
std::string scale_mismatch(double lab, double sim, const char* what, const char* small_unit, const char* large_unit) {
  if (!(lab > 0.0 && sim > 0.0)) return "";
  const double decades = std::log10(lab / sim);
  if (std::abs(decades) <= kScaleWarningDecades) return "";
  char ratio[32];
  std::snprintf(ratio, sizeof ratio, "%.3g", lab / sim);
  std::string out = std::string("its largest ") + what + " is " + ratio + " times the simulation's";
  if (std::abs(std::abs(decades) - 3.0) <= 0.5)
    out += decades < 0 ? std::string(" (a column in ") + large_unit + " labelled " + small_unit + "?)"
                       : std::string(" (a column in ") + small_unit + " labelled " + large_unit + "?)";
  else
    out += " (a curve of another specimen or test?)";
  return out;
}

bool stated_mode(const ModeGuess& guess) {
  return guess.basis.rfind("metadata", 0) == 0 || guess.basis.rfind("channel", 0) == 0;
}

}  // namespace

std::vector<std::string> comparison_warnings(const ForceCurve& lab, const ModeGuess& lab_own, const ForceCurve& sim,
                                             const ModeGuess& compared) {
  std::vector<std::string> out;
  const std::string both = lab.source + " against the simulation " + sim.source + ": ";
  const Extent l = extent_of(lab), s = extent_of(sim);
  if (l.sign != 0 && s.sign != 0 && l.sign != s.sign)
    out.push_back(both + "the laboratory's force is mostly " + (l.sign < 0 ? "negative" : "positive") +
                  " and the simulation's mostly " + (s.sign < 0 ? "negative" : "positive") +
                  ": is the laboratory's test the one simulated (compression against tension), or are "
                  "the sign conventions opposite? The curves are compared by magnitude");
  if (stated_mode(lab_own) && lab_own.mode != compared.mode && compared.basis != "--mode")
    out.push_back(both + "the laboratory curve is a " + lab_own.mode + " test (" + lab_own.basis +
                  ") but is compared as " + compared.mode + " (" + compared.basis + ")");
  for (const std::string& m : {scale_mismatch(l.largest_force, s.largest_force, "force", "N", "kN"),
                               scale_mismatch(l.largest_displacement, s.largest_displacement, "displacement", "mm", "m")})
    if (!m.empty()) out.push_back(both + m);
  return out;
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
