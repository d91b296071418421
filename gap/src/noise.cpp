#include "dtwire/gap/noise.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>

namespace dtwire::gap {
namespace {

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

}  // namespace

std::size_t default_half_window(std::size_t points) {
  return std::clamp<std::size_t>(points / 40, 3, 15);
}

Smoothed smooth_curve(const ForceCurve& curve, std::size_t half_window) {
  const std::size_t n = curve.size();
  Smoothed s{std::vector<double>(n), std::vector<double>(n)};
  for (std::size_t i = 0; i < n; ++i) {
    std::size_t lo = i >= half_window ? i - half_window : 0;
    std::size_t hi = std::min(n - 1, i + half_window);
    // Keep the window full near the ends so the quadratic stays determined.
    const std::size_t width = std::min(n - 1, 2 * half_window);
    if (hi - lo < width) {
      if (lo == 0) hi = std::min(n - 1, width);
      else lo = hi >= width ? hi - width : 0;
    }
    const std::size_t m = hi - lo + 1;
    double span = std::abs(curve.u[hi] - curve.u[lo]);
    if (!(span > 0)) span = 1.0;
    Eigen::MatrixXd a(m, 3);
    Eigen::VectorXd b(m);
    for (std::size_t k = 0; k < m; ++k) {
      const double x = (curve.u[lo + k] - curve.u[i]) / span;
      a(k, 0) = 1.0;
      a(k, 1) = x;
      a(k, 2) = x * x;
      b(k) = curve.f[lo + k];
    }
    const int columns = m >= 3 ? 3 : static_cast<int>(m);
    const Eigen::VectorXd c = a.leftCols(columns).colPivHouseholderQr().solve(b);
    s.value[i] = c(0);
    s.slope[i] = columns > 1 ? c(1) / span : 0.0;
  }
  return s;
}

double estimate_noise_sigma(const ForceCurve& curve) {
  const std::size_t h = default_half_window(curve.size());
  const Smoothed s = smooth_curve(curve, h);
  std::vector<double> residual(curve.size());
  for (std::size_t i = 0; i < residual.size(); ++i) residual[i] = curve.f[i] - s.value[i];
  const double med = median(residual);
  for (double& r : residual) r = std::abs(r - med);
  // Hat value of a centred quadratic window of 2h+1 evenly spaced points.
  const double m = static_cast<double>(h);
  const double hat = 3.0 * (3 * m * m + 3 * m - 1) / ((2 * m + 3) * (2 * m + 1) * (2 * m - 1));
  return 1.4826 * median(residual) / std::sqrt(1.0 - hat);
}

double lag1_autocorrelation(const std::vector<double>& residual) {
  const std::size_t n = residual.size();
  if (n < 3) return 0.0;
  double mean = 0.0;
  for (double r : residual) mean += r;
  mean /= static_cast<double>(n);
  double c0 = 0.0, c1 = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    c0 += (residual[i] - mean) * (residual[i] - mean);
    if (i > 0) c1 += (residual[i] - mean) * (residual[i - 1] - mean);
  }
  return c0 > 0 ? c1 / c0 : 0.0;
}

double effective_sample_size(std::size_t n, double rho1, double minimum) {
  const double rho = std::clamp(rho1, 0.0, 0.99);
  return std::max(minimum, static_cast<double>(n) * (1.0 - rho) / (1.0 + rho));
}

}  // namespace dtwire::gap
