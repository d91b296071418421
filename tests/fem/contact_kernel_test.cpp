// Contact kernel without a mesh: gap and normal of the analytic tools, penalty pressure, the
// Coulomb return map (stick below mu p, slip at mu p, slip length and dissipation) and the
// consistent tangent against central finite differences (relative error < 1e-6).
#include <gtest/gtest.h>

#include <cmath>

#include "contact/contact_kernel.hpp"

namespace dtwire::fem::contact {
namespace {

Vector3 vec(double x, double y, double z) {
  Vector3 v;
  v[0] = x;
  v[1] = y;
  v[2] = z;
  return v;
}

ToolGeometry plane() {  // z = 0, outward normal +z
  ToolGeometry t;
  t.shape = ToolShape::plane;
  t.point = vec(0.3, -0.2, 0.0);
  t.direction = vec(0, 0, 1);
  return t;
}

ToolGeometry cylinder() {  // axis along a skew direction through (1, 2, 0), radius 10
  ToolGeometry t;
  t.shape = ToolShape::cylinder;
  t.point = vec(1.0, 2.0, 0.0);
  t.direction = vec(1.0, 0.2, -0.1) / vec(1.0, 0.2, -0.1).norm();
  t.radius = 10.0;
  return t;
}

ContactLaw law(double mu) { return ContactLaw{100.0, 50.0, mu}; }

TEST(ContactKernel, PlaneGapPressureAndOpenContact) {
  const auto tool = plane();
  const ContactHistory fresh;
  const auto closed = evaluate_contact(tool, law(0.0), fresh, vec(1, 1, -0.01), vec(1, 1, 0));
  EXPECT_TRUE(closed.active);
  EXPECT_NEAR(closed.gap, -0.01, 1e-15);
  EXPECT_NEAR(closed.pressure, 1.0, 1e-12);  // -eps_N g
  EXPECT_NEAR(closed.traction[2], 1.0, 1e-12);
  const auto open = evaluate_contact(tool, law(0.3), fresh, vec(1, 1, 0.01), vec(1, 1, 0));
  EXPECT_FALSE(open.active);
  EXPECT_EQ(open.traction.norm(), 0.0);
  // The augmented multiplier keeps the contact closed at zero gap with pressure lambda.
  ContactHistory augmented;
  augmented.multiplier = 2.0;
  const auto held = evaluate_contact(tool, law(0.0), augmented, vec(1, 1, 0.0), vec(1, 1, 0));
  EXPECT_NEAR(held.pressure, 2.0, 1e-12);
}

TEST(ContactKernel, CylinderGapAndNormal) {
  const auto tool = cylinder();
  const Vector3 radial = vec(0.0, 0.3, 1.0) - (vec(0.0, 0.3, 1.0) * tool.direction) * tool.direction;
  const Vector3 n = radial / radial.norm();
  const Vector3 x = tool.point + 3.0 * tool.direction + 9.5 * n;
  const auto p = tool.project(x);
  EXPECT_NEAR(p.gap, -0.5, 1e-12);
  EXPECT_NEAR((p.normal - n).norm(), 0.0, 1e-12);
  EXPECT_THROW(tool.project(tool.point + 2.0 * tool.direction), std::domain_error);
}

TEST(ContactKernel, StickBelowCoulombLimit) {
  const auto tool = plane();
  const double mu = 0.3;
  // p = 100 * 0.02 = 2, mu p = 0.6; tangential motion 0.005 -> trial 50 * 0.005 = 0.25 < 0.6.
  const auto r = evaluate_contact(tool, law(mu), ContactHistory{}, vec(1.005, 1, -0.02), vec(1, 1, 0));
  ASSERT_TRUE(r.active);
  EXPECT_FALSE(r.slipping);
  EXPECT_NEAR(r.tangential_traction[0], -0.25, 1e-12);  // opposes the motion of the body
  EXPECT_LT(r.tangential_traction.norm(), mu * r.pressure);
  EXPECT_EQ(r.slip_increment, 0.0);
  EXPECT_EQ(r.dissipation, 0.0);
}

TEST(ContactKernel, SlipAtCoulombLimitWithSlipLengthAndDissipation) {
  const auto tool = plane();
  const double mu = 0.3;
  // Motion (0.03, 0.04): trial |t| = 50 * 0.05 = 2.5 > mu p = 0.6.
  const auto r = evaluate_contact(tool, law(mu), ContactHistory{}, vec(1.03, 1.04, -0.02), vec(1, 1, 0));
  ASSERT_TRUE(r.slipping);
  EXPECT_NEAR(r.tangential_traction.norm(), mu * r.pressure, 1e-12);
  EXPECT_NEAR(r.tangential_traction[0] / r.tangential_traction[1], 0.75, 1e-12);
  EXPECT_LT(r.tangential_traction[0], 0.0);
  const double slip = 0.05 - 0.6 / 50.0;  // total motion minus the elastic stick part
  EXPECT_NEAR(r.slip_increment, slip, 1e-12);
  EXPECT_NEAR(r.dissipation, 0.6 * slip, 1e-12);
  // Continued sliding from a committed slipping state: all of the motion is slip.
  ContactHistory sliding;
  sliding.tangential_traction = r.tangential_traction;
  const auto next = evaluate_contact(tool, law(mu), sliding, vec(1.06, 1.08, -0.02), vec(1.03, 1.04, 0));
  EXPECT_NEAR(next.slip_increment, 0.05, 1e-12);
  EXPECT_NEAR(next.dissipation, 0.6 * 0.05, 1e-12);
}

// Central differences of the traction with respect to x, compared to the kernel stiffness.
double tangent_error(const ToolGeometry& tool, const ContactLaw& l, const ContactHistory& h, const Vector3& x,
                     const Vector3& anchor, bool expect_slip) {
  const auto r = evaluate_contact(tool, l, h, x, anchor);
  EXPECT_TRUE(r.active);
  EXPECT_EQ(r.slipping, expect_slip);
  const double step = 1e-6;
  double error = 0.0, scale = 0.0;
  for (unsigned j = 0; j < 3; ++j) {
    Vector3 plus = x, minus = x;
    plus[j] += step;
    minus[j] -= step;
    const Vector3 d = (evaluate_contact(tool, l, h, plus, anchor).traction -
                       evaluate_contact(tool, l, h, minus, anchor).traction) /
                      (2.0 * step);
    for (unsigned i = 0; i < 3; ++i) {
      error = std::max(error, std::abs(d[i] - r.stiffness[i][j]));
      scale = std::max(scale, std::abs(r.stiffness[i][j]));
    }
  }
  return error / scale;
}

TEST(ContactKernel, TangentMatchesFiniteDifferencesOnPlane) {
  const auto tool = plane();
  ContactHistory h;
  h.tangential_traction = vec(0.1, -0.05, 0.0);
  EXPECT_LT(tangent_error(tool, law(0.3), h, vec(1.002, 0.999, -0.02), vec(1, 1, 0), false), 1e-6);
  EXPECT_LT(tangent_error(tool, law(0.3), h, vec(1.03, 0.98, -0.02), vec(1, 1, 0), true), 1e-6);
  EXPECT_LT(tangent_error(tool, law(0.0), h, vec(1.03, 0.98, -0.02), vec(1, 1, 0), false), 1e-6);
}

TEST(ContactKernel, TangentMatchesFiniteDifferencesOnCylinder) {
  const auto tool = cylinder();
  const Vector3 radial = vec(0.2, -0.4, 1.0) - (vec(0.2, -0.4, 1.0) * tool.direction) * tool.direction;
  const Vector3 n = radial / radial.norm();
  const Vector3 t1 = cross_product_3d(tool.direction, n);
  const Vector3 x = tool.point + 2.0 * tool.direction + 9.98 * n;  // gap -0.02, p = 2
  // Committed traction from a neighbouring tangent plane: exercises its transport terms.
  ContactHistory h;
  h.tangential_traction = 0.2 * t1 - 0.1 * tool.direction + 0.05 * n;
  h.multiplier = 0.5;
  const Vector3 small = 0.002 * t1 + 0.001 * tool.direction;
  const Vector3 large = 0.05 * t1 - 0.03 * tool.direction;
  EXPECT_LT(tangent_error(tool, law(0.3), h, x, x - small, false), 1e-6);
  EXPECT_LT(tangent_error(tool, law(0.3), h, x, x - large, true), 1e-6);
  EXPECT_LT(tangent_error(tool, law(0.0), h, x, x - large, false), 1e-6);
}

}  // namespace
}  // namespace dtwire::fem::contact

namespace dtwire::fem::contact {
namespace {

// Plate z = 0 (outward normal +z) with a groove of radius 2 along x through the origin.
ToolGeometry grooved_plate() {
  ToolGeometry t;
  t.shape = ToolShape::grooved_plate;
  t.point = vec(0, 0, 0);
  t.direction = vec(0, 0, 1);
  t.groove_axis = vec(1, 0, 0);
  t.radius = 2.0;
  return t;
}

TEST(ContactKernel, GroovedPlateGapAndNormal) {
  const auto tool = grooved_plate();
  // On the flat part, beside the groove.
  auto p = tool.project(vec(5.0, 3.0, -0.1));
  EXPECT_NEAR(p.gap, -0.1, 1e-14);
  EXPECT_NEAR(p.normal[2], 1.0, 1e-14);
  // Inside the channel, clear of the wall: open.
  p = tool.project(vec(5.0, 0.5, -1.0));
  EXPECT_GT(p.gap, 0.0);
  // Pressed into the groove wall at 45 degrees below the plate: normal towards the axis.
  const double s = std::sqrt(0.5);
  p = tool.project(vec(1.0, 2.1 * s, -2.1 * s));
  EXPECT_NEAR(p.gap, -0.1, 1e-12);
  EXPECT_NEAR(p.normal[1], -s, 1e-12);
  EXPECT_NEAR(p.normal[2], s, 1e-12);
  EXPECT_NEAR(tool.project(vec(0.0, 0.0, 0.0)).gap, 2.0, 1e-14);  // on the groove axis
}

TEST(ContactKernel, TangentMatchesFiniteDifferencesOnGrooveWall) {
  const auto tool = grooved_plate();
  const double s = std::sqrt(0.5);
  const Vector3 n = vec(0.0, -s, s);
  const Vector3 x = vec(1.0, 2.02 * s, -2.02 * s);  // gap -0.02 on the wall
  const Vector3 along = vec(1, 0, 0), around = vec(0, s, s);
  ContactHistory h;
  h.tangential_traction = 0.2 * along - 0.1 * around + 0.05 * n;
  EXPECT_LT(tangent_error(tool, law(0.3), h, x, x - 0.002 * along, false), 1e-6);
  EXPECT_LT(tangent_error(tool, law(0.3), h, x, x - 0.05 * along + 0.03 * around, true), 1e-6);
  EXPECT_LT(tangent_error(tool, law(0.0), h, x, x - 0.05 * along, false), 1e-6);
}

}  // namespace
}  // namespace dtwire::fem::contact
