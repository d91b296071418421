#include "j2_log_plasticity.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

namespace dtwire::fem {
namespace {

struct Spectral {
  std::array<double, 3> values;
  Tensor2 vectors;  // columns are the eigenvectors: vectors[i][a] = n_a[i]
};

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

}  // namespace

J2LogPlasticity::J2LogPlasticity(ElasticParameters elastic, IsotropicHardening hardening, FailureParameters failure)
    : elastic_(elastic), hardening_(std::move(hardening)), failure_(failure) {
  if (!(elastic_.young > 0) || !(elastic_.poisson > -1.0) || !(elastic_.poisson < 0.5))
    throw std::invalid_argument("elastic constants: need E > 0 and -1 < nu < 0.5");
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

StressUpdate J2LogPlasticity::update(const Tensor2& F, const PlasticState& committed,
                                     bool with_tangent) const {
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
  const Tensor2 F_inv = dealii::invert(F);
  const Tensor2 F_inv_T = dealii::transpose(F_inv);
  r.first_piola = Tensor2(r.kirchhoff) * F_inv_T;
  r.plastic_increment = dgamma;
  r.elastic_energy = 0.5 * K * volumetric * volumetric + G * dev_e_sq;
  r.state.equivalent_plastic_strain = alpha_n + dgamma;
  r.state.plastic_dissipation =
      committed.plastic_dissipation + hardening_.flow_stress(alpha_n + dgamma) * dgamma;
  r.state.plastic_metric_inverse = symmetric_part(F_inv * Tensor2(from_principal(s, b_e)) * F_inv_T);
  r.state.damage = committed.damage;
  if (dgamma > 0.0 && failure_.enabled()) {
    const double q = std::sqrt(1.5) * 2.0 * G * dev_norm * shrink;
    const double eta = K * volumetric / q;
    const double strain_to_failure = failure_.d1 + failure_.d2 * std::exp(failure_.d3 * eta);
    r.state.damage += dgamma / std::max(strain_to_failure, 1e-6);
  }
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

  // d ln(b)/db by the Daleckii-Krein formula in the eigenbasis (valid for repeated eigenvalues).
  double theta[3][3];
  for (unsigned a = 0; a < 3; ++a)
    for (unsigned b = 0; b < 3; ++b) theta[a][b] = log_divided_difference(s.values[a], s.values[b]);
  const Tensor2& Q = s.vectors;
  const Tensor2 QT = dealii::transpose(Q);
  const Tensor2 Cpi_FT = Cpi * dealii::transpose(F);
  const Tensor2 P_part = Tensor2(r.kirchhoff) * F_inv_T;  // tau F^-T

  for (unsigned k = 0; k < 3; ++k)
    for (unsigned l = 0; l < 3; ++l) {
      // Direction dF = e_k (x) e_l.
      Tensor2 X;  // dF Cp^-1 F^T
      for (unsigned j = 0; j < 3; ++j) X[k][j] = Cpi_FT[l][j];
      const Tensor2 db = X + dealii::transpose(X);
      Tensor2 h = QT * db * Q;
      for (unsigned a = 0; a < 3; ++a)
        for (unsigned b = 0; b < 3; ++b) h[a][b] *= 0.5 * theta[a][b];
      const SymTensor2 deps = symmetric_part(Q * h * QT);
      const double dvol = dealii::trace(deps);
      const SymTensor2 ddev = deps - dvol / 3.0 * dealii::unit_symmetric_tensor<3>();
      const SymTensor2 dtau = K * dvol * dealii::unit_symmetric_tensor<3>() + c_dev * ddev +
                              c_nn * (n_hat * ddev) * n_hat;
      // dP = dtau F^-T - tau F^-T dF^T F^-T
      Tensor2 dFT_FinvT;  // dF^T F^-T = e_l (x) (row k of F^-T)
      for (unsigned j = 0; j < 3; ++j) dFT_FinvT[l][j] = F_inv_T[k][j];
      const Tensor2 dP = Tensor2(dtau) * F_inv_T - P_part * dFT_FinvT;
      for (unsigned i = 0; i < 3; ++i)
        for (unsigned j = 0; j < 3; ++j) r.tangent[i][j][k][l] = dP[i][j];
    }
  return r;
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
