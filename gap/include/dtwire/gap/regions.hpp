#pragma once
// Where the gap lies. The laboratory curve is cut into named regions from its shape (toe,
// elastic, yield, hardening, peak, post_peak, unloading, reloading); the residual along the
// curve is cut at change points (binary segmentation of a piecewise-linear fit, BIC-type
// penalty); each residual segment takes the name of the region it mostly lies in, and
// neighbouring segments with the same name merge.
#include <string>
#include <vector>

#include "dtwire/gap/curve_metrics.hpp"

namespace dtwire::gap {

struct RegionSpan {
  std::string name;
  std::size_t begin = 0;  // lab point indices [begin, end)
  std::size_t end = 0;
};

struct GapSegment {
  std::string region;
  std::size_t begin = 0;  // lab point indices [begin, end)
  std::size_t end = 0;
  double from_m = 0.0;
  double to_m = 0.0;
  double gap = 0.0;       // normalised area inside the segment
  double share = 0.0;     // gap / total gap
  std::string direction;  // "horizontal offset", "vertical offset" or "slope"
  std::string mode;       // loading mode, in the combined diagnosis of several modes
};

// Named regions of the laboratory curve, covering every point in order.
std::vector<RegionSpan> name_regions(const ForceCurve& lab);

// Change points of the residual r along the normalised displacement; returns segment starts
// (first is 0). `noise_variance` is the variance of r expected from noise alone.
std::vector<std::size_t> residual_change_points(const std::vector<double>& x,
                                                const std::vector<double>& r,
                                                double noise_variance);

std::vector<GapSegment> locate_gap(const Comparison& comparison,
                                   const std::vector<double>& model_forces,
                                   const std::vector<RegionSpan>& regions, double noise_sigma_N);

// Normalised area of `model_forces` inside each segment.
std::vector<double> segment_gaps(const std::vector<GapSegment>& segments,
                                 const Comparison& comparison,
                                 const std::vector<double>& model_forces);

}  // namespace dtwire::gap
