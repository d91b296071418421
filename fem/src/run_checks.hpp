#pragma once
// The self-checks of a `dtwire run` (issue 37; docs/fem.md, "Checks"): evaluated on the record of
// every converged load step, the first one that leaves its bound stops the run, which is then
// reported as failed (exit 1) with its partial curve and summary.json marked failed. The bounds
// are the .prm's `subsection Checks` (checks_parameters.hpp). No deal.II: plain records in.
#include <optional>
#include <string>
#include <vector>

#include "checks_parameters.hpp"
#include "step_record.hpp"

namespace dtwire::fem {

struct FailedCheck {
  std::string check;  // "energy_balance", "penetration", "finite_state"
  std::string entry;  // the `Checks` entry of the bound ("" for finite_state)
  unsigned step = 0;
  double time = 0.0;                // the step's pseudo-time (the paths' time axis)
  double displacement = 0.0;        // m, the load path's displacement at that step
  double value = 0.0, bound = 0.0;  // fractions (finite_state: none)
  std::string message() const;
};

// Everything the wire stores or dissipates (J): elastic, plastic, friction and penalty energy of
// tools and wires, grip bond energy and slip.
double stored_energy(const StepRecord& r);

// The energy balance allows for its own quadrature: the external work is the trapezoidal sum over
// the steps, and within one step whose force changes monotonically the exact work lies between
// the left and right rectangle rules, so the trapezoid is off by at most
// 1/2 |dF| |du| (end translation) + 1/2 |dM| |dtheta| (end rotation) + 1/2 sum |dF_k| |dx_k| (tools).
// The check fails when |error| > bound x largest work + that allowance summed over the steps: a
// coarse step through yield (the first step of a plastic run) is not an imbalance, a term missing
// from the account still is once the steps resolve the curve.
class RunGuard {
 public:
  RunGuard(const RunChecks& checks, double wire_diameter) : checks_(checks), diameter_(wire_diameter) {}
  // One converged step: the first check that fails, if any.
  std::optional<FailedCheck> check(const StepRecord& r);
  // The largest figures seen (fractions), for the log and results.h5: the balance error beyond
  // the quadrature allowance, over the largest work.
  double largest_balance_error() const { return largest_balance_error_; }
  // The imbalance before the allowance (largest over the steps) and the allowance at the end, both
  // over the largest work: what the trapezoid could not resolve against what was left.
  double largest_imbalance() const { return largest_imbalance_; }
  double final_allowance() const { return largest_work_ > 0.0 ? quadrature_allowance_ / largest_work_ : 0.0; }
  double largest_penetration() const { return largest_penetration_; }

 private:
  RunChecks checks_;
  double diameter_;
  std::optional<double> initial_stored_;
  std::optional<StepRecord> previous_;
  double quadrature_allowance_ = 0.0;  // J
  double largest_work_ = 0.0;
  double largest_balance_error_ = 0.0, largest_penetration_ = 0.0, largest_imbalance_ = 0.0;
};

}  // namespace dtwire::fem
