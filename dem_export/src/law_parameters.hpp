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

// The bond's shear spring [N/m]. By default the PFC7 plugin's k_EA / (2 (1 + nu)): the shear of
// a short bar, G A / L. `shear_stiffness_N_per_m` gives it outright; `beam_shear = 1` makes it the
// slender beam's 12 EI / L^3 = 12 k_b / L^2, from the bond's bending spring k_b [N m/rad] and its
// reference_length_m L. The bond is two rigid halves joined at its midpoint by the shear and
// bending springs, so a cantilever bond deflects P / k_s + P L^2 / (4 k_b) under a tip load; with
// k_b = EI / L and k_s = 12 EI / L^3 that is the Euler-Bernoulli P L^3 / (3 EI), and the bond's
// stiffness matrix is the Euler-Bernoulli element's (docs/dem_laws.md, "Shear spring").
inline double read_shear_stiffness(const ParameterMap& p, const ParameterMap& with_length, const std::string& law,
                                   double axial, double bending_per_radian) {
  const double plugin_shear = axial / (2.0 * (1.0 + poisson_ratio));
  const auto beam = p.find("beam_shear");
  const double beam_shear = beam == p.end() ? 0.0 : beam->second;
  if (beam_shear != 0.0 && beam_shear != 1.0)
    throw std::invalid_argument(law + ": beam_shear must be 0 (the plugin's shear, k_EA / 2.6) or 1 (12 EI / L^3)");
  const auto given = p.find("shear_stiffness_N_per_m");
  if (beam_shear == 0.0)
    return given == p.end() ? plugin_shear : checked(law, "shear_stiffness_N_per_m", given->second);
  if (given != p.end())
    throw std::invalid_argument(law + ": give either shear_stiffness_N_per_m or beam_shear = 1, not both");
  const auto length = with_length.find("reference_length_m");
  if (length == with_length.end() || !std::isfinite(length->second) || !(length->second > 0.0))
    throw std::invalid_argument(law + ": beam_shear = 1 needs the bond's reference_length_m > 0");
  return 12.0 * bending_per_radian / (length->second * length->second);
}

inline double nonnegative_parameter(const ParameterMap& parameters, const std::string& law,
                                    const std::string& field) {
  return checked(law, field, require_parameter(parameters, law, field), true);
}

}  // namespace dtwire::dem::detail
