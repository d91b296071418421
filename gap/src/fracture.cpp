#include "dtwire/gap/fracture.hpp"

#include <algorithm>

namespace dtwire::gap {

RecordEnd record_end(const ForceCurve& lab) {
  RecordEnd out;
  const std::size_t n = lab.size();
  out.intact_points = n;
  out.end_m = n ? lab.u.back() : 0.0;
  if (n < 3) return out;
  const auto [lo, hi] = std::minmax_element(lab.u.begin(), lab.u.end());
  const double window = kFractureWindow * (*hi - *lo);
  // The window: the trailing points within 1 % of the range of the last one, the displacement
  // never going back on the way (an unloading branch is no fracture).
  std::size_t first = n - 1;
  while (first > 0 && lab.u[first - 1] >= lab.u.back() - window && lab.u[first - 1] <= lab.u[first]) --first;
  double largest = 0.0;
  for (std::size_t i = first; i < n; ++i) largest = std::max(largest, lab.f[i]);
  if (!(largest > 0) || !(lab.f.back() < kFractureRemainder * largest)) return out;
  std::size_t last_intact = n - 1;
  while (last_intact > first && lab.f[last_intact] < 0.5 * largest) --last_intact;
  if (lab.f[last_intact] < 0.5 * largest) return out;
  out.fracture = true;
  out.intact_points = last_intact + 1;
  out.end_m = lab.u[last_intact];
  return out;
}

ForceCurve intact_part(const ForceCurve& lab, const RecordEnd& end) {
  ForceCurve out = lab;
  out.u.resize(end.intact_points);
  out.f.resize(end.intact_points);
  return out;
}

void set_damage_clocks(std::vector<Comparison>& labs) {
  double reference = 0.0;
  for (const Comparison& c : labs) reference = std::max(reference, c.fracture_m);
  for (Comparison& c : labs) c.damage_clock = c.fracture_m > 0 ? reference / c.fracture_m : 1.0;
}

}  // namespace dtwire::gap
