#include "dtwire/gap/specimen_scatter.hpp"

#include <algorithm>
#include <cmath>

namespace dtwire::gap {
namespace {

constexpr double kLengthProbe = 0.01;  // displacement scale step for the length derivative

// Curve j where curve i was recorded too: the weights outside i's displacement range set to 0
// (a specimen that broke earlier is no scatter of the one that went on), renormalised.
Comparison within_range_of(const ForceCurve& i, Comparison j) {
  const auto [lo, hi] = std::minmax_element(i.u.begin(), i.u.end());
  double total = 0.0;
  for (std::size_t k = 0; k < j.weight.size(); ++k) {
    if (j.lab.u[k] < *lo || j.lab.u[k] > *hi) j.weight[k] = 0.0;
    total += j.weight[k];
  }
  if (total > 0)
    for (double& w : j.weight) w /= total;
  return j;
}

}  // namespace

ForceCurve scaled(const ForceCurve& model, const ScaleFit& s) {
  ForceCurve out = model;
  for (double& u : out.u) u *= 1.0 + s.length;
  for (double& f : out.f) f *= 1.0 + s.force;
  return out;
}

ScaleFit fit_specimen_scale(const ForceCurve& model, const Comparison& lab) {
  // r(a, b) = (1 + a) M(u / (1 + b)) - y ~ r0 + a M + b dM/db, dM/db by a forward difference.
  const std::vector<double> m = model_forces_at_lab(model, lab);
  const std::vector<double> probe = model_forces_at_lab(scaled(model, {0.0, kLengthProbe}), lab);
  double aa = 0, ab = 0, bb = 0, ar = 0, br = 0;
  for (std::size_t i = 0; i < m.size(); ++i) {
    const double w = lab.weight[i];
    const double ja = m[i], jb = (probe[i] - m[i]) / kLengthProbe, r = m[i] - lab.lab.f[i];
    aa += w * ja * ja;
    ab += w * ja * jb;
    bb += w * jb * jb;
    ar += w * ja * r;
    br += w * jb * r;
  }
  ScaleFit s;
  const double det = aa * bb - ab * ab;
  if (det > 1e-9 * aa * bb && aa > 0) {
    s.force = (-ar * bb + br * ab) / det;
    s.length = (-br * aa + ar * ab) / det;
  } else if (aa > 0) {  // no displacement sensitivity (e.g. a flat curve): force scale only
    s.force = -ar / aa;
  }
  // A deviation of more than half is not scatter but a different curve: keep the fit sane.
  s.force = std::clamp(s.force, -0.5, 0.5);
  s.length = std::clamp(s.length, -0.5, 0.5);
  return s;
}

std::vector<std::vector<double>> forces_with_scatter(const ForceCurve& model, const std::vector<Comparison>& labs,
                                                     const SpecimenScatter& scatter) {
  return forces_with_scatter(std::vector<ForceCurve>(labs.size(), model), labs, scatter);
}

std::vector<std::vector<double>> forces_with_scatter(const std::vector<ForceCurve>& models,
                                                     const std::vector<Comparison>& labs,
                                                     const SpecimenScatter& scatter) {
  std::vector<std::vector<double>> out;
  if (!scatter.active) {
    for (std::size_t k = 0; k < labs.size(); ++k) out.push_back(model_forces_at_lab(models[k], labs[k]));
    return out;
  }
  std::vector<ScaleFit> fits;
  ScaleFit mean;
  for (std::size_t k = 0; k < labs.size(); ++k) {
    const Comparison& c = labs[k];
    fits.push_back(fit_specimen_scale(models[k], c));
    mean.force += fits.back().force / static_cast<double>(labs.size());
    mean.length += fits.back().length / static_cast<double>(labs.size());
  }
  // The mean specimen is the simulation: its deviation only within the bounds.
  const double shift_force = std::clamp(mean.force, -scatter.force_bound, scatter.force_bound) - mean.force;
  const double shift_length = std::clamp(mean.length, -scatter.length_bound, scatter.length_bound) - mean.length;
  for (std::size_t k = 0; k < labs.size(); ++k) {
    fits[k].force += shift_force;
    fits[k].length += shift_length;
    out.push_back(model_forces_at_lab(scaled(models[k], fits[k]), labs[k]));
  }
  return out;
}

ScatterEstimate estimate_scatter(const std::vector<ForceCurve>& labs, const std::vector<Comparison>& comparisons) {
  ScatterEstimate e;
  const std::size_t n = labs.size();
  if (n < 2) return e;
  double sum_a = 0, sum_b = 0, gap = 0;
  int pairs = 0;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j)
      if (i != j) {
        const Comparison overlap = within_range_of(labs[i], comparisons[j]);
        const ScaleFit s = fit_specimen_scale(labs[i], overlap);
        sum_a += s.force * s.force;
        sum_b += s.length * s.length;
        gap += normalised_area(scaled(labs[i], s), overlap);
        ++pairs;
      }
  // a_j - a_i has variance 2 sd^2.
  e.force_sd = std::sqrt(sum_a / (2.0 * pairs));
  e.length_sd = std::sqrt(sum_b / (2.0 * pairs));
  e.aligned_gap = gap / pairs;
  const double root_n = std::sqrt(static_cast<double>(n));
  e.scatter.active = true;
  e.scatter.force_bound = kScatterAllowance * std::max(e.force_sd, kMinimumSpecimenScatter) / root_n;
  e.scatter.length_bound = kScatterAllowance * std::max(e.length_sd, kMinimumSpecimenScatter) / root_n;
  return e;
}

}  // namespace dtwire::gap
