// Geometry of the rigid tools: nearest surface point and outward normal for a node centre.
#include "dtwire/dem/tools.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace dtwire::dem {

double PlaneWall::bounding_radius() const { return std::numeric_limits<double>::infinity(); }

Eigen::Vector2d nearest_on_ellipse(double A, double B, double x, double y) {
  // The nearest point is (A^2 x/(t + A^2), B^2 y/(t + B^2)) with t the largest root of
  // F(t) = (A x/(t + A^2))^2 + (B y/(t + B^2))^2 - 1 (Eberly, "Distance from a point to an
  // ellipse"). F is convex and decreasing for t > -min(A, B)^2, and F >= 0 at the start below,
  // so Newton climbs monotonically to the root.
  const double tiny = 1e-300;
  if (y <= tiny && x <= tiny) return A <= B ? Eigen::Vector2d(A, 0.0) : Eigen::Vector2d(0.0, B);
  // On the major axis inside the evolute the nearest point leaves the axis (Eberly's special case).
  if (y <= tiny && A > B) {
    const double reach = (A * A - B * B) / A;
    if (x >= reach) return {A, 0.0};
    const double u = A * x / (A * A - B * B);
    return {A * u, B * std::sqrt(1.0 - u * u)};
  }
  if (x <= tiny && B > A) {
    const double reach = (B * B - A * A) / B;
    if (y >= reach) return {0.0, B};
    const double u = B * y / (B * B - A * A);
    return {A * std::sqrt(1.0 - u * u), B * u};
  }
  const double lower = -std::min(A * A, B * B);
  double t = std::max({A * x - A * A, B * y - B * B, lower + 1e-15 * (A * A + B * B)});
  for (int iteration = 0; iteration < 60; ++iteration) {
    const double p = A * x / (t + A * A), q = B * y / (t + B * B);
    const double f = p * p + q * q - 1.0;
    const double df = -2.0 * (p * p / (t + A * A) + q * q / (t + B * B));
    if (!(df < 0.0)) break;
    const double step = f / df;
    t -= step;
    if (std::abs(step) <= 1e-14 * (std::abs(t) + A * A + B * B)) break;
  }
  return {A * A * x / (t + A * A), B * B * y / (t + B * B)};
}

PlaneWall::PlaneWall(const Eigen::Vector3d& outward_normal) : normal_(outward_normal.normalized()) {
  if (!(outward_normal.norm() > 0.0)) throw std::invalid_argument("wall: normal must be non-zero");
}

bool PlaneWall::nearest(const Eigen::Vector3d& point, double reach, SurfacePoint& out) const {
  const Eigen::Vector3d normal = to_world_direction(normal_);
  out.distance = (point - position).dot(normal);
  out.normal = normal;
  return out.distance < reach;
}

SemiSpheroidPlatter::SemiSpheroidPlatter(double base_radius, double height) : a_(base_radius), h_(height) {
  if (!(a_ > 0.0) || !(h_ > 0.0)) throw std::invalid_argument("platter: base radius and height must be positive");
}

bool SemiSpheroidPlatter::nearest(const Eigen::Vector3d& point, double reach, SurfacePoint& out) const {
  const Eigen::Vector3d q = to_local(point);
  const double rho = std::hypot(q.x(), q.y());
  if (rho > a_ + reach || q.z() > h_ + reach || q.z() < -reach) return false;
  const Eigen::Vector2d radial = rho > 0.0 ? Eigen::Vector2d(q.x() / rho, q.y() / rho) : Eigen::Vector2d(1.0, 0.0);
  Eigen::Vector2d offset;  // (rho, z) from the nearest surface point to the point
  bool inside = false;
  if (q.z() >= 0.0) {
    const Eigen::Vector2d surface = nearest_on_ellipse(a_, h_, rho, q.z());
    offset = Eigen::Vector2d(rho, q.z()) - surface;
    inside = (rho / a_) * (rho / a_) + (q.z() / h_) * (q.z() / h_) < 1.0;
    if (inside && q.z() < offset.norm()) offset = Eigen::Vector2d(0.0, q.z());  // the base is nearer
  } else if (rho <= a_) {
    offset = Eigen::Vector2d(0.0, q.z());  // below the flat base
  } else {
    offset = Eigen::Vector2d(rho - a_, q.z());  // beside the rim
  }
  const double length = offset.norm();
  out.distance = inside ? -length : length;
  Eigen::Vector2d direction = length > 0.0 ? Eigen::Vector2d(offset / length) : Eigen::Vector2d(0.0, 1.0);
  if (inside) direction = -direction;
  const Eigen::Vector3d local(direction.x() * radial.x(), direction.x() * radial.y(), direction.y());
  out.normal = to_world_direction(local);
  return out.distance < reach;
}

TruncatedCube::TruncatedCube(double side, double corner_plane) : side_(side), corner_(corner_plane) {
  if (!(side_ > 0.0)) throw std::invalid_argument("boulder: side must be positive");
  if (!(corner_ > 0.5 * side_) || corner_ > 1.5 * side_)
    throw std::invalid_argument("boulder: corner plane must be in (s/2, 3s/2]");
}

bool TruncatedCube::nearest(const Eigen::Vector3d& point, double reach, SurfacePoint& out) const {
  const Eigen::Vector3d q = to_local(point);
  const double half = 0.5 * side_;
  if (q.cwiseAbs().maxCoeff() > half + reach) return false;
  double best = -1e300;
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  for (int axis = 0; axis < 3; ++axis)
    for (double s : {-1.0, 1.0}) {
      const double d = s * q[axis] - half;
      if (d > best) {
        best = d;
        normal = Eigen::Vector3d::Zero();
        normal[axis] = s;
      }
    }
  const double inv_sqrt3 = 1.0 / std::sqrt(3.0);
  for (double sx : {-1.0, 1.0})
    for (double sy : {-1.0, 1.0})
      for (double sz : {-1.0, 1.0}) {
        const double d = (sx * q.x() + sy * q.y() + sz * q.z() - corner_) * inv_sqrt3;
        if (d > best) {
          best = d;
          normal = Eigen::Vector3d(sx, sy, sz) * inv_sqrt3;
        }
      }
  out.distance = best;
  out.normal = to_world_direction(normal);
  return best < reach;
}

}  // namespace dtwire::dem
