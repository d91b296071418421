#include <algorithm>
#include <cmath>

#include "independent_effects.hpp"

namespace dtwire::gap::independent {

// Shape 0, cubic toe: the slack u0 of a wire not yet straight (or of grips seating) is taken up
// against a force growing with the cube of the take-up, f = F_t (x / u0)^3, so the seating
// displacement is u0 min(1, (F_max / F_t)^(1/3)).
// Shape 1, bilinear toe: a soft stage of stiffness F_t / u0 until F_t, then the specimen:
// u0 min(1, F_max / F_t). F_max is the running maximum (seating is not undone on unloading).
// u0 from 0.2 mm, F_t from 1 % of the visible peak, each out to its plausible range's edge (the
// catalogue's: 1.5 mm, 15 % of the peak).
ForceCurve initial_slack(const ForceCurve& base, const Setting& s) {
  ForceCurve out = visible(base, s.end_m);
  const double u0 = toward_edge(s, 0, 0.0, 0.2, plausible_upper("initial_slack", 0)) * 1e-3;
  Setting unscattered = s;
  unscattered.scatter = 1.0;
  const double toe = toward_edge(unscattered, 1, 0.0, 0.01, plausible_upper("initial_slack", 1)) * s.visible_peak_N;
  const std::vector<double> fmax = running_max(out.f);
  for (std::size_t i = 0; i < out.size(); ++i) {
    const double r = std::min(1.0, std::max(fmax[i], 0.0) / toe);
    out.u[i] += u0 * (s.shape == 0 ? std::cbrt(r) : r);
  }
  return out;
}

}  // namespace dtwire::gap::independent
