// The self-checks of a DEM run (run_checks.hpp).
#include "dtwire/dem/run_checks.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace dtwire::dem {
namespace {

constexpr double kSmallestReferenceWork = 1.0;  // [J]

}  // namespace

std::string FailedCheck::message() const {
  std::ostringstream os;
  os << "check '" << check << "' failed at t = " << time << " s (step " << step << ")";
  if (before_loading) os << ", the loading's first row";
  if (check == "finite_state")
    os << ": the state became non-finite (NaN or inf)";
  else
    os << ": " << (check == "energy_balance" ? "|energy balance error|" : "kinetic energy") << " is " << 100.0 * value
       << " % of the work on the mesh, above the bound " << 100.0 * bound << " % (" << key << ")";
  if (before_loading)
    os << "; the state is the one the settle under gravity left, so the settle failed, not the loading (see the "
          "summary's settled_at_rest and settle_unbalanced_force_ratio; docs/dem_engine.md, \"Settling to rest\")";
  return os.str();
}

std::optional<FailedCheck> RunGuard::check(const EnergySplit& e, double time, long step, double row_figure) {
  const bool first_row = rows_++ == 0;
  auto failed = [&](const std::string& name, const std::string& key, double value, double bound) {
    return FailedCheck{name, key, time, step, value, bound, first_row};
  };
  if (!std::isfinite(e.kinetic) || !std::isfinite(e.balance_error()) || !std::isfinite(e.stored_and_dissipated()) ||
      !std::isfinite(row_figure))
    return failed("finite_state", "", 0.0, 0.0);
  // The work on the mesh so far; its largest value is the reference, so that a work passing
  // through zero (gravity against the tool) does not inflate the ratios, and at least 1 J: the
  // start-up offset of a clamp (0.009 J in the strips, constant after the first step) is not a
  // runaway while the work is still a fraction of a joule.
  largest_work_ = std::max(largest_work_, std::abs(e.gravity_work) + std::abs(e.tool_work) + std::abs(e.boundary_work));
  if (!(largest_work_ > 0.0)) return std::nullopt;
  const double reference = std::max(largest_work_, kSmallestReferenceWork);
  const double error = std::abs(e.balance_error()) / reference;
  if (error > checks_.max_balance_error)
    return failed("energy_balance", "checks.max_balance_error_percent", error, checks_.max_balance_error);
  // Not on the first row: the settled state's kinetic energy is the settling's (up to 42 % of
  // the work after the gap module's short settles), before any quasi-static loading.
  const double kinetic = e.kinetic / reference;
  if (quasi_static_ && ++loaded_rows_ > 1 && kinetic > checks_.max_kinetic_share)
    return failed("kinetic_share", "checks.max_kinetic_share_percent", kinetic, checks_.max_kinetic_share);
  return std::nullopt;
}

}  // namespace dtwire::dem
