#pragma once
// Reading the yield/flow surface and the energy damage that the thesis element and macro3d share
// (internal to dem_export). The laws name the hardening rates differently (thesis: k_F, k_M as
// the plugin; macro3d: k_F_per_m, k_M_per_rad), so the caller gives those two names.
#include <stdexcept>
#include <string>

#include "dtwire/dem/detail/macroelement_damage.hpp"
#include "dtwire/dem/detail/macroelement_surface.hpp"
#include "law_parameters.hpp"

namespace dtwire::dem::detail {

inline SurfaceParameters read_surface(const ParameterMap& p, const std::string& law, const std::string& k_F,
                                      const std::string& k_M, double rotation_flow_scale) {
  SurfaceParameters s;
  s.D = positive_parameter(p, law, "D_m");
  s.N0 = positive_parameter(p, law, "N0_N");
  s.Nult = positive_parameter(p, law, "Nult_N");
  s.Nc = positive_parameter(p, law, "Nc_N");
  s.m_f = positive_parameter(p, law, "m_f");
  s.beta_f = positive_parameter(p, law, "beta_f");
  s.k_F = nonnegative_parameter(p, law, k_F);
  s.k_M = nonnegative_parameter(p, law, k_M);
  s.m_g = positive_parameter(p, law, "m_g");
  s.alpha_g = nonnegative_parameter(p, law, "alpha_g");
  s.beta_g = positive_parameter(p, law, "beta_g");
  s.rotation_flow_scale = rotation_flow_scale;
  s.prepare();
  if (s.Nult < s.N0) throw std::invalid_argument(law + ": Nult_N must be >= N0_N");
  return s;
}

// macro3d's optional moment_hardening_ratio r_M (surface.moment_split): the moment capacity
// D sqrt(m_f) N_yM with N_yM = N0 + eta (r_M N0 - N0) = N0 (1 - sigma) + sigma N_y.
inline void read_moment_hardening(const ParameterMap& p, const std::string& law, SurfaceParameters& s) {
  if (!p.count("moment_hardening_ratio")) return;
  const double ratio = checked(law, "moment_hardening_ratio", p.at("moment_hardening_ratio"));
  if (!(ratio >= 1.0)) throw std::invalid_argument(law + ": moment_hardening_ratio must be >= 1");
  const double span = s.Nult - s.N0;
  if (span > 0.0) {
    s.moment_split = true;
    s.moment_sigma = (ratio - 1.0) * s.N0 / span;
    s.moment_offset = s.N0 * (1.0 - s.moment_sigma);
  } else if (ratio != 1.0) {
    throw std::invalid_argument(law + ": moment_hardening_ratio must be 1 when Nult_N = N0_N (no hardening)");
  }
}

inline DamageParameters read_damage(const ParameterMap& p, const std::string& law) {
  DamageParameters d;
  d.W1 = nonnegative_parameter(p, law, "W1_J");
  d.W2 = positive_parameter(p, law, "W2_J");
  d.alpha_d = positive_parameter(p, law, "alpha_d");
  if (d.W2 <= d.W1) throw std::invalid_argument(law + ": W2_J must be > W1_J");
  return d;
}

}  // namespace dtwire::dem::detail
