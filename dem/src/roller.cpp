// Roller-segment contact: nearest point of a link's axis to a roller's axis, penalty and
// Coulomb forces, lever-rule shares (roller.hpp).
#include "dtwire/dem/roller.hpp"

#include <algorithm>

namespace dtwire::dem {

SegmentPoint nearest_to_axis(const Roller& roller, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  // Components normal to the axis e: the distance of a + s (b - a) from the axis is
  // |w + s d| with w = (a - p)_perp, d = (b - a)_perp, least at s = -w.d / d.d (clamped).
  const Eigen::Vector3d e = roller.axis.normalized();
  const auto perp = [&](const Eigen::Vector3d& x) -> Eigen::Vector3d { return x - x.dot(e) * e; };
  const Eigen::Vector3d w = perp(a - roller.point), d = perp(b - a);
  SegmentPoint out;
  const double dd = d.squaredNorm();
  out.s = dd > 1e-24 * (b - a).squaredNorm() && dd > 0.0 ? std::clamp(-w.dot(d) / dd, 0.0, 1.0) : 0.5;
  const Eigen::Vector3d radial = w + out.s * d;
  out.distance = radial.norm();
  if (out.distance > 0.0) out.normal = radial / out.distance;
  return out;
}

SegmentContact roller_segment_contact(const Roller& roller, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                      double wire_radius, const Eigen::Vector3d& v_a, const Eigen::Vector3d& v_b,
                                      double dt, Eigen::Vector3d& shear) {
  SegmentContact c;
  c.where = nearest_to_axis(roller, a, b);
  c.penetration = roller.radius + wire_radius - c.where.distance;
  if (!(c.penetration > 0.0)) {
    shear.setZero();
    return c;
  }
  c.touching = true;
  const double kn = roller.contact.normal_stiffness, ks = roller.contact.shear_stiffness;
  const Eigen::Vector3d& n = c.where.normal;
  const double s = c.where.s;
  // Slip velocity of the segment's point against the roller, in the tangent plane.
  const Eigen::Vector3d slip = (1.0 - s) * v_a + s * v_b - roller.velocity;
  const Eigen::Vector3d tangential = slip - slip.dot(n) * n;
  // The spring kept from the last step, turned into the current tangent plane (same length).
  Eigen::Vector3d spring = shear - shear.dot(n) * n;
  if (spring.norm() > 0.0) spring *= shear.norm() / spring.norm();
  spring -= ks * dt * tangential;
  const double normal_force = kn * c.penetration;
  const double limit = roller.contact.friction * normal_force;
  const double trial = spring.norm();
  if (trial > limit) {
    c.friction_work = limit * (trial - limit) / ks;
    spring *= trial > 0.0 ? limit / trial : 0.0;
  }
  shear = spring;
  c.force = normal_force * n + spring;
  c.on_a = (1.0 - s) * c.force;
  c.on_b = s * c.force;
  c.elastic_energy = 0.5 * normal_force * normal_force / kn + (ks > 0.0 ? 0.5 * spring.squaredNorm() / ks : 0.0);
  return c;
}

}  // namespace dtwire::dem
