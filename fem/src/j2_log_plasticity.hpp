#pragma once
// Multiplicative J2 plasticity with logarithmic (Hencky) elastic strains and the exponential-map
// return mapping: Simo (1992) CMAME 99; Eterovic & Bathe (1990) IJNME 30; de Souza Neto, Peric &
// Owen (2008) "Computational Methods for Plasticity", ch. 14 (Box 14.3).
// Only deal.II's tensor classes are used here, so this compiles fast and is testable alone.
#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>

#include <array>

#include "hardening.hpp"

namespace dtwire::fem {

using Tensor2 = dealii::Tensor<2, 3>;
using Tensor4 = dealii::Tensor<4, 3>;
using SymTensor2 = dealii::SymmetricTensor<2, 3>;

struct ElasticParameters {
  double young = 0.0;    // Pa
  double poisson = 0.0;
  double bulk() const { return young / (3.0 * (1.0 - 2.0 * poisson)); }
  double shear() const { return young / (2.0 * (1.0 + poisson)); }
};

// History at a quadrature point. Cp^-1 = Fp^-1 Fp^-T (Simo's plastic metric); det = 1 / Jp^2.
struct PlasticState {
  SymTensor2 plastic_metric_inverse = dealii::unit_symmetric_tensor<3>();
  double equivalent_plastic_strain = 0.0;
  double plastic_dissipation = 0.0;  // J per reference volume, accumulated
  double damage = 0.0;               // ductile failure indicator, failure at 1
  double softening = 0.0;            // w: the stress is (1 - w) times the undamaged one (after D = 1)
  // The non-local average of D around the point at the last converged step (FailureParameters::
  // nonlocal_radius > 0; set by the solver, not packed: it follows from the committed D field).
  double nonlocal_damage = 0.0;
  SymTensor2 backstress;             // Pa, deviatoric (Armstrong-Frederick), spatial log-strain frame
};

// Armstrong-Frederick kinematic hardening (Armstrong & Frederick 1966; Frederick & Armstrong
// 2007, Mater. High Temp. 24): d beta = (2/3) C d eps_p - gamma beta d alpha, in the logarithmic
// strain space of the trial state (Eterovic & Bathe 1990, IJNME 30, combined hardening). Uniaxial:
// X = (3/2) beta_zz = (C / gamma)(1 - exp(-gamma eps_p)). Off when C = 0.
struct KinematicParameters {
  double modulus = 0.0;          // C, Pa
  double saturation_rate = 0.0;  // gamma (0: linear Prager hardening)
  bool enabled() const { return modulus > 0.0; }
};

// Ductile failure indicator D = sum d(alpha) / eps_f(eta, theta) (linear accumulation over the
// plastic strain increments), with eta the stress triaxiality and theta = 1 - (2/pi) arccos(xi) the
// Lode angle parameter (xi = 27 J3 / (2 q^3); +1 axisymmetric tension, 0 shear or plane strain,
// -1 axisymmetric compression). Two loci eps_f:
//  * Johnson-Cook with a Lode factor (the default):
//      eps_f = (d1 + d2 exp(d3 eta)) (s + (1 - s) theta^2),
//    Johnson & Cook (1985, EFM 21) times the symmetric form of the Bai & Wierzbicki (2008, IJP 24,
//    eq. 25) locus with its shear branch (theta = 0) at s times the axisymmetric one; s = 1 is
//    plain Johnson-Cook. Off when d1 = d2 = 0.
//  * Hosford-Coulomb (Mohr & Marcadet 2015, IJSS 67-68, eq. 20; Roth & Mohr 2016, IJP 79):
//      eps_f = b (1 + c)^(1/n) [ g_HF + c (2 eta + f1 + f3) ]^(-1/n),
//      g_HF = ( ((f1 - f2)^a + (f2 - f3)^a + (f1 - f3)^a) / 2 )^(1/a),
//      f1 = 2/3 cos(pi/6 (1 - theta)), f2 = 2/3 cos(pi/6 (3 + theta)), f3 = -2/3 cos(pi/6 (1 + theta)):
//    the Hosford equivalent stress (exponent a) plus c times the normal stress on the plane of
//    maximum shear, mapped to strain by the transformation exponent n. b is the strain to fracture
//    in uniaxial (and equibiaxial) tension; a < 2 and small c lower the ductility in shear and
//    plane strain at low triaxiality. Where the bracket is <= 0 (high pressure) no damage accrues.
//    Off when b = 0.
// Softening (optional): once D reaches 1 the stress degrades, tau = (1 - w) tau_eff, with
//   dw = d(alpha) h / u_f,  w <= w_max,
// the crack band of Bazant & Oh (1983, Mater. Struct. 16): over a cell of size h the stress falls
// to zero within an opening of u_f, so the energy dissipated per unit crack area does not depend
// on h. The damage dissipation psi dw is booked with the plastic dissipation.
// Non-local initiation (optional): a local D at a strain gradient grows with each refinement (the
// quadrature points get nearer the peak), so where the crack starts depends on the element size.
// With a radius R the crack starts where the average of D over a ball of radius R (nonlocal_average.hpp)
// reaches 1: D_bar_n + (D - D_n) >= 1, the committed average plus this step's local increment
// (the average is refreshed after each converged step). The softening stays the crack band above.
enum class FractureLocus { johnson_cook, hosford_coulomb };

struct FailureParameters {
  double d1 = 0.0, d2 = 0.0, d3 = 0.0;
  double shear_ductility_ratio = 1.0;  // s in (0, 1]
  FractureLocus locus = FractureLocus::johnson_cook;
  double hc_a = 2.0, hc_b = 0.0, hc_c = 0.0, hc_n = 0.1;  // Hosford-Coulomb a, b, c, n
  double softening_displacement = 0.0;  // u_f, m; 0: indicator only, the stress never degrades
  double largest_softening = 0.99;      // w_max: the cracked point keeps 1 - w_max of its stress
  double nonlocal_radius = 0.0;         // R, m; 0: the local D starts the crack
  bool enabled() const {
    return locus == FractureLocus::hosford_coulomb ? hc_b > 0.0 : (d1 != 0.0 || d2 != 0.0);
  }
  bool softens() const { return enabled() && softening_displacement > 0.0; }
  bool nonlocal() const { return enabled() && nonlocal_radius > 0.0; }
  // The indicator that starts the crack: D, or its non-local average.
  double initiation_indicator(const PlasticState& s) const { return nonlocal() ? s.nonlocal_damage : s.damage; }
  // Plastic strain to failure (floored at 1e-6 so that D stays finite; +inf where the locus
  // accrues no damage).
  double strain_to_failure(double triaxiality, double lode_parameter) const;
};

struct StressUpdate {
  Tensor2 first_piola;      // P = tau F^-T
  Tensor4 tangent;          // dP/dF: tangent[i][j][k][l] = dP_ij / dF_kl (algorithmic)
  SymTensor2 kirchhoff;     // tau
  double plastic_increment = 0.0;  // Delta alpha of this step
  double elastic_energy = 0.0;     // Hencky energy per reference volume
  PlasticState state;              // updated history (commit only on convergence)
};

struct Spectral;  // eigen-decomposition of a symmetric tensor (implementation detail)

class J2LogPlasticity {
 public:
  J2LogPlasticity(ElasticParameters elastic, IsotropicHardening hardening, FailureParameters failure = {},
                  KinematicParameters kinematic = {});

  // Stress at deformation gradient F from the committed history. Throws std::domain_error if
  // det F <= 0 (the caller cuts the load step back). `cell_size` (m) is the crack band h of the
  // softening; 0 (a material point without a cell) leaves the stress undegraded.
  StressUpdate update(const Tensor2& F, const PlasticState& committed, bool with_tangent,
                      double cell_size = 0.0) const;

  const ElasticParameters& elastic() const { return elastic_; }
  const IsotropicHardening& hardening() const { return hardening_; }
  const KinematicParameters& kinematic() const { return kinematic_; }

 private:
  double solve_plastic_increment(double trial_equivalent_stress, double alpha_n) const;
  StressUpdate update_kinematic(const Tensor2& F, const Tensor2& F_inv_T, const Tensor2& Cpi, const Spectral& s,
                                const std::array<double, 3>& eps, const PlasticState& committed,
                                bool with_tangent, double cell_size) const;
  // The indicator's and the softening's increments over a plastic increment dalpha; returns
  // dw / d(dalpha) (0 when w does not grow) for the tangent.
  double accrue_damage(const PlasticState& committed, double dalpha, double cell_size, StressUpdate& r) const;
  double solve_kinematic_increment(const SymTensor2& trial_deviator, const SymTensor2& backstress,
                                   double alpha_n) const;

  ElasticParameters elastic_;
  IsotropicHardening hardening_;
  FailureParameters failure_;
  KinematicParameters kinematic_;
};

// Stress invariants for output: von Mises, triaxiality (mean / von Mises), Lode parameter
// (normalised third invariant, xi = 27/2 J3 / q^3 in [-1, 1]).
struct StressInvariants {
  double von_mises = 0.0;
  double triaxiality = 0.0;
  double lode_parameter = 0.0;
};
StressInvariants stress_invariants(const SymTensor2& cauchy);

}  // namespace dtwire::fem
