#pragma once
// The double-twist macro-element of Previtali's PhD thesis, as published (public PFC7 plugin
// marcoprevitali/macroelement-doubletwist-PFC7, source_code/macroelement_v1.cpp): planar N-M
// (axial u and bending theta_y), rotations in degrees internally, tension/compression yield
// surface with isotropic hardening, non-associated flow, RK2(3) substepping without drift
// correction, damage beyond W1 and break. Shear, torsion and the second bending moment are
// elastic and undamaged, as in the plugin. Equations and deviations: docs/dem_laws.md.
//
// Parameters (the keys of experiments/data/macroelement_thesis_params.json):
//   D_m, EA_N (axial stiffness, N per m of elongation), EI_Nm2_per_deg_convention (moment per
//   degree), N0_N, Nult_N, Nc_N, m_f, beta_f, k_F (1/m), k_M (1/deg), m_g, alpha_g, beta_g,
//   W1_J, W2_J, alpha_d; optional: slide_a (must be 0: the sliding spring is not implemented),
//   slide_b, reference_length_m (read only for break_plastic_strain), rk_tolerance (default 1e-6), damage_scales_forces (1:
//   beyond W1 the axial force and moment are d times the effective ones, default; 0: as the PFC7
//   plugin, which tracks d but transmits the undamaged forces until the bond is deleted at d <= 0.01),
//   break_plastic_strain (0: off, default; else the bond also breaks when |u_p| reaches it times
//   reference_length_m, a wire's ductility), shear_stiffness_N_per_m (default the plugin's
//   EA_N / 2.6) or beam_shear (1: the slender beam's 12 EI / L^3 from the bending spring and
//   reference_length_m; default 0).
#include "dtwire/dem/contact_law.hpp"
#include "dtwire/dem/detail/macroelement_damage.hpp"
#include "dtwire/dem/detail/macroelement_integrator.hpp"

namespace dtwire::dem {

class ThesisMacroElement final : public ContactLaw {
 public:
  explicit ThesisMacroElement(const ParameterMap& parameters);

  void update(const Vector6& displacement_increment) override;
  Vector6 forces() const override;
  EnergyAccount energy() const override;
  bool broken() const override { return broken_; }
  std::string_view name() const override { return "thesis"; }
  std::unique_ptr<ContactLaw> clone() const override;

  // Internal variables, for verification.
  double yield_strength() const { return plastic_.Ny; }     // N_y [N]
  double damage_work() const { return damage_work_; }        // W_p (thesis convention) [J]
  double damage_factor() const { return damage_factor_; }    // 1 before W1 (tracked in both modes)
  double normalised_yield_function() const;                  // 0 on the surface, < 0 inside
  double plastic_elongation() const { return plastic_.y[3]; }  // signed u_p [m]
  double plastic_rotation() const;                           // signed omega_p [rad]
  int last_substeps() const { return last_substeps_; }       // RK substeps of the last update

 private:
  double transmitted_factor() const { return damage_scales_forces_ ? damage_factor_ : 1.0; }
  double undamaged_elastic_energy() const;
  double damaged_effective_energy(const detail::PlasticState& s) const;

  detail::SurfaceParameters surface_;
  detail::DamageParameters damage_;
  detail::IntegratorSettings settings_;
  detail::ElasticStiffness stiffness_{};  // axial [N/m], bending [N m/deg]
  double shear_stiffness_ = 0.0;          // [N/m]
  double torsion_stiffness_ = 0.0;        // [N m/deg]

  detail::PlasticState plastic_;          // N, M_y [N m], u_p, omega_p [deg], ...
  double shear_y_ = 0.0, shear_z_ = 0.0, torque_ = 0.0, moment_z_ = 0.0;
  double damage_work_ = 0.0;
  double damage_factor_ = 1.0;
  detail::EnergyTotals energy_;
  bool broken_ = false;
  bool damage_scales_forces_ = true;
  double break_plastic_strain_ = 0.0, reference_length_ = 0.0;
  int last_substeps_ = 0;
};

}  // namespace dtwire::dem
