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
  for (const char* name : {"EA_N", "EI_Nm2_per_deg_convention", "k_F", "k_M", "axial_stiffness_N_per_m",
                           "bending_stiffness_Nm_per_rad", "shear_stiffness_N_per_m", "torsion_stiffness_Nm_per_rad",
                           "k_F_per_m", "k_M_per_rad"})
    scale(name, stiffer);
  for (const char* name : {"W1_J", "W2_J"}) scale(name, 1.0 / stiffer);
  out["reference_length_m"] = link_length;
  return out;
}

ParameterMap split_in_series(const std::string& law, const ParameterMap& parameters, int parts) {
  if (parts < 1) throw std::invalid_argument("split_in_series: parts must be >= 1");
  const double n = parts;
  ParameterMap out = parameters;
  auto scale = [&](const char* name, double factor) {
    if (const auto found = out.find(name); found != out.end()) found->second *= factor;
  };
  auto require = [&](const char* name) {
    const auto found = out.find(name);
    if (found == out.end() || !(found->second > 0.0))
      throw std::invalid_argument(law + " split into links in series: needs " + name + " > 0");
  };
  if (law == "thesis" || law == "macro3d") {
    for (const char* name : {"EA_N", "EI_Nm2_per_deg_convention", "k_F", "k_M", "axial_stiffness_N_per_m",
                             "bending_stiffness_Nm_per_rad", "shear_stiffness_N_per_m",
                             "torsion_stiffness_Nm_per_rad", "k_F_per_m", "k_M_per_rad"})
      scale(name, n);
    for (const char* name : {"W1_J", "W2_J", "reference_length_m"}) scale(name, 1.0 / n);
    scale("bending_axial_coupling", n * n);
  } else if (law == "parallel_bond") {
    require("length_m");
    scale("length_m", 1.0 / n);
    scale("reference_length_m", 1.0 / n);
  } else if (law == "wirepm") {
    throw std::invalid_argument("wirepm links carry axial force only: split into links in series, each middle node "
                                "would be a hinge (use a law with bending stiffness: thesis, macro3d, parallel_bond)");
  } else {
    throw std::invalid_argument("split_in_series: unknown law '" + law + "'");
  }
  return out;
}

}  // namespace dtwire::dem
