// The engine against closed forms: a one-link oscillator (period, stability limit of the
// central-difference scheme), a hanging chain and a taut string under gravity (static
// solutions by dynamic relaxation), energy balance, 1 vs 2 threads. The settle's kinetic
// damping and unbalanced-force ratio: settle_damping_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <stdexcept>
#include <string>

#include "net_node_support.hpp"
#include "oscillator_support.hpp"
#include "dtwire/dem/engine.hpp"

namespace dtwire::dem {
namespace {

using test::elastic_bond;
using test::elastic_bond_stiffness;
using test::kPi;
using test::make_node;
using test::Oscillator;

// Tension-only wire (WirePM), elastic up to 250 MPa: no shear or bending stiffness (a string).
std::unique_ptr<ContactLaw> string_link(double length) {
  return make_contact_law("wirepm", {{"reference_length_m", length}, {"diameter_m", 0.0027},
                                     {"backbone_0_strain_1", 0.0019230769}, {"backbone_0_stress_Pa", 2.5e8},
                                     {"backbone_1_strain_1", 0.0192}, {"backbone_1_stress_Pa", 3.2195e8}});
}
double string_stiffness(double length) { return 2.5e8 / 0.0019230769 * kPi * 0.0027 * 0.0027 / 4.0 / length; }

TEST(DemEngine, OneLinkOscillatorPeriodMatchesClosedForm) {
  const Oscillator o;
  const double period = 2.0 * kPi / o.omega();
  Engine engine = o.make(period / 2000.0, 1e-5);
  // Upward zero crossings of the displacement, interpolated.
  std::vector<double> crossings;
  double previous = 1e-5;
  double previous_time = 0.0;
  while (engine.time() < 5.2 * period) {
    engine.step();
    const double u = engine.position(1).x() - o.length;
    if (previous < 0.0 && u >= 0.0) crossings.push_back(previous_time + (engine.time() - previous_time) * (-previous) / (u - previous));
    previous = u;
    previous_time = engine.time();
  }
  ASSERT_GE(crossings.size(), 4u);
  const double measured = (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
  // Central differences shorten the period by (omega dt)^2 / 24 = 4e-7 here; tolerance 1e-4.
  EXPECT_NEAR(measured / period, 1.0, 1e-4);
}

// A change of step (a parked tool placed) takes the variable-step central differences: the free
// oscillation keeps its closed-form amplitude across a doubling of the step: within 1.5e-3, three
// times the scheme's (omega dt)^2 / 8 = 5e-4 plus the sampling's 5e-4 at the coarser step
// (measured 3.7e-4; the constant-step update at the switch gives 4.8e-3 at this phase).
TEST(DemEngine, AChangeOfStepKeepsTheOscillationsAmplitude) {
  const Oscillator o;
  const double period = 2.0 * kPi / o.omega(), amplitude = 1e-5;
  Engine engine = o.make(period / 200.0, amplitude);
  while (engine.time() < 3.3 * period) engine.step();
  engine.set_time_step(period / 100.0);
  const double switched = engine.time();
  double largest = 0.0;
  while (engine.time() < switched + 3.0 * period) {
    engine.step();
    largest = std::max(largest, std::abs(engine.position(1).x() - o.length));
  }
  std::cout << "amplitude after the change / before: " << largest / amplitude << "\n";
  EXPECT_NEAR(largest / amplitude, 1.0, 1.5e-3);
}

TEST(DemEngine, CriticalStepIsAConservativeBoundAndTheSchemeDivergesAboveTheTrueOne) {
  const Oscillator o;
  const double exact = 2.0 / o.omega();  // central-difference limit of the axial mode
  const Engine probe = o.make(exact / 10.0, 1e-6);
  // The engine's bound includes the bond's shear-rotation modes: at most the axial limit.
  EXPECT_LE(probe.critical_time_step(), exact * (1.0 + 1e-12));
  EXPECT_GT(probe.critical_time_step(), 0.05 * exact);
  auto largest_amplitude = [&](double dt) {
    Engine engine = o.make(dt, 1e-6);
    double largest = 0.0;
    for (int k = 0; k < 400; ++k) {
      engine.step();
      largest = std::max(largest, std::abs(engine.position(1).x() - o.length));
    }
    return largest;
  };
  EXPECT_LT(largest_amplitude(0.98 * exact), 1e-5);  // bounded (amplification ~5 near the limit)
  EXPECT_GT(largest_amplitude(1.02 * exact), 1e-3);  // grows without bound
  // An explicit step above the bound is refused.
  EngineOptions options;
  options.time_step = 1.01 * probe.critical_time_step();
  std::vector<NetNode> nodes{make_node(Vector3::Zero(), o.mass, NodeFixity::Pinned), make_node(Vector3(o.length, 0, 0), o.mass)};
  std::vector<EngineLink> links;
  links.push_back({{0, 1, LinkTag::SingleWire}, elastic_bond(o.length)});
  EXPECT_THROW(Engine(nodes, std::move(links), options), std::invalid_argument);
}

// Rotational density scaling (EngineOptions::rotational_inertia_scale, issue 35): on a cantilever
// link whose free node has the wire's radius, the spin of the node sets the critical step; a
// heavier spin raises it up to the axial limit 2 / omega_axial, leaves the axial vibration's period
// (closed form 2 pi sqrt(m / k)) and the static deflection under gravity unchanged.
TEST(DemEngine, RotationalInertiaScaleRaisesTheStepAndLeavesStaticsAndAxialDynamicsAlone) {
  const double mass = 0.0043, length = 0.05, k = elastic_bond_stiffness(length);
  auto make = [&](double scale, double dt, const Vector3& gravity, double damping) {
    NetNode root = make_node(Vector3::Zero(), mass, NodeFixity::Pinned), tip = make_node(Vector3(length, 0, 0), mass);
    tip.radius = 0.00135;
    tip.rotational_inertia = 0.4 * mass * tip.radius * tip.radius;
    std::vector<NetNode> nodes{root, tip};
    std::vector<EngineLink> links;
    links.push_back({{0, 1, LinkTag::SingleWire}, elastic_bond(length)});
    EngineOptions options;
    options.gravity = gravity;
    options.local_damping = damping;
    options.rotational_inertia_scale = scale;
    options.time_step = dt;
    return Engine(nodes, std::move(links), options);
  };
  const double axial_limit = 2.0 / std::sqrt(k / mass);
  const double step_1 = make(1.0, 0.0, Vector3::Zero(), 0.0).critical_time_step();
  const double step_100 = make(100.0, 0.0, Vector3::Zero(), 0.0).critical_time_step();
  std::cout << "critical step: spin x1 " << step_1 << " s, x100 " << step_100 << " s, axial limit " << axial_limit << " s\n";
  EXPECT_GT(step_100, 1.2 * step_1);  // the spin limited the step
  EXPECT_LE(step_100, axial_limit * (1.0 + 1e-12));

  // Axial free vibration at the scaled spin's step: the period of the closed form.
  const double period = 2.0 * kPi * std::sqrt(mass / k);
  Engine vibrating = make(100.0, period / 2000.0, Vector3::Zero(), 0.0);
  vibrating.impose_positions({Vector3::Zero(), Vector3(length + 1e-5, 0, 0)});
  std::vector<double> crossings;
  double previous = 1e-5, previous_time = 0.0;
  while (vibrating.time() < 5.2 * period) {
    vibrating.step();
    const double u = vibrating.position(1).x() - length;
    if (previous < 0.0 && u >= 0.0) crossings.push_back(previous_time + (vibrating.time() - previous_time) * (-previous) / (u - previous));
    previous = u;
    previous_time = vibrating.time();
  }
  ASSERT_GE(crossings.size(), 4u);
  EXPECT_NEAR((crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1) / period, 1.0, 1e-4);

  // Static tip deflection under a lateral gravity, relaxed with each spin: the same state.
  const Vector3 lateral(0.0, 0.0, -9.81);
  Engine light = make(1.0, 0.0, lateral, 0.7), heavy = make(100.0, 0.0, lateral, 0.7);
  ASSERT_TRUE(light.relax(1e-8, 5000000).converged);
  ASSERT_TRUE(heavy.relax(1e-8, 5000000).converged);
  const double deflection = length - light.position(1).x() + std::abs(light.position(1).z());
  std::cout << "tip: x1 " << light.position(1).transpose() << ", x100 " << heavy.position(1).transpose() << "\n";
  ASSERT_GT(deflection, 0.0);
  EXPECT_LT((light.position(1) - heavy.position(1)).norm(), 1e-4 * std::abs(light.position(1).z()));
}

TEST(DemEngine, HangingChainStaticExtensionMatchesClosedForm) {
  const int count = 8;  // node 0 pinned, nodes 1..7 hang below
  const double mass = 0.004, spacing = 0.05, g = 9.81;
  std::vector<NetNode> nodes;
  std::vector<EngineLink> links;
  for (int j = 0; j < count; ++j) nodes.push_back(make_node(Vector3(0, 0, -j * spacing), mass, j == 0 ? NodeFixity::Pinned : NodeFixity::Free));
  for (int j = 1; j < count; ++j) links.push_back({{j - 1, j, LinkTag::SingleWire}, string_link(spacing)});
  EngineOptions options;
  options.local_damping = 0.7;
  Engine engine(nodes, std::move(links), options);
  const RelaxResult relaxed = engine.relax(1e-7, 2000000);
  ASSERT_TRUE(relaxed.converged) << relaxed.force_ratio;
  const double k = string_stiffness(spacing);
  double expected = 0.0;
  for (int j = 1; j < count; ++j) {
    expected += (count - j) * mass * g / k;  // link j carries the nodes j..count-1
    const double stretch = -engine.position(j).z() - j * spacing;
    EXPECT_NEAR(stretch / expected, 1.0, 1e-5) << "node " << j;  // elastic; relaxed to 1e-7 of the link force
  }
}

TEST(DemEngine, TautStringUnderGravityTakesTheDiscreteParabola) {
  const int segments = 10;
  const double mass = 0.004, spacing = 0.05, g = 9.81, strain = 2e-4;
  std::vector<NetNode> nodes;
  std::vector<EngineLink> links;
  for (int j = 0; j <= segments; ++j)
    nodes.push_back(make_node(Vector3(j * spacing, 0, 0), mass, j == 0 || j == segments ? NodeFixity::Pinned : NodeFixity::Free));
  for (int j = 1; j <= segments; ++j) links.push_back({{j - 1, j, LinkTag::SingleWire}, string_link(spacing)});
  EngineOptions options;
  options.local_damping = 0.7;
  Engine engine(nodes, std::move(links), options);
  std::vector<Vector3> stretched;
  for (int j = 0; j <= segments; ++j) stretched.emplace_back(j * spacing * (1.0 + strain), 0, 0);
  engine.impose_positions(stretched);
  ASSERT_TRUE(engine.relax(1e-10, 4000000).converged);
  // Horizontal tension H from the first link; equal loads m g at equal spacing a give
  // z_j = -(a m g / 2H) j (N - j) (a funicular polygon on a parabola).
  const double a = spacing * (1.0 + strain);
  const Vector3 first = engine.position(1) - engine.position(0);
  const double H = engine.link(0).law->forces()[0] * first.x() / first.norm();
  for (int j = 1; j < segments; ++j) {
    const double expected = -(a * mass * g / (2.0 * H)) * j * (segments - j);
    EXPECT_NEAR(engine.position(j).z() / expected, 1.0, 2e-3) << "node " << j;  // horizontal spacing changes by ~1e-4
  }
}

// The hanging chain released from a 1 % stretch (beyond yield, links snapping slack): gravity,
// plastic work and damping all act. The balance error is the time discretisation's (trapezoidal
// link work across the slack and yield kinks against the law's exact energy): second order.
double chain_balance_error(double safety, EnergySplit* split = nullptr) {
  const int count = 6;
  std::vector<NetNode> nodes;
  std::vector<EngineLink> links;
  std::vector<Vector3> imposed;
  for (int j = 0; j < count; ++j) {
    nodes.push_back(make_node(Vector3(0, 0, -j * 0.05), 0.004, j == 0 ? NodeFixity::Pinned : NodeFixity::Free));
    imposed.emplace_back(0.001 * j, 0, -j * 0.0505);
  }
  for (int j = 1; j < count; ++j) links.push_back({{j - 1, j, LinkTag::SingleWire}, string_link(0.05)});
  EngineOptions options;
  options.local_damping = 0.3;
  options.safety = safety;
  Engine engine(nodes, std::move(links), options);
  engine.impose_positions(imposed);
  const double duration = 20000 * engine.critical_time_step() * 0.5;
  while (engine.time() < duration) engine.step();
  if (split) *split = engine.energy();
  return std::abs(engine.energy().balance_error()) / engine.energy().external();
}

TEST(DemEngine, EnergyBalanceClosesWithGravityDampingAndPlasticity) {
  EnergySplit split;
  const double coarse = chain_balance_error(0.5, &split);
  EXPECT_GT(split.link_plastic, 0.0);
  EXPECT_GT(split.damping, 0.0);
  EXPECT_LT(coarse, 0.01);  // measured 0.30 % on this violent snap-back (issue: < 2 %)
  EXPECT_LT(chain_balance_error(0.1), 0.1 * coarse);  // second order: 25x smaller expected
}

// Every loop of the step's parallel region split between threads: a sagging chain of 600 links
// (three link blocks of 256), a wall it falls onto (the tools' loop) and a roller pressing it
// from above (the rollers' loop); its ends pinned.
TEST(DemEngine, OneAndTwoThreadsGiveIdenticalStates) {
  auto run = [](int threads) {
    std::vector<NetNode> nodes;
    std::vector<EngineLink> links;
    const int n = 600;
    const double spacing = 0.005;
    for (int j = 0; j <= n; ++j)
      nodes.push_back(make_node(Vector3(j * spacing, 0.001 * std::sin(j), 0), 0.004, j == 0 || j == n ? NodeFixity::Pinned : NodeFixity::Free));
    for (int j = 1; j <= n; ++j)
      links.push_back({{j - 1, j, LinkTag::SingleWire}, j % 2 ? elastic_bond(spacing) : string_link(spacing)});
    EngineOptions options;
    options.local_damping = 0.2;
    options.threads = threads;
    options.parallel_threshold = 0;
    Engine engine(nodes, std::move(links), options);
    auto wall = std::make_unique<PlaneWall>(Vector3::UnitZ());
    wall->position = Vector3(0.0, 0.0, -0.002);
    wall->contact.normal_stiffness = 1e5;
    wall->contact.shear_stiffness = 1e4;
    wall->contact.friction = 0.3;
    engine.add_tool(std::move(wall));
    Roller roller;
    roller.point = Vector3(0.5 * n * spacing, 0.0, 0.01);
    roller.axis = Vector3::UnitY();
    roller.radius = 0.01;
    roller.velocity = Vector3(0.0, 0.0, -0.05);
    roller.contact.normal_stiffness = 1e5;
    roller.contact.shear_stiffness = 1e4;
    roller.contact.friction = 0.2;
    engine.add_roller(roller, std::vector<double>(static_cast<std::size_t>(n), 0.00135));
    for (int k = 0; k < 3000; ++k) engine.step();
    EXPECT_GT(engine.tool_contacts(0), 0u);  // the loops under test did work
    EXPECT_GT(engine.roller_contacts(0), 0u);
    std::vector<double> state;
    for (int j = 0; j <= n; ++j)
      for (int c = 0; c < 3; ++c) state.push_back(engine.position(j)[c]);
    state.push_back(engine.energy().balance_error());
    state.push_back(engine.tool_force(0).z());
    state.push_back(engine.roller_force(0).z());
    return state;
  };
  EXPECT_EQ(run(1), run(2));  // bit-identical
}

// A guided node's velocity can be changed between steps (dem_specimen moves its grips by an
// increment, then holds them); a free node's cannot. The moment of the links on a clamped node
// is reported: a cantilever link bent by a transverse tip displacement delta (tip rotation
// held) carries V = k_s delta and a moment V L / 2 at each end.
// A tool added parked (the punch platter while the net settles) acts on nothing and stays out of
// the stability bound until it is placed; then the step drops to the bound with its contact
// (Gershgorin: k_link (1/m) + k_n / m for a node on a pinned link touching a wall), and a fixed
// step that the placed tool would make unstable is refused when the tool is added.
TEST(DemEngine, AParkedToolActsOnNothingUntilPlacedAndThenSetsTheStep) {
  const Oscillator o;
  auto make = [&](double fixed_step) {
    std::vector<NetNode> nodes{make_node(Vector3::Zero(), o.mass, NodeFixity::Pinned), make_node(Vector3(o.length, 0, 0), o.mass)};
    std::vector<EngineLink> links;
    links.push_back({{0, 1, LinkTag::SingleWire}, elastic_bond(o.length)});
    EngineOptions options;
    options.gravity = Vector3(0.0, 0.0, -9.81);
    options.time_step = fixed_step;
    return Engine(nodes, std::move(links), options);
  };
  auto wall = [] {
    auto w = std::make_unique<PlaneWall>(-Vector3::UnitX());
    w->contact.normal_stiffness = 1e9;
    w->contact.shear_stiffness = 0.0;
    return w;
  };
  Engine engine = make(0.0);
  const double bare = engine.critical_time_step(), bare_step = engine.time_step();
  auto parked = wall();
  parked->position = Vector3(0.01, 0.0, 0.0);  // the free node is inside its half-space: it would be pushed
  engine.add_tool(std::move(parked), /*parked=*/true);
  EXPECT_EQ(engine.critical_time_step(), bare);
  EXPECT_EQ(engine.time_step(), bare_step);
  for (int k = 0; k < 50; ++k) engine.step();
  EXPECT_EQ(engine.tool_contacts(0), 0u);
  EXPECT_EQ(engine.tool_force(0).norm(), 0.0);
  EXPECT_LT(engine.position(1).z(), 0.0);  // falling under gravity, untouched by the parked wall

  // Placed as an end stop 1 mm into the free node's side (normal -x): only that node touches it.
  engine.place_tool(0, Vector3(o.length - 0.001, 0.0, 0.0), Vector3::Zero());
  EXPECT_LT(engine.critical_time_step(), bare);
  // Gershgorin at the free node: its link terms (2 / bare)^2 plus the wall's k_n / m.
  const double expected_bound = 2.0 / std::sqrt(1e9 / o.mass + std::pow(2.0 / bare, 2));
  EXPECT_NEAR(engine.critical_time_step() / expected_bound, 1.0, 1e-9);
  EXPECT_DOUBLE_EQ(engine.time_step(), 0.5 * engine.critical_time_step());
  engine.step();
  EXPECT_EQ(engine.tool_contacts(0), 1u);
  EXPECT_GT(engine.tool_force(0).x(), 0.0);  // the wall pushes the node back (-x), the node the wall (+x)
  Engine fixed = make(0.9 * bare);
  EXPECT_THROW(fixed.add_tool(wall(), /*parked=*/true), std::invalid_argument);
}

TEST(DemEngine, GuidedVelocityCanChangeAndMomentsAreReported) {
  const double length = 0.05;
  std::vector<NetNode> nodes{make_node(Vector3::Zero(), 0.01, NodeFixity::Guided),
                             make_node(Vector3(length, 0.0, 0.0), 0.01, NodeFixity::Guided)};
  std::vector<EngineLink> links;
  links.push_back({NetLink{0, 1}, elastic_bond(length)});
  EngineOptions options;
  options.gravity = Vector3::Zero();
  Engine engine(nodes, std::move(links), options);
  const double dt = engine.time_step();
  const double delta = 1e-6;
  engine.set_guided_velocity(1, Vector3(0.0, 0.0, delta / (10 * dt)));
  for (int i = 0; i < 10; ++i) engine.step();
  engine.set_guided_velocity(1, Vector3::Zero());
  engine.step();
  engine.step();
  EXPECT_NEAR(engine.position(1).z(), delta, 1e-15);
  const double shear = engine.link(0).law->forces().segment<2>(1).norm();
  EXPECT_GT(shear, 0.0);
  EXPECT_NEAR(std::abs(engine.unbalanced_force(1).z()), shear, 1e-9 * shear);
  EXPECT_NEAR(engine.unbalanced_moment(0).norm(), 0.5 * length * shear, 1e-9 * shear * length);
  EXPECT_NEAR(engine.unbalanced_moment(1).norm(), 0.5 * length * shear, 1e-9 * shear * length);
  std::vector<NetNode> free_nodes = nodes;
  free_nodes[1].fixity = NodeFixity::Free;
  std::vector<EngineLink> more;
  more.push_back({NetLink{0, 1}, elastic_bond(length)});
  Engine other(free_nodes, std::move(more), options);
  EXPECT_THROW(other.set_guided_velocity(1, Vector3::Zero()), std::invalid_argument);
}

// A slider support (the thesis's pre-load edges): held along the pull and free along the edge.
// Node 1 is held in x and z and free in y; gravity along -y pulls it down the slider until the
// string link's tension balances it: T y / l = m g with T = k (l - L), l = sqrt(L^2 + y^2).
// Then the slider is moved along x at a prescribed speed and stopped: the support's work is
// booked (boundary work) and the energy balance closes; the held components never move but
// with the support.
TEST(DemEngine, SliderSupportIsFreeAlongTheEdgeAndItsPrescribedMotionDoesWork) {
  const double length = 0.05, mass = 0.004, g = 9.81;
  std::vector<NetNode> nodes{make_node(Vector3::Zero(), mass, NodeFixity::Pinned), make_node(Vector3(length, 0.0, 0.0), mass)};
  nodes[1].held_translation = {true, false, true};
  std::vector<EngineLink> links;
  links.push_back({NetLink{0, 1}, string_link(length)});
  EngineOptions options;
  options.gravity = Vector3(0.0, -g, 0.0);
  options.local_damping = 0.7;
  Engine engine(nodes, std::move(links), options);
  ASSERT_TRUE(engine.relax(1e-9, 4000000).converged);
  const double k = string_stiffness(length);
  double low = 0.0, high = length;  // y where k (l - L) y / l = m g (bisection)
  for (int i = 0; i < 200; ++i) {
    const double y = 0.5 * (low + high), l = std::hypot(length, y);
    (k * (l - length) * y / l > mass * g ? high : low) = y;
  }
  EXPECT_NEAR(-engine.position(1).y() / low, 1.0, 1e-5);  // relaxed to 1e-9 of the link force
  EXPECT_EQ(engine.position(1).x(), length);
  EXPECT_EQ(engine.position(1).z(), 0.0);

  // The slider pulled 0.1 mm along x, then held; the support's reaction did the work.
  const double pull = 1e-4, speed = 1e-3;
  engine.set_guided_velocity(1, Vector3(speed, 0.0, 0.0));
  const long pull_steps = std::lround(pull / speed / engine.time_step());
  for (long i = 0; i < pull_steps; ++i) engine.step();
  engine.set_guided_velocity(1, Vector3::Zero());
  ASSERT_TRUE(engine.relax(1e-9, 4000000).converged);
  EXPECT_NEAR(engine.position(1).x(), length + pull_steps * speed * engine.time_step(), 1e-13);  // round-off of the steps
  const EnergySplit& e = engine.energy();
  EXPECT_GT(e.boundary_work, 0.0);
  // tol: the trapezoidal support work against the law's exact energy, second order in the step
  EXPECT_LT(std::abs(e.balance_error()), 1e-4 * e.external());
  EXPECT_THROW(engine.set_guided_velocity(0, Vector3::Zero()), std::invalid_argument);  // pinned: no slider
}

// set_support holds a falling node where it is: the kinetic energy of the held components is
// taken out by the support and booked, so the balance still closes.
TEST(DemEngine, HoldingAMovingNodeBooksItsKineticEnergy) {
  std::vector<NetNode> nodes{make_node(Vector3::Zero(), 0.004, NodeFixity::Pinned), make_node(Vector3(0.05, 0.0, 0.0), 0.004)};
  std::vector<EngineLink> links;
  links.push_back({NetLink{0, 1}, string_link(0.05)});
  EngineOptions options;
  Engine engine(nodes, std::move(links), options);
  for (int i = 0; i < 2000; ++i) engine.step();  // swings down
  ASSERT_GT(engine.energy().kinetic, 0.0);
  engine.set_support(1, {true, true, true}, true);
  for (int i = 0; i < 100; ++i) engine.step();
  const Vector3 held = engine.position(1);
  for (int i = 0; i < 100; ++i) engine.step();
  EXPECT_EQ(engine.position(1), held);
  EXPECT_EQ(engine.energy().kinetic, 0.0);
  // The support took the fall's kinetic energy (boundary work about minus the gravity work):
  // the balance is judged against the gravity work.
  EXPECT_LT(engine.energy().boundary_work, 0.0);
  EXPECT_LT(std::abs(engine.energy().balance_error()), 1e-3 * engine.energy().gravity_work);
  EXPECT_THROW(engine.set_support(0, {true, true, true}, true), std::invalid_argument);  // pinned
}

// A slider node with every component held has no mode of its own: its springs (a light node's
// link, a wall's contact) leave the automatic step alone, which follows set_support both ways:
// up when the light node m is held (Gershgorin at the free node M: its two links, k / M each,
// and the wall's k_n / M), back down when it is released (the larger of k (2/M + 1/m) + k_n / M
// and k (1/M + 1/m) + k_n / m). A fixed step is checked as if every slider were free.
TEST(DemEngine, HeldSliderComponentsLeaveTheAutomaticStepAndReleasingThemBringsItBack) {
  const double heavy = 0.004, light = 0.0004, length = 0.05, kn = 1e6;
  auto make = [&](double fixed_step) {
    std::vector<NetNode> nodes{make_node(Vector3::Zero(), heavy, NodeFixity::Pinned),
                               make_node(Vector3(length, 0, 0), heavy), make_node(Vector3(2 * length, 0, 0), light)};
    nodes[2].held_translation = {true, true, true};
    nodes[2].held_rotation = true;
    std::vector<EngineLink> links;
    links.push_back({{0, 1, LinkTag::SingleWire}, string_link(length)});
    links.push_back({{1, 2, LinkTag::SingleWire}, string_link(length)});
    EngineOptions options;
    options.gravity = Vector3::Zero();
    options.time_step = fixed_step;
    return Engine(nodes, std::move(links), options);
  };
  const double ks = string_stiffness(length);
  Engine engine = make(0.0);
  auto wall = std::make_unique<PlaneWall>(Vector3::UnitZ());
  wall->position = Vector3(0.0, 0.0, -1.0);  // far below: touches nothing, counts in the bound
  wall->contact.normal_stiffness = kn;
  wall->contact.shear_stiffness = 0.0;
  engine.add_tool(std::move(wall));
  // Held: the free node's two links, each k / M (the held end adds no 1/m), and the wall's kn / M.
  const double held_bound = 2.0 / std::sqrt(2.0 * ks / heavy + kn / heavy);
  EXPECT_NEAR(engine.critical_time_step() / held_bound, 1.0, 1e-9);
  EXPECT_NEAR(engine.time_step() / (0.5 * held_bound), 1.0, 1e-9);
  engine.set_support(2, {false, false, false}, false);
  engine.step();  // the step follows the release before it moves anything
  const double free_bound = 2.0 / std::sqrt(std::max(ks * (2.0 / heavy + 1.0 / light) + kn / heavy,
                                                      ks * (1.0 / heavy + 1.0 / light) + kn / light));
  EXPECT_NEAR(engine.critical_time_step() / free_bound, 1.0, 1e-9);
  EXPECT_NEAR(engine.time_step() / (0.5 * free_bound), 1.0, 1e-9);
  engine.set_support(2, {true, true, true}, true);
  engine.step();
  EXPECT_NEAR(engine.time_step() / (0.5 * held_bound), 1.0, 1e-9);
  // A fixed step above the bound with the slider released is refused, though held it is stable.
  Engine fixed = make(0.0);
  const double released = 2.0 / std::sqrt(ks * (2.0 / heavy + 1.0 / light));  // no wall here
  ASSERT_LT(1.1 * released, 2.0 / std::sqrt(2.0 * ks / heavy));
  EXPECT_THROW(fixed.set_time_step(1.1 * released), std::invalid_argument);
  EXPECT_NO_THROW(fixed.set_time_step(0.9 * released));
  EXPECT_THROW(make(1.1 * released), std::invalid_argument);
}

// A law that gives up inside the threaded link loop (the macro-element's "too many plastic
// substeps") ends the step with an exception that names the link, never a terminate (SIGABRT):
// `dem run` turns it into exit 1 with the message, `dem propagate` into a failed set.
class GivesUpAfterStretch final : public ContactLaw {
 public:
  void update(const Vector6& increment) override {
    stretch_ += increment[0];
    if (stretch_ > 1e-4) throw std::runtime_error("too many plastic substeps in one increment");
  }
  Vector6 forces() const override { return Vector6::Zero(); }
  EnergyAccount energy() const override { return {}; }
  bool broken() const override { return false; }
  std::string_view name() const override { return "gives_up"; }
  std::unique_ptr<ContactLaw> clone() const override { return std::make_unique<GivesUpAfterStretch>(*this); }

 private:
  double stretch_ = 0.0;
};

TEST(DemEngine, ALawThatGivesUpInTheThreadedLoopEndsTheStepWithItsLinkNamed) {
  for (const int threads : {1, 2}) {
    std::vector<NetNode> nodes;
    std::vector<EngineLink> links;
    for (int i = 0; i < 8; ++i) nodes.push_back(make_node(Vector3(0.05 * i, 0, 0), 0.0043, i == 0 ? NodeFixity::Pinned : NodeFixity::Free));
    for (std::size_t i = 0; i + 1 < nodes.size(); ++i) links.push_back({{static_cast<int>(i), static_cast<int>(i + 1), LinkTag::SingleWire}, std::make_unique<GivesUpAfterStretch>()});
    EngineOptions options;
    options.gravity = Vector3::Zero();
    options.time_step = 1e-6;
    options.allow_above_critical = true;
    options.threads = threads;
    options.parallel_threshold = 1;
    Engine engine(nodes, std::move(links), options);
    std::vector<Vector3> stretched;
    for (int i = 0; i < 8; ++i) stretched.push_back(Vector3(0.05 * i + (i == 7 ? 1e-3 : 0.0), 0, 0));
    engine.impose_positions(stretched);
    try {
      engine.step();
      ADD_FAILURE() << "no exception with " << threads << " thread(s)";
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find("link 6 (nodes 6-7)"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("too many plastic substeps"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace dtwire::dem
