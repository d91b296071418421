#pragma once
// A fitted parameter: name, SI unit, bounds, starting value and the scale that makes it O(1)
// for the optimiser (Ceres works on z = value / scale).
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace dtwire::calibrate {

// Parameter values in SI, by name (the names the simulator understands, e.g. "N0_N").
using ParameterValues = std::map<std::string, double>;

struct ParameterDefinition {
  std::string name;
  std::string unit = "1";  // SI symbol
  double initial = 0.0;
  double lower = 0.0;
  double upper = 0.0;
  double scale = 0.0;  // 0: chosen by effective_scale()
  std::optional<double> reference;  // a published value to compare with (informational)
  // Optimised (and sampled for multi-start) as z = ln(value / scale) instead of value / scale:
  // for bounds > 0 that span decades, where a step in value / scale that suits one end of the
  // range is far too small or too large at the other (docs/calibrate.md, "Optimisation").
  bool logarithmic = false;

  // |initial| if non-zero, else the bound width, else 1.
  double effective_scale() const;
  // The optimiser's coordinate z of a value and back, and d value / d z at z.
  double to_coordinate(double value) const;
  double from_coordinate(double z) const;
  double derivative(double z) const;
};

// Throws std::invalid_argument naming the parameter if bounds are inverted, the initial value
// lies outside them, a name repeats or a value is not finite.
void validate(const std::vector<ParameterDefinition>& parameters);

ParameterValues to_values(const std::vector<ParameterDefinition>& parameters,
                          const std::vector<double>& values);

}  // namespace dtwire::calibrate
