#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "dtwire/gap/curve_metrics.hpp"
#include "dtwire/gap/effects.hpp"
#include "independent_effects.hpp"

namespace dtwire::gap::independent {

double magnitude(const Setting& s, std::size_t k, double lo, double hi) {
  const double u = k < s.draws.size() ? s.draws[k] : 0.5;
  return (lo + (hi - lo) * u) * s.scatter;
}

double toward_edge(const Setting& s, std::size_t k, double neutral, double inner, double outer) {
  const double u = k < s.draws.size() ? s.draws[k] : 0.5;
  const double nominal = inner + (outer - inner) * std::min(1.0, u / 0.8);
  const double scattered = neutral + (nominal - neutral) * s.scatter;
  return outer > neutral ? std::min(scattered, outer) : std::max(scattered, outer);
}

namespace {
ParameterSpec range_of(const std::string& effect, std::size_t index) {
  CurveScale unit;
  unit.peak_force_N = 1.0;
  return find_effect(effect).parameters(unit).at(index);
}
}  // namespace

double plausible_lower(const std::string& effect, std::size_t index) { return range_of(effect, index).plausible_lower; }
double plausible_upper(const std::string& effect, std::size_t index) { return range_of(effect, index).plausible_upper; }

double force_at(const ForceCurve& base, double u) {
  if (u <= base.u.front()) return base.f.front();
  if (u >= base.u.back()) return base.f.back();
  const auto it = std::upper_bound(base.u.begin(), base.u.end(), u);
  const std::size_t i = static_cast<std::size_t>(it - base.u.begin());
  const double t = (u - base.u[i - 1]) / (base.u[i] - base.u[i - 1]);
  return base.f[i - 1] + t * (base.f[i] - base.f[i - 1]);
}

ForceCurve visible(const ForceCurve& base, double end_m) {
  ForceCurve out;
  out.source = base.source;
  for (std::size_t i = 0; i < base.size() && base.u[i] < end_m; ++i) {
    out.u.push_back(base.u[i]);
    out.f.push_back(base.f[i]);
  }
  out.u.push_back(end_m);
  out.f.push_back(force_at(base, end_m));
  return out;
}

std::vector<double> running_max(const std::vector<double>& v) {
  std::vector<double> out(v.size());
  double m = -1e300;
  for (std::size_t i = 0; i < v.size(); ++i) out[i] = m = std::max(m, v[i]);
  return out;
}

ForceCurve apply(const std::string& effect, const ForceCurve& base, const Setting& s) {
  if (effect == "machine_compliance") return machine_compliance(base, s);
  if (effect == "grip_slip") return grip_slip(base, s);
  if (effect == "initial_slack") return initial_slack(base, s);
  if (effect == "gauge_length") return gauge_length(base, s);
  if (effect == "ductile_damage") return ductile_damage(base, s);
  if (effect == "strain_rate") return strain_rate(base, s);
  throw std::invalid_argument("no independent generator for effect " + effect);
}

int shape_count(const std::string& effect) { return effect == "strain_rate" ? 3 : 2; }

std::string shape_name(const std::string& effect, int shape) {
  static const std::vector<std::pair<std::string, std::vector<std::string>>> names = {
      {"machine_compliance", {"seating_log_compliance", "power_law_compliance"}},
      {"grip_slip", {"stick_slip_drops", "smooth_quadratic_creep"}},
      {"initial_slack", {"cubic_toe", "bilinear_toe"}},
      {"gauge_length", {"drifting_knife_edge", "zero_offset_and_scale"}},
      {"ductile_damage", {"late_exponential", "linear"}},
      {"strain_rate", {"rate_jump", "adiabatic_softening", "hardening_rate_sensitivity"}}};
  for (const auto& [name, shapes] : names)
    if (name == effect) return shapes.at(static_cast<std::size_t>(shape));
  return "none";
}

ForceCurve measure(const ForceCurve& truth, const Measurement& m, std::mt19937& rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::normal_distribution<double> normal(0.0, 1.0);
  const double end = m.end_m > 0 ? m.end_m : truth.u.back();
  // Irregular spacing: each step 1 +- jitter times the mean step.
  std::vector<double> steps(std::max<std::size_t>(m.points, 3) - 1);
  double total = 0.0;
  for (double& d : steps) total += d = 1.0 + m.jitter * (2.0 * unit(rng) - 1.0);
  ForceCurve grid;
  grid.u.push_back(truth.u.front());
  for (double d : steps) grid.u.push_back(grid.u.back() + d / total * (end - truth.u.front()));
  grid.f.assign(grid.u.size(), 1.0);
  ForceCurve lab = grid;
  lab.f = model_forces_at_lab(truth, make_comparison(grid));
  lab.source = "synthetic laboratory curve (independent family)";
  const double rho = m.noise_rho;
  double e = 0.0;
  for (std::size_t i = 0; i < lab.size(); ++i) {
    e = i == 0 ? normal(rng) : rho * e + std::sqrt(1.0 - rho * rho) * normal(rng);
    lab.f[i] += m.noise_sigma_N * e + m.drift_N * static_cast<double>(i) / static_cast<double>(lab.size() - 1);
  }
  if (m.fracture) {
    // The noise carried on at its expectation, rho^k e, with no new draw: the drop leaves every
    // later draw of the selfcheck as it was without it.
    const double step = (end - truth.u.front()) / static_cast<double>(lab.size() - 1);
    for (int k = 1; k <= 2; ++k) {
      e *= rho;
      lab.u.push_back(end + 0.5 * k * step);
      lab.f.push_back(m.noise_sigma_N * e + m.drift_N);
    }
  }
  return lab;
}

}  // namespace dtwire::gap::independent
