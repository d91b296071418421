#pragma once
// A fitted parameter: name, SI unit, bounds, starting value and the scale that makes it O(1)
// for the optimiser (Ceres works on z = value / scale).
//
// A parameter may be fitted as an OFFSET from another fitted parameter (`offset_from`): the
// optimiser, the bounds, the start and the Latin hypercube see the offset d, the simulator and
// the reports see the parameter's own value, d + the other's value (resolved: offsets may chain).
// A physical order between two parameters then becomes a box bound: the thesis law refuses
// Nult < N0, a constraint two boxes on N0 and Nult cannot express (the optimiser stalls against
// it, every trial step beyond refused), while the hardening reserve Nult - N0 >= 0 is a lower
// bound of 0. The map from the fitted values x to the simulator's values v is linear, v = A x
// (A unit lower triangular in the order of the chains: A_ij = 1 if j is i or a parameter i's
// chain of offsets passes through), so the covariance of v is exactly A Cov(x) A^T:
// var(d + b) = var d + var b + 2 cov(d, b).
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace dtwire::calibrate {

// Parameter values in SI, by name (the names the simulator understands, e.g. "N0_N").
using ParameterValues = std::map<std::string, double>;

struct ParameterDefinition {
  std::string name;
  std::string unit = "1";  // SI symbol
  // Of the fitted quantity: the parameter itself, or its offset from `offset_from`.
  double initial = 0.0;
  double lower = 0.0;
  double upper = 0.0;
  double scale = 0.0;  // 0: chosen by effective_scale()
  std::optional<double> reference;  // a published value to compare with (informational)
  // Optimised (and sampled for multi-start) as z = ln(value / scale) instead of value / scale:
  // for bounds > 0 that span decades, where a step in value / scale that suits one end of the
  // range is far too small or too large at the other (docs/calibrate.md, "Optimisation").
  bool logarithmic = false;
  // Non-empty: fitted as the offset from this other fitted parameter (its name); the simulator
  // reads this parameter's name with the value offset + that parameter's (resolved) value.
  std::string offset_from{};

  // |initial| if non-zero, else the bound width, else 1.
  double effective_scale() const;
  // The optimiser's coordinate z of a value and back, and d value / d z at z.
  double to_coordinate(double value) const;
  double from_coordinate(double z) const;
  double derivative(double z) const;
};

// Throws std::invalid_argument naming the parameter if bounds are inverted, the initial value
// lies outside them, a name repeats, a value is not finite, or an offset_from names no other
// fitted parameter or closes a cycle.
void validate(const std::vector<ParameterDefinition>& parameters);

// For each parameter, the index of the parameter it is an offset from (offset_from), or -1.
// Throws std::invalid_argument for an unknown name, the parameter itself or a cycle.
std::vector<int> offset_bases(const std::vector<ParameterDefinition>& parameters);

// The values the simulator reads, in the parameters' order, from the fitted values: an offset's
// value plus its base's resolved value. Without offsets, `values` itself.
std::vector<double> resolve_offsets(const std::vector<ParameterDefinition>& parameters,
                                    const std::vector<double>& values);

// The inverse: the fitted values (offsets) from the values the simulator reads.
std::vector<double> offsets_from_resolved(const std::vector<ParameterDefinition>& parameters,
                                          const std::vector<double>& resolved);

// d resolved / d fitted values (the matrix A above; the identity without offsets).
Eigen::MatrixXd offset_map(const std::vector<ParameterDefinition>& parameters);

// Covariance of the resolved values from the covariance of the fitted values: A C A^T.
Eigen::MatrixXd resolve_covariance(const std::vector<ParameterDefinition>& parameters,
                                   const Eigen::MatrixXd& covariance);

// The resolved bounds: the range each resolved value takes over the box of fitted values
// (an offset's bounds plus its base's resolved bounds).
std::vector<double> resolved_lower(const std::vector<ParameterDefinition>& parameters);
std::vector<double> resolved_upper(const std::vector<ParameterDefinition>& parameters);

// The resolved reference of each parameter: its reference plus its base's resolved reference;
// empty where the parameter or a base along its chain has none.
std::vector<std::optional<double>> resolved_references(const std::vector<ParameterDefinition>& parameters);

// The fitted values at the references (a parameter without one at its initial value), as
// `dtwire fit --synthesize` simulates them.
std::vector<double> reference_point(const std::vector<ParameterDefinition>& parameters);

// What the optimiser varies, for messages: "Nult_N - N0_N" for an offset, else the name.
std::string coordinate_name(const ParameterDefinition& parameter);

// The simulator's values by name (offsets resolved).
ParameterValues to_values(const std::vector<ParameterDefinition>& parameters,
                          const std::vector<double>& values);

}  // namespace dtwire::calibrate
