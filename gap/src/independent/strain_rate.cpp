#include <algorithm>
#include <cmath>

#include "dtwire/gap/synthetic_curves.hpp"
#include "independent_effects.hpp"

namespace dtwire::gap::independent {

// Flow stress scaled by a factor s(u) along the test, elastic slope kept (f' = s f,
// u' = u + (s - 1) f / k0):
// Shape 0, crosshead speed changed mid-test (a rate-jump test, or a machine switching from
// the elastic to the plastic speed of EN ISO 6892-1 method B): s = 1 before the jump at 30-60 %
// of the test, s1 after it, smoothed over 3 % of the test.
// Shape 1, adiabatic heating at a high rate: the rate gain s0 fades as the wire warms,
// s = s0 - (s0 - 1) u / (2 u_end).
// Shape 2, a rate sensitivity that grows with the hardening (issue 37): in the fcc relation of
// Zerilli and Armstrong (1987) the rate term multiplies the strain hardening, so the gain of
// the hardening part grows with it while the yield part keeps a share a (0.3-0.7) of the end
// gain: s = 1 + (s1 - 1)(a + (1 - a) H / H_end), H = 1 - F_y / F_max the hardening's share of
// the running peak force, F_y the force at 0.2 % plastic strain (not the fitted linear clock).
// s0, s1: from 1.04 or 0.96 out to the plausible range's edges (the catalogue's).
ForceCurve strain_rate(const ForceCurve& base, const Setting& s) {
  ForceCurve out = visible(base, s.end_m);
  const bool above = (s.draws.size() > 1 ? s.draws[1] : 0.5) < 0.5;
  const double factor = above ? toward_edge(s, 0, 1.0, 1.04, plausible_upper("strain_rate", 0))
                              : toward_edge(s, 0, 1.0, 0.96, plausible_lower("strain_rate", 0));
  const double d2 = s.draws.size() > 2 ? s.draws[2] : 0.5;
  const double jump = (0.3 + 0.3 * d2) * s.end_m;
  std::vector<double> share(out.size(), 1.0);
  if (s.shape == 2) {
    const double offset = 0.002 * kGaugeLength_m;
    double yield = 0.0;
    for (std::size_t i = 0; i < out.size() && yield == 0.0; ++i)
      if (out.u[i] - out.f[i] / s.stiffness_N_per_m >= offset) yield = out.f[i];
    const std::vector<double> peak = running_max(out.f);
    for (std::size_t i = 0; i < out.size(); ++i)
      share[i] = yield > 0 && peak[i] > yield ? 1.0 - yield / peak[i] : 0.0;
    const double end = share.back() > 0 ? share.back() : 1.0;
    const double a = 0.3 + 0.4 * d2;
    for (double& h : share) h = a + (1.0 - a) * h / end;
  }
  for (std::size_t i = 0; i < out.size(); ++i) {
    const double u = out.u[i];
    const double scale = s.shape == 0 ? 1.0 + (factor - 1.0) * 0.5 * (1.0 + std::tanh((u - jump) / (0.03 * s.end_m)))
                       : s.shape == 1 ? factor - (factor - 1.0) * u / (2.0 * s.end_m)
                                      : 1.0 + (factor - 1.0) * share[i];
    out.u[i] += (scale - 1.0) * out.f[i] / s.stiffness_N_per_m;
    out.f[i] *= scale;
  }
  return out;
}

}  // namespace dtwire::gap::independent
