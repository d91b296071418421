#pragma once
// Curve operations: interpolation/resampling, arc-length parametrisation, and splitting into
// monotone branches (loading / unloading).
#include <cstddef>
#include <string_view>
#include <vector>

#include "dtwire/core/curve.hpp"

namespace dtwire {

// Linear interpolation of y(x) at xq; x must be strictly monotone (either direction).
// Queries outside [min x, max x] take the end values (no extrapolation).
// Throws std::invalid_argument if sizes differ, x has < 2 points or is not strictly monotone.
std::vector<double> interpolate(const std::vector<double>& x, const std::vector<double>& y,
                                const std::vector<double>& xq);

// n evenly spaced values from first to last (n >= 2).
std::vector<double> linspace(double first, double last, std::size_t n);

// Every channel of `curve` resampled at the given abscissa values (in the abscissa channel's
// own unit). The abscissa channel must be strictly monotone.
Curve resample(const Curve& curve, std::string_view abscissa, const std::vector<double>& at);

// Cumulative arc length along (x/x_scale, y/y_scale); starts at 0.
std::vector<double> arc_length(const std::vector<double>& x, const std::vector<double>& y,
                               double x_scale, double y_scale);
// Arc length with both axes normalised by their ranges, divided by its total: runs 0 -> 1.
// Throws std::invalid_argument for a curve of zero length.
std::vector<double> normalized_arc_length(const std::vector<double>& x, const std::vector<double>& y);

enum class BranchDirection { Loading, Unloading };

struct Branch {
  std::size_t begin;  // first index
  std::size_t end;    // one past the last index; consecutive branches share their turning point
  BranchDirection direction;
};

// Splits x into maximal monotone runs. A reversal counts only once x has moved back by more
// than `tolerance` from the running extreme, so noise does not create spurious branches.
std::vector<Branch> split_monotone_branches(const std::vector<double>& x, double tolerance = 0.0);

}  // namespace dtwire
