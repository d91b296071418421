#pragma once
// Coverage of the reported uncertainty: fit many noise realisations of synthetic curves made
// by the same model at known parameters, and collect z = (estimate - truth) / sigma.
#include <cmath>
#include <cstddef>
#include <vector>

namespace dtwire::calibrate::test {

struct Coverage {
  std::vector<double> z;
  double fraction_within(double k) const {
    std::size_t inside = 0;
    for (double v : z) inside += std::abs(v) < k;
    return static_cast<double>(inside) / static_cast<double>(z.size());
  }
  double rms() const {
    double s = 0;
    for (double v : z) s += v * v;
    return std::sqrt(s / static_cast<double>(z.size()));
  }
};

}  // namespace dtwire::calibrate::test
