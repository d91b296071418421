#pragma once
// Yield surface, flow direction and isotropic hardening of the double-twist macro-element
// (Previtali, PhD thesis; public PFC7 plugin marcoprevitali/macroelement-doubletwist-PFC7), shared
// by the planar "thesis" law and "macro3d" so that macro3d reduces to the thesis on planar paths.
//
// The moment enters through its magnitude M = |(M_1, M_2)| (planar: M_2 = 0), so gradients with
// respect to the moment vector are coefficient * (M_1, M_2). Angles are in the caller's unit: k_M
// and the moment stiffness must use the unit of the plastic rotation.
#include <algorithm>
#include <cmath>

namespace dtwire::dem::detail {

struct SurfaceParameters {
  double D = 0.0;        // wire diameter, scales M in the surface           [m]
  double N0 = 0.0;       // initial axial strength                           [N]
  double Nult = 0.0;     // ultimate axial strength (hardening limit)        [N]
  double Nc = 0.0;       // compressive strength                             [N]
  double m_f = 0.0;      // moment/force ratio of the surface                 [-]
  double beta_f = 0.0;   // shape of the tension surface                      [-]
  double k_F = 0.0;      // hardening rate per axial plastic displacement     [1/m]
  double k_M = 0.0;      // hardening rate per plastic rotation               [1/angle unit]
  double m_g = 0.0;      // plastic potential: m_f counterpart                [-]
  double alpha_g = 0.5;  // plastic potential: shift (1/2 in the surface)     [-]
  double beta_g = 0.0;   // plastic potential: beta_f counterpart             [-]
  // Plastic rotation per unit of the potential's moment gradient: 1 in the thesis (degrees);
  // pi/180 in macro3d (radians) when the parameters come from the degree-based calibration.
  double rotation_flow_scale = 1.0;
  // macro3d's optional moment hardening apart from the axial one (moment_hardening_ratio r_M):
  // the moment capacity hardens from D sqrt(m_f) N0 to r_M D sqrt(m_f) N0 with the same eta(z),
  // i.e. the surface's moment terms use N_yM = N0 + eta (r_M N0 - N0) = N0 (1 - sigma) + sigma N_y,
  // sigma = (r_M - 1) N0 / (Nult - N0). Off (the thesis' N_yM = N_y) unless moment_split.
  bool moment_split = false;
  double moment_sigma = 1.0;    // d N_yM / d N_y
  double moment_offset = 0.0;   // N0 (1 - sigma)

  // Derived constants (call prepare() after setting the parameters): no divisions per update.
  double inv_D2_mf = 0.0, inv_beta_f = 0.0, inv_Nc2 = 0.0, inv_beta_g = 0.0;
  double h_min = 0.0;  // lower bound of h on 0 <= F <= N_y: exp(-1 / (4 beta_f))
  void prepare() {
    inv_D2_mf = 1.0 / (D * D * m_f);
    inv_beta_f = 1.0 / beta_f;
    inv_Nc2 = 1.0 / (Nc * Nc);
    inv_beta_g = 1.0 / beta_g;
    h_min = std::exp(-0.25 * inv_beta_f);
  }
};

// N_y = N0 + eta (Nult - N0), eta = 1 - exp(-k_F a_u - k_M a_w), a_u, a_w the accumulated
// magnitudes of plastic displacement and rotation (the thesis' |u_p|, |omega_p|).
struct Hardening {
  double Ny;
  double dNy_dau;
  double dNy_daw;
};

// N_yM, the axial-force scale of the moment terms (= N_y unless moment_split).
inline double moment_yield(const SurfaceParameters& p, double Ny) {
  return p.moment_split ? p.moment_offset + p.moment_sigma * Ny : Ny;
}

inline Hardening hardening(const SurfaceParameters& p, double a_u, double a_w) {
  const double exponent = p.k_F * a_u + p.k_M * a_w;
  // Saturated: exp(-40) (N_ult - N_0) is below the round-off of N_y; spare the exponential.
  if (exponent > 40.0) return {p.Nult, 0.0, 0.0};
  const double decay = std::exp(-exponent);
  const double span = p.Nult - p.N0;
  return {p.N0 + (1.0 - decay) * span, p.k_F * decay * span, p.k_M * decay * span};
}

// Normalised yield function: -1 at the origin, 0 on the surface. Relative to the thesis' f it is
// divided by m_f N_y^2 in tension and by M_Y / D in compression.
//   tension (F >= 0):  f = (M/D)^2 + m_f h (F^2 - N_y^2),  h = exp(-(F/(2 N_y))^2 / beta_f)
//   compression:       f = (M_Y/D) (F^2/Nc^2 + (M/M_Y)^2 - 1),  M_Y = D sqrt(m_f) N_y
inline double yield_function(const SurfaceParameters& p, double F, double M_squared, double Ny) {
  const double inv_Ny2 = 1.0 / (Ny * Ny);
  const double NyM = moment_yield(p, Ny);
  const double moment_term = M_squared * (1.0 / (NyM * NyM)) * p.inv_D2_mf;
  if (F < 0.0) return F * F * p.inv_Nc2 + moment_term - 1.0;
  const double r = F * F * inv_Ny2;
  return moment_term + std::exp(-0.25 * r * p.inv_beta_f) * (r - 1.0);
}

// True when the state is certainly inside (f < 0), decided without the exponential: on
// 0 <= F < N_y, h >= max(1 - z, h_min) with z = (F / (2 N_y))^2 / beta_f, and (r - 1) < 0.
inline bool certainly_inside(const SurfaceParameters& p, double F, double M_squared, double Ny) {
  const double inv_Ny2 = 1.0 / (Ny * Ny);
  const double NyM = moment_yield(p, Ny);
  const double moment_term = M_squared * (1.0 / (NyM * NyM)) * p.inv_D2_mf;
  const double r = F * F * inv_Ny2;
  if (F < 0.0) return F * F * p.inv_Nc2 + moment_term < 1.0;
  if (r >= 1.0) return false;
  const double h_lower = std::max(1.0 - 0.25 * r * p.inv_beta_f, p.h_min);
  return moment_term + h_lower * (r - 1.0) < 0.0;
}

// Gradient of the normalised yield function and the flow direction at one state.
struct SurfaceGradients {
  double f;          // normalised yield function
  double df_dF;
  double df_dM;      // coefficient: d f / d(M_1, M_2) = df_dM * (M_1, M_2)
  double df_dNy;
  double flow_F;     // plastic displacement per unit multiplier
  double flow_M;     // coefficient: plastic rotation per unit multiplier = flow_M * (M_1, M_2)
};

inline SurfaceGradients surface_gradients(const SurfaceParameters& p, double F, double M_squared,
                                          double Ny) {
  SurfaceGradients g{};
  const double inv_Ny = 1.0 / Ny;
  const double inv_Ny2 = inv_Ny * inv_Ny;
  const double inv_NyM = p.moment_split ? 1.0 / moment_yield(p, Ny) : inv_Ny;
  const double moment_scale = inv_NyM * inv_NyM * p.inv_D2_mf;
  const double dNyM_dNy = p.moment_sigma;  // 1 unless moment_split
  if (F < 0.0) {
    // Compression: associated flow (in the calibration's angle unit).
    const double inv_Nc2 = p.inv_Nc2;
    g.f = F * F * inv_Nc2 + M_squared * moment_scale - 1.0;
    g.df_dF = 2.0 * F * inv_Nc2;
    g.df_dM = 2.0 * moment_scale;
    g.df_dNy = -2.0 * M_squared * moment_scale * inv_NyM * dNyM_dNy;
    g.flow_F = g.df_dF;
    g.flow_M = p.rotation_flow_scale * g.df_dM;
    return g;
  }
  const double x = 0.5 * F * inv_Ny;
  const double h = std::exp(-x * x * p.inv_beta_f);
  const double r = F * F * inv_Ny2 - 1.0;  // (F^2 - N_y^2) / N_y^2
  g.f = M_squared * moment_scale + h * r;
  g.df_dF = h * (2.0 * F * inv_Ny2 - r * x * inv_Ny * p.inv_beta_f);
  g.df_dM = 2.0 * moment_scale;
  g.df_dNy = -2.0 * M_squared * moment_scale * inv_NyM * dNyM_dNy - 2.0 * h * F * F * inv_Ny2 * inv_Ny +
             h * r * x * F * inv_Ny2 * p.inv_beta_f;
  // Non-associated flow exactly as the published implementation evaluates it: the derivative of
  // m_g h_g (F^2 - N_y^2) with the exponential prefactor h taken from the yield surface (beta_f,
  // 1/2) and the bracket from the potential (alpha_g, beta_g); the moment part is 2 M / D^2. The
  // thesis' calibrated m_g, alpha_g, beta_g belong to this form.
  const double shift = x + (0.5 - p.alpha_g);  // (F + N_y) / (2 N_y) - alpha_g, exact at F = 0
  g.flow_F = p.m_g * h * (2.0 * F - (F * F - Ny * Ny) * shift * inv_Ny * p.inv_beta_g);
  g.flow_M = p.rotation_flow_scale * 2.0 / (p.D * p.D);
  return g;
}

}  // namespace dtwire::dem::detail
