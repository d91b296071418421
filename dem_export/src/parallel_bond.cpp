#include "dtwire/dem/parallel_bond.hpp"

#include <cmath>

#include "law_parameters.hpp"

namespace dtwire::dem {

namespace {
const std::string law_name = "parallel_bond";
constexpr double pi = 3.141592653589793238462643383279502884;
}  // namespace

ParallelBondLaw::ParallelBondLaw(const ParameterMap& p) {
  using detail::checked;
  using detail::optional_parameter;
  using detail::positive_parameter;
  const double E = positive_parameter(p, law_name, "E_Pa");
  const double poisson = optional_parameter(p, "poisson_1", 0.3);
  if (!(poisson > -1.0 && poisson < 0.5))
    throw std::invalid_argument("parallel_bond: parameter 'poisson_1' must be in (-1, 0.5)");
  const double G = checked(law_name, "G_Pa", optional_parameter(p, "G_Pa", E / (2.0 * (1.0 + poisson))));
  const double diameter = positive_parameter(p, law_name, "diameter_m");
  const double length = positive_parameter(p, law_name, "length_m");
  tensile_strength_ = checked(law_name, "tensile_strength_Pa", optional_parameter(p, "tensile_strength_Pa", 0.0), true);
  shear_strength_ = checked(law_name, "shear_strength_Pa", optional_parameter(p, "shear_strength_Pa", 0.0), true);

  radius_ = 0.5 * diameter;
  area_ = pi * radius_ * radius_;
  inertia_ = 0.25 * pi * std::pow(radius_, 4);
  polar_inertia_ = 2.0 * inertia_;
  const double kn = E * area_ / length, ks = G * area_ / length;
  const double k_bend = E * inertia_ / length, k_twist = G * polar_inertia_ / length;
  stiffness_ << kn, ks, ks, k_twist, k_bend, k_bend;
}

double ParallelBondLaw::max_tensile_stress() const {
  return forces_[0] / area_ + std::sqrt(forces_[4] * forces_[4] + forces_[5] * forces_[5]) * radius_ / inertia_;
}

double ParallelBondLaw::max_shear_stress() const {
  return std::sqrt(forces_[1] * forces_[1] + forces_[2] * forces_[2]) / area_ +
         std::abs(forces_[3]) * radius_ / polar_inertia_;
}

void ParallelBondLaw::update(const Vector6& increment) {
  if (failure_mode_ != FailureMode::None) return;
  const Vector6 next = forces_ + stiffness_.cwiseProduct(increment);
  external_work_ += 0.5 * (forces_ + next).dot(increment);  // exact for a linear spring
  forces_ = next;
  if (tensile_strength_ > 0.0 && max_tensile_stress() >= tensile_strength_)
    failure_mode_ = FailureMode::Necking;
  else if (shear_strength_ > 0.0 && max_shear_stress() >= shear_strength_)
    failure_mode_ = FailureMode::Shear;
  if (failure_mode_ != FailureMode::None) {
    released_energy_ = 0.5 * forces_.cwiseProduct(forces_).cwiseQuotient(stiffness_).sum();
    forces_.setZero();
  }
}

EnergyAccount ParallelBondLaw::energy() const {
  EnergyAccount account;
  account.external = external_work_;
  account.elastic = 0.5 * forces_.cwiseProduct(forces_).cwiseQuotient(stiffness_).sum();
  account.damage = released_energy_;
  return account;
}

std::unique_ptr<ContactLaw> ParallelBondLaw::clone() const {
  return std::make_unique<ParallelBondLaw>(*this);
}

}  // namespace dtwire::dem
