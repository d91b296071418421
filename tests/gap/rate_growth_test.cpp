// A rate gain that grows during a wire tension test (issue 37): past the uniform elongation the
// strain localises in the neck, and the local strain rate, with it the Johnson-Cook gain, rises.
// The laboratory curves are made here, point by point, from a power-law wire with a diffuse neck
// and the Johnson-Cook gain of its local rate: not from the effect's own formula.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "dtwire/gap/diagnosis.hpp"
#include "dtwire/gap/effects.hpp"
#include "dtwire/gap/synthetic_curves.hpp"

namespace dtwire::gap {
namespace {

// A 2.7 mm wire with Swift hardening, sigma = K (eps0 + eps_p)^n, uniform up to the Considere
// point. Past it a diffuse neck: the travel du strains a zone of length
// l(u) = l_min + (L - l_min) exp(-(u - u_n) / delta) that shrinks from the gauge length L to
// l_min = 2 d (the elastic unloading of the rest of the gauge is left out). The force is the
// flow stress on the neck's section A0 exp(-eps); the neck's strain rate over the nominal one
// is L / l(u).
struct NeckedWire {
  double K_Pa = 700e6, eps0 = 0.01, n = 0.1, young_Pa = 180e9;
  double neck_min_m = 5.4e-3, localisation_m = 1.0e-3;
  double fracture_strain = 0.9;  // true strain in the neck at fracture (reduction of area 59 %)
};

struct WirePoint {
  double u, force, rate_ratio;  // rate_ratio: local over nominal strain rate
};

std::vector<WirePoint> necked_wire(const NeckedWire& w) {
  const double L = kGaugeLength_m, A0 = kWireArea_m2;
  const auto flow = [&](double eps_p) { return w.K_Pa * std::pow(w.eps0 + eps_p, w.n); };
  std::vector<WirePoint> out = {{0.0, 0.0, 1.0}};
  const double yield = flow(0.0);
  for (int k = 1; k <= 20; ++k) {  // elastic
    const double sigma = yield * k / 20.0, eps = sigma / w.young_Pa;
    out.push_back({L * (std::exp(eps) - 1.0), sigma * A0 * std::exp(-eps), 1.0});
  }
  double eps_p = 0.0;
  for (;;) {  // uniform, until the force stops rising
    const double next = eps_p + 2e-4, sigma = flow(next), eps = next + sigma / w.young_Pa;
    const double force = sigma * A0 * std::exp(-eps);
    if (force <= out.back().force) break;
    eps_p = next;
    out.push_back({L * (std::exp(eps) - 1.0), force, 1.0});
  }
  const double u_neck = out.back().u;
  for (double u = u_neck + 2e-5;; u += 2e-5) {  // the neck
    const double zone = w.neck_min_m + (L - w.neck_min_m) * std::exp(-(u - u_neck) / w.localisation_m);
    eps_p += 2e-5 / zone;
    const double sigma = flow(eps_p), eps = eps_p + sigma / w.young_Pa;
    if (eps > w.fracture_strain) break;
    out.push_back({u, sigma * A0 * std::exp(-eps), L / zone});
  }
  return out;
}

ForceCurve simulation(const std::vector<WirePoint>& points) {
  ForceCurve sim;
  sim.source = "power-law wire at the reference rate";
  for (const WirePoint& p : points) {
    sim.u.push_back(p.u);
    sim.f.push_back(p.force);
  }
  return sim;
}

// The wire tested `nominal` times faster than the model's reference rate: Johnson and Cook
// (1983), sigma = sigma_static (1 + C ln(local rate / reference rate)); the extra force
// stretches the gauge elastically (E A0 / L). Returns the curve and the gain at its end.
std::pair<ForceCurve, double> tested_faster(const std::vector<WirePoint>& points, const NeckedWire& w,
                                            double C, double nominal) {
  const double k_gauge = w.young_Pa * kWireArea_m2 / kGaugeLength_m;
  ForceCurve truth;
  double gain = 1.0;
  for (const WirePoint& p : points) {
    gain = 1.0 + C * std::log(nominal * p.rate_ratio);
    truth.u.push_back(p.u + (gain - 1.0) * p.force / k_gauge);
    truth.f.push_back(gain * p.force);
  }
  return {truth, gain};
}

ForceCurve sampled(const ForceCurve& truth, double noise_share, unsigned seed) {
  std::mt19937 rng(seed);
  LabSampling sampling;
  sampling.points = 700;
  sampling.noise_sigma_N = noise_share * *std::max_element(truth.f.begin(), truth.f.end());
  ForceCurve lab = sample_lab_curve(truth, sampling, rng);
  lab.source = "synthetic laboratory curve";
  return lab;
}

// C = 0.014 (a mild steel wire), 100 x the reference rate: the gain is 0.064 until the neck and
// 0.118 at fracture, where the neck's rate is 46 x the nominal. Before the neck growth was
// representable this read as grip_slip+strain_rate (top of the ranking, a constant gain of 0.07
// beside a slip).
TEST(GapRateGrowth, GainRisingInTheNeckIsTheRateAlone) {
  const NeckedWire wire;
  const auto points = necked_wire(wire);
  const ForceCurve sim = simulation(points);
  const auto [truth, end_gain] = tested_faster(points, wire, 0.014, 100.0);
  const Diagnosis d = diagnose({sampled(truth, 0.003, 7)}, sim, {});
  ASSERT_EQ(d.cause, "strain_rate") << d.reason;
  const RankedEffect& top = d.ranking.front();
  ASSERT_EQ(top.effect, "strain_rate");
  EXPECT_LE(top.gap_after, 1.5 * d.noise_floor);
  // The fitted gain at the end of the test within 10 % of the true one.
  const ForceCurve fitted = apply_effects(sim, top.fitted, curve_scale(sim));
  const double fitted_gain = fitted.f.back() / sim.f.back();
  EXPECT_NEAR(fitted_gain - 1.0, end_gain - 1.0, 0.10 * (end_gain - 1.0))
      << "fitted " << fitted_gain << ", true " << end_gain;
  // The gain before the neck too (stress factor = the gain at the start of the test).
  EXPECT_NEAR(top.fitted[0].params[0] - 1.0, 0.014 * std::log(100.0), 0.10 * 0.014 * std::log(100.0));
}

// A real grip slip beside the rate that grows in the neck is still a pair: the growth the rate
// may now take does not swallow the slip.
TEST(GapRateGrowth, GripSlipBesideAGrowingRateGainIsStillThePair) {
  const NeckedWire wire;
  const auto points = necked_wire(wire);
  const ForceCurve sim = simulation(points);
  const double peak = curve_scale(sim).peak_force_N;
  const ForceCurve rate = tested_faster(points, wire, 0.014, 100.0).first;
  // Slip of 3 mm/kN once the force passes 60 % of the peak (the catalogue's slip law, applied
  // to the rate's curve).
  const ForceCurve slipped = apply_effects(rate, {{&find_effect("grip_slip"), {0.6 * peak, 3.0, 0.0}}}, curve_scale(rate));
  const Diagnosis d = diagnose({sampled(slipped, 0.003, 8)}, sim, {});
  EXPECT_EQ(d.cause, "grip_slip+strain_rate") << d.reason;
}

// The same pair with a constant gain (the catalogue's forms for both).
TEST(GapRateGrowth, GripSlipBesideAConstantRateGainIsThePair) {
  const ForceCurve sim = voce_tension_curve();
  const CurveScale scale = curve_scale(sim);
  const ForceCurve lab = apply_effects(sim, {{&find_effect("strain_rate"), {1.08}},
                                             {&find_effect("grip_slip"), {0.6 * scale.peak_force_N, 3.0, 0.0}}},
                                       scale);
  const Diagnosis d = diagnose({sampled(lab, 0.003, 9)}, sim, {});
  EXPECT_EQ(d.cause, "grip_slip+strain_rate") << d.reason;
}

}  // namespace
}  // namespace dtwire::gap
