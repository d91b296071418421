#include "contact_kernel.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace dtwire::fem::contact {
namespace {

Matrix3 identity() {
  Matrix3 I;
  for (unsigned k = 0; k < 3; ++k) I[k][k] = 1.0;
  return I;
}

}  // namespace

Projection ToolGeometry::project(const Vector3& x) const {
  Projection p;
  if (shape == ToolShape::plane) {
    p.normal = direction;
    p.gap = (x - point) * direction;
    return p;  // normal_gradient stays zero
  }
  if (shape == ToolShape::grooved_plate) {
    const Vector3 r = x - point;
    const Vector3 radial = r - (r * groove_axis) * groove_axis;
    const double rho = radial.norm();
    const double height = r * direction;
    if (!(rho > 1e-12 * radius)) {  // on the groove axis: inside the channel, open
      p.normal = direction;
      p.gap = radius;
      return p;
    }
    if (height >= radius - rho) {  // the flat part is nearer (or the point is above the plate)
      p.normal = direction;
      p.gap = height;
      return p;
    }
    // Groove wall (concave cylinder): the normal points back towards the groove axis.
    p.normal = -radial / rho;
    p.gap = radius - rho;
    p.normal_gradient =
        -(identity() - outer_product(groove_axis, groove_axis) - outer_product(p.normal, p.normal)) / rho;
    return p;
  }
  const Vector3 r = x - point;
  const Vector3 radial = r - (r * direction) * direction;
  const double rho = radial.norm();
  if (!(rho > 1e-12 * radius)) throw std::domain_error("contact point on the cylinder axis");
  p.normal = radial / rho;
  p.gap = rho - radius;
  p.normal_gradient = (identity() - outer_product(direction, direction) - outer_product(p.normal, p.normal)) / rho;
  return p;
}

ContactResponse evaluate_contact(const ToolGeometry& tool, const ContactLaw& law, const ContactHistory& history,
                                 const Vector3& x, const Vector3& anchor, FrictionStatus forced) {
  ContactResponse out;
  const Projection proj = tool.project(x);
  out.gap = proj.gap;
  const double pressure = history.multiplier - law.normal_penalty * proj.gap;
  if (!(pressure > 0.0)) return out;  // open: no traction, friction history released
  out.active = true;
  out.pressure = pressure;
  const Vector3& n = proj.normal;
  const Matrix3& H = proj.normal_gradient;
  const Matrix3 I = identity();
  const Matrix3 nn = outer_product(n, n);
  const Vector3 dp_dx = -law.normal_penalty * n;  // d g / d x = n for both shapes

  // Normal part: t_N = p n.
  out.traction = pressure * n;
  out.stiffness = outer_product(n, dp_dx) + pressure * H;
  if (law.friction <= 0.0) return out;

  // Tangential elastic predictor (Wriggers 2006, eq. 10.47): the committed traction pushed onto
  // the current tangent plane, minus epsilon_T times the tangential motion relative to the tool.
  const Vector3 v = x - anchor;
  const double vn = v * n;
  const Vector3 slip_trial = v - vn * n;
  const Vector3& t_old = history.tangential_traction;
  const double tn = t_old * n;
  const Vector3 trial = t_old - tn * n - law.tangential_penalty * slip_trial;
  // d(trial)/dx = -(t_old.n) H - n (x) H t_old - epsilon_T (I - n(x)n - (v.n) H - n (x) H v)
  const Matrix3 d_trial = -tn * H - outer_product(n, H * t_old) -
                          law.tangential_penalty * (I - nn - vn * H - outer_product(n, H * v));

  const double trial_norm = trial.norm();
  const double limit = law.friction * pressure;
  const bool stick = forced == FrictionStatus::free ? trial_norm <= limit : forced == FrictionStatus::stick;
  if (stick || !(trial_norm > 0.0)) {  // stick (or frozen as stick)
    out.tangential_traction = trial;
    out.traction += trial;
    out.stiffness += d_trial;
    return out;
  }
  // Slip: radial return onto the Coulomb cone, t_T = mu p m, m = trial / |trial|
  // (Wriggers 2006, eq. 10.51; tangent eq. 10.58, here for a rigid master surface).
  const Vector3 m = trial / trial_norm;
  out.slipping = true;
  out.tangential_traction = limit * m;
  out.traction += out.tangential_traction;
  out.stiffness += law.friction * outer_product(m, dp_dx) + (limit / trial_norm) * ((I - outer_product(m, m)) * d_trial);
  out.slip_increment = std::max(0.0, trial_norm - limit) / law.tangential_penalty;
  out.dissipation = limit * out.slip_increment;
  return out;
}

}  // namespace dtwire::fem::contact
