// Backward-Euler closest-point return of the macro-element (equations in
// dtwire/dem/detail/macroelement_return.hpp; Simo & Hughes 1998, ch. 3).
#include "dtwire/dem/detail/macroelement_return.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "dtwire/dem/detail/macroelement_coupled.hpp"
#include "dtwire/dem/detail/macroelement_integrator.hpp"

namespace dtwire::dem::detail {

namespace {

// value * exp(delta). Newton moves the arguments of the two exponentials (hardening, and h in
// tension) by small amounts: there a 10th-order Taylor polynomial is exact to round-off
// (|delta| < 1/8: remainder < 3e-18) and much cheaper than a libm call.
inline double times_exp(double value, double delta) {
  const double a = std::abs(delta);
  if (a < 2e-4) return value * (1.0 + delta * (1.0 + delta * (1.0 / 2 + delta * (1.0 / 6))));  // rest < 7e-17
  if (a >= 0.125) return value * std::exp(delta);
  // Estrin's scheme: the polynomial with a shorter dependency chain than Horner's.
  const double d2 = delta * delta, d4 = d2 * d2, d8 = d4 * d4;
  const double c0 = (1.0 + delta) + d2 * (1.0 / 2 + delta * (1.0 / 6));
  const double c4 = (1.0 / 24 + delta * (1.0 / 120)) + d2 * (1.0 / 720 + delta * (1.0 / 5040));
  const double c8 = (1.0 / 40320 + delta * (1.0 / 362880)) + d2 * (1.0 / 3628800);
  return value * (c0 + d4 * c4 + d8 * c8);
}

// The Newton step x = -J^-1 R of the 3 x 3 return system (unknowns N, z, lambda) by Cramer's
// rule, the first row's cofactors shared with the determinant; false when J is singular or
// not finite (the caller stops iterating).
bool solve_newton_step(const std::array<std::array<double, 3>, 3>& J, const std::array<double, 3>& R, double& dN,
                       double& dz, double& dlambda) {
  const double J11 = J[0][0], J12 = J[0][1], J13 = J[0][2];
  const double J21 = J[1][0], J22 = J[1][1], J23 = J[1][2];
  const double J31 = J[2][0], J32 = J[2][1], J33 = J[2][2];
  const double C11 = J22 * J33 - J23 * J32, C12 = J23 * J31 - J21 * J33, C13 = J21 * J32 - J22 * J31;
  const double det = J11 * C11 + J12 * C12 + J13 * C13;
  if (!(std::abs(det) > 0.0) || !std::isfinite(det)) return false;
  const double inv_det = 1.0 / det;
  const double b1 = -R[0], b2 = -R[1], b3 = -R[2];
  dN = (b1 * C11 + J12 * (J23 * b3 - b2 * J33) + J13 * (b2 * J32 - J22 * b3)) * inv_det;
  dz = (J11 * (b2 * J33 - J23 * b3) + b1 * C12 + J13 * (J21 * b3 - b2 * J31)) * inv_det;
  dlambda = (J11 * (J22 * b3 - b2 * J32) + J12 * (b2 * J31 - J21 * b3) + b1 * C13) * inv_det;
  return true;
}

// What one Newton iteration needs at (N, m, N_y), in two parts: the residual terms (yield
// function f and the compression-scaled axial flow G) and, only when another step is taken,
// their derivatives. `h` = exp(-(N/(2 N_y))^2 / beta_f) in tension (unused in compression).
struct ResidualTerms {
  double f, G;
};
struct DerivativeTerms {
  double f_N, f_m, f_Ny;
  double G_N, G_Ny;
};

inline ResidualTerms residual_terms(const SurfaceParameters& p, double N, double m, double Ny, double inv_Ny,
                                    double h) {
  const double inv_Ny2 = inv_Ny * inv_Ny;
  // N_yM = N_y unless the moment hardens apart (moment_yield): then the moment terms use N_yM.
  const double NyM = p.moment_split ? moment_yield(p, Ny) : Ny;
  const double inv_NyM = p.moment_split ? 1.0 / NyM : inv_Ny;
  const double moment_term = m * m * (inv_NyM * inv_NyM) * p.inv_D2_mf;
  if (N < 0.0) {
    // f = N^2/Nc^2 + (M/M_Y)^2 - 1, associated flow times kappa = N_yM^2 m_f:
    //   G = 2 N N_yM^2 m_f / Nc^2,  moment flow 2/D^2 (times rotation_flow_scale).
    return {N * N * p.inv_Nc2 + moment_term - 1.0, 2.0 * N * NyM * NyM * p.m_f * p.inv_Nc2};
  }
  // f = (M/D)^2/(m_f N_y^2) + h (N^2/N_y^2 - 1),  h = exp(-x^2/beta_f),  x = N/(2 N_y)
  // G = m_g h B,  B = 2N - T,  T = P s / (N_y beta_g),  P = N^2 - N_y^2,  s = x + 1/2 - alpha_g
  // (the published flow, surface_gradients' flow_F).
  const double x = 0.5 * N * inv_Ny;
  const double T = (N * N - Ny * Ny) * (x + (0.5 - p.alpha_g)) * inv_Ny * p.inv_beta_g;
  return {moment_term + h * (N * N * inv_Ny2 - 1.0), p.m_g * h * (2.0 * N - T)};
}

inline DerivativeTerms derivative_terms(const SurfaceParameters& p, double N, double m, double Ny, double inv_Ny,
                                        double h) {
  DerivativeTerms t{};
  const double inv_Ny2 = inv_Ny * inv_Ny;
  const double NyM = p.moment_split ? moment_yield(p, Ny) : Ny;
  const double inv_NyM = p.moment_split ? 1.0 / NyM : inv_Ny;
  const double sigma = p.moment_sigma;  // d N_yM / d N_y (1 unless moment_split)
  const double moment_scale = (inv_NyM * inv_NyM) * p.inv_D2_mf;
  const double moment_term = m * m * moment_scale;
  t.f_m = 2.0 * m * moment_scale;
  if (N < 0.0) {
    t.f_N = 2.0 * N * p.inv_Nc2;
    t.f_Ny = -2.0 * moment_term * inv_NyM * sigma;
    t.G_N = 2.0 * NyM * NyM * p.m_f * p.inv_Nc2;
    t.G_Ny = 4.0 * N * NyM * sigma * p.m_f * p.inv_Nc2;
    return t;
  }
  const double x = 0.5 * N * inv_Ny;
  const double r = N * N * inv_Ny2 - 1.0;
  t.f_N = h * (2.0 * N * inv_Ny2 - r * x * inv_Ny * p.inv_beta_f);
  t.f_Ny = -2.0 * moment_term * inv_NyM * sigma - 2.0 * h * N * N * inv_Ny2 * inv_Ny +
           h * r * x * N * inv_Ny2 * p.inv_beta_f;
  const double s = x + (0.5 - p.alpha_g);
  const double P = N * N - Ny * Ny;
  const double T = P * s * inv_Ny * p.inv_beta_g;
  const double B = 2.0 * N - T;
  const double dh_dN = -h * x * inv_Ny * p.inv_beta_f;            // dx/dN = 1/(2 N_y)
  const double dh_dNy = 2.0 * h * x * x * inv_Ny * p.inv_beta_f;  // dx/dN_y = -x/N_y
  const double dB_dN = 2.0 - (2.0 * N * s + 0.5 * P * inv_Ny) * inv_Ny * p.inv_beta_g;
  const double dT_dNy = (-2.0 * Ny * s - P * x * inv_Ny) * inv_Ny * p.inv_beta_g - T * inv_Ny;
  t.G_N = p.m_g * (dh_dN * B + h * dB_dN);
  t.G_Ny = p.m_g * (dh_dNy * B - h * dT_dNy);
  return t;
}

}  // namespace

bool closest_point_return(const SurfaceParameters& p, const ElasticStiffness& k, const ReturnSettings& settings,
                          const PlasticState& start, const std::array<double, 3>& dq, PlasticState& end,
                          int* iterations, bool use_hint) {
  const double N_trial = start.y[0] + k.axial * dq[0];
  const double M1_trial = start.y[1] + k.moment * dq[1];
  const double M2_trial = start.y[2] + k.moment * dq[2];
  const double m_trial = std::sqrt(M1_trial * M1_trial + M2_trial * M2_trial);
  const double c = p.rotation_flow_scale * 2.0 / (p.D * p.D);  // moment flow per unit M and multiplier
  const double z_start = p.k_F * start.y[6] + p.k_M * start.y[7];

  // Unknowns (N, z, dlambda), started at the elastic trial (dlambda = 0). N_y(z) = N_ult -
  // (N_ult - N_y,n) e^-(z - z_n), so dN_y/dz = N_ult - N_y (0 once saturated, as hardening()).
  double N = N_trial, z = z_start, lambda = 0.0;
  double Ny = start.Ny;
  // h = exp(h_exponent), carried from the last return (any pair with h = exp(exponent) is a
  // valid start, whatever changed N since: only the difference of exponents is used).
  double h = start.h_cache, h_exponent = start.h_exponent;
  double residual = 0.0, previous_residual = 0.0, f_trial_value = 0.0;
  bool converged = false, elastic = false;
  const double inv_z_scale = 1.0 / std::max(1.0, z_start);  // R2 relative to z (z >= z_n >= 0)
  // A hint from a return on the other side of N = 0 (the flow's kink) is not used.
  const bool warm_start = use_hint && start.return_hint[0] > 0.0 && (N_trial < 0.0) == (start.y[0] < 0.0) &&
                          std::isfinite(start.return_hint[0] + start.return_hint[1] + start.return_hint[2]);
  int newton_steps = 0;  // Newton steps since the last start (trial or warm start)
  int iteration = 0;

  // The trial: only f is needed to tell an elastic increment and to scale the warm start.
  {
    const double inv_Ny = 1.0 / Ny;
    if (N_trial >= 0.0) {
      const double x = 0.5 * N_trial * inv_Ny;
      const double exponent = -x * x * p.inv_beta_f;
      h = times_exp(h, exponent - h_exponent);
      h_exponent = exponent;
    }
    const double inv_NyM = p.moment_split ? 1.0 / moment_yield(p, Ny) : inv_Ny;
    const double moment_term = m_trial * m_trial * inv_NyM * inv_NyM * p.inv_D2_mf;
    f_trial_value = N_trial < 0.0 ? N_trial * N_trial * p.inv_Nc2 + moment_term - 1.0
                                  : moment_term + h * (N_trial * N_trial * inv_Ny * inv_Ny - 1.0);
  }
  if (f_trial_value <= 0.0) {
    elastic = true;  // the trial is inside or on the surface: dlambda = 0
  } else if (warm_start) {
    // Warm start: the last return's solution scaled by this trial's f (first order in the
    // change between consecutive increments); Newton goes on from there.
    lambda = f_trial_value * start.return_hint[0];
    N = N_trial - f_trial_value * start.return_hint[1];
    z = z_start + f_trial_value * start.return_hint[2];
    Ny = p.Nult - times_exp(p.Nult - Ny, -(z - z_start));
  }
  for (; !elastic && iteration <= settings.max_iterations; ++iteration) {
    const double dNy_dz = p.Nult - Ny;
    const double inv_Ny = 1.0 / Ny;
    const double inv_stretch = 1.0 / (1.0 + k.moment * c * lambda);  // M = M_trial / stretch
    const double m = m_trial * inv_stretch;
    const double dm_dlambda = -k.moment * c * m * inv_stretch;
    if (N >= 0.0) {
      const double x = 0.5 * N * inv_Ny;
      const double exponent = -x * x * p.inv_beta_f;
      h = times_exp(h, exponent - h_exponent);
      h_exponent = exponent;
    }
    const ResidualTerms rt = residual_terms(p, N, m, Ny, inv_Ny, h);
    const double sign_G = rt.G < 0.0 ? -1.0 : 1.0;
    const double hardening_rate = p.k_F * sign_G * rt.G + p.k_M * c * m;  // dz/dlambda
    const double R1 = N - N_trial + k.axial * lambda * rt.G;
    const double R2 = z - z_start - lambda * hardening_rate;
    const double R3 = rt.f;
    previous_residual = residual;
    residual = std::max({std::abs(R3), std::abs(R1) * inv_Ny, std::abs(R2) * inv_z_scale});
    if (residual <= settings.residual_tolerance) {
      converged = true;
      break;
    }
    if (iteration == settings.max_iterations) break;
    const DerivativeTerms t = derivative_terms(p, N, m, Ny, inv_Ny, h);
    // Jacobian d(R1, R2, R3) / d(N, z, dlambda); Cramer's rule keeps dN exactly 0 when row 1 is
    // (a, 0, 0) with R1 = 0 (pure bending at N = 0 with alpha_g = 1/2 stays at N = 0).
    const double J11 = 1.0 + k.axial * lambda * t.G_N;
    const double J12 = k.axial * lambda * t.G_Ny * dNy_dz;
    const double J13 = k.axial * rt.G;
    const double J21 = -lambda * p.k_F * sign_G * t.G_N;
    const double J22 = 1.0 - lambda * p.k_F * sign_G * t.G_Ny * dNy_dz;
    const double J23 = -hardening_rate - lambda * p.k_M * c * dm_dlambda;
    const double J31 = t.f_N;
    const double J32 = t.f_Ny * dNy_dz;
    const double J33 = t.f_m * dm_dlambda;
    double dN, dz, dlambda;
    if (!solve_newton_step({{{J11, J12, J13}, {J21, J22, J23}, {J31, J32, J33}}}, {R1, R2, R3}, dN, dz, dlambda)) break;
    // The flow has a kink at N = 0 (slope ~m_g (2 + 1/(2 beta_g)) in tension, 2 N_y^2 m_f / Nc^2
    // in compression): a step across it is shortened to end at N = 0, the next one starts from
    // the tangent of the other side.
    if (N != 0.0 && (N + dN < 0.0) != (N < 0.0)) {
      const double shorten = -N / dN;
      dz *= shorten;
      dlambda *= shorten;
      dN = -N;
    }
    // The predicted next residual of a quadratically converging iteration is C residual^2 with
    // C = residual / previous^2: when it is below the tolerance the step is taken and accepted.
    // (The residual at a warm start is no Newton predecessor: no prediction from it.)
    ++newton_steps;
    const bool last = newton_steps > (warm_start ? 1 : 0) && residual < previous_residual &&
                      residual * residual * residual <= settings.residual_tolerance * previous_residual * previous_residual;
    N += dN;
    z += dz;
    lambda += dlambda;
    Ny = p.Nult - times_exp(dNy_dz, -dz);
    if (!std::isfinite(N + z + lambda + Ny)) break;
    if (last) {
      converged = true;
      ++iteration;
      break;
    }
  }
  if (iterations != nullptr) *iterations = iteration;
  if (elastic) {
    end = start;
    end.h_cache = h;
    end.h_exponent = h_exponent;
    end.y[0] = N_trial;
    end.y[1] = M1_trial;
    end.y[2] = M2_trial;
    end.f = f_trial_value;
    end.f_known = true;
    return true;
  }
  if (!converged || lambda < 0.0) return false;

  const double stretch = 1.0 + k.moment * c * lambda;
  const double M1 = M1_trial / stretch, M2 = M2_trial / stretch;
  // Plastic parts as the elastic complements: Q_1 - Q_0 = K (dq - dq_p) to round-off.
  const double dup = (N_trial - N) / k.axial;
  const double dw1 = (M1_trial - M1) / k.moment;
  const double dw2 = (M2_trial - M2) / k.moment;
  end = start;
  end.y[0] = N;
  end.y[1] = M1;
  end.y[2] = M2;
  end.y[3] += dup;
  end.y[4] += dw1;
  end.y[5] += dw2;
  end.y[6] += std::abs(dup);
  end.y[7] += std::sqrt(dw1 * dw1 + dw2 * dw2);
  end.Ny = Ny;  // N_y(z) of the accepted iterate (z = k_F a_u + k_M a_w to the tolerance)
  // On the surface to the tolerance (|f| <= residual_tolerance, measured or predicted): recorded
  // as 0, which is all the next increment's on-surface test (|f| < 1e-9) needs.
  end.f = 0.0;
  end.f_known = true;
  end.h_cache = h;
  end.h_exponent = h_exponent;
  const double inv_f_trial = 1.0 / f_trial_value;
  end.return_hint = {lambda * inv_f_trial, (N_trial - N) * inv_f_trial, (z - z_start) * inv_f_trial};
  return true;
}

// With the bending-axial coupling (macroelement_coupled.hpp): the surface acts on the end moment
// M = M_s + 2 c N w_end, the flow moves w_p by dlambda c_f M, so M_s = A - k_m c_f dlambda M with
// A = M_s,n + k_m dw, i.e. M = (A + N B) / (1 + k_m c_f dlambda), B = 2 c w_end: the unknowns stay
// (N, z, dlambda), with m = |M| depending on N too. Newton from the elastic trial.
bool coupled_return(const SurfaceParameters& p, const ElasticStiffness& k, const ReturnSettings& settings,
                    double c, const std::array<double, 2>& w_end, const PlasticState& start,
                    const std::array<double, 3>& dq, PlasticState& end, int* iterations) {
  const double N_trial = start.y[0] + k.axial * dq[0];
  const double A1 = start.y[1] + k.moment * dq[1], A2 = start.y[2] + k.moment * dq[2];
  const double B1 = 2.0 * c * w_end[0], B2 = 2.0 * c * w_end[1];
  const double cf = p.rotation_flow_scale * 2.0 / (p.D * p.D);
  const double z_start = p.k_F * start.y[6] + p.k_M * start.y[7];
  const double inv_z_scale = 1.0 / std::max(1.0, z_start);
  if (iterations != nullptr) *iterations = 0;
  {
    const double M1 = A1 + N_trial * B1, M2 = A2 + N_trial * B2;
    const double f_trial = yield_function(p, N_trial, M1 * M1 + M2 * M2, start.Ny);
    if (f_trial <= 0.0) {
      end = start;
      end.y[0] = N_trial;
      end.y[1] = A1;
      end.y[2] = A2;
      end.f_known = false;
      return true;
    }
  }
  double N = N_trial, z = z_start, lambda = 0.0, Ny = start.Ny;
  bool converged = false;
  const int max_iterations = 2 * settings.max_iterations;
  int iteration = 0;
  for (; iteration <= max_iterations; ++iteration) {
    const double stretch = 1.0 + k.moment * cf * lambda;
    const double P1 = A1 + N * B1, P2 = A2 + N * B2;  // M * stretch
    const double m = std::sqrt(P1 * P1 + P2 * P2) / stretch;
    const double dm_dN = m > 0.0 ? (P1 * B1 + P2 * B2) / (m * stretch * stretch) : 0.0;
    const double dm_dlambda = -k.moment * cf * m / stretch;
    const double inv_Ny = 1.0 / Ny;
    double h = 1.0;
    if (N >= 0.0) {
      const double x = 0.5 * N * inv_Ny;
      h = std::exp(-x * x * p.inv_beta_f);
    }
    const ResidualTerms rt = residual_terms(p, N, m, Ny, inv_Ny, h);
    const double sign_G = rt.G < 0.0 ? -1.0 : 1.0;
    const double rate = p.k_F * sign_G * rt.G + p.k_M * cf * m;
    const double R1 = N - N_trial + k.axial * lambda * rt.G;
    const double R2 = z - z_start - lambda * rate;
    const double R3 = rt.f;
    const double residual = std::max({std::abs(R3), std::abs(R1) * inv_Ny, std::abs(R2) * inv_z_scale});
    if (residual <= settings.residual_tolerance) {
      converged = true;
      break;
    }
    if (iteration == max_iterations) break;
    const DerivativeTerms t = derivative_terms(p, N, m, Ny, inv_Ny, h);
    const double dNy_dz = p.Nult - Ny;
    const double J11 = 1.0 + k.axial * lambda * t.G_N;
    const double J12 = k.axial * lambda * t.G_Ny * dNy_dz;
    const double J13 = k.axial * rt.G;
    const double J21 = -lambda * (p.k_F * sign_G * t.G_N + p.k_M * cf * dm_dN);
    const double J22 = 1.0 - lambda * p.k_F * sign_G * t.G_Ny * dNy_dz;
    const double J23 = -rate - lambda * p.k_M * cf * dm_dlambda;
    const double J31 = t.f_N + t.f_m * dm_dN;
    const double J32 = t.f_Ny * dNy_dz;
    const double J33 = t.f_m * dm_dlambda;
    double dN, dz, dlambda;
    if (!solve_newton_step({{{J11, J12, J13}, {J21, J22, J23}, {J31, J32, J33}}}, {R1, R2, R3}, dN, dz, dlambda)) break;
    if (N != 0.0 && (N + dN < 0.0) != (N < 0.0)) {  // the flow's kink at N = 0
      const double shorten = -N / dN;
      dz *= shorten;
      dlambda *= shorten;
      dN = -N;
    }
    N += dN;
    z += dz;
    lambda += dlambda;
    Ny = p.Nult - dNy_dz * std::exp(-dz);
    if (!std::isfinite(N + z + lambda + Ny)) break;
  }
  if (iterations != nullptr) *iterations = iteration;
  if (!converged || lambda < 0.0) return false;
  const double stretch = 1.0 + k.moment * cf * lambda;
  const double M1 = (A1 + N * B1) / stretch, M2 = (A2 + N * B2) / stretch;
  const double Ms1 = M1 - N * B1, Ms2 = M2 - N * B2;
  // Plastic parts as the elastic complements (Q_1 - Q_0 = K (dq - dq_p) in (N, M_s)).
  const double dup = (N_trial - N) / k.axial;
  const double dw1 = (A1 - Ms1) / k.moment, dw2 = (A2 - Ms2) / k.moment;
  end = start;
  end.y[0] = N;
  end.y[1] = Ms1;
  end.y[2] = Ms2;
  end.y[3] += dup;
  end.y[4] += dw1;
  end.y[5] += dw2;
  end.y[6] += std::abs(dup);
  end.y[7] += std::sqrt(dw1 * dw1 + dw2 * dw2);
  end.Ny = Ny;
  end.f_known = false;
  return true;
}

}  // namespace dtwire::dem::detail
