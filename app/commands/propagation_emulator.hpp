#pragma once
// The emulated band of `dtwire dem propagate --emulator` (docs/dem_engine.md, "The emulated
// band"): a Gaussian-process emulator (calibrate/emulator.hpp) per headline figure, trained on the
// sets run so far, predicts the figure on many more sets drawn from the same distribution; its
// band is the quantiles of those predictions plus their own error (latent and noise).
//
// Coordinates: parameter i of a set enters as (y_i - y_i(fitted)) / s_i, y the sampled coordinate
// (ln v for a log one) and s_i its sampled spread (sigma, or the uniform's (upper - lower) /
// sqrt(12)), so that every length scale is in units of the spread the draws cover. A parameter
// with zero spread enters as 0.
//
// Convergence: the emulated band's ends moved by at most tolerance x its width over each of the
// last two batches (three emulated rows), from `minimum_training` runs on: 2 x the parameter
// count (two runs per hyperparameter; Loeppky, Sacks & Welch 2009, Technometrics 51:366, find
// about 10 x that many needed for accurate prediction everywhere, which the band does not ask:
// the leave-one-out Q^2 and coverage in the report say how well it predicts).
#include <cstdint>
#include <optional>
#include <vector>

#include "propagation_outputs.hpp"

namespace dtwire::app {

// The emulator's coordinates of a set of own values.
std::vector<double> emulator_coordinates(const PropagationResult& r, const std::vector<double>& values);

std::size_t emulator_minimum_training(const PropagationResult& r);

// Figure f's emulated band on `points` (emulator coordinates); empty below the minimum count of
// successful runs with f defined.
std::optional<EmulatedFigure> emulate_figure(const PropagationResult& r, std::size_t f,
                                             const std::vector<std::vector<double>>& points, std::uint64_t seed);

// The rule above on r.convergence's rows, per figure.
std::vector<bool> emulator_converged(const PropagationResult& r, double tolerance);

}  // namespace dtwire::app
