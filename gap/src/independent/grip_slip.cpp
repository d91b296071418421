#include <algorithm>
#include <cmath>

#include "independent_effects.hpp"

namespace dtwire::gap::independent {

// Shape 0, stick-slip in wedge grips: above the onset force the wire slides by a step delta each
// time the force reaches the grip's current holding force, which rises by delta / c per step as
// the wedges bite deeper; each slip drops the force, which then reloads elastically. The record
// is on the crosshead displacement, the specimen sees u_lab - slip.
// Shape 1, smooth creep: slip growing with the square of the excess force,
// s = c (F_max - F_s)^2 / (F_p - F_s) (a friction grip whose slip rate rises with the load).
// Onset 0.3-0.8 x the visible peak, the slip rate ds/dF_max (the quantity the catalogue's range
// of `slip_mm_per_kN` is stated for) from 1 mm/kN out to the range's edge: the stick-slip's
// mean rate c, the creep's largest, 2c at the peak (so its c is half the drawn rate); steps
// 0.1-0.5 mm (as the fitted family).
ForceCurve grip_slip(const ForceCurve& base, const Setting& s) {
  const double peak = s.visible_peak_N;
  const double onset = magnitude(s, 0, 0.3, 0.8) * peak / s.scatter;
  const double c = toward_edge(s, 1, 0.0, 1.0, plausible_upper("grip_slip", 1)) * 1e-6;
  if (s.shape == 1) {
    const double creep = 0.5 * c;
    ForceCurve out = visible(base, s.end_m);
    const std::vector<double> fmax = running_max(out.f);
    for (std::size_t i = 0; i < out.size(); ++i) {
      const double excess = std::max(0.0, fmax[i] - onset);
      out.u[i] += creep * excess * excess / std::max(peak - onset, 1e-9);
    }
    return out;
  }
  const double step = magnitude(s, 2, 0.1e-3, 0.5e-3) / s.scatter;
  ForceCurve out;
  out.source = base.source;
  double slip = 0.0, holding = onset;
  const std::size_t n = 6000;
  const double du = s.end_m / static_cast<double>(n) * 1.5;
  for (double u = base.u.front();; u += du) {
    double f = force_at(base, u - slip);
    while (f > holding && u - slip < s.end_m) {
      slip += step;
      holding += step / c;
      f = force_at(base, u - slip);
    }
    out.u.push_back(u);
    out.f.push_back(f);
    if (u - slip >= s.end_m) break;
  }
  return out;
}

}  // namespace dtwire::gap::independent
