#include <algorithm>
#include <cmath>

#include "independent_effects.hpp"

namespace dtwire::gap::independent {

// Flow stress scaled by a factor s(u) along the test, elastic slope kept (f' = s f,
// u' = u + (s - 1) f / k0):
// Shape 0, crosshead speed changed mid-test (a rate-jump test, or a machine switching from
// the elastic to the plastic speed of EN ISO 6892-1 method B): s = 1 before the jump at 30-60 %
// of the test, s1 after it, smoothed over 3 % of the test.
// Shape 1, adiabatic heating at a high rate: the rate gain s0 fades as the wire warms,
// s = s0 - (s0 - 1) u / (2 u_end). s0, s1: 1.04-1.15 or 0.88-0.96 (as the fitted family).
ForceCurve strain_rate(const ForceCurve& base, const Setting& s) {
  ForceCurve out = visible(base, s.end_m);
  const double d0 = s.draws.empty() ? 0.5 : s.draws[0];
  const bool above = (s.draws.size() > 1 ? s.draws[1] : 0.5) < 0.5;
  const double factor = 1.0 + (above ? 0.04 + 0.11 * d0 : -(0.04 + 0.08 * d0)) * s.scatter;
  const double jump = (0.3 + 0.3 * (s.draws.size() > 2 ? s.draws[2] : 0.5)) * s.end_m;
  for (std::size_t i = 0; i < out.size(); ++i) {
    const double u = out.u[i];
    const double scale = s.shape == 0
        ? 1.0 + (factor - 1.0) * 0.5 * (1.0 + std::tanh((u - jump) / (0.03 * s.end_m)))
        : factor - (factor - 1.0) * u / (2.0 * s.end_m);
    out.u[i] += (scale - 1.0) * out.f[i] / s.stiffness_N_per_m;
    out.f[i] *= scale;
  }
  return out;
}

}  // namespace dtwire::gap::independent
