#include "dtwire/dem/macro3d.hpp"

#include <cmath>
#include <stdexcept>

#include "dtwire/dem/detail/macroelement_coupled.hpp"
#include "law_parameters.hpp"
#include "macroelement_reading.hpp"

namespace dtwire::dem {

using detail::degrees_per_radian;
using detail::poisson_ratio;

namespace {
const std::string law_name = "macro3d";
}  // namespace

ParameterMap macro3d_parameters_from_thesis(const ParameterMap& thesis) {
  ParameterMap out = thesis;
  auto move = [&](const std::string& from, const std::string& to, double factor) {
    const auto found = out.find(from);
    if (found == out.end()) return;
    if (out.count(to) == 0) out[to] = found->second * factor;
    out.erase(from);
  };
  const bool degree_based = thesis.count("EI_Nm2_per_deg_convention") || thesis.count("k_M");
  move("EA_N", "axial_stiffness_N_per_m", 1.0);
  move("EI_Nm2_per_deg_convention", "bending_stiffness_Nm_per_rad", degrees_per_radian);
  move("k_F", "k_F_per_m", 1.0);
  move("k_M", "k_M_per_rad", degrees_per_radian);
  if (degree_based) {
    if (out.count("rotation_flow_scale") == 0) out["rotation_flow_scale"] = 1.0 / degrees_per_radian;
    if (out.count("damage_moment_work_weight") == 0) out["damage_moment_work_weight"] = degrees_per_radian;
  }
  if (detail::optional_parameter(out, "slide_a", 0.0) != 0.0)
    throw std::invalid_argument("macro3d: slide_a != 0 (wire-sliding spring) is not supported");
  out.erase("slide_a");
  out.erase("slide_b");
  out.erase("reference_length_m");
  return out;
}

Macro3dLaw::Macro3dLaw(const ParameterMap& given) {
  using detail::optional_parameter;
  using detail::positive_parameter;
  const ParameterMap p = given.count("EA_N") ? macro3d_parameters_from_thesis(given) : given;
  surface_ = detail::read_surface(p, law_name, "k_F_per_m", "k_M_per_rad",
                                  detail::checked(law_name, "rotation_flow_scale",
                                                  optional_parameter(p, "rotation_flow_scale", 1.0)));
  detail::read_moment_hardening(p, law_name, surface_);
  damage_ = detail::read_damage(p, law_name);
  moment_work_weight_ = detail::checked(law_name, "damage_moment_work_weight",
                                        optional_parameter(p, "damage_moment_work_weight", 1.0));
  shear_strength_ = detail::checked(law_name, "shear_strength_N",
                                    optional_parameter(p, "shear_strength_N", 0.0), true);
  settings_.tolerance = detail::checked(law_name, "rk_tolerance", optional_parameter(p, "rk_tolerance", 1e-6));
  settings_.drift_correction = true;
  // 1: backward-Euler closest-point return (first order in the increment, RK2(3) as fallback);
  // 0: RK2(3) substepping to rk_tolerance throughout. Default 1, but 0 when rk_tolerance is
  // given: a tolerance is a request for the error-controlled RK2(3) integration (the implicit
  // return has no tolerance; its accuracy is set by the increment, first order).
  const double implicit = optional_parameter(p, "implicit_return", p.count("rk_tolerance") ? 0.0 : 1.0);
  if (implicit != 0.0 && implicit != 1.0) throw std::invalid_argument("macro3d: implicit_return must be 0 or 1");
  settings_.implicit_return = implicit == 1.0;
  settings_.moment_error_weight = 1.0 / (surface_.D * std::sqrt(surface_.m_f));

  stiffness_.axial = positive_parameter(p, law_name, "axial_stiffness_N_per_m");
  stiffness_.moment = positive_parameter(p, law_name, "bending_stiffness_Nm_per_rad");
  shear_stiffness_ = detail::read_shear_stiffness(p, given, law_name, stiffness_.axial, stiffness_.moment);
  torsion_stiffness_ = detail::checked(
      law_name, "torsion_stiffness_Nm_per_rad",
      optional_parameter(p, "torsion_stiffness_Nm_per_rad", stiffness_.moment / (1.0 + poisson_ratio)));
  compliance_ = {1.0 / stiffness_.axial, 1.0 / stiffness_.moment, 1.0 / shear_stiffness_, 1.0 / torsion_stiffness_};
  const double kappa = detail::checked(law_name, "bending_axial_coupling",
                                       optional_parameter(p, "bending_axial_coupling", 0.0), true);
  if (kappa > 0.0) {
    // The bond's length (macro3d_parameters_from_thesis drops it from p: read the given map).
    const auto length = given.find("reference_length_m");
    if (length == given.end() || !(length->second > 0.0) || !std::isfinite(length->second))
      throw std::invalid_argument("macro3d: bending_axial_coupling > 0 needs the bond's reference_length_m > 0");
    coupling_ = kappa * length->second / 24.0;
    // Compression softens bending (k_m + 2 c N): the elastic tangent loses definiteness at the
    // bond's first-order buckling load N_b = k_m / (2 c) (12 EI/L^2 for k_m = EI/L, kappa = 1).
    // The compression branch of the surface bounds admissible states by N >= -Nc, so Nc is
    // capped at 0.9 N_b: k_m + 2 c N >= k_m / 10 in every admissible state.
    buckling_force_ = stiffness_.moment / (2.0 * coupling_);
    if (surface_.Nc > 0.9 * buckling_force_) {
      surface_.Nc = 0.9 * buckling_force_;
      surface_.prepare();
    }
  }
  plastic_.Ny = surface_.N0;
}

double Macro3dLaw::effective_energy(const detail::PlasticState& s, double shear_y, double shear_z,
                                    double torque) const {
  return 0.5 * (s.y[0] * s.y[0] * compliance_[0] + (s.y[1] * s.y[1] + s.y[2] * s.y[2]) * compliance_[1] +
                (shear_y * shear_y + shear_z * shear_z) * compliance_[2] + torque * torque * compliance_[3]);
}

void Macro3dLaw::update(const Vector6& given_increment) {
  if (broken_) return;
  // Bending-axial coupling: the law works in the conjugate pair (s, w) with the stretch
  // s = u + c |w|^2 (w the total rotation), where the elasticity is linear and uncoupled
  // (N = k_a (s - u_p), M_s = k_m (w - w_p)): the axial increment becomes ds = du + c d|w|^2.
  // The surface acts on the end moment M = M_s + 2 c N w: general_update with the coupled
  // integrator unless the end state is certainly inside.
  if (coupling_ > 0.0) {
    Vector6 stretched = given_increment;
    const double wy = rotation_[0], wz = rotation_[1];
    const double dwy = given_increment[4], dwz = given_increment[5];
    stretched[0] += coupling_ * ((2.0 * wy + dwy) * dwy + (2.0 * wz + dwz) * dwz);
    // Elastic fast path: the end state certainly inside (as the uncoupled one, which also tests
    // the end of the increment only; the general update tests its end and start the same way).
    const double N1 = plastic_.y[0] + stiffness_.axial * stretched[0];
    const double Msy1 = plastic_.y[1] + stiffness_.moment * dwy, Msz1 = plastic_.y[2] + stiffness_.moment * dwz;
    const double My1 = Msy1 + 2.0 * coupling_ * N1 * (wy + dwy), Mz1 = Msz1 + 2.0 * coupling_ * N1 * (wz + dwz);
    if (detail::certainly_inside(surface_, N1, My1 * My1 + Mz1 * Mz1, plastic_.Ny)) {
      const double shear_y1 = shear_y_ + shear_stiffness_ * stretched[1];
      const double shear_z1 = shear_z_ + shear_stiffness_ * stretched[2];
      const double torque1 = torque_ + torsion_stiffness_ * stretched[3];
      energy_.external += damage_factor_ * (0.5 * (plastic_.y[0] + N1) * stretched[0] +
                                            0.5 * (shear_y_ + shear_y1) * stretched[1] +
                                            0.5 * (shear_z_ + shear_z1) * stretched[2] +
                                            0.5 * (torque_ + torque1) * stretched[3] +
                                            0.5 * (plastic_.y[1] + Msy1) * dwy + 0.5 * (plastic_.y[2] + Msz1) * dwz);
      plastic_.y[0] = N1, plastic_.y[1] = Msy1, plastic_.y[2] = Msz1;
      plastic_.f_known = false;
      shear_y_ = shear_y1, shear_z_ = shear_z1, torque_ = torque1;
      rotation_[0] = wy + dwy, rotation_[1] = wz + dwz;
      if (shear_strength_ > 0.0 && damage_factor_ * std::hypot(shear_y_, shear_z_) > shear_strength_)
        break_bond(FailureMode::Shear);
      return;
    }
    general_update(stretched);
    rotation_[0] = wy + dwy, rotation_[1] = wz + dwz;
    return;
  }
  const Vector6& increment = given_increment;
  // Elastic fast path, kept small so that it stays cheap: the trial state is certainly inside.
  const double N1 = plastic_.y[0] + stiffness_.axial * increment[0];
  const double My1 = plastic_.y[1] + stiffness_.moment * increment[4];
  const double Mz1 = plastic_.y[2] + stiffness_.moment * increment[5];
  if (!detail::certainly_inside(surface_, N1, My1 * My1 + Mz1 * Mz1, plastic_.Ny)) {
    general_update(increment);
    return;
  }
  const double shear_y1 = shear_y_ + shear_stiffness_ * increment[1];
  const double shear_z1 = shear_z_ + shear_stiffness_ * increment[2];
  const double torque1 = torque_ + torsion_stiffness_ * increment[3];
  // Same booking as an elastic piece of general_update: external += d Qbar.dq.
  energy_.external += damage_factor_ * (0.5 * (plastic_.y[0] + N1) * increment[0] +
                                        0.5 * (shear_y_ + shear_y1) * increment[1] +
                                        0.5 * (shear_z_ + shear_z1) * increment[2] +
                                        0.5 * (torque_ + torque1) * increment[3] +
                                        0.5 * (plastic_.y[1] + My1) * increment[4] +
                                        0.5 * (plastic_.y[2] + Mz1) * increment[5]);
  plastic_.y[0] = N1, plastic_.y[1] = My1, plastic_.y[2] = Mz1;
  plastic_.f_known = false;
  shear_y_ = shear_y1, shear_z_ = shear_z1, torque_ = torque1;
  if (shear_strength_ > 0.0 && damage_factor_ * std::hypot(shear_y_, shear_z_) > shear_strength_)
    break_bond(FailureMode::Shear);
}

void Macro3dLaw::general_update(const Vector6& increment) {
  const std::array<double, 3> dq{increment[0], increment[4], increment[5]};
  const double shear_y0 = shear_y_, shear_z0 = shear_z_, torque0 = torque_;
  const double d_shear_y = shear_stiffness_ * increment[1];
  const double d_shear_z = shear_stiffness_ * increment[2];
  const double d_torque = torsion_stiffness_ * increment[3];

  auto on_substep = [&](const detail::PlasticState& before, const detail::PlasticState& after,
                        double t0, double t1) {
    const double dt = t1 - t0;
    const double shear_y1 = shear_y0 + t1 * d_shear_y, shear_z1 = shear_z0 + t1 * d_shear_z;
    const double torque1 = torque0 + t1 * d_torque;
    const double N_mean = 0.5 * (before.y[0] + after.y[0]);
    const double My_mean = 0.5 * (before.y[1] + after.y[1]);
    const double Mz_mean = 0.5 * (before.y[2] + after.y[2]);
    // Qbar.dq over all six components (the shear and torsion parts are linear).
    const double work = dt * (N_mean * increment[0] + 0.5 * (shear_y_ + shear_y1) * increment[1] +
                              0.5 * (shear_z_ + shear_z1) * increment[2] +
                              0.5 * (torque_ + torque1) * increment[3] + My_mean * increment[4] +
                              Mz_mean * increment[5]);
    const double axial_plastic = N_mean * (after.y[3] - before.y[3]);
    const double moment_plastic = My_mean * (after.y[4] - before.y[4]) + Mz_mean * (after.y[5] - before.y[5]);
    if (axial_plastic == 0.0 && moment_plastic == 0.0) {  // elastic piece: damage unchanged
      energy_.external += damage_factor_ * work;
    } else {
      // With the coupling the free energy's dissipation is N du_p + M_s.dw_p (booked as plastic);
      // the damage and the failure mode use the thesis' plastic work with the end moment,
      // M.dw_p = (M_s + 2 c N w).dw_p >= 0 (the flow is along M).
      double hinge_plastic = moment_plastic;
      if (coupling_ > 0.0) {
        const double wy0 = rotation_[0] + t0 * increment[4], wz0 = rotation_[1] + t0 * increment[5];
        const double wy1 = rotation_[0] + t1 * increment[4], wz1 = rotation_[1] + t1 * increment[5];
        const double Nw_y = 0.5 * (before.y[0] * wy0 + after.y[0] * wy1);
        const double Nw_z = 0.5 * (before.y[0] * wz0 + after.y[0] * wz1);
        hinge_plastic += 2.0 * coupling_ * (Nw_y * (after.y[4] - before.y[4]) + Nw_z * (after.y[5] - before.y[5]));
      }
      axial_plastic_work_ += axial_plastic;
      moment_plastic_work_ += hinge_plastic;
      damage_work_ += axial_plastic + moment_work_weight_ * hinge_plastic;
      const double d1 = damage_.factor(damage_work_);
      energy_.book({damage_factor_, d1, effective_energy(before, shear_y_, shear_z_, torque_),
                    effective_energy(after, shear_y1, shear_z1, torque1), work,
                    axial_plastic + moment_plastic});
      damage_factor_ = d1;
    }
    shear_y_ = shear_y1, shear_z_ = shear_z1, torque_ = torque1;
    return damage_factor_ > detail::DamageParameters::break_factor;
  };
  if (coupling_ > 0.0) {
    const detail::CouplingPath path{coupling_, rotation_, {increment[4], increment[5]}};
    last_substeps_ =
        detail::integrate_increment_coupled(surface_, stiffness_, settings_, path, plastic_, dq, on_substep);
  } else {
    last_substeps_ = detail::integrate_increment(surface_, stiffness_, settings_, plastic_, dq, on_substep);
  }
  if (damage_factor_ <= detail::DamageParameters::break_factor) {
    // Necking when the dissipation was mostly axial and the wire ends in tension.
    const bool tension_dominated = axial_plastic_work_ >= moment_plastic_work_ && plastic_.y[0] > 0.0;
    break_bond(tension_dominated ? FailureMode::Necking : FailureMode::Shear);
  } else if (shear_strength_ > 0.0 &&
             damage_factor_ * std::hypot(shear_y_, shear_z_) > shear_strength_) {
    break_bond(FailureMode::Shear);
  }
}

void Macro3dLaw::break_bond(FailureMode mode) {
  // The energy still stored is released when the bond is deleted.
  energy_.damage += damage_factor_ * effective_energy(plastic_, shear_y_, shear_z_, torque_);
  broken_ = true;
  failure_mode_ = mode;
  damage_factor_ = 0.0;
}

Vector6 Macro3dLaw::forces() const {
  Vector6 q;
  q << plastic_.y[0], shear_y_, shear_z_, torque_, plastic_.y[1], plastic_.y[2];
  if (coupling_ > 0.0) {  // end moment M = M_s + 2 c N w
    q[4] += 2.0 * coupling_ * plastic_.y[0] * rotation_[0];
    q[5] += 2.0 * coupling_ * plastic_.y[0] * rotation_[1];
  }
  return damage_factor_ * q;
}

EnergyAccount Macro3dLaw::energy() const {
  EnergyAccount account;
  account.external = energy_.external;
  account.plastic = energy_.plastic;
  account.damage = energy_.damage;
  account.elastic = damage_factor_ * effective_energy(plastic_, shear_y_, shear_z_, torque_);
  return account;
}

double Macro3dLaw::normalised_yield_function() const {
  if (coupling_ > 0.0) return detail::coupled_yield(surface_, coupling_, plastic_.y, rotation_, plastic_.Ny);
  return detail::yield_value(surface_, plastic_);
}

std::unique_ptr<ContactLaw> Macro3dLaw::clone() const { return std::make_unique<Macro3dLaw>(*this); }

}  // namespace dtwire::dem
