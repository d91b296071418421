// Laboratory summary figures: their names, the `--lab-summary` text and the features of a curve.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <set>
#include <sstream>
#include <stdexcept>

#include "dtwire/core/error.hpp"
#include "dtwire/gap/diagnosis.hpp"
#include "dtwire/gap/loading_mode.hpp"
#include "dtwire/gap/summary_lab.hpp"

namespace dtwire::gap {
namespace {

const std::vector<std::string>& fixed_features() {
  static const std::vector<std::string> names = {"peak_force_N", "residual_force_N",
                                                 "peak_displacement_mm", "onset_displacement_mm",
                                                 "strength_N_per_m", "secant_stiffness_N_per_m"};
  return names;
}

constexpr const char* kForceAtPrefix = "force_at_";
constexpr const char* kForceAtSuffix = "mm_N";
constexpr const char* kDisplacementAtPrefix = "displacement_at_";
constexpr const char* kDisplacementAtSuffix = "N_mm";

// The positive plain decimal between `prefix` and `suffix` of a column-style name (digits and one
// decimal point: no sign, exponent or spaces), else none.
std::optional<double> value_between(const std::string& name, const std::string& prefix, const std::string& suffix) {
  if (name.size() <= prefix.size() + suffix.size() || name.compare(0, prefix.size(), prefix) != 0 ||
      name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0)
    return std::nullopt;
  const std::string middle = name.substr(prefix.size(), name.size() - prefix.size() - suffix.size());
  if (middle.find_first_not_of("0123456789.") != std::string::npos || std::count(middle.begin(), middle.end(), '.') > 1)
    return std::nullopt;
  std::size_t used = 0;
  double value = 0.0;
  try {
    value = std::stod(middle, &used);
  } catch (const std::exception&) {
    return std::nullopt;
  }
  if (used != middle.size() || !(value > 0.0) || !std::isfinite(value)) return std::nullopt;
  return value;
}

double number(const std::string& text, const std::string& field, const std::string& what) {
  std::size_t used = 0;
  double v = 0.0;
  try {
    v = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size() || !std::isfinite(v))
    throw InputError(field, what + ": expected a number, found '" + text + "'");
  return v;
}

bool known_feature(const std::string& name) {
  return std::find(fixed_features().begin(), fixed_features().end(), name) != fixed_features().end() ||
         force_at_displacement_mm(name).has_value() || displacement_at_force_N(name).has_value();
}

}  // namespace

std::optional<double> force_at_displacement_mm(const std::string& name) {
  return value_between(name, kForceAtPrefix, kForceAtSuffix);
}

std::optional<double> displacement_at_force_N(const std::string& name) {
  return value_between(name, kDisplacementAtPrefix, kDisplacementAtSuffix);
}

std::string force_at_feature_name(double displacement_mm) {
  if (!(displacement_mm > 0.0) || !std::isfinite(displacement_mm))
    throw std::invalid_argument("force_at_feature_name: the displacement must be positive");
  char text[32];
  std::snprintf(text, sizeof text, "%.10g", displacement_mm);
  const std::string name = std::string(kForceAtPrefix) + text + kForceAtSuffix;
  if (!force_at_displacement_mm(name))
    throw std::invalid_argument("force_at_feature_name: " + std::string(text) + " mm has no plain decimal form");
  return name;
}

std::string summary_feature_names() {
  std::string out;
  for (const auto& n : fixed_features()) out += (out.empty() ? "" : ", ") + n;
  return out + ", force_at_<D>mm_N (the force at D mm, e.g. force_at_420mm_N), displacement_at_<F>N_mm (where "
               "the force first reaches F N, e.g. displacement_at_1000N_mm)";
}

std::vector<SummaryFeature> parse_lab_summary(const std::string& text, const std::string& field) {
  std::vector<SummaryFeature> out;
  std::stringstream s(text);
  std::string item;
  std::set<std::string> seen;
  while (std::getline(s, item, ',')) {
    if (item.empty()) continue;
    const auto eq = item.find('=');
    if (eq == std::string::npos)
      throw InputError(field, "'" + item + "': expected name=mean:sd, e.g. peak_force_N=1510:196");
    SummaryFeature f;
    f.name = item.substr(0, eq);
    if (!known_feature(f.name))
      throw InputError(field, "unknown feature '" + f.name + "', expected one of: " + summary_feature_names());
    if (!seen.insert(f.name).second) throw InputError(field, "feature '" + f.name + "' given twice");
    const std::string rest = item.substr(eq + 1);
    const auto colon = rest.find(':');
    if (colon == std::string::npos)
      throw InputError(field, f.name + ": expected mean:sd (the laboratory scatter sets the noise "
                              "floor), found '" + rest + "'");
    f.mean = number(rest.substr(0, colon), field, f.name + " mean");
    f.sd = number(rest.substr(colon + 1), field, f.name + " sd");
    if (!(f.sd > 0)) throw InputError(field, f.name + " sd: expected a positive number, found " + rest.substr(colon + 1));
    out.push_back(f);
  }
  if (out.empty())
    throw InputError(field, "expected at least one feature name=mean:sd, e.g. peak_force_N=1510:196");
  return out;
}

namespace {

// The force where the displacement first reaches displacement_m (the loading branch of a cycle).
double force_at(const ForceCurve& c, double displacement_m) {
  if (displacement_m <= c.u.front()) return c.f.front();
  for (std::size_t i = 1; i < c.size(); ++i)
    if (c.u[i] >= displacement_m) {
      const double t = c.u[i] > c.u[i - 1] ? (displacement_m - c.u[i - 1]) / (c.u[i] - c.u[i - 1]) : 1.0;
      return c.f[i - 1] + std::clamp(t, 0.0, 1.0) * (c.f[i] - c.f[i - 1]);
    }
  return c.f.back();
}

}  // namespace

double curve_feature(const ForceCurve& c, const std::string& name) {
  const auto peak = std::max_element(c.f.begin(), c.f.end());
  if (name == "peak_force_N") return *peak;
  if (name == "residual_force_N") return c.f.back();
  if (name == "peak_displacement_mm") return c.u[static_cast<std::size_t>(peak - c.f.begin())] * 1e3;
  if (name == "onset_displacement_mm") {
    // Where the force first reaches 4 % of the peak (the thesis punch: 1 kN of 25 kN), linearly
    // interpolated between samples.
    const double level = kOnsetFraction * *peak;
    for (std::size_t i = 1; i < c.size(); ++i)
      if (c.f[i] >= level) {
        const double t = c.f[i] > c.f[i - 1] ? (level - c.f[i - 1]) / (c.f[i] - c.f[i - 1]) : 1.0;
        return (c.u[i - 1] + std::clamp(t, 0.0, 1.0) * (c.u[i] - c.u[i - 1])) * 1e3;
      }
    return c.u.front() * 1e3;
  }
  if (const auto mm = force_at_displacement_mm(name)) return force_at(c, *mm * 1e-3);
  if (const auto level = displacement_at_force_N(name)) {
    // Linear between samples; a curve that never reaches the force gives its last displacement
    // (the crossing lies beyond the run: a lower bound).
    for (std::size_t i = 1; i < c.size(); ++i)
      if (c.f[i] >= *level) {
        if (c.f[i - 1] >= *level) return c.u[i - 1] * 1e3;
        const double t = (*level - c.f[i - 1]) / (c.f[i] - c.f[i - 1]);
        return (c.u[i - 1] + t * (c.u[i] - c.u[i - 1])) * 1e3;
      }
    return c.u.back() * 1e3;
  }
  if (name == "strength_N_per_m" || name == "secant_stiffness_N_per_m") {
    if (!(c.strip_width_m > 0) || !(c.free_length_m > 0))
      throw InputError(c.source, name + " needs a strip tension (its metadata strip_width_m and free_length_m, as "
                                        "`dtwire dem run` writes them for tool.kind = \"strip_tension\")");
    if (name == "strength_N_per_m") return *peak / c.strip_width_m;
    // The chord between the first crossings of 10 % and 50 % of the peak force on the way up,
    // per metre of width and per unit strain (dtwire dem run's summary.json, "secant EA").
    const auto peak_index = static_cast<std::size_t>(peak - c.f.begin());
    const auto crossing = [&](double level) {
      for (std::size_t i = 1; i <= peak_index; ++i)
        if (c.f[i] >= level) {
          const double t = c.f[i] > c.f[i - 1] ? (level - c.f[i - 1]) / (c.f[i] - c.f[i - 1]) : 1.0;
          return c.u[i - 1] + std::clamp(t, 0.0, 1.0) * (c.u[i] - c.u[i - 1]);
        }
      return c.u[peak_index];
    };
    const double du = crossing(kSecantHigh * *peak) - crossing(kSecantLow * *peak);
    if (!(du > 0))
      throw InputError(c.source, "secant_stiffness_N_per_m: the force does not rise between " +
                                     std::to_string(static_cast<int>(100 * kSecantLow)) + " % and " +
                                     std::to_string(static_cast<int>(100 * kSecantHigh)) + " % of its peak");
    return (kSecantHigh - kSecantLow) * *peak / c.strip_width_m / (du / c.free_length_m);
  }
  throw std::invalid_argument("unknown summary feature " + name);
}

bool peak_at_curve_end(const ForceCurve& c) {
  if (c.size() < 2) return false;
  const auto peak = static_cast<std::size_t>(std::max_element(c.f.begin(), c.f.end()) - c.f.begin());
  const double start = c.u.front(), end = *std::max_element(c.u.begin(), c.u.end());
  return end > start && c.u[peak] >= end - kCurveEndShare * (end - start);
}

bool feature_needs_peak(const std::string& name) {
  return name == "peak_force_N" || name == "peak_displacement_mm" || name == "onset_displacement_mm" ||
         name == "strength_N_per_m" || name == "secant_stiffness_N_per_m";
}

std::vector<std::string> summary_scale_warnings(const std::vector<SummaryFeature>& lab, const ForceCurve& sim) {
  validate_force_curve(sim);
  const ForceCurve curve = oriented(sim);
  std::vector<std::string> out;
  for (const SummaryFeature& figure : lab)
    if (feature_needs_peak(figure.name) && peak_at_curve_end(curve)) {
      out.push_back("the simulation's largest force lies at the end of its curve (" + sim.source +
                    "): if the specimen fails in the test, the run ended before it did, and its " + figure.name +
                    " and every figure of the peak are lower bounds");
      break;
    }
  for (const SummaryFeature& figure : lab) {
    const double given = figure.mean, simulated = curve_feature(curve, figure.name);
    std::ostringstream text;
    text << "--lab-summary " << figure.name << "=" << given << ": ";
    if (given < 0.0 && simulated > 0.0) {
      text << "negative, but the figures are magnitudes (each curve is oriented to a positive force; the "
              "simulation's is " << simulated << ")";
      out.push_back(text.str());
      continue;
    }
    if (!(given > 0.0 && simulated > 0.0)) continue;  // a residual force may end below zero
    const double decades = std::log10(given / simulated);
    if (std::abs(decades) <= kScaleWarningDecades) continue;
    char ratio[32];
    std::snprintf(ratio, sizeof ratio, "%.3g", given / simulated);
    text << ratio << " times the simulation's " << simulated;
    // The name's unit and the one a thousand times larger, which a figure copied from a table
    // in kN or m most often is.
    const std::string& name = figure.name;
    const auto ends = [&](const std::string& tail) {
      return name.size() >= tail.size() && name.compare(name.size() - tail.size(), tail.size(), tail) == 0;
    };
    const std::string unit = ends("_N_per_m") ? "N/m" : ends("_N") ? "N" : ends("_mm") ? "mm" : "";
    const std::string larger = unit == "N/m" ? "kN/m" : unit == "N" ? "kN" : unit == "mm" ? "m" : "";
    if (!unit.empty() && std::abs(std::abs(decades) - 3.0) <= 0.5)
      text << (decades < 0 ? "; a figure in " + larger + " given in " + unit + "?"
                           : "; a figure in " + unit + " given in " + larger + "?");
    else
      text << "; a figure of another specimen or test?";
    out.push_back(text.str());
  }
  return out;
}

}  // namespace dtwire::gap
