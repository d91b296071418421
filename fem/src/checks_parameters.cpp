#include "checks_parameters.hpp"

#include <deal.II/base/parameter_handler.h>

namespace dtwire::fem {

using dealii::ParameterHandler;
using dealii::Patterns::Double;

void declare_check_parameters(ParameterHandler& prm) {
  const RunChecks defaults;
  prm.enter_subsection("Checks");
  prm.declare_entry("Max energy balance error (%)", std::to_string(100 * defaults.max_balance_error), Double(0.0),
                    "the run fails (exit 1) when |external work - (elastic + plastic + friction + penalty + grip "
                    "energy)| exceeds this share of the largest external work so far");
  prm.declare_entry("Energy floor (J)", std::to_string(defaults.energy_floor), Double(0.0),
                    "the energy balance is judged once the external work has reached this figure");
  prm.declare_entry("Max penetration (% of diameter)", std::to_string(100 * defaults.max_penetration), Double(0.0),
                    "the run fails when a contact (tools, wire on wire) penetrates deeper than this share of the "
                    "wire diameter");
  prm.leave_subsection();
}

RunChecks parse_check_parameters(ParameterHandler& prm) {
  RunChecks checks;
  prm.enter_subsection("Checks");
  checks.max_balance_error = prm.get_double("Max energy balance error (%)") / 100;
  checks.energy_floor = prm.get_double("Energy floor (J)");
  checks.max_penetration = prm.get_double("Max penetration (% of diameter)") / 100;
  prm.leave_subsection();
  return checks;
}

}  // namespace dtwire::fem
