#include "j2_log_plasticity.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace dtwire::fem {
struct Spectral {
  std::array<double, 3> values;
  Tensor2 vectors;  // columns are the eigenvectors: vectors[i][a] = n_a[i]
};

namespace {

Spectral spectral(const SymTensor2& b) {
  const auto pairs = dealii::eigenvectors(b, dealii::SymmetricTensorEigenvectorMethod::jacobi);
  Spectral s;
  for (unsigned a = 0; a < 3; ++a) {
    s.values[a] = pairs[a].first;
    for (unsigned i = 0; i < 3; ++i) s.vectors[i][a] = pairs[a].second[i];
  }
  return s;
}

SymTensor2 from_principal(const Spectral& s, const std::array<double, 3>& principal) {
  SymTensor2 t;
  for (unsigned i = 0; i < 3; ++i)
    for (unsigned j = i; j < 3; ++j) {
      double v = 0.0;
      for (unsigned a = 0; a < 3; ++a) v += principal[a] * s.vectors[i][a] * s.vectors[j][a];
      t[i][j] = v;
    }
  return t;
}

// Divided difference of ln: (ln x - ln y) / (x - y), stable when x ~ y (limit 1/y).
double log_divided_difference(double x, double y) {
  const double r = (x - y) / y;
  if (std::abs(r) < 1e-8) return (1.0 - 0.5 * r + r * r / 3.0) / y;
  return std::log1p(r) / (x - y);
}

SymTensor2 symmetric_part(const Tensor2& t) {
  SymTensor2 s;
  for (unsigned i = 0; i < 3; ++i)
    for (unsigned j = i; j < 3; ++j) s[i][j] = 0.5 * (t[i][j] + t[j][i]);
  return s;
}

// dP/dF from a log-space modulus deps -> dtau: d ln(b)/db by the Daleckii-Krein formula in the
// eigenbasis of b_tr (valid for repeated eigenvalues), then dP = dtau F^-T - tau F^-T dF^T F^-T.
template <class Modulus>
Tensor4 chain_tangent(const Spectral& s, const Tensor2& F, const Tensor2& F_inv_T, const Tensor2& Cpi,
                      const SymTensor2& kirchhoff, const Modulus& modulus) {
  double theta[3][3];
  for (unsigned a = 0; a < 3; ++a)
    for (unsigned b = 0; b < 3; ++b) theta[a][b] = log_divided_difference(s.values[a], s.values[b]);
  const Tensor2& Q = s.vectors;
  const Tensor2 QT = dealii::transpose(Q);
  const Tensor2 Cpi_FT = Cpi * dealii::transpose(F);
  const Tensor2 P_part = Tensor2(kirchhoff) * F_inv_T;  // tau F^-T
  Tensor4 tangent;
  for (unsigned k = 0; k < 3; ++k)
    for (unsigned l = 0; l < 3; ++l) {
      // Direction dF = e_k (x) e_l.
      Tensor2 X;  // dF Cp^-1 F^T
      for (unsigned j = 0; j < 3; ++j) X[k][j] = Cpi_FT[l][j];
      const Tensor2 db = X + dealii::transpose(X);
      Tensor2 h = QT * db * Q;
      for (unsigned a = 0; a < 3; ++a)
        for (unsigned b = 0; b < 3; ++b) h[a][b] *= 0.5 * theta[a][b];
      const SymTensor2 dtau = modulus(symmetric_part(Q * h * QT));
      Tensor2 dFT_FinvT;  // dF^T F^-T = e_l (x) (row k of F^-T)
      for (unsigned j = 0; j < 3; ++j) dFT_FinvT[l][j] = F_inv_T[k][j];
      const Tensor2 dP = Tensor2(dtau) * F_inv_T - P_part * dFT_FinvT;
      for (unsigned i = 0; i < 3; ++i)
        for (unsigned j = 0; j < 3; ++j) tangent[i][j][k][l] = dP[i][j];
    }
  return tangent;
}

// Scales a softened point's stress and stored energy by 1 - w; returns its undamaged Kirchhoff
// stress, which the softening's tangent term needs.
SymTensor2 soften(double w, StressUpdate& r) {
  const SymTensor2 undamaged = r.kirchhoff;
  if (w > 0.0) {
    r.kirchhoff *= 1.0 - w;
    r.first_piola *= 1.0 - w;
    r.elastic_energy *= 1.0 - w;
  }
  return undamaged;
}

}  // namespace

J2LogPlasticity::J2LogPlasticity(ElasticParameters elastic, IsotropicHardening hardening, FailureParameters failure,
                                 KinematicParameters kinematic)
    : elastic_(elastic), hardening_(std::move(hardening)), failure_(failure), kinematic_(kinematic) {
  if (!(elastic_.young > 0) || !(elastic_.poisson > -1.0) || !(elastic_.poisson < 0.5))
    throw std::invalid_argument("elastic constants: need E > 0 and -1 < nu < 0.5");
  if (!(kinematic_.modulus >= 0.0) || !(kinematic_.saturation_rate >= 0.0))
    throw std::invalid_argument("kinematic hardening: need C >= 0 and gamma >= 0");
}

// Backward-Euler Armstrong-Frederick return: with eta(x) = s_tr - beta_n / (1 + gamma x) the
// relative stress stays parallel to eta and x = Delta alpha solves
//   g(x) = sqrt(3/2) |eta(x)| - (3 G + C / (1 + gamma x)) x - sigma_y(alpha_n + x) = 0.
// Safeguarded Newton; g(0) > 0 and g < 0 at the upper bracket below.
double J2LogPlasticity::solve_kinematic_increment(const SymTensor2& s_trial, const SymTensor2& beta_n,
                                                  double alpha_n) const {
  const double G = elastic_.shear(), C = kinematic_.modulus, gm = kinematic_.saturation_rate;
  const double scale = std::sqrt(1.5) * (s_trial.norm() + beta_n.norm());
  double lo = 0.0, hi = scale / (3.0 * G);
  double x = 0.0;
  for (int it = 0; it < 200; ++it) {
    const double d = 1.0 + gm * x;
    const SymTensor2 eta = s_trial - beta_n / d;
    const double eta_norm = eta.norm();
    const double g = std::sqrt(1.5) * eta_norm - (3.0 * G + C / d) * x - hardening_.flow_stress(alpha_n + x);
    if (std::abs(g) <= 1e-13 * scale) return x;
    if (g > 0) lo = x; else hi = x;
    const double deta_n = eta_norm > 0.0 ? (eta * beta_n) * gm / (d * d) / eta_norm : 0.0;
    const double dg = std::sqrt(1.5) * deta_n - 3.0 * G - C / (d * d) - hardening_.slope(alpha_n + x);
    double next = x - g / dg;
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (hi - lo <= 1e-16 * std::max(1.0, hi)) return next;
    x = next;
  }
  throw std::domain_error("kinematic return mapping did not converge");
}

// Safeguarded Newton (bisection fallback) on q_tr - 3 G x - sigma_y(alpha_n + x) = 0; the root is
// bracketed by [0, q_tr / 3G] since sigma_y > 0.
double J2LogPlasticity::solve_plastic_increment(double q_trial, double alpha_n) const {
  const double G = elastic_.shear();
  double lo = 0.0, hi = q_trial / (3.0 * G);
  double x = 0.0;
  for (int it = 0; it < 100; ++it) {
    const double g = q_trial - 3.0 * G * x - hardening_.flow_stress(alpha_n + x);
    if (std::abs(g) <= 1e-13 * q_trial) return x;
    if (g > 0) lo = x; else hi = x;
    const double dg = -3.0 * G - hardening_.slope(alpha_n + x);
    double next = x - g / dg;
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (hi - lo <= 1e-16 * std::max(1.0, hi)) return next;
    x = next;
  }
  throw std::domain_error("return mapping did not converge");
}

StressUpdate J2LogPlasticity::update(const Tensor2& F, const PlasticState& committed, bool with_tangent,
                                     double cell_size) const {
  const double J = dealii::determinant(F);
  if (!(J > 0.0) || !std::isfinite(J)) throw std::domain_error("det F <= 0");
  const double K = elastic_.bulk(), G = elastic_.shear();

  // Elastic trial state: b_tr = F Cp_n^-1 F^T, eps_tr = 1/2 ln b_tr (principal).
  const Tensor2 Cpi = committed.plastic_metric_inverse;
  const SymTensor2 b_trial = symmetric_part(F * Cpi * dealii::transpose(F));
  const Spectral s = spectral(b_trial);
  std::array<double, 3> eps{}, dev{};
  for (unsigned a = 0; a < 3; ++a) eps[a] = 0.5 * std::log(s.values[a]);
  const double volumetric = eps[0] + eps[1] + eps[2];
  for (unsigned a = 0; a < 3; ++a) dev[a] = eps[a] - volumetric / 3.0;
  const Tensor2 F_inv = dealii::invert(F);
  const Tensor2 F_inv_T = dealii::transpose(F_inv);
  if (kinematic_.enabled()) return update_kinematic(F, F_inv_T, Cpi, s, eps, committed, with_tangent, cell_size);
  const double dev_norm = std::sqrt(dev[0] * dev[0] + dev[1] * dev[1] + dev[2] * dev[2]);
  const double q_trial = std::sqrt(1.5) * 2.0 * G * dev_norm;

  const double alpha_n = committed.equivalent_plastic_strain;
  double dgamma = 0.0;
  if (q_trial - hardening_.flow_stress(alpha_n) > 1e-12 * hardening_.flow_stress(alpha_n))
    dgamma = solve_plastic_increment(q_trial, alpha_n);

  // Radial return in principal log-strain space: dev eps_e = dev eps_tr (1 - 3 G dgamma / q_tr).
  const double shrink = dgamma > 0.0 ? 1.0 - 3.0 * G * dgamma / q_trial : 1.0;
  std::array<double, 3> eps_e{}, tau{}, b_e{};
  double dev_e_sq = 0.0;
  for (unsigned a = 0; a < 3; ++a) {
    const double d = dev[a] * shrink;
    eps_e[a] = volumetric / 3.0 + d;
    tau[a] = K * volumetric + 2.0 * G * d;
    b_e[a] = std::exp(2.0 * eps_e[a]);
    dev_e_sq += d * d;
  }

  StressUpdate r;
  r.kirchhoff = from_principal(s, tau);
  r.first_piola = Tensor2(r.kirchhoff) * F_inv_T;
  r.plastic_increment = dgamma;
  r.elastic_energy = 0.5 * K * volumetric * volumetric + G * dev_e_sq;
  r.state.equivalent_plastic_strain = alpha_n + dgamma;
  r.state.plastic_metric_inverse = symmetric_part(F_inv * Tensor2(from_principal(s, b_e)) * F_inv_T);
  const double dw_ddgamma = accrue_damage(committed, dgamma, cell_size, r);
  const double w_n = committed.softening, w = r.state.softening;
  // Plastic work: the (degraded) flow stress integrated over Delta alpha by the trapezoidal rule,
  // second order in the step like the external work it is balanced against; plus the elastic
  // energy released by the softening.
  r.state.plastic_dissipation =
      committed.plastic_dissipation +
      0.5 * ((1.0 - w_n) * hardening_.flow_stress(alpha_n) + (1.0 - w) * hardening_.flow_stress(alpha_n + dgamma)) *
          dgamma +
      r.elastic_energy * (w - w_n);
  const SymTensor2 tau_undamaged = soften(w, r);
  if (!with_tangent) return r;

  // Algorithmic modulus D = d tau / d eps_tr (de Souza Neto et al. 2008, eq. 7.120, in log space).
  SymTensor2 n_hat;  // unit deviatoric trial direction
  if (dev_norm > 0.0) {
    std::array<double, 3> n{};
    for (unsigned a = 0; a < 3; ++a) n[a] = dev[a] / dev_norm;
    n_hat = from_principal(s, n);
  }
  double c_dev = 2.0 * G, c_nn = 0.0;
  if (dgamma > 0.0) {
    const double H = hardening_.slope(alpha_n + dgamma);
    c_dev = 2.0 * G * (1.0 - 3.0 * G * dgamma / q_trial);
    c_nn = 6.0 * G * G * (dgamma / q_trial - 1.0 / (3.0 * G + H));
  }
  // With softening: d tau = (1 - w) d tau_eff - tau_eff dw, dw = (dw/d dalpha) d dalpha and
  // d dalpha = sqrt(6) G (n_hat : d dev eps) / (3 G + H) from the radial return.
  const double dgamma_slope =
      dw_ddgamma > 0.0 ? std::sqrt(6.0) * G / (3.0 * G + hardening_.slope(alpha_n + dgamma)) : 0.0;
  r.tangent = chain_tangent(s, F, F_inv_T, Cpi, r.kirchhoff, [&](const SymTensor2& deps) {
    const double dvol = dealii::trace(deps);
    const SymTensor2 ddev = deps - dvol / 3.0 * dealii::unit_symmetric_tensor<3>();
    SymTensor2 dtau = K * dvol * dealii::unit_symmetric_tensor<3>() + c_dev * ddev + c_nn * (n_hat * ddev) * n_hat;
    if (w > 0.0) dtau *= 1.0 - w;
    if (dgamma_slope > 0.0) dtau -= dw_ddgamma * dgamma_slope * (n_hat * ddev) * tau_undamaged;
    return dtau;
  });
  return r;
}

// Combined isotropic / Armstrong-Frederick hardening. The backstress lives in the spatial
// log-strain space of the trial state and is not rotated with the material (no spin term):
// exact for paths with fixed principal axes (tension-compression cycles), an approximation
// under large rigid rotations. The plastic flow direction is then no longer coaxial with b_tr;
// b_e = exp(2 eps_e) with eps_e = eps_tr - Delta eps_p (Eterovic & Bathe 1990).
StressUpdate J2LogPlasticity::update_kinematic(const Tensor2& F, const Tensor2& F_inv_T, const Tensor2& Cpi,
                                               const Spectral& s, const std::array<double, 3>& eps,
                                               const PlasticState& committed, bool with_tangent,
                                               double cell_size) const {
  const double K = elastic_.bulk(), G = elastic_.shear();
  const double C = kinematic_.modulus, gm = kinematic_.saturation_rate;
  const SymTensor2 I = dealii::unit_symmetric_tensor<3>();
  const SymTensor2 eps_tr = from_principal(s, eps);
  const double volumetric = dealii::trace(eps_tr);
  const SymTensor2 s_trial = 2.0 * G * dealii::deviator(eps_tr);
  const SymTensor2& beta_n = committed.backstress;
  const double alpha_n = committed.equivalent_plastic_strain;
  const double q_trial = std::sqrt(1.5) * (s_trial - beta_n).norm();
  const double sigma_y0 = hardening_.flow_stress(alpha_n);

  double dalpha = 0.0;
  if (q_trial - sigma_y0 > 1e-12 * sigma_y0) dalpha = solve_kinematic_increment(s_trial, beta_n, alpha_n);
  const double d = 1.0 + gm * dalpha;
  const SymTensor2 eta = s_trial - beta_n / d;
  const double eta_norm = eta.norm();
  const SymTensor2 n_hat = dalpha > 0.0 ? SymTensor2(eta / eta_norm) : SymTensor2();
  const SymTensor2 plastic_strain_increment = std::sqrt(1.5) * dalpha * n_hat;
  const SymTensor2 deviator = s_trial - 2.0 * G * plastic_strain_increment;
  const SymTensor2 eps_e = eps_tr - plastic_strain_increment;

  StressUpdate r;
  r.kirchhoff = K * volumetric * I + deviator;
  r.first_piola = Tensor2(r.kirchhoff) * F_inv_T;
  r.plastic_increment = dalpha;
  const SymTensor2 dev_e = dealii::deviator(eps_e);
  r.elastic_energy = 0.5 * K * volumetric * volumetric + G * (dev_e * dev_e);
  r.state.equivalent_plastic_strain = alpha_n + dalpha;
  r.state.backstress = dalpha > 0.0 ? SymTensor2((beta_n + C * std::sqrt(2.0 / 3.0) * dalpha * n_hat) / d) : beta_n;
  const Spectral e = spectral(eps_e);
  std::array<double, 3> b_e{};
  for (unsigned a = 0; a < 3; ++a) b_e[a] = std::exp(2.0 * e.values[a]);
  const Tensor2 F_inv = dealii::transpose(F_inv_T);
  r.state.plastic_metric_inverse = symmetric_part(F_inv * Tensor2(from_principal(e, b_e)) * F_inv_T);
  const double dw_ddalpha = accrue_damage(committed, dalpha, cell_size, r);
  const double w_n = committed.softening, w = r.state.softening;
  // Plastic work tau : Delta eps_p (includes the energy stored in the backstress), degraded by the
  // mean softening of the step, plus the elastic energy the softening releases.
  r.state.plastic_dissipation = committed.plastic_dissipation +
                                (1.0 - 0.5 * (w_n + w)) * (deviator * plastic_strain_increment) +
                                r.elastic_energy * (w - w_n);
  const SymTensor2 tau_undamaged = soften(w, r);
  if (!with_tangent) return r;

  // Linearisation of the return: d(Delta alpha) from dg = 0, d n_hat from d eta.
  const SymTensor2 b = gm / (d * d) * beta_n;  // d eta / d(Delta alpha)
  const double hardening_slope = hardening_.slope(alpha_n + dalpha);
  const double denominator = 3.0 * G + C / (d * d) + hardening_slope - std::sqrt(1.5) * (n_hat * b);
  r.tangent = chain_tangent(s, F, F_inv_T, Cpi, r.kirchhoff, [&](const SymTensor2& deps) {
    const double dvol = dealii::trace(deps);
    const SymTensor2 ddev = deps - dvol / 3.0 * I;
    SymTensor2 dtau = K * dvol * I + 2.0 * G * ddev;
    if (dalpha > 0.0) {
      const double ddalpha = std::sqrt(1.5) * 2.0 * G * (n_hat * ddev) / denominator;
      const SymTensor2 deta = 2.0 * G * ddev + ddalpha * b;
      const SymTensor2 dn = (deta - (n_hat * deta) * n_hat) / eta_norm;
      dtau -= 2.0 * G * std::sqrt(1.5) * (ddalpha * n_hat + dalpha * dn);
      if (w > 0.0) dtau *= 1.0 - w;
      if (dw_ddalpha > 0.0) dtau -= dw_ddalpha * ddalpha * tau_undamaged;
    } else if (w > 0.0) {
      dtau *= 1.0 - w;
    }
    return dtau;
  });
  return r;
}

double J2LogPlasticity::accrue_damage(const PlasticState& committed, double dalpha, double cell_size,
                                      StressUpdate& r) const {
  r.state.damage = committed.damage;
  r.state.softening = committed.softening;
  r.state.nonlocal_damage = committed.nonlocal_damage;
  if (!(dalpha > 0.0) || !failure_.enabled()) return 0.0;
  const StressInvariants inv = stress_invariants(r.kirchhoff);  // undamaged: w scales tau, not its invariants
  const double strain_to_failure = failure_.strain_to_failure(inv.triaxiality, inv.lode_parameter);
  r.state.damage += dalpha / strain_to_failure;
  const double initiation_n = failure_.initiation_indicator(committed);
  const double initiation = initiation_n + (r.state.damage - committed.damage);
  if (!failure_.softens() || !(cell_size > 0.0) || initiation < 1.0) return 0.0;
  // The part of Delta alpha after the indicator reached 1 (it grows linearly over the step).
  const double after_initiation = initiation_n >= 1.0 ? dalpha : (initiation - 1.0) * strain_to_failure;
  const double rate = cell_size / failure_.softening_displacement;  // dw / d alpha
  const double w = committed.softening + after_initiation * rate;
  if (w >= failure_.largest_softening) {
    r.state.softening = std::max(committed.softening, failure_.largest_softening);
    return 0.0;
  }
  r.state.softening = w;
  return rate;
}

double FailureParameters::strain_to_failure(double triaxiality, double lode_parameter) const {
  const double theta = 1.0 - 2.0 / dealii::numbers::PI * std::acos(std::clamp(lode_parameter, -1.0, 1.0));
  if (locus == FractureLocus::hosford_coulomb) {
    const double sixth = dealii::numbers::PI / 6.0;
    const double f1 = 2.0 / 3.0 * std::cos(sixth * (1.0 - theta));
    const double f2 = 2.0 / 3.0 * std::cos(sixth * (3.0 + theta));
    const double f3 = -2.0 / 3.0 * std::cos(sixth * (1.0 + theta));
    const auto power = [&](double x) { return std::pow(std::max(x, 0.0), hc_a); };
    const double hosford = std::pow(0.5 * (power(f1 - f2) + power(f2 - f3) + power(f1 - f3)), 1.0 / hc_a);
    const double bracket = hosford + hc_c * (2.0 * triaxiality + f1 + f3);
    if (!(bracket > 0.0)) return std::numeric_limits<double>::infinity();
    return std::max(hc_b * std::pow((1.0 + hc_c) / bracket, 1.0 / hc_n), 1e-6);
  }
  const double lode_factor = shear_ductility_ratio + (1.0 - shear_ductility_ratio) * theta * theta;
  return std::max((d1 + d2 * std::exp(d3 * triaxiality)) * lode_factor, 1e-6);
}

StressInvariants stress_invariants(const SymTensor2& cauchy) {
  StressInvariants inv;
  const SymTensor2 s = dealii::deviator(cauchy);
  const double q = std::sqrt(1.5 * (s * s));
  inv.von_mises = q;
  if (q > 0.0) {
    inv.triaxiality = dealii::trace(cauchy) / 3.0 / q;
    inv.lode_parameter = std::clamp(13.5 * dealii::determinant(s) / (q * q * q), -1.0, 1.0);
  }
  return inv;
}

}  // namespace dtwire::fem
