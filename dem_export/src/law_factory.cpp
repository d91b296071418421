#include <stdexcept>

#include "dtwire/dem/contact_law.hpp"
#include "dtwire/dem/law_schema.hpp"
#include "dtwire/dem/macro3d.hpp"
#include "dtwire/dem/parallel_bond.hpp"
#include "dtwire/dem/thesis_macroelement.hpp"
#include "dtwire/dem/wirepm.hpp"

namespace dtwire::dem {

double require_parameter(const ParameterMap& parameters, const std::string& law,
                         const std::string& field) {
  const auto found = parameters.find(field);
  if (found == parameters.end())
    throw std::invalid_argument(law + ": missing parameter '" + field + "'");
  return found->second;
}

std::unique_ptr<ContactLaw> make_contact_law(const std::string& name, const ParameterMap& parameters) {
  // A misspelled name would otherwise leave its parameter at the default without a word.
  const std::vector<std::string> unknown = unknown_law_parameters(name, parameters);
  if (!unknown.empty()) {
    std::string known;
    for (const std::string& n : law_parameter_names(name)) known += (known.empty() ? "" : ", ") + n;
    throw std::invalid_argument(name + ": unknown parameter '" + unknown.front() + "' (the law reads: " + known +
                                (name == "wirepm" ? ", backbone_<i>_strain_1, backbone_<i>_stress_Pa" : "") + ")");
  }
  // Each law adds one line here when it lands.
  if (name == "thesis") return std::make_unique<ThesisMacroElement>(parameters);
  if (name == "macro3d") return std::make_unique<Macro3dLaw>(parameters);
  if (name == "parallel_bond") return std::make_unique<ParallelBondLaw>(parameters);
  if (name == "wirepm") return std::make_unique<WirePmLaw>(make_wirepm_backbone(parameters));
  throw std::invalid_argument("unknown contact law '" + name +
                              "', expected one of: thesis, macro3d, wirepm, parallel_bond");
}

}  // namespace dtwire::dem
