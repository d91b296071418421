#pragma once
// Laboratory-like curves for the selfcheck and the tests: base models of a 2.7 mm wire in
// tension (the DEM backbone of Bertrand 2008 / Thoeni 2013 on a 250 mm gauge, and a Voce
// elastic-plastic curve with necking), and sampling them as a testing machine would.
#include <filesystem>
#include <random>

#include "dtwire/gap/force_curve.hpp"

namespace dtwire::gap {

// 2.7 mm wire: A = pi 2.7^2 / 4 = 5.7256 mm^2; EN 10223-3 gauge length 250 mm.
inline constexpr double kWireArea_m2 = 5.7256e-6;
inline constexpr double kGaugeLength_m = 0.25;

struct VoceWire {
  double young_Pa = 180e9;
  double yield_Pa = 380e6;
  double saturation_Pa = 170e6;  // Q in sigma = sigma_y + Q (1 - exp(-b eps_p)) + H eps_p
  double rate = 25.0;            // b
  double linear_Pa = 150e6;      // H
  double neck_width = 0.03;      // post-peak force decay length, fraction of the gauge
  double fracture_ratio = 0.4;   // curve ends when the force falls below this x peak
};

// Engineering force-displacement of a uniform bar (true stress times the current area,
// A0 exp(-eps)), which peaks at the Considere point; past the peak a necking factor
// exp(-((u - u_peak) / w)^2) takes over until fracture.
ForceCurve voce_tension_curve(const VoceWire& wire = {}, std::size_t points = 600);

// The DEM backbone (strain_1, stress_Pa) as force-displacement on the 250 mm gauge, refined to
// `points` (its vertices kept).
ForceCurve backbone_tension_curve(const std::filesystem::path& backbone_csv, std::size_t points = 600);

struct LabSampling {
  std::size_t points = 800;       // evenly spaced in displacement (displacement control)
  double end_m = 0.0;             // test end (<= 0: the model's last displacement)
  double noise_sigma_N = 0.0;     // load-cell noise
  double noise_rho = 0.0;         // its lag-1 correlation (AR(1))
};

// The model evaluated at the sampling displacements (branch-aware, clamped), plus noise.
ForceCurve sample_lab_curve(const ForceCurve& model, const LabSampling& sampling, std::mt19937& rng);

}  // namespace dtwire::gap
