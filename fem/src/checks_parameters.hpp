#pragma once
// The bounds of a `dtwire run`'s self-checks (run_checks.hpp): the .prm's `subsection Checks`,
// one entry per bound, in percent as the user states them, kept here as fractions.
#include <string>

namespace dealii {
class ParameterHandler;
}

namespace dtwire::fem {

struct RunChecks {
  // The balance error |W_ext - (stored - stored at the first record)| beyond what the trapezoidal
  // work cannot resolve (run_checks.hpp), over the largest |W_ext| so far: a missing or runaway
  // term is tens of percent (docs/fem.md, "Checks").
  double max_balance_error = 0.05;
  double energy_floor = 0.01;  // J: below this work the balance is not judged (start-up offsets)
  // Largest penetration of a contact (tools or wire on wire) as a fraction of the wire diameter:
  // a converged augmented-Lagrangian contact holds it near its gap tolerance (1 um), a penalty
  // too soft for the load lets the wires pass through each other.
  double max_penetration = 0.1;
};

void declare_check_parameters(dealii::ParameterHandler& prm);
RunChecks parse_check_parameters(dealii::ParameterHandler& prm);

}  // namespace dtwire::fem
