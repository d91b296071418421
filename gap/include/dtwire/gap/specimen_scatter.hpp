#pragma once
// Smooth specimen-to-specimen scatter of repeated laboratory curves: each specimen differs from
// the mean specimen by a force scale (section, strength) and a displacement scale (gauge,
// strain), lab_i(u) = (1 + a_i) M(u / (1 + b_i)). The simulation stands for the mean specimen:
// the deviations a_i, b_i are free, their mean only within the uncertainty of a mean of n
// specimens. They are profiled out of every fit (variable projection), so an effect is judged
// on what the scatter cannot explain (docs/gap.md, "Specimen scatter").
#include <vector>

#include "dtwire/gap/curve_metrics.hpp"

namespace dtwire::gap {

struct SpecimenScatter {
  bool active = false;        // two or more laboratory curves
  double force_bound = 0.0;   // largest |mean a_i|
  double length_bound = 0.0;  // largest |mean b_i|
};

inline constexpr double kScatterAllowance = 3.0;      // standard errors of the mean allowed
inline constexpr double kMinimumSpecimenScatter = 0.01;  // sd of a_i, b_i assumed at least

// Best (a, b) of the model against one curve (weighted linearised least squares, one
// Gauss-Newton step from 0), unbounded.
struct ScaleFit {
  double force = 0.0, length = 0.0;
};
ScaleFit fit_specimen_scale(const ForceCurve& model, const Comparison& lab);

// The model scaled: u (1 + length), f (1 + force).
ForceCurve scaled(const ForceCurve& model, const ScaleFit& s);

// Model forces at each curve's points with the scatter profiled out: per-curve scales, their
// mean clamped to the bounds (all shifted alike). Without `active`: the plain model forces.
std::vector<std::vector<double>> forces_with_scatter(const ForceCurve& model, const std::vector<Comparison>& labs,
                                                     const SpecimenScatter& scatter);
// The same with a model per curve (`models[k]` for `labs[k]`: a damage on each record's clock).
std::vector<std::vector<double>> forces_with_scatter(const std::vector<ForceCurve>& models,
                                                     const std::vector<Comparison>& labs,
                                                     const SpecimenScatter& scatter);

// The scatter of repeated curves: bounds on the mean from the pairwise scale differences
// (sd_a^2 = mean (a_j - a_i)^2 / 2 over pairs, at least kMinimumSpecimenScatter; bound
// kScatterAllowance sd / sqrt(n)), and the mean gap between the curves once each pair is
// aligned by its scales (`aligned_gap`).
struct ScatterEstimate {
  SpecimenScatter scatter;
  double aligned_gap = 0.0;
  double force_sd = 0.0, length_sd = 0.0;  // as estimated, before the minimum
};
ScatterEstimate estimate_scatter(const std::vector<ForceCurve>& labs, const std::vector<Comparison>& comparisons);

}  // namespace dtwire::gap
