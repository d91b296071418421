#pragma once
// macro3d's N-dependent bending stiffness (bending_axial_coupling; equations in docs/dem_laws.md).
// Free energy, with u the chord elongation, w the total bending rotation (w_1, w_2) and u_p, w_p
// the plastic displacements:
//
//   psi = 1/2 k_a s_e^2 + 1/2 k_m |w - w_p|^2,   s_e = u - u_p + c |w|^2   (c = kappa L / 24)
//   N = k_a s_e,   M = M_s + 2 c N w,   M_s = k_m (w - w_p),
//
// so elastically M = (k_m + 2 c N) w: the first-order beam column (k_m (1 + N L^2 / (12 EI)) for
// k_m = EI/L, kappa = 1). The law works in the conjugate pair (s, w), s = u + c |w|^2, where the
// elasticity is linear and uncoupled (external work N du + M.dw = N ds + M_s.dw); the state
// y = (N, M_s1, M_s2, u_p, w_p1, w_p2, a_u, a_w) is the uncoupled law's with M_s for M. The yield
// surface, flow and hardening act on the END moment M = M_s + 2 c N w (the section capacity bounds
// the moment at the bond's ends, P-delta included); the plastic rotation follows the flow in M.
//
// This file holds integrate_increment (macroelement_integrator.hpp) for that case: the same
// crossing, backward-Euler return (coupled_return, macroelement_return.cpp) with halvings and
// RK2(3) fallback with drift correction, with the surface evaluated at M.
#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include "dtwire/dem/detail/macroelement_integrator.hpp"

namespace dtwire::dem::detail {

// The coupling within one increment: total rotation w(t) = w0 + t dw over t in [0, 1].
struct CouplingPath {
  double c = 0.0;                 // [m/rad^2]
  std::array<double, 2> w0{};     // total rotation at the start of the increment [rad]
  std::array<double, 2> dw{};     // its increment [rad]
  std::array<double, 2> at(double t) const { return {w0[0] + t * dw[0], w0[1] + t * dw[1]}; }
};

// End moment M = M_s + 2 c N w of the state y at total rotation w.
inline std::array<double, 2> end_moment(double c, const std::array<double, 8>& y, const std::array<double, 2>& w) {
  return {y[1] + 2.0 * c * y[0] * w[0], y[2] + 2.0 * c * y[0] * w[1]};
}

inline double coupled_yield(const SurfaceParameters& p, double c, const std::array<double, 8>& y,
                            const std::array<double, 2>& w, double Ny) {
  const auto M = end_moment(c, y, w);
  return yield_function(p, y[0], M[0] * M[0] + M[1] * M[1], Ny);
}

// Backward-Euler return of a plastic piece dq = (ds, dw_1, dw_2) (the stretch increment ds =
// du + c d|w|^2) ending at total rotation w_end; the unknowns (N, z, dlambda) as in
// closest_point_return, with M = (M_s,trial + 2 c N w_end) / (1 + k_m c_f dlambda).
bool coupled_return(const SurfaceParameters& p, const ElasticStiffness& k, const ReturnSettings& settings,
                    double c, const std::array<double, 2>& w_end, const PlasticState& start,
                    const std::array<double, 3>& dq, PlasticState& end, int* iterations = nullptr);

namespace coupled_impl {

// Rates over the pseudo-time of the plastic part: lambda = (a'.K dq + 2 c N a_M.dw) / (a'.K b + H)
// with a' = (a_N + 2 c a_M.w, a_M) the gradient with respect to (N, M_s).
inline std::array<double, 8> rates(const SurfaceParameters& p, const ElasticStiffness& k, double c,
                                   const std::array<double, 8>& y, const std::array<double, 2>& w,
                                   const std::array<double, 3>& dq, double* loading = nullptr) {
  const Hardening hard = hardening(p, y[6], y[7]);
  const auto M = end_moment(c, y, w);
  const double M2 = M[0] * M[0] + M[1] * M[1];
  const SurfaceGradients g = surface_gradients(p, y[0], M2, hard.Ny);
  const double aM_w = g.df_dM * (M[0] * w[0] + M[1] * w[1]);
  const double aM_dw = g.df_dM * (M[0] * dq[1] + M[1] * dq[2]);
  const double a_N = g.df_dF + 2.0 * c * aM_w;
  const double flow_M_norm = std::abs(g.flow_M) * std::sqrt(M2);
  const double H = -g.df_dNy * (hard.dNy_dau * std::abs(g.flow_F) + hard.dNy_daw * flow_M_norm);
  const double numerator = a_N * k.axial * dq[0] + (k.moment + 2.0 * c * y[0]) * aM_dw;
  const double denominator = a_N * k.axial * g.flow_F + g.df_dM * k.moment * g.flow_M * M2 + H;
  if (loading != nullptr) *loading = numerator;
  const double lambda = denominator != 0.0 ? std::max(numerator / denominator, 0.0) : 0.0;
  std::array<double, 8> rate{};
  rate[3] = lambda * g.flow_F;
  rate[4] = lambda * g.flow_M * M[0];
  rate[5] = lambda * g.flow_M * M[1];
  rate[0] = k.axial * (dq[0] - rate[3]);
  rate[1] = k.moment * (dq[1] - rate[4]);
  rate[2] = k.moment * (dq[2] - rate[5]);
  rate[6] = std::abs(rate[3]);
  rate[7] = lambda * flow_M_norm;
  return rate;
}

// Consistent drift correction at fixed total displacement (rotation w).
inline void correct_drift(const SurfaceParameters& p, const ElasticStiffness& k, double c,
                          const std::array<double, 2>& w, PlasticState& s) {
  constexpr double accepted_drift = 1e-10;
  const double f_original = coupled_yield(p, c, s.y, w, s.Ny);
  if (f_original <= accepted_drift) return;
  const PlasticState original = s;
  double f = f_original;
  for (int iteration = 0; iteration < 8 && f > 1e-13; ++iteration) {
    const Hardening hard = hardening(p, s.y[6], s.y[7]);
    const auto M = end_moment(c, s.y, w);
    const double M2 = M[0] * M[0] + M[1] * M[1];
    const SurfaceGradients g = surface_gradients(p, s.y[0], M2, hard.Ny);
    const double a_N = g.df_dF + 2.0 * c * g.df_dM * (M[0] * w[0] + M[1] * w[1]);
    const double flow_M_norm = std::abs(g.flow_M) * std::sqrt(M2);
    const double H = -g.df_dNy * (hard.dNy_dau * std::abs(g.flow_F) + hard.dNy_daw * flow_M_norm);
    const double denominator = a_N * k.axial * g.flow_F + g.df_dM * k.moment * g.flow_M * M2 + H;
    if (denominator <= 0.0) break;
    const double dl = g.f / denominator;
    const double dup = dl * g.flow_F, dw1 = dl * g.flow_M * M[0], dw2 = dl * g.flow_M * M[1];
    s.y[0] -= k.axial * dup;
    s.y[1] -= k.moment * dw1;
    s.y[2] -= k.moment * dw2;
    s.y[3] += dup;
    s.y[4] += dw1;
    s.y[5] += dw2;
    s.y[6] += std::abs(dup);
    s.y[7] += dl * flow_M_norm;
    s.Ny = hardening(p, s.y[6], s.y[7]).Ny;
    f = coupled_yield(p, c, s.y, w, s.Ny);
  }
  if (f > f_original) s = original;
}

}  // namespace coupled_impl

// integrate_increment with the coupling: dq = (ds, dw_1, dw_2), ds = du + c d|w|^2; `path` gives
// the total rotation along the increment. Same callback contract. The state's f cache is not
// used (it would hold f at M_s).
template <class OnSubstep>
int integrate_increment_coupled(const SurfaceParameters& p, const ElasticStiffness& k,
                                const IntegratorSettings& settings, const CouplingPath& path,
                                PlasticState& state, const std::array<double, 3>& dq, OnSubstep&& on_substep) {
  using namespace integrator_impl;
  const double c = path.c;
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
    const std::array<double, 8> y = elastic_at(t).y;
    return coupled_yield(p, c, y, path.at(t), state.Ny);
  };
  auto elastic_step = [&] {
    const PlasticState before = state;
    state = elastic_at(1.0);
    on_substep(before, state, 0.0, 1.0);
    return 0;
  };
  const double f1 = phi(1.0);
  constexpr double on_surface = 1e-9;
  const double f_start = coupled_yield(p, c, state.y, path.w0, state.Ny);
  if (f1 <= 0.0 && f_start < -on_surface) return elastic_step();

  double t_plastic = 0.0;
  std::array<double, 8> first_rates{};
  bool first_rates_known = false;
  if (f_start < -on_surface) {
    t_plastic = find_crossing(phi, 0.0, f_start, 1.0, f1);
  } else if (!settings.implicit_return) {
    double loading = 0.0;
    first_rates = coupled_impl::rates(p, k, c, state.y, path.w0, dq, &loading);
    first_rates_known = loading > 0.0;
    if (!first_rates_known) {
      if (f1 <= 0.0) return elastic_step();
      double t_inside = -1.0;
      for (int i = 1; i < 64 && t_inside < 0.0; ++i)
        if (phi(i / 64.0) < 0.0) t_inside = i / 64.0;
      if (t_inside > 0.0) t_plastic = find_crossing(phi, t_inside, phi(t_inside), 1.0, f1);
    }
  } else if (f1 <= 0.0) {
    return elastic_step();
  }
  if (t_plastic > 0.0) {
    const PlasticState before = state;
    state = elastic_at(t_plastic);
    if (!on_substep(before, state, 0.0, t_plastic)) return 0;
  }
  const std::array<double, 3> rest{dq[0] * (1.0 - t_plastic), dq[1] * (1.0 - t_plastic), dq[2] * (1.0 - t_plastic)};
  auto rotation_at = [&](double T) { return path.at(t_plastic + (1.0 - t_plastic) * T); };
  double T = 0.0;
  int substeps = 0;
  if (settings.implicit_return) {
    double piece_size = 1.0;
    int halvings = 0;
    while (T < 1.0) {
      const double T1 = std::min(1.0, T + piece_size);
      const std::array<double, 3> piece{rest[0] * (T1 - T), rest[1] * (T1 - T), rest[2] * (T1 - T)};
      const PlasticState before = state;
      if (coupled_return(p, k, settings.return_settings, c, rotation_at(T1), before, piece, state)) {
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
    if (!first_rates_known) first_rates = coupled_impl::rates(p, k, c, y, rotation_at(T), rest);
    first_rates_known = true;
    const auto& k1 = first_rates;
    const auto k2 = coupled_impl::rates(p, k, c, combine(y, 0.5 * dT, k1), rotation_at(T + 0.5 * dT), rest);
    const auto k3 = coupled_impl::rates(p, k, c, combine(y, -dT, k1, 2.0 * dT, k2), rotation_at(T + dT), rest);
    const auto second = combine(y, dT, k2);
    const auto third = combine(y, dT / 6.0, k1, dT * 2.0 / 3.0, k2, dT / 6.0, k3);
    const auto [residual, next, Ny_third] = substep_error(p, second, third, dT, settings);
    if (residual < settings.tolerance) {
      const PlasticState before = state;
      state.y = third;
      state.Ny = Ny_third;
      state.f_known = false;
      const double T_end = std::min(1.0, T + dT);
      if (settings.drift_correction) coupled_impl::correct_drift(p, k, c, rotation_at(T_end), state);
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
