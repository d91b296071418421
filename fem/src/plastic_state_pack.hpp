#pragma once
// A PlasticState as 16 doubles (plastic metric 6, equivalent plastic strain, dissipation,
// damage, backstress 6, softening), for checkpoints and the as-made state file; doubles kept exactly.
#include <vector>

#include "j2_log_plasticity.hpp"

namespace dtwire::fem {

constexpr unsigned kPackedPlasticStateSize = 16;

inline void pack_plastic_state(const PlasticState& s, std::vector<double>& out) {
  for (unsigned k = 0; k < 6; ++k) out.push_back(s.plastic_metric_inverse.access_raw_entry(k));
  out.insert(out.end(), {s.equivalent_plastic_strain, s.plastic_dissipation, s.damage});
  for (unsigned k = 0; k < 6; ++k) out.push_back(s.backstress.access_raw_entry(k));
  out.push_back(s.softening);
}

// Reads kPackedPlasticStateSize values from `in`, which it advances.
inline PlasticState unpack_plastic_state(const double*& in) {
  PlasticState s;
  for (unsigned k = 0; k < 6; ++k) s.plastic_metric_inverse.access_raw_entry(k) = *in++;
  s.equivalent_plastic_strain = *in++;
  s.plastic_dissipation = *in++;
  s.damage = *in++;
  for (unsigned k = 0; k < 6; ++k) s.backstress.access_raw_entry(k) = *in++;
  s.softening = *in++;
  return s;
}

}  // namespace dtwire::fem
