#pragma once
// Integration of one generalised-displacement increment of the macro-element: elastic trial,
// elastic-plastic crossing, then explicit embedded Runge-Kutta 2(3) substepping as in the
// published implementation (Kutta's third-order scheme with the midpoint rule as the embedded
// second order; relative error tolerance, step factor 0.9 (tol/R)^(1/3) bounded to [1/4, 4]; the
// third-order solution is kept; Sloan 1987), optionally followed after every substep by a
// consistent drift correction back to the yield surface (Sloan, Abbo & Sheng 2001).
//
// With `implicit_return` the plastic part is instead one backward-Euler closest-point return
// (macroelement_return.hpp), halved up to three times when Newton does not converge, and the
// RK2(3) substepping above integrates whatever is left after that.
//
// The state carries the surface forces (N, M_1, M_2), the signed plastic displacements
// (u_p, w_p1, w_p2) and the hardening variables a_u = sum |du_p|, a_w = sum |dw_p|.
#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include "dtwire/dem/detail/macroelement_return.hpp"
#include "dtwire/dem/detail/macroelement_surface.hpp"

namespace dtwire::dem::detail {

struct PlasticState {
  // y = (N, M_1, M_2, u_p, w_p1, w_p2, a_u, a_w)
  std::array<double, 8> y{};
  double Ny = 0.0;         // yield strength of the current hardening state (cache)
  double f = -1.0;         // normalised yield function of this state, when f_known
  bool f_known = false;
  // Implicit return only: (dlambda, N_trial - N, z - z_n) of the last plastic return per unit of
  // its trial f, the warm start of the next return (consecutive DEM increments are alike).
  std::array<double, 3> return_hint{};
  // Implicit return only: h = exp(h_exponent) of the tension surface at its last evaluation, from
  // which the next return updates h by exp(difference) (a short series, not a libm call).
  double h_cache = 1.0, h_exponent = 0.0;
};

struct IntegratorSettings {
  double tolerance = 1e-6;      // relative error tolerance of the RK2(3) pair
  bool drift_correction = false;
  // Weight of the moments against the axial force in the error norm. The published norm adds
  // newtons and newton-metres (weight 1): near N = 0 it asks for micro-newton accuracy of N and
  // needs ~100 substeps. 1 / (D sqrt(m_f)) (= N_y / M_Y) measures both on the surface's scale.
  double moment_error_weight = 1.0;
  int max_substeps = 100000;
  // Backward-Euler closest-point return instead of the RK2(3) substepping (first order in the
  // increment, unconditionally stable); RK2(3) remains the fallback.
  bool implicit_return = false;
  ReturnSettings return_settings;
  int max_return_halvings = 3;  // pieces of 1/2, 1/4, 1/8 of the plastic part before the fallback
};

struct ElasticStiffness {
  double axial;   // [N/m]
  double moment;  // [N m / angle unit]
};

namespace integrator_impl {

inline double moment_squared(const std::array<double, 8>& y) { return y[1] * y[1] + y[2] * y[2]; }

// Rates d y / d T over the pseudo-time T in [0, 1] of a plastic increment (du, dw1, dw2):
// consistency gives the multiplier lambda = a.K.dq / (a.K.b + H), H the hardening modulus.
// `loading` (optional) receives a.K.dq, positive when the increment loads the surface.
inline std::array<double, 8> plastic_rates(const SurfaceParameters& p, const ElasticStiffness& k,
                                           const std::array<double, 8>& y,
                                           const std::array<double, 3>& dq, double* loading = nullptr) {
  const Hardening hard = hardening(p, y[6], y[7]);
  const double M2 = moment_squared(y);
  const SurfaceGradients g = surface_gradients(p, y[0], M2, hard.Ny);
  const double flow_M_norm = std::abs(g.flow_M) * std::sqrt(M2);
  const double H = -g.df_dNy * (hard.dNy_dau * std::abs(g.flow_F) + hard.dNy_daw * flow_M_norm);
  const double numerator = g.df_dF * k.axial * dq[0] + g.df_dM * k.moment * (y[1] * dq[1] + y[2] * dq[2]);
  const double denominator = g.df_dF * k.axial * g.flow_F + g.df_dM * k.moment * g.flow_M * M2 + H;
  if (loading != nullptr) *loading = numerator;
  const double lambda = denominator != 0.0 ? std::max(numerator / denominator, 0.0) : 0.0;
  std::array<double, 8> rate{};
  rate[3] = lambda * g.flow_F;
  rate[4] = lambda * g.flow_M * y[1];
  rate[5] = lambda * g.flow_M * y[2];
  rate[0] = k.axial * (dq[0] - rate[3]);
  rate[1] = k.moment * (dq[1] - rate[4]);
  rate[2] = k.moment * (dq[2] - rate[5]);
  rate[6] = std::abs(rate[3]);
  rate[7] = lambda * flow_M_norm;
  return rate;
}

inline std::array<double, 8> combine(const std::array<double, 8>& y, double a,
                                     const std::array<double, 8>& ra, double b = 0.0,
                                     const std::array<double, 8>& rb = {}, double c = 0.0,
                                     const std::array<double, 8>& rc = {}) {
  std::array<double, 8> out;
  for (int i = 0; i < 8; ++i) out[i] = y[i] + a * ra[i] + b * rb[i] + c * rc[i];
  return out;
}

// Pegasus regula falsi for the root of phi on [lo, hi] with phi(lo) < 0 < phi(hi).
template <class Phi>
double find_crossing(const Phi& phi, double lo, double phi_lo, double hi, double phi_hi) {
  for (int iteration = 0; iteration < 200; ++iteration) {
    const double mid = hi - phi_hi * (hi - lo) / (phi_hi - phi_lo);
    const double phi_mid = phi(mid);
    if (std::abs(phi_mid) < 1e-14 || hi - lo < 1e-16) return mid;
    if (phi_mid > 0.0) {
      hi = mid;
      phi_hi = phi_mid;
      phi_lo *= 0.5;  // Pegasus-style weight keeps both ends moving
    } else {
      lo = mid;
      phi_lo = phi_mid;
      phi_hi *= 0.5;
    }
  }
  return lo;
}

// The local error of the RK2(3) pair over a substep dT: the forces' difference on the surface's
// scale (the moments weighted by `moment_error_weight`) and N_y's relative difference, N_y of the
// second-order solution linearised about the third's (their hardening variables differ by the
// local error only); and the next substep, 0.9 dT (tol/R)^(1/3) at most 4 dT (Sloan 1987).
struct SubstepError {
  double residual;
  double next_step;
  double Ny_third;  // N_y of the kept, third-order solution
};

inline SubstepError substep_error(const SurfaceParameters& p, const std::array<double, 8>& second,
                                  const std::array<double, 8>& third, double dT, const IntegratorSettings& settings) {
  const double tiny = 1e-13;
  const double w = settings.moment_error_weight;
  const double sigma_norm =
      std::max(std::sqrt(third[0] * third[0] + w * w * (third[1] * third[1] + third[2] * third[2])), tiny);
  const Hardening hard_third = hardening(p, third[6], third[7]);
  const double Ny_third = hard_third.Ny;
  const double Ny_second = Ny_third + hard_third.dNy_dau * (second[6] - third[6]) +
                           hard_third.dNy_daw * (second[7] - third[7]);
  const double e0 = (third[0] - second[0]) / sigma_norm;
  const double e1 = w * (third[1] - second[1]) / sigma_norm;
  const double e2 = w * (third[2] - second[2]) / sigma_norm;
  const double e3 = (Ny_third - Ny_second) / std::max(std::abs(Ny_third), tiny);
  const double residual = std::max(std::sqrt(e0 * e0 + e1 * e1 + e2 * e2 + e3 * e3), tiny);
  // 0.9 (tol/R)^(1/3) >= 4 when R <= tol / 87.8: the growth bound applies, no cube root needed.
  const double next = residual * 87.8 <= settings.tolerance ? 4.0 * dT
                                                            : 0.9 * dT * std::cbrt(settings.tolerance / residual);
  return {residual, next, Ny_third};
}

}  // namespace integrator_impl

// Moves a state that drifted outside back onto f = 0 at fixed total displacement: the correction
// is plastic, along K b, with the hardening it implies (consistent correction, Sloan, Abbo &
// Sheng 2001). States inside are left alone: pulling them outward would harden the surface
// against the correction. `s.Ny` must be current. Drift below 1e-10 is left (the guarantee is
// f <= 1e-8 after every step), which spares most corrections.
inline void correct_drift(const SurfaceParameters& p, const ElasticStiffness& k, PlasticState& s) {
  constexpr double accepted_drift = 1e-10;
  const double f_original = yield_function(p, s.y[0], integrator_impl::moment_squared(s.y), s.Ny);
  s.f = f_original;
  s.f_known = true;
  if (f_original <= accepted_drift) return;
  const PlasticState original = s;
  double f = f_original;
  for (int iteration = 0; iteration < 8 && f > 1e-13; ++iteration) {
    const Hardening hard = hardening(p, s.y[6], s.y[7]);
    const double M2 = integrator_impl::moment_squared(s.y);
    const SurfaceGradients g = surface_gradients(p, s.y[0], M2, hard.Ny);
    const double flow_M_norm = std::abs(g.flow_M) * std::sqrt(M2);
    const double H = -g.df_dNy * (hard.dNy_dau * std::abs(g.flow_F) + hard.dNy_daw * flow_M_norm);
    const double denominator = g.df_dF * k.axial * g.flow_F + g.df_dM * k.moment * g.flow_M * M2 + H;
    if (denominator <= 0.0) break;
    const double dl = g.f / denominator;
    const double dup = dl * g.flow_F;
    const double dw1 = dl * g.flow_M * s.y[1];
    const double dw2 = dl * g.flow_M * s.y[2];
    s.y[0] -= k.axial * dup;
    s.y[1] -= k.moment * dw1;
    s.y[2] -= k.moment * dw2;
    s.y[3] += dup;
    s.y[4] += dw1;
    s.y[5] += dw2;
    s.y[6] += std::abs(dup);
    s.y[7] += dl * flow_M_norm;
    s.Ny = hardening(p, s.y[6], s.y[7]).Ny;
    f = yield_function(p, s.y[0], integrator_impl::moment_squared(s.y), s.Ny);
  }
  if (f > f_original) {
    s = original;
  } else {
    s.f = f;
  }
}

inline double yield_value(const SurfaceParameters& p, const PlasticState& s) {
  return yield_function(p, s.y[0], integrator_impl::moment_squared(s.y), s.Ny);
}

// Advances `state` by the increment dq = (du, dw1, dw2). After each accepted piece the callback
// on_substep(before, after, t0, t1) books it (t in [0, 1] is the fraction of the increment);
// returning false stops the increment (the bond broke). Returns the number of RK substeps.
template <class OnSubstep>
int integrate_increment(const SurfaceParameters& p, const ElasticStiffness& k,
                        const IntegratorSettings& settings, PlasticState& state,
                        const std::array<double, 3>& dq, OnSubstep&& on_substep) {
  using namespace integrator_impl;
  const double dN = k.axial * dq[0];
  const double dM1 = k.moment * dq[1];
  const double dM2 = k.moment * dq[2];
  auto elastic_at = [&](double t) {
    PlasticState s = state;
    s.f_known = false;
    s.y[0] += t * dN;
    s.y[1] += t * dM1;
    s.y[2] += t * dM2;
    return s;
  };
  auto phi = [&](double t) {
    const double N = state.y[0] + t * dN, M1 = state.y[1] + t * dM1, M2 = state.y[2] + t * dM2;
    return yield_function(p, N, M1 * M1 + M2 * M2, state.Ny);
  };

  auto elastic_step = [&] {
    const PlasticState before = state;
    state = elastic_at(1.0);
    on_substep(before, state, 0.0, 1.0);
    return 0;
  };
  const double N_trial = state.y[0] + dN, M1_trial = state.y[1] + dM1, M2_trial = state.y[2] + dM2;
  const double M2_sq_trial = M1_trial * M1_trial + M2_trial * M2_trial;
  if (certainly_inside(p, N_trial, M2_sq_trial, state.Ny)) return elastic_step();  // fast path
  auto f_trial = [&] { return yield_function(p, N_trial, M2_sq_trial, state.Ny); };

  // Where along the elastic segment does plastic flow start? States within 1e-9 of the surface
  // (the drift left by the substepping) count as on it; there the sign of a.K.dq decides.
  constexpr double on_surface = 1e-9;
  const double f_start = state.f_known ? state.f : yield_value(p, state);
  double t_plastic = 0.0;
  std::array<double, 8> first_rates{};
  bool first_rates_known = false;
  if (f_start < -on_surface) {
    const double f1 = f_trial();
    if (f1 <= 0.0) return elastic_step();
    t_plastic = find_crossing(phi, 0.0, f_start, 1.0, f1);
  } else if (!settings.implicit_return) {
    double loading = 0.0;
    first_rates = plastic_rates(p, k, state.y, dq, &loading);
    first_rates_known = loading > 0.0;
    if (!first_rates_known) {
      const double f1 = f_trial();
      if (f1 <= 0.0) return elastic_step();
      // Elastic unloading that crosses the elastic domain and reaches the far side of the surface.
      double t_inside = -1.0;
      for (int i = 1; i < 64 && t_inside < 0.0; ++i)
        if (phi(i / 64.0) < 0.0) t_inside = i / 64.0;
      if (t_inside > 0.0) t_plastic = find_crossing(phi, t_inside, phi(t_inside), 1.0, f1);
    }
  }
  if (t_plastic > 0.0) {
    const PlasticState before = state;
    state = elastic_at(t_plastic);
    if (!on_substep(before, state, 0.0, t_plastic)) return 0;
  }

  // Plastic part: RK2(3) with local extrapolation (the third-order solution is kept).
  const std::array<double, 3> rest{dq[0] * (1.0 - t_plastic), dq[1] * (1.0 - t_plastic),
                                   dq[2] * (1.0 - t_plastic)};
  double T = 0.0;
  int substeps = 0;
  if (settings.implicit_return) {
    // One closest-point return over the whole plastic part; pieces of 1/2, 1/4, ... when Newton
    // fails (a piece whose trial stays inside is elastic). What no piece manages goes to RK2(3).
    // From a state on the surface no loading test is made: a trial inside is elastic, one
    // outside is returned (an unloading that reaches the far side of the elastic domain within
    // one increment is returned as a whole, as in implicit finite-element codes).
    double piece_size = 1.0;
    int halvings = 0;
    while (T < 1.0) {
      const double T1 = std::min(1.0, T + piece_size);
      const std::array<double, 3> piece{rest[0] * (T1 - T), rest[1] * (T1 - T), rest[2] * (T1 - T)};
      const PlasticState before = state;
      // A failed warm start is retried from the trial before the piece is halved.
      const bool accepted = closest_point_return(p, k, settings.return_settings, before, piece, state) ||
                            closest_point_return(p, k, settings.return_settings, before, piece, state, nullptr, false);
      if (accepted) {
        ++substeps;
        const double t0 = t_plastic + (1.0 - t_plastic) * T;
        const double t1 = T1 >= 1.0 ? 1.0 : t_plastic + (1.0 - t_plastic) * T1;
        T = T1;
        if (!on_substep(before, state, t0, t1)) return substeps;
      } else if (halvings < settings.max_return_halvings) {
        piece_size *= 0.5;
        ++halvings;
      } else {
        break;
      }
    }
    if (T >= 1.0) return substeps;
    first_rates_known = false;
  }
  double dT = 1.0 - T;
  while (T < 1.0) {
    if (++substeps > settings.max_substeps)
      throw std::runtime_error("macro-element: too many plastic substeps in one increment");
    const auto& y = state.y;
    // The rates at the start of a substep are kept while it is retried (and come from the
    // loading test for the first one).
    if (!first_rates_known) first_rates = plastic_rates(p, k, y, rest);
    first_rates_known = true;
    const auto& k1 = first_rates;
    const auto k2 = plastic_rates(p, k, combine(y, 0.5 * dT, k1), rest);
    const auto k3 = plastic_rates(p, k, combine(y, -dT, k1, 2.0 * dT, k2), rest);
    const auto second = combine(y, dT, k2);
    const auto third = combine(y, dT / 6.0, k1, dT * 2.0 / 3.0, k2, dT / 6.0, k3);
    const auto [residual, next, Ny_third] = substep_error(p, second, third, dT, settings);
    if (residual < settings.tolerance) {
      const PlasticState before = state;
      state.y = third;
      state.Ny = Ny_third;
      state.f_known = false;
      if (settings.drift_correction) correct_drift(p, k, state);
      const double t0 = t_plastic + (1.0 - t_plastic) * T;
      T += dT;
      const double t1 = T >= 1.0 ? 1.0 : t_plastic + (1.0 - t_plastic) * T;
      first_rates_known = false;
      if (!on_substep(before, state, t0, t1)) return substeps;
      dT = std::min({4.0 * dT, next, 1.0 - T});
    } else {
      dT = std::max(0.25 * dT, next);
    }
  }
  return substeps;
}

}  // namespace dtwire::dem::detail
