#include "hardening.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace dtwire::fem {

HardeningLaw parse_hardening_law(const std::string& name) {
  if (name == "linear") return HardeningLaw::linear;
  if (name == "voce") return HardeningLaw::voce;
  if (name == "swift") return HardeningLaw::swift;
  if (name == "table") return HardeningLaw::table;
  throw std::invalid_argument("hardening law '" + name + "': expected linear, voce, swift or table");
}

IsotropicHardening::IsotropicHardening(HardeningParameters parameters) : p_(std::move(parameters)) {
  switch (p_.law) {
    case HardeningLaw::linear:
    case HardeningLaw::voce:
      if (!(p_.yield_stress > 0)) throw std::invalid_argument("yield stress must be > 0");
      if (p_.law == HardeningLaw::voce && !(p_.saturation_rate >= 0))
        throw std::invalid_argument("Voce saturation rate must be >= 0");
      break;
    case HardeningLaw::swift:
      if (!(p_.swift_coefficient > 0) || !(p_.swift_offset > 0) || !(p_.swift_exponent >= 0))
        throw std::invalid_argument("Swift law needs K > 0, eps0 > 0, n >= 0");
      break;
    case HardeningLaw::table: {
      const auto& e = p_.table_plastic_strain;
      const auto& s = p_.table_stress;
      if (e.size() < 2 || e.size() != s.size())
        throw std::invalid_argument("hardening table needs >= 2 (plastic strain, stress) rows");
      if (e.front() != 0.0) throw std::invalid_argument("hardening table must start at plastic strain 0");
      for (std::size_t i = 1; i < e.size(); ++i)
        if (!(e[i] > e[i - 1]))
          throw std::invalid_argument("hardening table plastic strain must increase strictly");
      for (double v : s)
        if (!(v > 0)) throw std::invalid_argument("hardening table stresses must be > 0");
      break;
    }
  }
}

std::size_t IsotropicHardening::table_segment(double alpha) const {
  const auto& e = p_.table_plastic_strain;
  const auto it = std::upper_bound(e.begin(), e.end(), alpha);
  const std::size_t i = static_cast<std::size_t>(std::distance(e.begin(), it));
  return std::min(std::max<std::size_t>(i, 1), e.size() - 1) - 1;
}

double IsotropicHardening::flow_stress(double alpha) const {
  switch (p_.law) {
    case HardeningLaw::linear:
      return p_.yield_stress + p_.linear_modulus * alpha;
    case HardeningLaw::voce:  // Simo (1992) necking benchmark form: saturation plus linear
      return p_.yield_stress + (p_.saturation_stress - p_.yield_stress) * (1.0 - std::exp(-p_.saturation_rate * alpha)) +
             p_.linear_modulus * alpha;
    case HardeningLaw::swift:
      return p_.swift_coefficient * std::pow(p_.swift_offset + alpha, p_.swift_exponent);
    case HardeningLaw::table: {
      // Piecewise linear; beyond the last row the last segment's slope continues.
      const std::size_t i = table_segment(alpha);
      const auto& e = p_.table_plastic_strain;
      const auto& s = p_.table_stress;
      return s[i] + (s[i + 1] - s[i]) / (e[i + 1] - e[i]) * (alpha - e[i]);
    }
  }
  return 0.0;
}

double IsotropicHardening::slope(double alpha) const {
  switch (p_.law) {
    case HardeningLaw::linear:
      return p_.linear_modulus;
    case HardeningLaw::voce:
      return (p_.saturation_stress - p_.yield_stress) * p_.saturation_rate * std::exp(-p_.saturation_rate * alpha) +
             p_.linear_modulus;
    case HardeningLaw::swift:
      return p_.swift_coefficient * p_.swift_exponent * std::pow(p_.swift_offset + alpha, p_.swift_exponent - 1.0);
    case HardeningLaw::table: {
      const std::size_t i = table_segment(alpha);
      const auto& e = p_.table_plastic_strain;
      const auto& s = p_.table_stress;
      return (s[i + 1] - s[i]) / (e[i + 1] - e[i]);
    }
  }
  return 0.0;
}

}  // namespace dtwire::fem
