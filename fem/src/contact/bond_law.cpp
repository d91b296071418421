#include "bond_law.hpp"

#include <algorithm>

namespace dtwire::fem::contact {

BondResponse evaluate_bond(const BondLaw& law, const BondHistory& committed, const Vector3& normal,
                           const Vector3& gap) {
  const double k = law.stiffness;
  Matrix3 identity;
  for (unsigned i = 0; i < 3; ++i) identity[i][i] = 1.0;
  const Matrix3 nn = outer_product(normal, normal);
  const double g_n = gap * normal;
  const Vector3 g_t = gap - g_n * normal;

  BondResponse out;
  out.history = committed;
  const Vector3 trial = -k * (g_t - committed.slip_vector);  // elastic predictor, tangential
  const double trial_norm = trial.norm();
  Vector3 t_t = trial;
  out.stiffness = -k * identity;
  if (law.slides && trial_norm > law.strength) {
    // Radial return onto |t_T| = tau_b: the plastic slip grows along -m by Delta gamma.
    const Vector3 m = trial / trial_norm;
    out.slipping = true;
    out.slip_increment = (trial_norm - law.strength) / k;
    t_t = law.strength * m;
    out.history.slip_vector = committed.slip_vector - out.slip_increment * m;
    out.history.slip = committed.slip + out.slip_increment;
    // d t_T / d g = (tau_b / |trial|) (I - m m) d trial / d g, d trial / d g = -k (I - n n).
    out.stiffness = -k * nn - (k * law.strength / trial_norm) * (identity - nn - outer_product(m, m));
    out.dissipation = law.strength * out.slip_increment;
  }
  out.traction = -k * g_n * normal + t_t;
  out.energy = 0.5 * k * g_n * g_n + t_t.norm_square() / (2.0 * k);
  return out;
}

}  // namespace dtwire::fem::contact
