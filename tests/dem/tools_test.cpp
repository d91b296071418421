// Rigid tools: geometry (nearest points), a node resting on a wall, sliding and rolling down an
// incline with Coulomb friction, and the free truncated-cube boulder (6-DOF flight, momentum in a
// collision).
#include <gtest/gtest.h>

#include <cmath>

#include "dtwire/dem/engine.hpp"

namespace dtwire::dem {
namespace {

constexpr double kPi = 3.14159265358979323846;

NetNode free_node(const Vector3& p, double mass = 0.004, double radius = 0.0054) {
  NetNode node;
  node.position = p;
  node.mass = mass;
  node.radius = radius;
  node.rotational_inertia = 0.4 * mass * radius * radius;
  return node;
}

TEST(DemTools, NearestPointOnEllipseIsOrthogonalAndOnTheCurve) {
  const double A = 0.5, B = 0.181;
  for (double x : {0.0, 0.1, 0.3, 0.49, 0.7}) {
    for (double y : {0.0, 0.05, 0.17, 0.3}) {
      if (x == 0.0 && y == 0.0) continue;
      const Eigen::Vector2d p = nearest_on_ellipse(A, B, x, y);
      EXPECT_NEAR(std::pow(p.x() / A, 2) + std::pow(p.y() / B, 2), 1.0, 1e-12);
      // Brute force over the quarter ellipse: no point is nearer (1e-9 m).
      double best = 1e300;
      for (int k = 0; k <= 200000; ++k) {
        const double t = 0.5 * kPi * k / 200000.0;
        best = std::min(best, std::hypot(A * std::cos(t) - x, B * std::sin(t) - y));
      }
      EXPECT_NEAR(std::hypot(p.x() - x, p.y() - y), best, 1e-9) << x << "," << y;
    }
  }
}

TEST(DemTools, PlatterAndBoulderSignedDistances) {
  SemiSpheroidPlatter platter(0.5, 0.181);
  platter.position = Vector3(1, 2, 3);
  SurfacePoint s;
  ASSERT_TRUE(platter.nearest(Vector3(1, 2, 3.2), 0.1, s));
  EXPECT_NEAR(s.distance, 0.2 - 0.181, 1e-14);  // above the apex
  EXPECT_NEAR(s.normal.z(), 1.0, 1e-14);
  ASSERT_TRUE(platter.nearest(Vector3(1.52, 2, 3.0 + 1e-9), 0.1, s));
  EXPECT_NEAR(s.distance, 0.02, 1e-6);  // beside the rim, at the base level
  ASSERT_TRUE(platter.nearest(Vector3(1, 2, 3.1), 0.1, s));
  EXPECT_NEAR(s.distance, -0.081, 1e-12);  // inside, nearest to the apex
  EXPECT_FALSE(platter.nearest(Vector3(1, 2, 3.5), 0.1, s));
  TruncatedCube cube(0.3, 0.1875);
  ASSERT_TRUE(cube.nearest(Vector3(0, 0, 0.16), 0.05, s));
  EXPECT_NEAR(s.distance, 0.01, 1e-14);
  ASSERT_TRUE(cube.nearest(Vector3(0.15, 0.15, 0.15), 0.2, s));  // cut corner: plane x+y+z = 0.1875
  EXPECT_NEAR(s.distance, (0.45 - 0.1875) / std::sqrt(3.0), 1e-14);
  EXPECT_THROW(TruncatedCube(0.3, 0.1), std::invalid_argument);
}

TEST(DemTools, NodeRestingOnAWallCarriesItsWeight) {
  const double m = 0.004, r = 0.0054, kn = 1e6, g = 9.81;
  std::vector<NetNode> nodes{free_node(Vector3(0, 0, r), m, r)};
  EngineOptions options;
  options.local_damping = 0.5;
  Engine engine(nodes, {}, options);
  auto wall = std::make_unique<PlaneWall>(Vector3::UnitZ());
  wall->contact = {kn, kn, 0.3};
  engine.add_tool(std::move(wall));
  for (int k = 0; k < 20000; ++k) engine.step();
  EXPECT_NEAR(-engine.tool_force(0).z() / (m * g), 1.0, 1e-6);
  EXPECT_NEAR((r - engine.position(0).z()) / (m * g / kn), 1.0, 1e-6);  // penetration m g / kn
}

// Node released on an incline at angle theta; returns the distance travelled down the slope.
double slope_travel(double theta, double mu, double time) {
  const double r = 0.0054, m = 0.004;
  const Vector3 normal(0.0, -std::sin(theta), std::cos(theta));
  std::vector<NetNode> nodes{free_node(r * normal, m, r)};
  EngineOptions options;
  options.time_step = 2e-6;
  Engine engine(nodes, {}, options);
  auto wall = std::make_unique<PlaneWall>(normal);
  wall->contact = {1e7, 1e7, mu};
  engine.add_tool(std::move(wall));
  while (engine.time() < time) engine.step();
  const Vector3 up_slope(0.0, std::cos(theta), std::sin(theta));
  return -(engine.position(0) - r * normal).dot(up_slope);
}

TEST(DemTools, SlidingAndRollingDownAnInclineWithCoulombFriction) {
  const double g = 9.81, mu = 0.2, t = 0.2;
  // 45 deg: mu < (2/7) tan(theta), the sphere slides: a = g (sin - mu cos).
  const double sliding = slope_travel(kPi / 4, mu, t);
  EXPECT_NEAR(sliding / (0.5 * g * (std::sin(kPi / 4) - mu * std::cos(kPi / 4)) * t * t), 1.0, 0.01);
  // 20 deg: mu > (2/7) tan(theta), it rolls without slipping: a = (5/7) g sin (solid sphere).
  const double rolling = slope_travel(20.0 * kPi / 180.0, mu, t);
  EXPECT_NEAR(rolling / (0.5 * (5.0 / 7.0) * g * std::sin(20.0 * kPi / 180.0) * t * t), 1.0, 0.01);
}

TEST(DemTools, BoulderFliesFreelyAndConservesMomentumInACollision) {
  const double M = 44.5, side = 0.3;
  std::vector<NetNode> nodes{free_node(Vector3(0, 0, 0), 0.5)};
  EngineOptions options;
  options.gravity = Vector3::Zero();
  Engine engine(nodes, {}, options);
  auto cube = std::make_unique<TruncatedCube>(side, 0.1875);
  cube->mass = M;
  cube->rotational_inertia = M * side * side / 6.0;
  cube->position = Vector3(0.0, 0.0, 0.2);
  cube->angular_velocity = Vector3(0.0, 0.0, 2.0);  // spin about the fall axis
  cube->contact = {1e7, 1e6, 0.0};
  engine.add_tool(std::move(cube));
  engine.place_tool(0, Vector3(0.0, 0.0, 0.2), Vector3(0.0, 0.0, -3.2));
  const double momentum = -3.2 * M;
  const double energy = engine.energy().external();
  // The given kinetic energy is booked as work and as kinetic energy at once: balanced before the first step.
  EXPECT_NEAR(engine.energy().balance_error() / energy, 0.0, 1e-14);
  while (engine.time() < 0.05) engine.step();
  const double after = M * engine.tool(0).velocity.z() + 0.5 * engine.velocity(0).z();
  EXPECT_NEAR(after / momentum, 1.0, 1e-12);  // action = reaction
  EXPECT_LT(engine.velocity(0).z(), -3.2);    // the node was hit and flies ahead
  EXPECT_NEAR(engine.tool(0).angular_velocity.z(), 2.0, 1e-12);  // frictionless: spin kept
  // Torque-free isotropic rotation: the orientation is exp(omega t).
  const double angle = Eigen::AngleAxisd(engine.tool(0).orientation).angle();
  EXPECT_NEAR(angle, std::fmod(2.0 * engine.time(), 2 * kPi), 1e-9);
  // Elastic collision: the balance closes to the time-discretisation error of the contact onset
  // (measured 1.5e-3 at safety 0.5); tolerance 5e-3.
  EXPECT_NEAR(engine.energy().balance_error() / energy, 0.0, 5e-3);
}

}  // namespace
}  // namespace dtwire::dem
