#pragma once
// The self-checks of a `dtwire dem run` (docs/dem_engine.md, "Checks"): evaluated at every output
// row, the first one that leaves its bound stops the run, which is then reported as failed (exit
// 1) with its partial results. The bounds are the input's `[checks]` table.
#include <optional>
#include <string>

#include "dtwire/dem/engine.hpp"

namespace dtwire::dem {

struct RunChecks {
  // |balance error| / work on the mesh (the largest work so far, at least 1 J): 5 %, twenty times
  // the largest figure of a valid 3 x 3 m punch (0.25 %), a third of the smallest runaway (14 %).
  double max_balance_error = 0.05;
  // Kinetic energy / the same work, quasi-static runs (punch, cyclic punch, strip), from the
  // second row on: valid punches peak at 23 % (3 x 3 m) and 37 % (1.6 m at 5 cm/s) when the
  // platter first meets the net; a runaway exceeds 100 %.
  double max_kinetic_share = 0.8;
};

struct FailedCheck {
  std::string check;  // "energy_balance", "kinetic_share", "finite_state"
  std::string key;    // the [checks] key of the bound ("" for finite_state)
  double time = 0.0;  // [s] after settling
  long step = 0;
  double value = 0.0, bound = 0.0;  // fractions (finite_state: none)
  // Failed on the loading's first row, in the state the settle left: the settle ran away (or
  // left the net moving), not the loading.
  bool before_loading = false;
  std::string message() const;
};

class RunGuard {
 public:
  RunGuard(const RunChecks& checks, bool quasi_static) : checks_(checks), quasi_static_(quasi_static) {}
  // One output row: the energies at `time` after settling, step `step`, and any other figure of
  // the row that must be finite (e.g. the tool force). Returns the first check that fails.
  std::optional<FailedCheck> check(const EnergySplit& energy, double time, long step, double row_figure = 0.0);

 private:
  RunChecks checks_;
  bool quasi_static_;
  double largest_work_ = 0.0;
  long rows_ = 0;         // rows checked
  long loaded_rows_ = 0;  // rows with work on the mesh
};

}  // namespace dtwire::dem
