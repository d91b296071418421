#pragma once
// Helpers shared by the calibrate tests: synthetic targets with deterministic Gaussian noise.
#include <cmath>
#include <cstdint>
#include <random>
#include <string>

#include "dtwire/calibrate/simulator.hpp"

namespace dtwire::calibrate::test {

// Box-Muller on std::mt19937_64 (whose output the standard fixes), so the noise is the same
// on every platform.
class Gaussian {
 public:
  explicit Gaussian(std::uint64_t seed) : generator_(seed) {}
  double operator()() {
    const double u1 = (static_cast<double>(generator_() >> 11) + 0.5) * 0x1.0p-53;
    const double u2 = static_cast<double>(generator_() >> 11) * 0x1.0p-53;
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * M_PI * u2);
  }

 private:
  std::mt19937_64 generator_;
};

// The simulator's curve with N(0, sigma^2) noise added to channel `quantity` (SI).
inline Curve noisy(const Curve& clean, const std::string& quantity, double sigma, std::uint64_t seed) {
  Gaussian noise(seed);
  Curve out;
  for (const Channel& c : clean.channels()) {
    std::vector<double> v = c.values;
    if (c.quantity == quantity)
      for (double& x : v) x += sigma / c.unit.to_si * noise();
    out.add_channel(c.quantity, c.unit, v);
  }
  return out;
}

}  // namespace dtwire::calibrate::test
