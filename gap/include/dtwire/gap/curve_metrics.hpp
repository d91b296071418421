#pragma once
// Comparing a model curve with a laboratory curve on normalised axes: displacement divided by
// the laboratory's total travel, force by its peak force. The gap metric is the area between
// the curves on these axes, evaluated at the laboratory points (trapezoid weights), branch by
// branch (loading / unloading, core's split_monotone_branches).
#include <vector>

#include "dtwire/core/curve_ops.hpp"
#include "dtwire/gap/force_curve.hpp"

namespace dtwire::gap {

struct Comparison {
  ForceCurve lab;
  double u_scale = 1.0;               // total displacement travel of the lab curve [m]
  double f_scale = 1.0;               // peak |force| of the lab curve [N]
  std::vector<double> weight;         // per point, sums to 1 (normalised trapezoid widths)
  std::vector<Branch> branches;       // monotone branches of lab.u
  std::vector<std::size_t> branch_of; // branch index of each point
  // Where the record broke (its terminal drop, gap/include/dtwire/gap/fracture.hpp; 0: it ended
  // otherwise), and the damage's clock on this record: the reference fracture displacement over
  // this one's (1 for a record that did not break). Data of the record, kept by every copy (the
  // held-out blocks, the predictive check's single curve).
  double fracture_m = 0.0;
  double damage_clock = 1.0;
};

Comparison make_comparison(const ForceCurve& lab);

// Model force at every lab point: lab branch k is compared with model branch k (the last one
// when the model has fewer). Within a branch the model displacement is made monotone (a
// snap-back becomes a vertical drop) and the model is clamped at its ends.
std::vector<double> model_forces_at_lab(const ForceCurve& model, const Comparison& comparison);

// (model - lab) / f_scale at every lab point.
std::vector<double> normalised_residual(const std::vector<double>& model_forces,
                                        const Comparison& comparison);

// Area between the curves on normalised axes: sum of weight * |residual|.
double normalised_area(const std::vector<double>& model_forces, const Comparison& comparison);
double normalised_area(const ForceCurve& model, const Comparison& comparison);

// Discrete Frechet distance (Eiter and Mannila 1994) on the comparison's normalised axes;
// curves longer than `max_points` are thinned evenly first.
double frechet_distance(const ForceCurve& model, const Comparison& comparison,
                        std::size_t max_points = 400);

// Partial curve mapping (after Witowski et al. 2012, LS-OPT): on the normalised axes, the shorter
// curve (by arc length) is slid along the longer one; at each of `offsets` shifts the mean
// distance between points at equal arc length is taken; the result is the smallest mean. A
// curve that is an exact part of the other scores 0, whatever the test end.
double partial_curve_mapping(const ForceCurve& model, const Comparison& comparison,
                             std::size_t samples = 200, std::size_t offsets = 60);

// Clamped linear interpolation on a non-decreasing abscissa (repeated values allowed).
double interpolate_clamped(const std::vector<double>& x, const std::vector<double>& y, double xq);

}  // namespace dtwire::gap
