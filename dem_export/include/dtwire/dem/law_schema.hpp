#pragma once
// The parameter names each contact law reads: one schema shared by the law factory (and so the
// C ABI and the DEM engine), the exporter, `dtwire dem driver` and the fit files, so that a
// misspelled name ("slideb") is refused instead of silently falling back to a default.
// Standard library only, like the laws.
#include <string>
#include <vector>

#include "dtwire/dem/contact_law.hpp"

namespace dtwire::dem {

// Every name `law` accepts (including the bond's reference_length_m, which the DEM assembly
// and the exporters read). WirePM also accepts its backbone points by pattern:
// backbone_<i>_strain_1 and backbone_<i>_stress_Pa. Throws std::invalid_argument for an
// unknown law.
const std::vector<std::string>& law_parameter_names(const std::string& law);

// True if `name` is one of law_parameter_names(law) or matches one of the law's patterns.
bool is_law_parameter(const std::string& law, const std::string& name);

// The names in `parameters` that `law` does not read, in map order.
std::vector<std::string> unknown_law_parameters(const std::string& law, const ParameterMap& parameters);

}  // namespace dtwire::dem
