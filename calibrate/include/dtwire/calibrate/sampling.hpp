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

}  // namespace dtwire::calibrate
