#include <algorithm>
#include <cmath>

#include "independent_effects.hpp"

namespace dtwire::gap::independent {

// Shape 0, cubic toe: the slack u0 of a wire not yet straight (or of grips seating) is taken up
// against a force growing with the cube of the take-up, f = F_t (x / u0)^3, so the seating
// displacement is u0 min(1, (F_max / F_t)^(1/3)).
// Shape 1, bilinear toe: a soft stage of stiffness F_t / u0 until F_t, then the specimen:
// u0 min(1, F_max / F_t). F_max is the running maximum (seating is not undone on unloading).
// u0 0.2-1.5 mm, F_t 1-8 % of the visible peak (as the fitted family).
ForceCurve initial_slack(const ForceCurve& base, const Setting& s) {
  ForceCurve out = visible(base, s.end_m);
  const double u0 = magnitude(s, 0, 0.2e-3, 1.5e-3);
  const double toe = (0.01 + 0.07 * (s.draws.size() > 1 ? s.draws[1] : 0.5)) * s.visible_peak_N;
  const std::vector<double> fmax = running_max(out.f);
  for (std::size_t i = 0; i < out.size(); ++i) {
    const double r = std::min(1.0, std::max(fmax[i], 0.0) / toe);
    out.u[i] += u0 * (s.shape == 0 ? std::cbrt(r) : r);
  }
  return out;
}

}  // namespace dtwire::gap::independent
