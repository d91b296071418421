#include "dtwire/dem/thesis_macroelement.hpp"

#include <cmath>
#include <stdexcept>

#include "law_parameters.hpp"
#include "macroelement_reading.hpp"

namespace dtwire::dem {

using detail::degrees_per_radian;
using detail::poisson_ratio;

namespace {
const std::string law_name = "thesis";
}  // namespace

ThesisMacroElement::ThesisMacroElement(const ParameterMap& p) {
  using detail::positive_parameter;
  surface_ = detail::read_surface(p, law_name, "k_F", "k_M", 1.0);  // degrees throughout, as the plugin
  damage_ = detail::read_damage(p, law_name);
  if (detail::optional_parameter(p, "slide_a", 0.0) != 0.0)
    throw std::invalid_argument(
        "thesis: slide_a != 0 (wire-sliding spring) is not implemented; both published "
        "calibrations use slide_a = 0");
  settings_.tolerance = detail::checked(law_name, "rk_tolerance",
                                        detail::optional_parameter(p, "rk_tolerance", 1e-6));
  settings_.drift_correction = false;  // the published integration has none
  // The PFC7 plugin (macroelement_v1.cpp, forceDisplacementLaw) transmits the undamaged force and
  // only deletes the bond when the damage factor reaches 0.01; 1 (default) softens the forces.
  const double scales = detail::optional_parameter(p, "damage_scales_forces", 1.0);
  if (scales != 0.0 && scales != 1.0)
    throw std::invalid_argument("thesis: damage_scales_forces must be 0 (as the PFC7 plugin) or 1, got " +
                                std::to_string(scales));
  damage_scales_forces_ = scales == 1.0;
  // An optional break at a plastic strain (u_p / reference length), as wire-scale ductility data
  // give it (EN 10223-3: elongation at fracture >= 8 %); 0: the bond breaks by damage only.
  break_plastic_strain_ = detail::optional_parameter(p, "break_plastic_strain", 0.0);
  if (!(break_plastic_strain_ >= 0.0))
    throw std::invalid_argument("thesis: break_plastic_strain must be >= 0 (0: off)");
  if (break_plastic_strain_ > 0.0) {
    reference_length_ = detail::optional_parameter(p, "reference_length_m", 0.0);
    if (!(reference_length_ > 0.0))
      throw std::invalid_argument("thesis: break_plastic_strain needs the bond's reference_length_m > 0");
  }

  stiffness_.axial = positive_parameter(p, law_name, "EA_N");
  stiffness_.moment = positive_parameter(p, law_name, "EI_Nm2_per_deg_convention");
  // Plugin: kEA_shear = kEA / (2 (1 + 0.3)); torque per degree = kEA_shear / A * 2 I with
  // I = EI A / EA, i.e. 2 EI kEA_shear / EA. The shear spring may be given or the beam's instead
  // (read_shear_stiffness); the torsion stays the plugin's.
  const double plugin_shear = stiffness_.axial / (2.0 * (1.0 + poisson_ratio));
  shear_stiffness_ = detail::read_shear_stiffness(p, p, law_name, stiffness_.axial, stiffness_.moment * degrees_per_radian);
  torsion_stiffness_ = 2.0 * stiffness_.moment * plugin_shear / stiffness_.axial;
  plastic_.Ny = surface_.N0;
}

double ThesisMacroElement::undamaged_elastic_energy() const {
  const double rotational = degrees_per_radian;  // stiffness per degree -> per radian
  return 0.5 * (shear_y_ * shear_y_ + shear_z_ * shear_z_) / shear_stiffness_ +
         0.5 * torque_ * torque_ / (torsion_stiffness_ * rotational) +
         0.5 * moment_z_ * moment_z_ / (stiffness_.moment * rotational);
}

double ThesisMacroElement::damaged_effective_energy(const detail::PlasticState& s) const {
  return 0.5 * s.y[0] * s.y[0] / stiffness_.axial +
         0.5 * s.y[1] * s.y[1] / (stiffness_.moment * degrees_per_radian);
}

void ThesisMacroElement::update(const Vector6& increment) {
  if (broken_) return;
  const std::array<double, 3> dq{increment[0], increment[4] * degrees_per_radian, 0.0};
  const double shear_y0 = shear_y_, shear_z0 = shear_z_, torque0 = torque_, moment_z0 = moment_z_;
  const double d_shear_y = shear_stiffness_ * increment[1];
  const double d_shear_z = shear_stiffness_ * increment[2];
  const double d_torque = torsion_stiffness_ * increment[3] * degrees_per_radian;
  const double d_moment_z = stiffness_.moment * increment[5] * degrees_per_radian;

  auto on_substep = [&](const detail::PlasticState& before, const detail::PlasticState& after,
                        double t0, double t1) {
    const double dt = t1 - t0;
    // Undamaged elastic components: the trapezoid is their exact work.
    const double shear_y1 = shear_y0 + t1 * d_shear_y, shear_z1 = shear_z0 + t1 * d_shear_z;
    const double torque1 = torque0 + t1 * d_torque, moment_z1 = moment_z0 + t1 * d_moment_z;
    energy_.external += dt * (0.5 * (shear_y_ + shear_y1) * increment[1] +
                              0.5 * (shear_z_ + shear_z1) * increment[2] +
                              0.5 * (torque_ + torque1) * increment[3] +
                              0.5 * (moment_z_ + moment_z1) * increment[5]);
    shear_y_ = shear_y1, shear_z_ = shear_z1, torque_ = torque1, moment_z_ = moment_z1;

    const double N_mean = 0.5 * (before.y[0] + after.y[0]);
    const double M_mean = 0.5 * (before.y[1] + after.y[1]);
    const double dup = after.y[3] - before.y[3];
    const double dwp_deg = after.y[4] - before.y[4];
    // Thesis convention: moment work in N m deg drives the damage.
    damage_work_ += N_mean * dup + M_mean * dwp_deg;
    const double d1 = damage_.factor(damage_work_);
    const double softened0 = transmitted_factor(), softened1 = damage_scales_forces_ ? d1 : 1.0;
    energy_.book({softened0, softened1, damaged_effective_energy(before), damaged_effective_energy(after),
                  N_mean * dt * increment[0] + M_mean * dt * increment[4],
                  N_mean * dup + M_mean * dwp_deg / degrees_per_radian});
    damage_factor_ = d1;
    if (d1 <= detail::DamageParameters::break_factor) broken_ = true;
    if (break_plastic_strain_ > 0.0 && std::abs(after.y[3]) >= break_plastic_strain_ * reference_length_) broken_ = true;
    return !broken_;
  };
  last_substeps_ = detail::integrate_increment(surface_, stiffness_, settings_, plastic_, dq, on_substep);
  if (broken_) {
    // The bond is deleted: the energy still stored is released.
    energy_.damage += transmitted_factor() * damaged_effective_energy(plastic_) + undamaged_elastic_energy();
    shear_y_ = shear_z_ = torque_ = moment_z_ = 0.0;
    damage_factor_ = 0.0;
  }
}

Vector6 ThesisMacroElement::forces() const {
  Vector6 q = Vector6::Zero();
  if (broken_) return q;
  const double d = transmitted_factor();
  q << d * plastic_.y[0], shear_y_, shear_z_, torque_, d * plastic_.y[1], moment_z_;
  return q;
}

EnergyAccount ThesisMacroElement::energy() const {
  EnergyAccount account;
  account.external = energy_.external;
  account.plastic = energy_.plastic;
  account.damage = energy_.damage;
  account.elastic = broken_ ? 0.0 : transmitted_factor() * damaged_effective_energy(plastic_) + undamaged_elastic_energy();
  return account;
}

double ThesisMacroElement::normalised_yield_function() const {
  return detail::yield_value(surface_, plastic_);
}

double ThesisMacroElement::plastic_rotation() const { return plastic_.y[4] / degrees_per_radian; }

std::unique_ptr<ContactLaw> ThesisMacroElement::clone() const {
  return std::make_unique<ThesisMacroElement>(*this);
}

}  // namespace dtwire::dem
