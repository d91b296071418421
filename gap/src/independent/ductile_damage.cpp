#include <algorithm>
#include <cmath>

#include "independent_effects.hpp"

namespace dtwire::gap::independent {

// Damage D after the onset u_d, reaching D_end at the test end, f' = f (1 - D):
// Shape 0, late exponential softening (void coalescence accelerating before fracture, after
// Gurson-Tvergaard-Needleman): D = D_end (exp(a x) - 1) / (exp(a) - 1), a = 4.
// Shape 1, linear softening (Lemaitre-type damage growing with plastic strain): D = D_end x.
// x = (u_max - u_d) / (u_end - u_d) on the running maximum displacement. Onset 20-60 % of the
// test, force loss at its end from 5 % out to the plausible range's edge (the catalogue's, the
// damage the test shows; the fitted law is quadratic).
ForceCurve ductile_damage(const ForceCurve& base, const Setting& s) {
  ForceCurve out = visible(base, s.end_m);
  const double onset = (0.2 + 0.4 * (s.draws.empty() ? 0.5 : s.draws[0])) * s.end_m;
  const double loss = toward_edge(s, 1, 0.0, 0.05, plausible_upper("ductile_damage", 1));
  const std::vector<double> umax = running_max(out.u);
  for (std::size_t i = 0; i < out.size(); ++i) {
    const double x = std::clamp((umax[i] - onset) / (s.end_m - onset), 0.0, 1.0);
    const double d = s.shape == 0 ? loss * std::expm1(4.0 * x) / std::expm1(4.0) : loss * x;
    out.f[i] *= 1.0 - d;
  }
  return out;
}

}  // namespace dtwire::gap::independent
