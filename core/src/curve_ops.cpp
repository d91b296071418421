#include "dtwire/core/curve_ops.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace dtwire {

std::vector<double> interpolate(const std::vector<double>& x, const std::vector<double>& y,
                                const std::vector<double>& xq) {
  if (x.size() != y.size()) throw std::invalid_argument("interpolate: x and y differ in length");
  if (x.size() < 2) throw std::invalid_argument("interpolate: need at least 2 points");
  const bool increasing = x.back() > x.front();
  for (std::size_t i = 1; i < x.size(); ++i)
    if (increasing ? !(x[i] > x[i - 1]) : !(x[i] < x[i - 1]))
      throw std::invalid_argument("interpolate: abscissa is not strictly monotone at index " +
                                  std::to_string(i));
  std::vector<double> xs = x, ys = y;
  if (!increasing) {
    std::reverse(xs.begin(), xs.end());
    std::reverse(ys.begin(), ys.end());
  }
  std::vector<double> out(xq.size());
  for (std::size_t q = 0; q < xq.size(); ++q) {
    const double v = xq[q];
    if (v <= xs.front()) {
      out[q] = ys.front();
    } else if (v >= xs.back()) {
      out[q] = ys.back();
    } else {
      const auto upper = std::upper_bound(xs.begin(), xs.end(), v);
      const std::size_t i = static_cast<std::size_t>(upper - xs.begin());
      const double t = (v - xs[i - 1]) / (xs[i] - xs[i - 1]);
      out[q] = ys[i - 1] + t * (ys[i] - ys[i - 1]);
    }
  }
  return out;
}

std::vector<double> linspace(double first, double last, std::size_t n) {
  if (n < 2) throw std::invalid_argument("linspace: need at least 2 points");
  std::vector<double> out(n);
  for (std::size_t i = 0; i < n; ++i)
    out[i] = first + (last - first) * static_cast<double>(i) / static_cast<double>(n - 1);
  out.back() = last;
  return out;
}

Curve resample(const Curve& curve, std::string_view abscissa, const std::vector<double>& at) {
  const Channel& x = curve.channel(abscissa);
  Curve out;
  for (const auto& [key, value] : curve.metadata_entries()) out.set_metadata(key, value);
  for (const Channel& c : curve.channels()) {
    if (c.quantity == x.quantity)
      out.add_channel(c.quantity, c.unit, at);
    else
      out.add_channel(c.quantity, c.unit, interpolate(x.values, c.values, at));
  }
  return out;
}

std::vector<double> arc_length(const std::vector<double>& x, const std::vector<double>& y,
                               double x_scale, double y_scale) {
  if (x.size() != y.size()) throw std::invalid_argument("arc_length: x and y differ in length");
  if (!(x_scale > 0) || !(y_scale > 0)) throw std::invalid_argument("arc_length: scales must be > 0");
  std::vector<double> s(x.size(), 0.0);
  for (std::size_t i = 1; i < x.size(); ++i)
    s[i] = s[i - 1] + std::hypot((x[i] - x[i - 1]) / x_scale, (y[i] - y[i - 1]) / y_scale);
  return s;
}

std::vector<double> normalized_arc_length(const std::vector<double>& x, const std::vector<double>& y) {
  if (x.empty()) throw std::invalid_argument("normalized_arc_length: empty curve");
  const auto [xmin, xmax] = std::minmax_element(x.begin(), x.end());
  const auto [ymin, ymax] = std::minmax_element(y.begin(), y.end());
  const double xr = *xmax - *xmin > 0 ? *xmax - *xmin : 1.0;
  const double yr = *ymax - *ymin > 0 ? *ymax - *ymin : 1.0;
  std::vector<double> s = arc_length(x, y, xr, yr);
  if (!(s.back() > 0)) throw std::invalid_argument("normalized_arc_length: curve has zero length");
  for (double& v : s) v /= s.back();
  return s;
}

std::vector<Branch> split_monotone_branches(const std::vector<double>& x, double tolerance) {
  std::vector<Branch> branches;
  if (x.size() < 2) return branches;
  std::size_t begin = 0;
  std::size_t extreme = 0;  // index of the running extreme within the current branch
  int direction = 0;        // +1 loading, -1 unloading, 0 not yet known
  for (std::size_t i = 1; i < x.size(); ++i) {
    if (direction == 0) {
      if (std::abs(x[i] - x[begin]) > tolerance) {
        direction = x[i] > x[begin] ? 1 : -1;
        extreme = i;
      }
      continue;
    }
    if ((x[i] - x[extreme]) * direction >= 0) {
      extreme = i;
    } else if (std::abs(x[i] - x[extreme]) > tolerance) {
      branches.push_back({begin, extreme + 1,
                          direction > 0 ? BranchDirection::Loading : BranchDirection::Unloading});
      begin = extreme;
      direction = -direction;
      extreme = i;
    }
  }
  branches.push_back({begin, x.size(),
                      direction >= 0 ? BranchDirection::Loading : BranchDirection::Unloading});
  return branches;
}

}  // namespace dtwire
