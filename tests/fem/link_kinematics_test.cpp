// The twist as a DEM link read off FE points (fem/src/link_kinematics.hpp), against rigid-body
// motions and statics whose answers are known exactly.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "link_kinematics.hpp"

namespace dtwire::fem {
namespace {

using Matrix3 = std::array<Point3, 3>;

Matrix3 axis_angle(Point3 n, double angle) {  // Rodrigues
  const double c = std::cos(angle), s = std::sin(angle), t = 1 - c;
  const double l = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  for (auto& v : n) v /= l;
  return {{{{c + t * n[0] * n[0], t * n[0] * n[1] - s * n[2], t * n[0] * n[2] + s * n[1]}},
           {{t * n[0] * n[1] + s * n[2], c + t * n[1] * n[1], t * n[1] * n[2] - s * n[0]}},
           {{t * n[0] * n[2] - s * n[1], t * n[1] * n[2] + s * n[0], c + t * n[2] * n[2]}}}};
}

Point3 apply(const Matrix3& r, const Point3& x, const Point3& about, const Point3& shift) {
  Point3 y{};
  for (unsigned i = 0; i < 3; ++i) {
    y[i] = about[i] + shift[i];
    for (unsigned j = 0; j < 3; ++j) y[i] += r[i][j] * (x[j] - about[j]);
  }
  return y;
}

SectionPoints moved(const SectionPoints& p, const Matrix3& r, const Point3& about, const Point3& shift) {
  return {{apply(r, p[0], about, shift), apply(r, p[1], about, shift), apply(r, p[2], about, shift),
           apply(r, p[3], about, shift)}};
}

// The 40 mm twist of the default DT: wire axes at x = +-1.355 mm at both ends, and a point
// 0.9 mm off in y inside each wire.
const SectionPoints kBottom{
    {{{1.355e-3, 0, 0}}, {{-1.355e-3, 0, 0}}, {{1.355e-3, 0.9e-3, 0}}, {{-1.355e-3, 0.9e-3, 0}}}};
const SectionPoints kTop{
    {{{-1.355e-3, 0, 40e-3}}, {{1.355e-3, 0, 40e-3}}, {{-1.355e-3, 0.9e-3, 40e-3}}, {{1.355e-3, 0.9e-3, 40e-3}}}};
const Point3 kTopOrigin{{0, 0, 40e-3}}, kZero{{0, 0, 0}};
const Matrix3 kIdentity{{{{1, 0, 0}}, {{0, 1, 0}}, {{0, 0, 1}}}};

TEST(LinkKinematics, TopSectionTurnedAboutItsOriginGivesThatRotationAndNoElongation) {
  for (const Point3& axis : {Point3{{0, 1, 0}}, Point3{{1, 0, 0}}, Point3{{0, 0, 1}}, Point3{{1, -2, 0.5}}}) {
    const double angle = 0.7;
    const LinkState s = link_state(kBottom, kBottom, kTop, moved(kTop, axis_angle(axis, angle), kTopOrigin, kZero),
                                   kZero, kZero, kTopOrigin);
    const double l = std::sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
    for (unsigned i = 0; i < 3; ++i) EXPECT_NEAR(s.rotation[i], angle * axis[i] / l, 1e-12);
    EXPECT_NEAR(s.elongation, 0.0, 1e-15);
    EXPECT_NEAR(s.length, 40e-3, 1e-15);
  }
}

TEST(LinkKinematics, RigidMotionOfTheWholeLinkIsNoDeformation) {
  const Matrix3 r = axis_angle({{0.3, 1, -0.2}}, 1.1);
  const Point3 about{{0.01, -0.02, 0.005}}, shift{{0.003, 0.001, -0.004}};
  const LinkState s = link_state(kBottom, moved(kBottom, r, about, shift), kTop, moved(kTop, r, about, shift), kZero,
                                 kZero, kTopOrigin);
  for (unsigned i = 0; i < 3; ++i) EXPECT_NEAR(s.rotation[i], 0.0, 1e-13);
  EXPECT_NEAR(s.elongation, 0.0, 1e-15);
}

TEST(LinkKinematics, StretchAlongTheChordIsTheElongationAndTheAxialForce) {
  const LinkState s = link_state(kBottom, kBottom, kTop, moved(kTop, kIdentity, kTopOrigin, {{0, 0, 2e-3}}),
                                 {{30.0, 0.0, 5000.0}}, kZero, {{0, 0, 42e-3}});
  EXPECT_NEAR(s.elongation, 2e-3, 1e-15);
  EXPECT_NEAR(s.axial_force, 5000.0, 1e-9);
  EXPECT_NEAR(s.shear_force, 30.0, 1e-9);
  // The load acts at the top section's origin: about the midpoint (21 mm below) the shear gives
  // M_y = 0.021 m x 30 N.
  EXPECT_NEAR(s.moment[1], 0.021 * 30.0, 1e-12);
  EXPECT_NEAR(s.moment[0], 0.0, 1e-12);
}

TEST(LinkKinematics, EndMomentIsCarriedToTheMidpoint) {
  // A force F = (0, 0, 1000) N at an end centre 22 mm above and 5 mm beside (x) the top section,
  // plus an end moment: M_mid = M_e + (x_e - m) x F.
  const Point3 centre{{5e-3, 0, 62e-3}}, force{{0, 0, 1000}}, moment{{0.1, -2.0, 0.3}};
  const LinkState s = link_state(kBottom, kBottom, kTop, kTop, force, moment, centre);
  EXPECT_NEAR(s.moment[0], 0.1, 1e-12);
  EXPECT_NEAR(s.moment[1], -2.0 - 5e-3 * 1000, 1e-12);
  EXPECT_NEAR(s.moment[2], 0.3, 1e-12);
}

TEST(LinkKinematics, RotationVectorNearHalfATurn) {
  for (const double angle : {M_PI - 1e-9, M_PI - 1e-4, M_PI / 2, 1e-9, 0.0}) {
    const Point3 axis{{2, -1, 3}};
    const Point3 v = rotation_vector(axis_angle(axis, angle));
    const double l = std::sqrt(14.0);
    for (unsigned i = 0; i < 3; ++i) EXPECT_NEAR(v[i], angle * axis[i] / l, 1e-7) << "angle " << angle;
  }
}

// As the helix straightens each wire's cross-section rolls about the line of the axis points, the
// two wires the opposite way (their helix tangents at a section tilt oppositely): no rotation of
// the link.
TEST(LinkKinematics, OppositeRollOfTheTwoWiresIsNoRotation) {
  SectionPoints top = kTop;
  const double roll = 0.3;
  top[2] = apply(axis_angle({{1, 0, 0}}, roll), kTop[2], kTop[0], kZero);
  top[3] = apply(axis_angle({{1, 0, 0}}, -roll), kTop[3], kTop[1], kZero);
  const LinkState s = link_state(kBottom, kBottom, kTop, top, kZero, kZero, kTopOrigin);
  for (unsigned i = 0; i < 3; ++i) EXPECT_NEAR(s.rotation[i], 0.0, 1e-15);
}

TEST(LinkKinematics, DegenerateSectionsAreRefused) {
  EXPECT_THROW(check_section({{{{0, 0, 0}}, {{1, 0, 0}}, {{2, 0, 0}}, {{-1, 0, 0}}}}), std::invalid_argument);
  EXPECT_THROW(check_section({{{{0, 0, 0}}, {{0, 0, 0}}, {{0, 1, 0}}, {{0, 1, 0}}}}), std::invalid_argument);
  EXPECT_THROW(check_section({{{{0, 0, 0}}, {{1, 0, 0}}, {{0, 1, 0}}, {{1, -1, 0}}}}), std::invalid_argument);
  EXPECT_NO_THROW(check_section(kBottom));
}

}  // namespace
}  // namespace dtwire::fem
