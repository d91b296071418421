#pragma once
// Damage of the macro-element (Previtali thesis): beyond the plastic work W1 every damaged force
// is multiplied by 1 - ((W_p - W1) / (W2 - W1))^alpha_d; the bond breaks when the factor falls
// to 0.01 (so always before W_p reaches W2).
#include <cmath>

namespace dtwire::dem::detail {

struct DamageParameters {
  double W1 = 0.0;       // [J] (moment work in the calibration's angle convention)
  double W2 = 0.0;       // [J]
  double alpha_d = 1.0;  // [-]

  double factor(double plastic_work) const {
    if (plastic_work <= W1) return 1.0;
    const double x = (plastic_work - W1) / (W2 - W1);
    return x >= 1.0 ? 0.0 : 1.0 - std::pow(x, alpha_d);
  }
  static constexpr double break_factor = 0.01;
};

// One accepted piece of an increment, booked so that external = elastic + plastic + damage holds
// to round-off (damaged forces are d times the effective ones, stored energy d e):
//   external += dbar Qbar.dq, plastic += dbar Qbar.dq_p, damage += -(d1 - d0) ebar,
// because Qbar.dq = (e1 - e0) + Qbar.dq_p exactly for a linear elastic part and
// d1 e1 - d0 e0 = dbar (e1 - e0) + (d1 - d0) ebar.
struct DamagedPiece {
  double d0, d1;          // damage factor before / after
  double e0, e1;          // effective elastic energy of the damaged components before / after [J]
  double work;            // Qbar.dq of the damaged components [J]
  double plastic_work;    // Qbar.dq_p [J]
};

struct EnergyTotals {
  double external = 0.0;
  double plastic = 0.0;
  double damage = 0.0;

  void book(const DamagedPiece& piece) {
    const double d_mean = 0.5 * (piece.d0 + piece.d1);
    external += d_mean * piece.work;
    plastic += d_mean * piece.plastic_work;
    damage -= (piece.d1 - piece.d0) * 0.5 * (piece.e0 + piece.e1);
  }
};

}  // namespace dtwire::dem::detail
