#pragma once
// Space-filling start points for multi-start fits.
#include <cstdint>
#include <vector>

namespace dtwire::calibrate {

// Latin hypercube design: `count` points in the box [lower, upper], one per stratum in every
// dimension, from a fixed seed (same seed -> same design on every platform: the generator is
// std::mt19937_64, whose output the standard fixes, with our own mapping to [0, 1)).
std::vector<std::vector<double>> latin_hypercube(std::size_t count, const std::vector<double>& lower,
                                                 const std::vector<double>& upper,
                                                 std::uint64_t seed);

// The same design with dimension d stratified in log(value) where logarithmic[d] is true
// (bounds must then be > 0): for bounds spanning decades a linear design puts nearly every
// start in the top decade (bounds 20-2e4: 90 % of the points above 2e3).
std::vector<std::vector<double>> latin_hypercube(std::size_t count, const std::vector<double>& lower,
                                                 const std::vector<double>& upper,
                                                 const std::vector<bool>& logarithmic, std::uint64_t seed);

}  // namespace dtwire::calibrate
