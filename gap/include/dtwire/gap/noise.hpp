#pragma once
// Noise of a laboratory curve and the statistics of residuals: local-quadratic smoothing
// (Savitzky and Golay 1964, on the actual abscissa), a robust noise estimate from the
// high-frequency residual, lag-1 autocorrelation and the effective sample size.
#include <cstddef>
#include <vector>

#include "dtwire/gap/force_curve.hpp"

namespace dtwire::gap {

struct Smoothed {
  std::vector<double> value;  // smoothed force [N]
  std::vector<double> slope;  // d force / d displacement [N/m]
};

// Local quadratic least squares over index windows of 2 * half_window + 1 points.
Smoothed smooth_curve(const ForceCurve& curve, std::size_t half_window);

// The half window used for noise estimation and region naming: n / 40, within [3, 15].
std::size_t default_half_window(std::size_t points);

// Standard deviation of the force noise [N]: 1.4826 * MAD of the smoothing residual,
// corrected for the variance the smoother absorbs (hat value at the window centre).
double estimate_noise_sigma(const ForceCurve& curve);

double lag1_autocorrelation(const std::vector<double>& residual);

// n (1 - rho1) / (1 + rho1) for AR(1)-like residuals (e.g. Wilks, Statistical Methods in the
// Atmospheric Sciences, eq. 5.12), rho1 clamped to [0, 0.99]; at least `minimum`.
double effective_sample_size(std::size_t n, double rho1, double minimum);

}  // namespace dtwire::gap
