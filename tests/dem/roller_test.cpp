// Rollers that touch links (dem/include/dtwire/dem/roller.hpp): the contact against closed forms
// (nearest point, penalty force, lever-rule split, Coulomb cap, no force when apart), in the
// engine on a node-free segment (reactions, work), and a chain of elastic links bent on three
// rollers against the beam formula.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "dtwire/dem/engine.hpp"

namespace dtwire::dem {
namespace {

constexpr double kPi = 3.14159265358979323846;
const double kR = 0.02, kWire = 0.00135, kKn = 1e7;

// A roller along z above the point (x, 0, 0), overlapping a wire of radius kWire on the x axis
// by `overlap`.
Roller roller_above(double x, double overlap, double friction = 0.0) {
  Roller r;
  r.point = Vector3(x, kR + kWire - overlap, 0.0);
  r.axis = Vector3::UnitZ();
  r.radius = kR;
  r.contact.normal_stiffness = kKn;
  r.contact.shear_stiffness = kKn;
  r.contact.friction = friction;
  return r;
}

TEST(DemRoller, MidSegmentForceSplitsHalfHalf) {
  const Vector3 a(0, 0, 0), b(0.04, 0, 0), zero = Vector3::Zero();
  Vector3 shear = Vector3::Zero();
  const SegmentContact c = roller_segment_contact(roller_above(0.02, 1e-5), a, b, kWire, zero, zero, 1e-6, shear);
  ASSERT_TRUE(c.touching);
  EXPECT_NEAR(c.where.s, 0.5, 1e-12);
  EXPECT_NEAR(c.penetration, 1e-5, 1e-15);
  EXPECT_NEAR(c.force.y(), -kKn * 1e-5, 1e-9);  // pushes the segment down, normal to both axes
  EXPECT_NEAR(c.force.x(), 0.0, 1e-12);
  EXPECT_NEAR(c.on_a.y(), 0.5 * c.force.y(), 1e-12);
  EXPECT_NEAR(c.on_b.y(), 0.5 * c.force.y(), 1e-12);
  EXPECT_NEAR(c.elastic_energy, 0.5 * kKn * 1e-10, 1e-12 * 0.5 * kKn * 1e-10);
}

TEST(DemRoller, QuarterPointSplitsThreeQuartersOneQuarterAndKeepsTheMoment) {
  const Vector3 a(0, 0, 0), b(0.04, 0, 0), zero = Vector3::Zero();
  Vector3 shear = Vector3::Zero();
  const SegmentContact c = roller_segment_contact(roller_above(0.01, 2e-5), a, b, kWire, zero, zero, 1e-6, shear);
  ASSERT_TRUE(c.touching);
  EXPECT_NEAR(c.where.s, 0.25, 1e-12);
  EXPECT_NEAR(c.force.norm(), kKn * 2e-5, 1e-9);
  EXPECT_NEAR((c.on_a - 0.75 * c.force).norm(), 0.0, 1e-12);
  EXPECT_NEAR((c.on_b - 0.25 * c.force).norm(), 0.0, 1e-12);
  // Statics: the shares have the force's resultant and its moment about any point.
  const Vector3 p(0.3, -0.2, 0.1), at(0.01, 0, 0);
  EXPECT_NEAR(((a - p).cross(c.on_a) + (b - p).cross(c.on_b) - (at - p).cross(c.force)).norm(), 0.0, 1e-12);
}

TEST(DemRoller, NearestPointOfASkewSegmentAndOfAnEndBeyondTheAxis) {
  // Segment from (0, 0, 0) to (0.04, 0, 0.04), roller axis along z through x = 0.01: nearest at
  // s = 1/4 (the distance from the axis is that of the x coordinate, in the x-y plane).
  Roller r = roller_above(0.01, 1e-5);
  SegmentPoint p = nearest_to_axis(r, Vector3::Zero(), Vector3(0.04, 0, 0.04));
  EXPECT_NEAR(p.s, 0.25, 1e-12);
  EXPECT_NEAR(p.distance, kR + kWire - 1e-5, 1e-15);
  // The axis beyond node b: the nearest point is the end itself.
  r.point.x() = 0.05;
  p = nearest_to_axis(r, Vector3::Zero(), Vector3(0.04, 0, 0));
  EXPECT_EQ(p.s, 1.0);
  EXPECT_NEAR(p.distance, std::hypot(0.01, kR + kWire - 1e-5), 1e-15);
}

TEST(DemRoller, NoForceWhenApartAndTheShearSpringIsReset) {
  const Vector3 a(0, 0, 0), b(0.04, 0, 0), zero = Vector3::Zero();
  Vector3 shear(1.0, 0.0, 0.0);
  const SegmentContact c = roller_segment_contact(roller_above(0.02, -1e-6), a, b, kWire, zero, zero, 1e-6, shear);
  EXPECT_FALSE(c.touching);
  EXPECT_EQ(c.force.norm(), 0.0);
  EXPECT_EQ(c.on_a.norm() + c.on_b.norm(), 0.0);
  EXPECT_EQ(shear.norm(), 0.0);
}

TEST(DemRoller, FrictionGrowsWithSlipUntilTheCoulombCap) {
  // The segment slides along x at 1 m/s under the roller: shear ks dt v (1 N) per step against
  // the slip, capped at mu kn delta (30 N) from the 30th step, then dissipates mu N x slip.
  const Vector3 a(0, 0, 0), b(0.04, 0, 0), v(1.0, 0, 0);
  const double dt = 1e-7, overlap = 1e-5, mu = 0.3;
  Vector3 shear = Vector3::Zero();
  SegmentContact c = roller_segment_contact(roller_above(0.02, overlap, mu), a, b, kWire, v, v, dt, shear);
  EXPECT_NEAR(c.force.x(), -kKn * dt * 1.0, 1e-9);
  for (int i = 0; i < 100; ++i) c = roller_segment_contact(roller_above(0.02, overlap, mu), a, b, kWire, v, v, dt, shear);
  EXPECT_NEAR(c.force.x(), -mu * kKn * overlap, 1e-9);
  EXPECT_NEAR(c.force.y(), -kKn * overlap, 1e-9);
  EXPECT_NEAR(c.friction_work, mu * kKn * overlap * v.x() * dt, 1e-12 * mu * kKn * overlap * v.x() * dt);
}

NetNode node_at(const Vector3& p, NodeFixity fixity) {
  NetNode node;
  node.position = p;
  node.mass = 1e-3;
  node.rotational_inertia = 1e-9;
  node.fixity = fixity;
  return node;
}

std::unique_ptr<ContactLaw> elastic_bond(double length, double diameter = 0.0027) {
  return make_contact_law("parallel_bond", {{"E_Pa", 2e11}, {"diameter_m", diameter}, {"length_m", length}});
}

TEST(DemRoller, ARollerPressedIntoANodeFreeSegmentLoadsItsEndNodesByTheLeverRule) {
  // A link between two held nodes; the roller comes down above x = 10 mm (s = 1/4) until it
  // overlaps the wire by delta: the penalty force kn delta, 3/4 of it on node a, 1/4 on b, and
  // the roller's work is the spring's energy (the link does not deform).
  std::vector<NetNode> nodes{node_at(Vector3::Zero(), NodeFixity::Pinned), node_at(Vector3(0.04, 0, 0), NodeFixity::Pinned)};
  std::vector<EngineLink> links;
  links.push_back({NetLink{0, 1}, elastic_bond(0.04)});
  EngineOptions options;
  options.gravity = Vector3::Zero();
  options.time_step = 1e-6;  // held nodes only: the critical step is unbounded
  Engine engine(std::move(nodes), std::move(links), options);
  Roller roller = roller_above(0.01, -1e-6);
  const double speed = 1e-2;
  roller.velocity = Vector3(0, -speed, 0);
  EXPECT_THROW(engine.add_roller(roller, {}), std::invalid_argument);
  EXPECT_THROW(engine.add_roller(roller, {-1.0}), std::invalid_argument);
  engine.add_roller(roller, {kWire});
  const double dt = engine.time_step();
  const int steps = 200;
  for (int i = 0; i < steps; ++i) engine.step();
  const double delta = speed * dt * (steps - 1) - 1e-6;  // the force is from the last step's start
  ASSERT_GT(delta, 0.0);
  EXPECT_EQ(engine.roller_contacts(0), 1u);
  EXPECT_NEAR(engine.roller_force(0).y(), kKn * delta, 1e-6 * kKn * delta);
  EXPECT_NEAR(engine.unbalanced_force(0).y(), -0.75 * kKn * delta, 1e-6 * kKn * delta);
  EXPECT_NEAR(engine.unbalanced_force(1).y(), -0.25 * kKn * delta, 1e-6 * kKn * delta);
  EXPECT_NEAR(engine.energy().contact_elastic, 0.5 * kKn * delta * delta, 1e-6 * kKn * delta * delta);
  EXPECT_NEAR(engine.energy().balance_error(), 0.0, 1e-3 * engine.energy().contact_elastic);
}

TEST(DemRoller, ChainOfElasticLinksBentOnThreeRollersFollowsTheBeamFormula) {
  // 48 parallel-bond links of 2.5 mm along x (d = 2.7 mm, E = 200 GPa) on two support rollers
  // under x = 11.25 and 111.25 mm (span 100 mm), the loading roller above x = 61.25 mm pressed
  // down step by step, all three at mid-link; frictionless, planar (z held), x held at one node.
  // The lever rule loads the nodes at +-h/2 of each roller: F/2, F/2 down at mid-span, F/4
  // twice up at each support. The roller moves by the relative deflection of these points
  // (roller's pair minus the supports' pairs, each averaged), by the unit-load method
  // delta = F int m^2 / (E I) dx with m the moment of that load pattern per unit F (Euler-
  // Bernoulli; the shear part is 0.1 %; m = F L / 4 would give L^3 / 48 EI, 0.4 % more), plus
  // the contacts' overlaps F / kn (loading) and F / (2 kn) (each support). The discrete chain
  // (midpoint shear, trapezoidal deflection per link) is within 2 (h/L)^2 = 0.13 % of the beam.
  // Kept small (20 um): as the beam turns by theta over a support the contact point moves in by
  // (R + r) theta (a roller's, as in the FE), which at 0.2 mm made the beam 0.5 % stiffer.
  const int n = 48;
  const double h = 0.0025, E = 2e11, d = 0.0027, kn = 1e8;
  std::vector<NetNode> nodes;
  for (int i = 0; i <= n; ++i) {
    NetNode node = node_at(Vector3(i * h, 0, 0), NodeFixity::Free);
    node.held_translation = {i == n / 2, false, true};  // planar; x held at mid-span
    nodes.push_back(node);
  }
  std::vector<EngineLink> links;
  for (int i = 0; i < n; ++i) links.push_back({NetLink{i, i + 1}, elastic_bond(h, d)});
  EngineOptions options;
  options.gravity = Vector3::Zero();
  options.local_damping = 0.7;
  Engine engine(std::move(nodes), std::move(links), options);
  const auto place = [&](double x, double side) {
    Roller r;
    r.point = Vector3(x, side * (kR + 0.5 * d), 0.0);
    r.axis = Vector3::UnitZ();
    r.radius = kR;
    r.contact.normal_stiffness = kn;
    r.contact.shear_stiffness = kn;
    r.contact.friction = 0.0;
    return engine.add_roller(r, std::vector<double>(n, 0.5 * d));
  };
  place(0.01125, -1.0);
  place(0.11125, -1.0);
  const int load = place(0.06125, 1.0);
  const double dt = engine.time_step(), target = 2e-5;
  const int move = 2000;
  engine.roller(load).velocity = Vector3(0, -target / (move * dt), 0);
  for (int i = 0; i < move; ++i) engine.step();
  engine.roller(load).velocity.setZero();
  const RelaxResult relaxed = engine.relax(1e-7, 400000);
  ASSERT_TRUE(relaxed.converged) << relaxed.force_ratio;
  std::cout << "beam on rollers: " << relaxed.steps << " relaxation steps\n";
  EXPECT_NEAR(kR + 0.5 * d - engine.roller(load).point.y(), target, 1e-12);
  const double force = engine.roller_force(load).y();
  const double inertia = kPi * std::pow(d, 4) / 64.0;
  const double loads[6][2] = {{0.010, 0.25}, {0.0125, 0.25}, {0.060, -0.5}, {0.0625, -0.5}, {0.110, 0.25}, {0.1125, 0.25}};
  double integral = 0.0;  // of m^2 over the span, trapezoidal on 0.1 um (m is piecewise linear)
  const int samples = 1000000;
  for (int k = 0; k <= samples; ++k) {
    const double x = 0.010 + 0.1025 * k / samples;
    double m = 0.0;
    for (const auto& load_at : loads)
      if (load_at[0] < x) m += load_at[1] * (x - load_at[0]);
    integral += (k == 0 || k == samples ? 0.5 : 1.0) * m * m * 0.1025 / samples;
  }
  const double compliance = integral / (E * inertia) + 1.5 / kn;
  std::cout << "beam on rollers: force " << force << " N, beam formula " << target / compliance << " N\n";
  EXPECT_NEAR(force, target / compliance, 0.003 * target / compliance);
  // Statics and symmetry: the supports carry half each.
  EXPECT_NEAR(engine.roller_force(0).y(), -0.5 * force, 1e-6 * force);
  EXPECT_NEAR(engine.roller_force(1).y(), -0.5 * force, 1e-6 * force);
  EXPECT_EQ(engine.roller_contacts(load), 1u);  // only the link under it (its neighbours' ends are 0.04 mm away)
}

}  // namespace
}  // namespace dtwire::dem
