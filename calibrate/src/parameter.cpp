#include "dtwire/calibrate/parameter.hpp"

#include <cmath>
#include <set>
#include <stdexcept>

namespace dtwire::calibrate {

double ParameterDefinition::effective_scale() const {
  if (scale > 0) return scale;
  if (initial != 0.0) return std::abs(initial);
  if (upper > lower) return upper - lower;
  return 1.0;
}

double ParameterDefinition::to_coordinate(double value) const {
  return logarithmic ? std::log(value / effective_scale()) : value / effective_scale();
}

double ParameterDefinition::from_coordinate(double z) const {
  return logarithmic ? effective_scale() * std::exp(z) : z * effective_scale();
}

double ParameterDefinition::derivative(double z) const { return logarithmic ? from_coordinate(z) : effective_scale(); }

void validate(const std::vector<ParameterDefinition>& parameters) {
  if (parameters.empty()) throw std::invalid_argument("no parameters to fit");
  std::set<std::string> names;
  for (const auto& p : parameters) {
    const std::string where = "parameter '" + p.name + "': ";
    if (p.name.empty()) throw std::invalid_argument("a parameter has an empty name");
    if (!names.insert(p.name).second) throw std::invalid_argument(where + "defined twice");
    if (!std::isfinite(p.initial) || !std::isfinite(p.lower) || !std::isfinite(p.upper) ||
        !std::isfinite(p.scale))
      throw std::invalid_argument(where + "initial, lower, upper and scale must be finite");
    if (!(p.lower < p.upper))
      throw std::invalid_argument(where + "expected lower < upper");
    if (p.initial < p.lower || p.initial > p.upper)
      throw std::invalid_argument(where + "initial value outside [lower, upper]");
    if (p.scale < 0) throw std::invalid_argument(where + "scale must be > 0");
    if (p.logarithmic && !(p.lower > 0)) throw std::invalid_argument(where + "logarithmic needs lower > 0");
  }
}

ParameterValues to_values(const std::vector<ParameterDefinition>& parameters,
                          const std::vector<double>& values) {
  if (values.size() != parameters.size())
    throw std::invalid_argument("to_values: wrong number of values");
  ParameterValues out;
  for (std::size_t i = 0; i < parameters.size(); ++i) out[parameters[i].name] = values[i];
  return out;
}

}  // namespace dtwire::calibrate
