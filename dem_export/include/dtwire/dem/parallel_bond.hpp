#pragma once
// The linear parallel bond of Potyondy & Cundall (2004, Int. J. Rock Mech. Min. Sci. 41,
// 1329-1364): an elastic beam-like bond of circular section; forces and moments grow
// incrementally with the relative motion, and the bond breaks when the maximum tensile or shear
// stress on its section reaches the strength.
//
// Parameters (SI): E_Pa, diameter_m (bond section, the wire diameter), length_m (bond length);
// optional: G_Pa (default E / (2 (1 + poisson_1))), poisson_1 (default 0.3),
// tensile_strength_Pa, shear_strength_Pa (default: no break).
//   k_n = E A / L, k_s = G A / L, k_bend = E I / L, k_twist = G J / L,
//   A = pi R^2, I = pi R^4 / 4, J = pi R^4 / 2, R = diameter / 2.
#include "dtwire/dem/contact_law.hpp"

namespace dtwire::dem {

class ParallelBondLaw final : public ContactLaw {
 public:
  explicit ParallelBondLaw(const ParameterMap& parameters);

  void update(const Vector6& displacement_increment) override;
  Vector6 forces() const override { return forces_; }
  EnergyAccount energy() const override;
  bool broken() const override { return failure_mode_ != FailureMode::None; }
  FailureMode failure_mode() const override { return failure_mode_; }
  std::string_view name() const override { return "parallel_bond"; }
  std::unique_ptr<ContactLaw> clone() const override;

  // Stiffness per component (k_n, k_s, k_s, k_twist, k_bend, k_bend) [N/m, N m/rad].
  const Vector6& stiffness() const { return stiffness_; }
  // Maximum tensile and shear stress on the section (Potyondy & Cundall 2004, eq. 12) [Pa].
  double max_tensile_stress() const;
  double max_shear_stress() const;

 private:
  Vector6 stiffness_;
  Vector6 forces_ = Vector6::Zero();
  double area_ = 0.0, inertia_ = 0.0, polar_inertia_ = 0.0, radius_ = 0.0;
  double tensile_strength_ = 0.0, shear_strength_ = 0.0;  // 0: no break
  double external_work_ = 0.0;
  double released_energy_ = 0.0;
  FailureMode failure_mode_ = FailureMode::None;
};

}  // namespace dtwire::dem
