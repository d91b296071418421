#include "dtwire/calibrate/sampling.hpp"

#include <cmath>
#include <random>
#include <stdexcept>

namespace dtwire::calibrate {

std::vector<std::vector<double>> latin_hypercube(std::size_t count, const std::vector<double>& lower,
                                                 const std::vector<double>& upper,
                                                 std::uint64_t seed) {
  return latin_hypercube(count, lower, upper, std::vector<bool>(lower.size(), false), seed);
}

std::vector<std::vector<double>> latin_hypercube(std::size_t count, const std::vector<double>& lower,
                                                 const std::vector<double>& upper,
                                                 const std::vector<bool>& logarithmic, std::uint64_t seed) {
  if (lower.size() != upper.size() || logarithmic.size() != lower.size())
    throw std::invalid_argument("latin_hypercube: bound sizes differ");
  for (std::size_t d = 0; d < lower.size(); ++d)
    if (logarithmic[d] && !(lower[d] > 0.0 && upper[d] > 0.0))
      throw std::invalid_argument("latin_hypercube: a logarithmic dimension needs bounds > 0");
  std::mt19937_64 generator(seed);
  const auto uniform = [&] { return static_cast<double>(generator() >> 11) * 0x1.0p-53; };
  std::vector<std::vector<double>> points(count, std::vector<double>(lower.size()));
  for (std::size_t d = 0; d < lower.size(); ++d) {
    std::vector<std::size_t> strata(count);
    for (std::size_t i = 0; i < count; ++i) strata[i] = i;
    // Fisher-Yates with our own index draw (std::shuffle's algorithm is not specified).
    for (std::size_t i = count; i > 1; --i) {
      const auto k = static_cast<std::size_t>(uniform() * static_cast<double>(i));
      std::swap(strata[i - 1], strata[k < i ? k : i - 1]);
    }
    for (std::size_t i = 0; i < count; ++i) {
      const double u = (static_cast<double>(strata[i]) + uniform()) / static_cast<double>(count);
      points[i][d] = logarithmic[d] ? lower[d] * std::pow(upper[d] / lower[d], u) : lower[d] + u * (upper[d] - lower[d]);
    }
  }
  return points;
}

}  // namespace dtwire::calibrate
