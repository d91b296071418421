#include "run_checks.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace dtwire::fem {

std::string FailedCheck::message() const {
  std::ostringstream text;
  text << "check '" << check << "' failed at step " << step << " (pseudo-time " << time << ", displacement "
       << displacement * 1e3 << " mm)";
  if (check == "finite_state") {
    text << ": a force, displacement or energy is not finite";
  } else {
    text << ": " << 100.0 * value << " % against the bound " << 100.0 * bound << " % (Checks/" << entry << ")";
  }
  return text.str();
}

namespace {

double distance(const std::array<double, 3>& a, const std::array<double, 3>& b) {
  return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

// Half the change of each force times the move of its point over the step (run_checks.hpp).
double trapezoid_error_bound(const StepRecord& a, const StepRecord& b) {
  double bound = distance(a.end_force, b.end_force) * distance(a.end_translation, b.end_translation) +
                 distance(a.end_moment, b.end_moment) * std::abs(b.end_rotation - a.end_rotation);
  const auto& fa = a.contact.tool_forces;
  const auto& fb = b.contact.tool_forces;
  const auto& xa = a.contact.tool_displacements;
  const auto& xb = b.contact.tool_displacements;
  for (std::size_t k = 0; k < fb.size() && k < fa.size() && k < xa.size() && k < xb.size(); ++k)
    bound += distance(fa[k], fb[k]) * distance(xa[k], xb[k]);
  return 0.5 * bound;
}

}  // namespace

double stored_energy(const StepRecord& r) {
  return r.elastic_energy + r.plastic_dissipation + r.contact.friction_dissipation + r.contact.contact_energy +
         r.wire_contact.friction_dissipation + r.wire_contact.contact_energy + r.grip.bond_energy +
         r.grip.slip_dissipation;
}

std::optional<FailedCheck> RunGuard::check(const StepRecord& r) {
  FailedCheck failed;
  failed.step = r.step;
  failed.time = r.time;
  failed.displacement = r.displacement;
  const auto out_of_bound = [&failed](const char* check, const char* entry, double value, double bound) {
    failed.check = check;
    failed.entry = entry;
    failed.value = value;
    failed.bound = bound;
    return failed;
  };
  const double stored = stored_energy(r);
  const double penetration = std::max(r.contact.max_penetration, r.wire_contact.max_penetration);
  if (!std::isfinite(r.force) || !std::isfinite(r.displacement) || !std::isfinite(stored) ||
      !std::isfinite(r.external_work) || !std::isfinite(penetration)) {
    failed.check = "finite_state";
    return failed;
  }
  if (!initial_stored_) initial_stored_ = stored;  // an as-made wire starts with its forming's energy
  if (previous_) quadrature_allowance_ += trapezoid_error_bound(*previous_, r);
  previous_ = r;
  largest_work_ = std::max(largest_work_, std::abs(r.external_work));
  if (largest_work_ >= checks_.energy_floor) {
    const double imbalance = std::abs(r.external_work - (stored - *initial_stored_));
    largest_imbalance_ = std::max(largest_imbalance_, imbalance / largest_work_);
    const double error = std::max(0.0, imbalance - quadrature_allowance_) / largest_work_;
    largest_balance_error_ = std::max(largest_balance_error_, error);
    if (error > checks_.max_balance_error)
      return out_of_bound("energy_balance", "Max energy balance error (%)", error, checks_.max_balance_error);
  }
  const double relative_penetration = penetration / diameter_;
  largest_penetration_ = std::max(largest_penetration_, relative_penetration);
  if (relative_penetration > checks_.max_penetration)
    return out_of_bound("penetration", "Max penetration (% of diameter)", relative_penetration, checks_.max_penetration);
  return std::nullopt;
}

}  // namespace dtwire::fem
