#pragma once
// "macro3d": our three-dimensional extension of the thesis macro-element. All six generalised
// forces (N, V_y, V_z, T, M_y, M_z), rotations in radians, the thesis yield surface evaluated
// with the resultant moment M = sqrt(M_y^2 + M_z^2) (so a planar path gives the thesis law
// exactly), a backward-Euler closest-point return per increment (macroelement_return.hpp; the
// default) or RK2(3) substepping with a consistent drift correction back to f = 0 after every
// substep (the thesis' integration; also the implicit return's fallback), complete energy bookkeeping (external = elastic + plastic + damage to round-off) and a
// failure mode telling necking (tension-dominated dissipation) from shear (bending/shear).
// Equations: docs/dem_laws.md.
//
// Parameters (SI, radians):
//   D_m, axial_stiffness_N_per_m, bending_stiffness_Nm_per_rad, N0_N, Nult_N, Nc_N, m_f, beta_f,
//   k_F_per_m, k_M_per_rad, m_g, alpha_g, beta_g, W1_J, W2_J, alpha_d
//   optional: shear_stiffness_N_per_m (default axial / (2 (1 + 0.3))) or beam_shear (1: the
//             slender beam's 12 bending / L^2 with L the bond's reference_length_m; default 0),
//             torsion_stiffness_Nm_per_rad (default bending / (1 + 0.3)),
//             rotation_flow_scale (default 1), damage_moment_work_weight (default 1),
//             shear_strength_N (resultant shear force that breaks the bond; default none),
//             rk_tolerance (default 1e-6), implicit_return (1: backward-Euler return, 0: RK2(3);
//             default 1, or 0 when rk_tolerance is given),
//             bending_axial_coupling kappa (default 0: off): N-dependent bending stiffness,
//               psi = 1/2 k_a (u - u_p + c |w|^2)^2 + 1/2 k_m |w - w_p|^2, c = kappa L / 24 with L
//               the bond's reference_length_m (required then; u the chord elongation, w the total
//               rotation), so N = k_a (u - u_p + c |w|^2), M = k_m (w - w_p) + 2 c N w: at kappa = 1
//               M = (k_m + N L/12) w elastically (first-order beam column). The yield surface
//               and flow act on (N, M), M the end moment (macroelement_coupled.hpp);
//               Nc is capped at 0.9 k_m / (2 c), so that the bending tangent k_m + 2 c N >= k_m / 10
//               in every admissible state,
//             moment_hardening_ratio r_M (default Nult/N0: the thesis' tie): the moment capacity
//               hardens from D sqrt(m_f) N0 to r_M D sqrt(m_f) N0 (same hardening variable)
// A map with the thesis keys (EA_N, EI_Nm2_per_deg_convention, k_F, k_M, ...) is converted with
// macro3d_parameters_from_thesis first, so the published calibrations can be used directly.
#include <array>
#include <cmath>

#include "dtwire/dem/contact_law.hpp"
#include "dtwire/dem/detail/macroelement_damage.hpp"
#include "dtwire/dem/detail/macroelement_integrator.hpp"

namespace dtwire::dem {

// Converts the thesis' degree-based calibration into macro3d parameters that give the same
// response: stiffness and k_M per radian, plastic rotation scaled by pi/180 (the thesis' flow
// rule acts on degrees) and the moment work weighted by 180/pi in the damage variable (the thesis
// accumulates N m deg). Keys already in macro3d form are kept.
ParameterMap macro3d_parameters_from_thesis(const ParameterMap& thesis_parameters);

class Macro3dLaw final : public ContactLaw {
 public:
  explicit Macro3dLaw(const ParameterMap& parameters);

  void update(const Vector6& displacement_increment) override;
  Vector6 forces() const override;
  EnergyAccount energy() const override;
  bool broken() const override { return broken_; }
  FailureMode failure_mode() const override { return failure_mode_; }
  std::string_view name() const override { return "macro3d"; }
  std::unique_ptr<ContactLaw> clone() const override;

  // Internal variables, for verification.
  double yield_strength() const { return plastic_.Ny; }        // N_y [N]
  double damage_work() const { return damage_work_; }           // W_p driving the damage [J]
  double damage_factor() const { return damage_factor_; }
  double normalised_yield_function() const;                     // 0 on the surface
  double axial_plastic_work() const { return axial_plastic_work_; }    // [J]
  double moment_plastic_work() const { return moment_plastic_work_; }  // [J]
  int last_substeps() const { return last_substeps_; }
  // Coupling c = kappa L / 24 [m/rad^2] (0: off); the bond's first-order buckling load
  // k_m / (2 c) [N] (infinite when off) and the compressive strength in use, min(Nc, 0.9 of it).
  double coupling_length() const { return coupling_; }
  double buckling_force() const { return buckling_force_; }
  double compressive_strength() const { return surface_.Nc; }
  // M_s = M - 2 c N w = k_m (w - w_p), undamaged (M_sy, M_sz) [N m], the moment conjugate to
  // the plastic rotation in the free energy (the end moment M when the coupling is off).
  std::array<double, 2> section_moment() const { return {plastic_.y[1], plastic_.y[2]}; }

 private:
  double effective_energy(const detail::PlasticState& s, double shear_y, double shear_z,
                          double torque) const;
  void break_bond(FailureMode mode);
  // Crossing, substepping and damage: everything but the elastic fast path of update().
  [[gnu::noinline]] void general_update(const Vector6& displacement_increment);

  detail::SurfaceParameters surface_;
  detail::DamageParameters damage_;
  detail::IntegratorSettings settings_;
  detail::ElasticStiffness stiffness_{};  // axial [N/m], bending [N m/rad]
  double shear_stiffness_ = 0.0;          // [N/m]
  double torsion_stiffness_ = 0.0;        // [N m/rad]
  double moment_work_weight_ = 1.0;       // weight of the moment work in the damage variable
  double shear_strength_ = 0.0;           // [N], 0: none
  std::array<double, 4> compliance_{};    // 1 / (axial, bending, shear, torsion stiffness)
  double coupling_ = 0.0;                 // c = kappa L / 24 [m/rad^2], 0: off
  double buckling_force_ = HUGE_VAL;      // k_m / (2 c) [N]
  std::array<double, 2> rotation_{};      // total bending rotation (w_y, w_z) [rad] (coupling only)

  detail::PlasticState plastic_;          // N, M_y, M_z, u_p, theta_py, theta_pz, a_u, a_w
  double shear_y_ = 0.0, shear_z_ = 0.0, torque_ = 0.0;
  double damage_work_ = 0.0;
  double damage_factor_ = 1.0;
  double axial_plastic_work_ = 0.0;
  double moment_plastic_work_ = 0.0;
  detail::EnergyTotals energy_;
  bool broken_ = false;
  FailureMode failure_mode_ = FailureMode::None;
  int last_substeps_ = 0;
};

}  // namespace dtwire::dem
