#pragma once
// The figures a punch curve is judged by against the thesis's punch (Previtali; loading from
// 0.20 m, most wires yielding near 0.42 m, peak 25 kN at 0.53 m): loading onset, force at a
// given platter travel, peak force and its displacement. Standard library only.
#include <vector>

namespace dtwire::dem {

struct PunchFigures {
  double onset = -1.0;          // travel where the force first reaches onset_force [m]; -1: never
  double force_at_probe = -1.0;  // force at probe travel (linear interpolation) [N]; -1: the travel was not reached
  double peak_force = 0.0;      // [N]
  double displacement_at_peak = 0.0;  // [m]
};

// The onset is where the force first reaches `onset_force` (1 kN by default: well above the weight
// of a 3 x 3 m panel, 0.13 kN, and 4 % of the thesis peak), interpolated between samples.
// Throws std::invalid_argument for columns of different sizes.
PunchFigures punch_figures(const std::vector<double>& displacement_m, const std::vector<double>& force_N,
                           double onset_force = 1000.0, double probe = 0.42);

}  // namespace dtwire::dem
