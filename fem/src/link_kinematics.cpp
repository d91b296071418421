#include "link_kinematics.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace dtwire::fem {
namespace {

using Matrix3 = std::array<Point3, 3>;  // rows

Point3 minus(const Point3& a, const Point3& b) { return {{a[0] - b[0], a[1] - b[1], a[2] - b[2]}}; }
Point3 scaled(const Point3& a, double s) { return {{a[0] * s, a[1] * s, a[2] * s}}; }
double dot(const Point3& a, const Point3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
double norm(const Point3& a) { return std::sqrt(dot(a, a)); }
Point3 cross(const Point3& a, const Point3& b) {
  return {{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}};
}
Point3 midpoint(const Point3& a, const Point3& b) { return {{(a[0] + b[0]) / 2, (a[1] + b[1]) / 2, (a[2] + b[2]) / 2}}; }

// The mean offset of the section's two off-axis points from their wires' axis points.
Point3 mean_offset(const SectionPoints& p) {
  const Point3 qa = minus(p[2], p[0]), qb = minus(p[3], p[1]);
  return scaled(Point3{{qa[0] + qb[0], qa[1] + qb[1], qa[2] + qb[2]}}, 0.5);
}

// The section's orthonormal frame as the rows e1, e2, e3 (Gram-Schmidt on b - a, mean offset).
Matrix3 section_frame(const SectionPoints& p) {
  const Point3 a = minus(p[1], p[0]), b = mean_offset(p);
  const Point3 e1 = scaled(a, 1.0 / norm(a));
  const Point3 normal_part = minus(b, scaled(e1, dot(b, e1)));
  const Point3 e2 = scaled(normal_part, 1.0 / norm(normal_part));
  return {{e1, e2, cross(e1, e2)}};
}

// R = E E0^T with E, E0 holding the frames as columns, i.e. sum_k e_k (e0_k)^T.
Matrix3 rotation_between(const Matrix3& reference_rows, const Matrix3& current_rows) {
  Matrix3 r{};
  for (unsigned i = 0; i < 3; ++i)
    for (unsigned j = 0; j < 3; ++j)
      for (unsigned k = 0; k < 3; ++k) r[i][j] += current_rows[k][i] * reference_rows[k][j];
  return r;
}

Matrix3 times_transpose(const Matrix3& a, const Matrix3& b) {  // a b^T
  Matrix3 r{};
  for (unsigned i = 0; i < 3; ++i)
    for (unsigned j = 0; j < 3; ++j)
      for (unsigned k = 0; k < 3; ++k) r[i][j] += a[i][k] * b[j][k];
  return r;
}

}  // namespace

void check_section(const SectionPoints& p) {
  const Point3 a = minus(p[1], p[0]), b = mean_offset(p);
  const double la = norm(a), lb = norm(b);
  if (!(la > 0.0)) throw std::invalid_argument("the two axis points of a link section coincide");
  if (!(lb > 0.0) || norm(cross(a, b)) < 1e-3 * la * lb)
    throw std::invalid_argument("the mean offset of a link section's off-axis points lies along its axis points' line");
}

Point3 rotation_vector(const Matrix3& r) {
  const Point3 w{{(r[2][1] - r[1][2]) / 2, (r[0][2] - r[2][0]) / 2, (r[1][0] - r[0][1]) / 2}};  // sin(t) n
  const double cosine = std::clamp((r[0][0] + r[1][1] + r[2][2] - 1.0) / 2.0, -1.0, 1.0);
  const double sine = norm(w);
  const double angle = std::atan2(sine, cosine);
  if (cosine > 0.0)  // angle < 90 deg: w / sin is well conditioned (angle / sin -> 1 at 0)
    return scaled(w, sine > 0.0 ? angle / sine : 1.0);
  // Near 180 deg sin -> 0: the axis from the symmetric part (1 - cos) n n^T, its largest column.
  unsigned k = 0;
  for (unsigned i = 1; i < 3; ++i)
    if (r[i][i] > r[k][k]) k = i;
  Point3 n{};
  for (unsigned i = 0; i < 3; ++i) n[i] = (r[i][k] + r[k][i]) / 2 - (i == k ? cosine : 0.0);
  n = scaled(n, 1.0 / norm(n));
  if (dot(n, w) < 0.0) n = scaled(n, -1.0);
  return scaled(n, angle);
}

LinkState link_state(const SectionPoints& bottom_reference, const SectionPoints& bottom_current,
                     const SectionPoints& top_reference, const SectionPoints& top_current, const Point3& end_force,
                     const Point3& end_moment, const Point3& end_centre) {
  const Matrix3 rotation_bottom = rotation_between(section_frame(bottom_reference), section_frame(bottom_current));
  const Matrix3 rotation_top = rotation_between(section_frame(top_reference), section_frame(top_current));
  const Point3 ob0 = midpoint(bottom_reference[0], bottom_reference[1]);
  const Point3 ot0 = midpoint(top_reference[0], top_reference[1]);
  const Point3 ob = midpoint(bottom_current[0], bottom_current[1]);
  const Point3 ot = midpoint(top_current[0], top_current[1]);
  const Point3 chord = minus(ot, ob);

  LinkState s;
  s.length = norm(chord);
  s.elongation = s.length - norm(minus(ot0, ob0));
  s.rotation = rotation_vector(times_transpose(rotation_top, rotation_bottom));
  const Point3 c = scaled(chord, 1.0 / s.length);
  s.axial_force = dot(end_force, c);
  s.shear_force = norm(minus(end_force, scaled(c, s.axial_force)));
  const Point3 arm = minus(end_centre, midpoint(ob, ot));
  const Point3 transfer = cross(arm, end_force);
  for (unsigned i = 0; i < 3; ++i) s.moment[i] = end_moment[i] + transfer[i];
  return s;
}

}  // namespace dtwire::fem
