#include "failure_place.hpp"

#include <cmath>

namespace dtwire::fem {

FailurePlace failure_place(double z, double diameter, const std::array<double, 2>& twist_ends) {
  for (const double end : twist_ends)
    if (std::abs(z - end) <= diameter) return FailurePlace::junction;
  if (z > twist_ends[0] && z < twist_ends[1]) return FailurePlace::twist;
  return FailurePlace::arm;
}

const char* to_string(FailurePlace place) {
  switch (place) {
    case FailurePlace::twist: return "twist";
    case FailurePlace::junction: return "junction";
    case FailurePlace::arm: return "arm";
  }
  return "";
}

std::string failure_mode(double triaxiality, double lode_parameter) {
  if (std::abs(lode_parameter) < 0.5) return "shear-driven";
  if (lode_parameter > 0.5 && triaxiality > 0.38) return "necking-driven";
  return "uniform tension";
}

}  // namespace dtwire::fem
