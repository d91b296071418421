#pragma once
// Synthetic target curves: an experiment's simulator run at given parameter values, thinned,
// with Gaussian noise on the compared channels. For demonstrations and for tests that recover
// known parameters (`dtwire fit --synthesize`).
#include <cstdint>
#include <random>

#include "dtwire/calibrate/experiment.hpp"

namespace dtwire::calibrate {

// Channels: the experiment's abscissa, the path channels the simulator reports (displacement,
// rotation, strain; context for plots), then the compared channels with noise of standard
// deviation `noise` x (range of the channel), drawn from `generator` (Box-Muller on its raw
// output, so the same seed gives the same curves on every platform). At most `points` rows
// (every k-th simulated point plus the last). Lengths are written in mm.
Curve synthesize_target(const Experiment& experiment, const ParameterValues& values, double noise,
                        std::mt19937_64& generator, std::size_t points);

}  // namespace dtwire::calibrate
