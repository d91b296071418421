#pragma once
// Synthetic target curves: an experiment's simulator run at given parameter values, thinned,
// with Gaussian noise on the compared channels. For demonstrations and for tests that recover
// known parameters (`dtwire fit --synthesize`).
#include <cstdint>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "dtwire/calibrate/experiment.hpp"
#include "dtwire/calibrate/fit_file.hpp"

namespace dtwire::calibrate {

// Channels: the experiment's abscissa, the path channels the simulator reports (displacement,
// rotation, strain; context for plots), then the compared channels with noise of standard
// deviation `noise` x (range of the channel), drawn from `generator` (Box-Muller on its raw
// output, so the same seed gives the same curves on every platform). At most `points` rows
// (every k-th simulated point plus the last). Lengths are written in mm. `also_written`: further
// simulated channels written without noise (those a target mapping reads, compared or not).
Curve synthesize_target(const Experiment& experiment, const ParameterValues& values, double noise,
                        std::mt19937_64& generator, std::size_t points,
                        const std::vector<std::string>& also_written = {});

// `dtwire fit --synthesize DIR`: every experiment's target at the parameters' reference values
// (else initial values; offsets resolved, parameter.hpp), under the target's column names
// (target_columns inverted) at its target name below `dir`, so that `--targets DIR` reads them
// back. Returns the files written.
// Throws InputError for two experiments with one target name or a mapping that cannot be
// inverted.
std::vector<std::filesystem::path> write_synthetic_targets(const FitDefinition& def, const std::filesystem::path& dir,
                                                           double noise, std::uint64_t seed, std::size_t points);

}  // namespace dtwire::calibrate
