#include "propagation_emulator.hpp"

#include <algorithm>
#include <cmath>

#include "dtwire/core/error.hpp"

namespace dtwire::app {

std::vector<double> emulator_coordinates(const PropagationResult& r, const std::vector<double>& values) {
  std::vector<double> z(r.parameters.size(), 0.0);
  for (std::size_t i = 0; i < z.size(); ++i) {
    const PropagatedParameter& p = r.parameters[i];
    if (!(p.coordinate_sd > 0.0)) continue;
    z[i] = p.logarithmic ? (std::log(values[i]) - std::log(p.value)) / p.coordinate_sd : (values[i] - p.value) / p.coordinate_sd;
  }
  return z;
}

std::size_t emulator_minimum_training(const PropagationResult& r) { return 2 * r.parameters.size(); }

std::optional<EmulatedFigure> emulate_figure(const PropagationResult& r, std::size_t f,
                                             const std::vector<std::vector<double>>& points, std::uint64_t seed) {
  std::vector<std::vector<double>> x;
  std::vector<double> y;
  for (std::size_t s = 0; s < r.sample_figures.size(); ++s)
    if (r.sample_status[s] == "ok" && std::isfinite(r.sample_figures[s][f])) {
      x.push_back(emulator_coordinates(r, r.sample_values[s]));
      y.push_back(r.sample_figures[s][f]);
    }
  if (x.size() < std::max<std::size_t>(3, emulator_minimum_training(r))) return std::nullopt;
  // A positive magnitude (every headline figure is) is emulated as ln f: its band cannot reach 0
  // and a figure spread over decades (the strip's stiffness under dt.EA's log-uniform range) has
  // an error of its own relative size.
  EmulatedFigure e;
  // (A constant figure stays as it is: exp(ln f) need not give f back to the last digit.)
  e.logarithmic = std::all_of(y.begin(), y.end(), [](double v) { return v > 0.0; }) &&
                  std::any_of(y.begin(), y.end(), [&](double v) { return v != y.front(); });
  if (e.logarithmic)
    for (double& v : y) v = std::log(v);
  const calibrate::GaussianProcessEmulator emulator(x, y);
  e.training = x.size();
  e.band = calibrate::emulated_band(emulator, points, seed, e.logarithmic);
  e.q_squared = emulator.q_squared();
  e.share_within_two_sd = emulator.share_within_two_sd();
  e.noise_sd = emulator.predict(std::vector<double>(r.parameters.size(), 0.0)).noise_sd;
  e.length_scales = emulator.length_scales();
  return e;
}

std::vector<bool> emulator_converged(const PropagationResult& r, double tolerance) {
  std::vector<bool> converged(r.figures.size(), false);
  const std::size_t rows = r.convergence.size();
  if (rows < 3) return converged;
  for (std::size_t f = 0; f < r.figures.size(); ++f) {
    bool ok = true;
    const auto& last = r.convergence[rows - 1].emulated;
    if (last.size() <= f || !last[f]) continue;
    const double width = last[f]->band.with_error.q95 - last[f]->band.with_error.q05;
    for (std::size_t k = rows - 2; k < rows; ++k) {
      const auto& now = r.convergence[k].emulated;
      const auto& before = r.convergence[k - 1].emulated;
      if (now.size() <= f || before.size() <= f || !now[f] || !before[f]) {
        ok = false;
        break;
      }
      ok = ok && std::abs(now[f]->band.with_error.q05 - before[f]->band.with_error.q05) <= tolerance * width &&
           std::abs(now[f]->band.with_error.q95 - before[f]->band.with_error.q95) <= tolerance * width;
    }
    converged[f] = ok;
  }
  return converged;
}

}  // namespace dtwire::app
