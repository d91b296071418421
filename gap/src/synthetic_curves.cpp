#include "dtwire/gap/synthetic_curves.hpp"

#include <algorithm>
#include <cmath>

#include "dtwire/core/curve_ops.hpp"
#include "dtwire/gap/curve_metrics.hpp"

namespace dtwire::gap {
namespace {

// Points evenly spaced in displacement, merged with the given vertices (kept exactly).
ForceCurve refine(const std::vector<double>& u, const std::vector<double>& f, std::size_t points,
                  const std::string& source) {
  std::vector<double> grid = linspace(u.front(), u.back(), points);
  grid.insert(grid.end(), u.begin(), u.end());
  std::sort(grid.begin(), grid.end());
  grid.erase(std::unique(grid.begin(), grid.end(),
                         [&](double a, double b) { return std::abs(a - b) < 1e-12; }),
             grid.end());
  ForceCurve out;
  out.source = source;
  out.u = grid;
  for (double x : grid) out.f.push_back(interpolate_clamped(u, f, x));
  return out;
}

}  // namespace

ForceCurve voce_tension_curve(const VoceWire& w, std::size_t points) {
  std::vector<double> u = {0.0}, f = {0.0};
  double peak_force = 0.0, peak_u = 0.0;
  const double neck = w.neck_width * kGaugeLength_m;
  for (std::size_t k = 0; k <= 4000; ++k) {
    const double eps_p = 0.6 * std::pow(static_cast<double>(k) / 4000.0, 2.0);
    const double stress = w.yield_Pa + w.saturation_Pa * (1.0 - std::exp(-w.rate * eps_p)) +
                          w.linear_Pa * eps_p;
    const double eps_true = eps_p + stress / w.young_Pa;
    const double disp = (std::exp(eps_true) - 1.0) * kGaugeLength_m;
    double force = stress * kWireArea_m2 * std::exp(-eps_true);
    if (force >= peak_force && peak_u == 0.0) {
      peak_force = force;
    } else if (peak_u == 0.0) {
      peak_u = u.back();
    }
    if (peak_u > 0.0) {
      const double x = (disp - peak_u) / neck;
      force *= std::exp(-x * x);
    }
    if (force < w.fracture_ratio * peak_force) break;
    u.push_back(disp);
    f.push_back(force);
  }
  return refine(u, f, points, "Voce wire model");
}

ForceCurve backbone_tension_curve(const std::filesystem::path& backbone_csv, std::size_t points) {
  CurveConversion conversion;
  conversion.gauge_length_m = kGaugeLength_m;
  conversion.area_m2 = kWireArea_m2;
  const ForceCurve raw = load_force_curve(backbone_csv, conversion);
  return refine(raw.u, raw.f, points, "DEM backbone (" + backbone_csv.filename().string() + ")");
}

ForceCurve sample_lab_curve(const ForceCurve& model, const LabSampling& sampling, std::mt19937& rng) {
  const double end = sampling.end_m > 0 ? sampling.end_m : model.u.back();
  ForceCurve grid;
  grid.u = linspace(model.u.front(), end, std::max<std::size_t>(sampling.points, 3));
  grid.f.assign(grid.u.size(), 0.0);
  const Comparison at = make_comparison(grid);
  ForceCurve lab = grid;
  lab.f = model_forces_at_lab(model, at);
  lab.source = "synthetic laboratory curve";
  std::normal_distribution<double> normal(0.0, 1.0);
  const double rho = sampling.noise_rho;
  double e = 0.0;
  for (std::size_t i = 0; i < lab.size(); ++i) {
    e = i == 0 ? normal(rng) : rho * e + std::sqrt(1.0 - rho * rho) * normal(rng);
    lab.f[i] += sampling.noise_sigma_N * e;
  }
  return lab;
}

}  // namespace dtwire::gap
