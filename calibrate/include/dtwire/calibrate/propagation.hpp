#pragma once
// Parameter sets drawn from a fit's uncertainty, for carrying it to a model the fit's parameters
// feed (`dtwire dem propagate`: the wire-scale fit's uncertainty to the mesh's strip and punch).
//
// Contract. The input is what `dtwire fit` writes to parameters.json: each fitted parameter's
// value, bounds, `identified` flag, `coordinate` ("linear" or "log": the fit's optimiser
// coordinate, value / scale or ln(value / scale)), `offset_from` and the offset's own bounds,
// and the covariance of the parameters' own values (docs/calibrate.md, "Uncertainty").
// A draw is a full vector of the fitted parameters' own values:
//   - identified parameters: multivariate normal with the fit's mean and covariance, in the
//     fit's coordinate y (y = v for "linear", y = ln v for "log": the covariance is carried to y
//     as the fit carried it from y, Cov(y) = D^-1 Cov(v) D^-1 with D = diag(dv/dy) = diag(v)).
//     The scale factor of the fit's coordinate is affine and changes nothing. The factor of
//     Cov(y) is Q sqrt(Lambda) from its symmetric eigen-decomposition, so a semi-definite
//     covariance (a fit's pseudo-inverse) draws along its null directions with zero spread;
//   - NOT IDENTIFIED parameters (and every fitted parameter when the fit has no covariance):
//     uniform in y over the parameter's stated [lower, upper], independent of the others; their
//     sigma is not an error bar (docs/calibrate.md), so it is not used;
//   - bounds: a draw outside any parameter's [lower, upper], breaking an offset's order
//     (v - v_base outside the offset's [lower, upper], e.g. Nult < N0) or refused by the
//     caller's check (e.g. the contact law's) is discarded and the whole vector drawn again.
//     This samples the normal truncated to the admissible region exactly (rejection sampling:
//     the accepted draws have the density restricted and renormalised, Robert 1995, Statistics
//     and Computing 5:121); the acceptance rate is reported.
// Random numbers: std::mt19937_64 (output fixed by the standard) with our own maps to [0, 1)
// and to the normal (Box-Muller 1958), so a seed gives the same sets on every platform.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <random>
#include <string>
#include <vector>

namespace dtwire::calibrate {

struct UncertainParameter {
  std::string name;  // as the fit names it (e.g. "N0_N", "dt.EA_N")
  std::string unit;
  double value = 0.0;
  double lower = 0.0, upper = 0.0;  // the parameter's own range
  bool identified = false;
  bool logarithmic = false;  // the fit's coordinate is ln(value / scale)
  std::string offset_from;   // fitted as value - offset_from's value within [offset_lower, offset_upper]
  double offset_lower = 0.0, offset_upper = 0.0;
};

struct FitUncertainty {
  std::filesystem::path file;
  std::vector<UncertainParameter> parameters;  // the fitted ones, the covariance's order
  std::vector<std::vector<double>> covariance;  // own values, SI; empty when the fit has none
  bool coordinates_recorded = true;  // false: the file predates `coordinate` (all taken as linear)
};

// Reads a fit's parameters.json. `prefix` keeps only the parameters whose name starts with it
// (a joint SW + DT fit names them "sw." and "dt."; "" keeps all). InputError naming the file
// and the field for anything malformed or missing.
FitUncertainty read_fit_uncertainty(const std::filesystem::path& file, const std::string& prefix = "");

class ParameterSampler {
 public:
  // Throws std::invalid_argument for a covariance of the wrong size or not symmetric, a log
  // coordinate with a value or bound <= 0, or a value outside its bounds.
  ParameterSampler(const FitUncertainty& fit, std::uint64_t seed);

  // One admissible draw (own values in the fit's order). `admissible` may refuse a draw (e.g. a
  // set the contact law rejects). Throws std::runtime_error after `max_tries` refused draws,
  // naming the constraint that refused most.
  std::vector<double> draw(const std::function<bool(const std::vector<double>&)>& admissible = {},
                           int max_tries = 100000);

  // The draw's coordinate y of parameter i and back (ln v for a log coordinate).
  double to_coordinate(std::size_t i, double value) const;
  double from_coordinate(std::size_t i, double y) const;
  // Whether v satisfies every bound and offset order; `why` names the first one broken.
  bool within_constraints(const std::vector<double>& v, std::string* why = nullptr) const;

  // The spread of parameter i's coordinate the sampler uses: sigma of the normal for an
  // identified one, (upper - lower) / sqrt(12) of the uniform otherwise (the linearised
  // propagation's input variance).
  double coordinate_sd(std::size_t i) const;
  // Covariance of the coordinates as sampled (before truncation): Cov(y) on the identified
  // block, the uniform's variance on the diagonal of the others, zero between the two groups.
  const std::vector<std::vector<double>>& coordinate_covariance() const { return coordinate_covariance_; }
  bool sampled_normal(std::size_t i) const { return normal_[i]; }

  std::size_t accepted() const { return accepted_; }
  std::size_t refused() const { return refused_; }

 private:
  double uniform01();
  double standard_normal();

  FitUncertainty fit_;
  std::vector<bool> normal_;
  std::vector<std::size_t> normal_index_;              // identified parameters drawn jointly
  std::vector<std::vector<double>> factor_;            // Cov(y) = factor factor^T on that block
  std::vector<std::vector<double>> coordinate_covariance_;
  std::mt19937_64 generator_;
  std::optional<double> spare_normal_;
  std::size_t accepted_ = 0, refused_ = 0;
};

}  // namespace dtwire::calibrate
