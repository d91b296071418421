#include "dtwire/calibrate/band_statistics.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <stdexcept>

namespace dtwire::calibrate {
namespace {

double sorted_quantile(const std::vector<double>& sorted, double p) {
  const double h = (static_cast<double>(sorted.size()) - 1.0) * p;
  const auto low = static_cast<std::size_t>(std::floor(h));
  const std::size_t high = std::min(low + 1, sorted.size() - 1);
  return sorted[low] + (h - static_cast<double>(low)) * (sorted[high] - sorted[low]);
}

// Shifted by the first value: equal values give that value exactly, and the sums stay small.
double mean_of(const std::vector<double>& v) {
  double sum = 0.0;
  for (double x : v) sum += x - v.front();
  return v.front() + sum / static_cast<double>(v.size());
}

double sd_of(const std::vector<double>& v) {
  if (v.size() < 2) return 0.0;
  const double m = mean_of(v) - v.front();
  double s = 0.0;
  for (double x : v) s += (x - v.front() - m) * (x - v.front() - m);
  return std::sqrt(s / static_cast<double>(v.size() - 1));
}

}  // namespace

double sample_quantile(std::vector<double> values, double p) {
  if (values.empty()) throw std::invalid_argument("sample_quantile: no values");
  std::sort(values.begin(), values.end());
  return sorted_quantile(values, p);
}

BandStatistics band_statistics(const std::vector<double>& values, std::uint64_t seed, int resamples) {
  if (values.empty()) throw std::invalid_argument("band_statistics: no values");
  BandStatistics s;
  s.count = values.size();
  s.mean = mean_of(values);
  s.sd = sd_of(values);
  std::vector<double> sorted = values;
  std::sort(sorted.begin(), sorted.end());
  s.q05 = sorted_quantile(sorted, 0.05);
  s.q95 = sorted_quantile(sorted, 0.95);
  if (values.size() < 2) return s;
  std::mt19937_64 generator(seed);
  const auto index = [&] {
    const double u = static_cast<double>(generator() >> 11) * 0x1.0p-53;
    return std::min(static_cast<std::size_t>(u * static_cast<double>(values.size())), values.size() - 1);
  };
  std::vector<double> low(static_cast<std::size_t>(resamples)), high(low.size()), resample(values.size());
  for (std::size_t b = 0; b < low.size(); ++b) {
    for (double& x : resample) x = values[index()];
    std::sort(resample.begin(), resample.end());
    low[b] = sorted_quantile(resample, 0.05);
    high[b] = sorted_quantile(resample, 0.95);
  }
  s.q05_standard_error = sd_of(low);
  s.q95_standard_error = sd_of(high);
  return s;
}

bool band_converged(const BandStatistics& s, double tolerance) {
  if (s.count < kSmallestConvergenceCount) return false;
  const double delta = tolerance * (s.q95 - s.q05);
  return 2.0 * s.q05_standard_error <= delta && 2.0 * s.q95_standard_error <= delta;
}

FirstOrderIndex first_order_index(const std::vector<double>& x, const std::vector<double>& f) {
  if (x.size() != f.size()) throw std::invalid_argument("first_order_index: sizes differ");
  const std::size_t n = f.size();
  if (n < 4) return {};
  const double total = sd_of(f) * sd_of(f);
  if (!(total > 0.0)) return {};
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return x[a] < x[b]; });
  const std::size_t classes = std::max<std::size_t>(2, static_cast<std::size_t>(std::floor(std::sqrt(static_cast<double>(n)))));
  const double mean = mean_of(f);
  double between = 0.0;
  for (std::size_t c = 0; c < classes; ++c) {
    const std::size_t begin = c * n / classes, end = (c + 1) * n / classes;
    double sum = 0.0;
    for (std::size_t k = begin; k < end; ++k) sum += f[order[k]];
    const double class_mean = sum / static_cast<double>(end - begin);
    between += static_cast<double>(end - begin) * (class_mean - mean) * (class_mean - mean);
  }
  // Both variances over n - 1, so a step function of x_i scores 1.
  FirstOrderIndex result;
  result.index = between / static_cast<double>(n - 1) / total;
  result.floor = static_cast<double>(classes - 1) / static_cast<double>(n - 1);
  return result;
}

double linearised_sd(const std::vector<double>& gradient, const std::vector<std::vector<double>>& covariance) {
  double v = 0.0;
  for (std::size_t i = 0; i < gradient.size(); ++i)
    for (std::size_t j = 0; j < gradient.size(); ++j) v += gradient[i] * covariance.at(i).at(j) * gradient[j];
  return std::sqrt(std::max(v, 0.0));
}

}  // namespace dtwire::calibrate
