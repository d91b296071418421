#include "dtwire/dem/law_schema.hpp"

#include <algorithm>
#include <cctype>
#include <map>
#include <stdexcept>

namespace dtwire::dem {
namespace {

// Read by the DEM assembly (link length) and by the exporters, for every law.
const char* const kBondGeometry[] = {"reference_length_m"};

// The thesis macro-element (Previtali's PFC7 plugin names; slide_b is exported, slide_a must be 0).
const char* const kThesis[] = {"D_m", "EA_N", "EI_Nm2_per_deg_convention", "N0_N", "Nult_N", "Nc_N",
                               "m_f", "beta_f", "k_F", "k_M", "m_g", "alpha_g", "beta_g",
                               "W1_J", "W2_J", "alpha_d", "slide_a", "slide_b", "rk_tolerance",
                               "damage_scales_forces", "break_plastic_strain", "shear_stiffness_N_per_m",
                               "beam_shear"};

// macro3d reads its own SI names and also a thesis set (converted on construction).
const char* const kMacro3dOwn[] = {"k_F_per_m", "k_M_per_rad", "axial_stiffness_N_per_m",
                                   "bending_stiffness_Nm_per_rad", "torsion_stiffness_Nm_per_rad",
                                   "rotation_flow_scale", "damage_moment_work_weight", "shear_strength_N",
                                   "implicit_return", "bending_axial_coupling", "moment_hardening_ratio"};

const char* const kParallelBond[] = {"E_Pa", "poisson_1", "G_Pa", "diameter_m", "length_m",
                                     "tensile_strength_Pa", "shear_strength_Pa"};

const char* const kWirePm[] = {"diameter_m", "double_twist", "double_twist_model", "lambda_u", "lambda_F",
                               "lambda_k", "lambda_eps", "poisson_1", "seed"};

template <std::size_t N>
void append(std::vector<std::string>& names, const char* const (&list)[N]) {
  names.insert(names.end(), list, list + N);
}

using Schema = std::map<std::string, std::vector<std::string>>;

Schema make_schema() {
  Schema schema;
  for (const char* law : {"thesis", "macro3d", "parallel_bond", "wirepm"}) append(schema[law], kBondGeometry);
  append(schema["thesis"], kThesis);
  append(schema["macro3d"], kThesis);
  append(schema["macro3d"], kMacro3dOwn);
  append(schema["parallel_bond"], kParallelBond);
  append(schema["wirepm"], kWirePm);
  return schema;
}

// backbone_<digits>_strain_1 or backbone_<digits>_stress_Pa
bool is_backbone_point(const std::string& name) {
  const std::string prefix = "backbone_";
  if (name.compare(0, prefix.size(), prefix) != 0) return false;
  std::size_t at = prefix.size();
  const std::size_t digits_start = at;
  while (at < name.size() && std::isdigit(static_cast<unsigned char>(name[at]))) ++at;
  if (at == digits_start) return false;
  const std::string rest = name.substr(at);
  return rest == "_strain_1" || rest == "_stress_Pa";
}

}  // namespace

const std::vector<std::string>& law_parameter_names(const std::string& law) {
  static const Schema schema = make_schema();
  const auto found = schema.find(law);
  if (found == schema.end())
    throw std::invalid_argument("unknown contact law '" + law +
                                "', expected one of: thesis, macro3d, wirepm, parallel_bond");
  return found->second;
}

bool is_law_parameter(const std::string& law, const std::string& name) {
  const std::vector<std::string>& names = law_parameter_names(law);
  if (std::find(names.begin(), names.end(), name) != names.end()) return true;
  return law == "wirepm" && is_backbone_point(name);
}

std::vector<std::string> unknown_law_parameters(const std::string& law, const ParameterMap& parameters) {
  std::vector<std::string> unknown;
  for (const auto& entry : parameters)
    if (!is_law_parameter(law, entry.first)) unknown.push_back(entry.first);
  return unknown;
}

}  // namespace dtwire::dem
