#include <algorithm>
#include <cmath>

#include "independent_effects.hpp"

namespace dtwire::gap::independent {

// Shape 0, extensometer knife edges creeping on the wire: the gauge factor drifts linearly over
// the test, lambda(u) = lambda0 + (lambda1 - lambda0) u / u_end with |lambda1 - lambda0| 0.02-0.06.
// Shape 1, crosshead displacement over a longer free length whose ends stay elastic (shoulders
// in the grips): the plastic part is scaled, the elastic part is not, u' = f/k0 + lambda (u - f/k0).
// lambda from 1.05 or 0.95 out to the plausible range's edges (the catalogue's; e.g. 0.5: an
// extensometer over half the free length). The range is stated for the gauge factor, so shape 0's
// factor stays within it over the whole test: a drift that would carry it past an edge starts
// that much inside.
ForceCurve gauge_length(const ForceCurve& base, const Setting& s) {
  ForceCurve out = visible(base, s.end_m);
  const bool above = (s.draws.size() > 1 ? s.draws[1] : 0.5) < 0.5;
  const double lambda = above ? toward_edge(s, 0, 1.0, 1.05, plausible_upper("gauge_length", 0))
                              : toward_edge(s, 0, 1.0, 0.95, plausible_lower("gauge_length", 0));
  const double drift = (s.draws.size() > 2 && s.draws[2] < 0.5 ? -1.0 : 1.0) *
                       (0.02 + 0.04 * (s.draws.size() > 3 ? s.draws[3] : 0.5));
  const double start = std::clamp(lambda, plausible_lower("gauge_length", 0) - std::min(drift, 0.0),
                                  plausible_upper("gauge_length", 0) - std::max(drift, 0.0));
  for (std::size_t i = 0; i < out.size(); ++i) {
    const double u = out.u[i];
    if (s.shape == 0) {
      out.u[i] = (start + drift * u / s.end_m) * u;
    } else {
      const double elastic = std::min(u, std::max(out.f[i], 0.0) / s.stiffness_N_per_m);
      out.u[i] = elastic + lambda * (u - elastic);
    }
  }
  return out;
}

}  // namespace dtwire::gap::independent
