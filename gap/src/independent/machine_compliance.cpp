#include <algorithm>
#include <cmath>

#include "independent_effects.hpp"

namespace dtwire::gap::independent {

// Shape 0, wedge grips bedding in: the load train is softer at low force, its displacement
// grows with the logarithm of the force, u' = u + C f + C F_b ln(1 + f / F_b).
// Shape 1, Hertzian contacts in the load train (pins, wedge faces): u' = u + C F_p (f / F_p)^(2/3)
// (contact approach proportional to load^(2/3), Johnson, Contact Mechanics, 1985, eq. 4.23).
// The magnitude is the secant compliance at the visible peak, u'(F_p) - u(F_p) = C_s F_p (the
// quantity the catalogue's plausible range is stated for), from 0.1 mm/kN out to the range's edge;
// shape 0's linear part is then C = C_s / (1 + (F_b / F_p) ln(1 + F_p / F_b)), so its log part
// does not carry the load train beyond the range. F_b 5-20 % of the visible peak.
ForceCurve machine_compliance(const ForceCurve& base, const Setting& s) {
  ForceCurve out = visible(base, s.end_m);
  const double secant = toward_edge(s, 0, 0.0, 0.1, plausible_upper("machine_compliance", 0)) * 1e-6;  // mm/kN -> m/N
  const double peak = s.visible_peak_N;
  const double seating = (0.05 + 0.15 * (s.draws.size() > 1 ? s.draws[1] : 0.5)) * peak;
  const double c = s.shape == 0 ? secant / (1.0 + seating / peak * std::log1p(peak / seating)) : secant;
  for (std::size_t i = 0; i < out.size(); ++i) {
    const double f = std::max(out.f[i], 0.0);
    out.u[i] += s.shape == 0 ? c * f + c * seating * std::log1p(f / seating)
                             : c * peak * std::pow(f / peak, 2.0 / 3.0);
  }
  return out;
}

}  // namespace dtwire::gap::independent
