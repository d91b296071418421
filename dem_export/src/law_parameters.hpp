#pragma once
// Reading and checking named law parameters (std::invalid_argument names the law and the field).
#include <cmath>
#include <stdexcept>
#include <string>

#include "dtwire/dem/contact_law.hpp"

namespace dtwire::dem::detail {

inline constexpr double degrees_per_radian = 57.295779513082320876798154814105;
// Shear stiffness kEA / (2 (1 + nu)) with nu fixed at 0.3, as in the published PFC7 plugin.
inline constexpr double poisson_ratio = 0.3;

inline double optional_parameter(const ParameterMap& parameters, const std::string& field,
                                 double fallback) {
  const auto found = parameters.find(field);
  return found == parameters.end() ? fallback : found->second;
}

inline double checked(const std::string& law, const std::string& field, double value,
                      bool allow_zero = false) {
  if (!std::isfinite(value) || value < 0.0 || (!allow_zero && value == 0.0))
    throw std::invalid_argument(law + ": parameter '" + field + "' must be " +
                                (allow_zero ? "finite and >= 0" : "finite and > 0") + ", got " +
                                std::to_string(value));
  return value;
}

inline double positive_parameter(const ParameterMap& parameters, const std::string& law,
                                 const std::string& field) {
  return checked(law, field, require_parameter(parameters, law, field));
}

inline double nonnegative_parameter(const ParameterMap& parameters, const std::string& law,
                                    const std::string& field) {
  return checked(law, field, require_parameter(parameters, law, field), true);
}

}  // namespace dtwire::dem::detail
