#include "dtwire/dem/length_rescaling.hpp"

#include <stdexcept>
#include <string>

namespace dtwire::dem {

ParameterMap rescale_to_link_length(const ParameterMap& parameters, double link_length) {
  const auto reference = parameters.find("reference_length_m");
  if (reference == parameters.end() || !(reference->second > 0.0))
    throw std::invalid_argument("length = \"link\" needs the set's reference_length_m > 0 (the bond length it was calibrated on)");
  if (!(link_length > 0.0)) throw std::invalid_argument("length = \"link\": the link length must be positive");
  const double stiffer = reference->second / link_length;  // L_ref / L
  ParameterMap out = parameters;
  auto scale = [&](const char* name, double factor) {
    if (const auto found = out.find(name); found != out.end()) found->second *= factor;
  };
  for (const char* name : {"EA_N", "EI_Nm2_per_deg_convention", "k_F", "axial_stiffness_N_per_m",
                           "bending_stiffness_Nm_per_rad", "shear_stiffness_N_per_m", "torsion_stiffness_Nm_per_rad",
                           "k_F_per_m"})
    scale(name, stiffer);
  for (const char* name : {"W1_J", "W2_J"}) scale(name, 1.0 / stiffer);
  out["reference_length_m"] = link_length;
  return out;
}

}  // namespace dtwire::dem
