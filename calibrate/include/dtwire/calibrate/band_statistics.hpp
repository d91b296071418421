#pragma once
// Statistics of a figure computed on parameter sets drawn from a fit's uncertainty
// (propagation.hpp): its band, the band's convergence, the linearised band and sensitivities.
//
// - Band: mean, sample standard deviation (n - 1) and the 5 % and 95 % sample quantiles by
//   Hyndman & Fan (1996, Am. Stat. 50:361) definition 7 (linear interpolation between order
//   statistics at h = (n - 1) p; R's and NumPy's default).
// - Convergence: the standard error of each band end by the bootstrap (Efron & Tibshirani 1993,
//   An Introduction to the Bootstrap, ch. 6: B resamples of the n values, the SD of their
//   quantile), and the stopping rule of the adaptive Monte Carlo procedure of JCGM 101:2008
//   (GUM Supplement 1, 7.9): stop when twice each result's standard error is below the
//   numerical tolerance delta. Here delta = tolerance x (q95 - q05) for both ends, so the ends
//   are known to that fraction of the band's width at about 95 % confidence. The check starts
//   at n = 21, the smallest n at which the definition-7 5 % quantile lies above the sample's
//   minimum ((n - 1) 0.05 >= 1): below it the lower end is the smallest value drawn.
// - Linearised band (first-order propagation, JCGM 100:2008 (GUM) 5.1.2): var f = g^T C g with
//   g the finite-difference gradient of f in the sampled coordinates and C their covariance as
//   sampled (the NOT IDENTIFIED ones with the uniform's variance); band = f(mean) -+ 1.645 sd, the
//   normal's 5-95 % quantiles.
// - Sensitivity from the same samples: the first-order (main-effect) index
//   S_i = Var(E[f | x_i]) / Var(f) by the given-data estimator of Plischke, Borgonovo & Smith
//   (2013, Eur. J. Oper. Res. 226:536): the samples sorted by x_i and cut into M classes of
//   equal count, Var of the class means (weighted by class size) over Var f. M = floor(sqrt(n))
//   (at least 2), their suggestion for small samples; a parameter f does not depend on still
//   scores about (M - 1) / (n - 1) (the class means of pure noise), reported as the index's floor.
#include <cstdint>
#include <vector>

namespace dtwire::calibrate {

struct BandStatistics {
  std::size_t count = 0;
  double mean = 0.0, sd = 0.0;
  double q05 = 0.0, q95 = 0.0;
  double q05_standard_error = 0.0, q95_standard_error = 0.0;  // bootstrap; 0 below 2 values
};

// Definition-7 quantile of `values` (any order), p in [0, 1]. Throws std::invalid_argument when empty.
double sample_quantile(std::vector<double> values, double p);

// Mean, SD, 5-95 % band and the bootstrap standard errors of its ends (`resamples` resamples
// drawn from `seed`, std::mt19937_64 with our own index map: the same on every platform).
BandStatistics band_statistics(const std::vector<double>& values, std::uint64_t seed = 1, int resamples = 1000);

constexpr std::size_t kSmallestConvergenceCount = 21;  // (n - 1) 0.05 >= 1 (header)

// JCGM 101 7.9's rule on the band's ends: n >= kSmallestConvergenceCount and
// 2 SE(q05) <= tolerance (q95 - q05) and 2 SE(q95) <= tolerance (q95 - q05). A band of zero
// width (a figure the parameters do not move) counts as converged.
bool band_converged(const BandStatistics& s, double tolerance);

// First-order index of f with respect to x (Plischke et al. 2013; header) and its floor
// (M - 1) / (n - 1). Returns {0, 0} when f does not vary or n < 4.
struct FirstOrderIndex {
  double index = 0.0;
  double floor = 0.0;
};
FirstOrderIndex first_order_index(const std::vector<double>& x, const std::vector<double>& f);

// sqrt(g^T C g): the linearised standard deviation.
double linearised_sd(const std::vector<double>& gradient, const std::vector<std::vector<double>>& covariance);

// The normal's 95 % quantile: the linearised band is centre -+ kNormal95 sd.
constexpr double kNormal95 = 1.6448536269514722;

}  // namespace dtwire::calibrate
