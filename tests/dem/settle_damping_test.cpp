// The settle's kinetic damping (Barnes 1999) on the one-link oscillator, and YADE's
// unbalanced-force ratio that ends the settle (dem/src/settle.cpp; docs/dem_engine.md,
// "Settling to rest").
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <vector>

#include "oscillator_support.hpp"

namespace dtwire::dem {
namespace {

using test::elastic_bond;
using test::elastic_bond_stiffness;
using test::kPi;
using test::make_node;
using test::Oscillator;

// One step of the settle's kinetic damping (dem/src/settle.cpp): an arrest at the step whose
// kinetic energy fell below the step before's (`previous`); true when it arrested.
bool step_with_kinetic_damping(Engine& engine, double& previous) {
  engine.step();
  if (engine.kinetic_energy() < previous) {
    engine.arrest();
    previous = 0.0;
    return true;
  }
  previous = engine.kinetic_energy();
  return false;
}

// Kinetic damping (Barnes 1999): the undamped one-link oscillator, arrested at its first peak
// of kinetic energy, stops within a step of the equilibrium (the peak lies there): the amplitude
// left is at most omega dt of the initial one (one step's travel at the largest speed), against a
// swing that never decays without it. The kinetic energy the arrest takes out is booked as
// damping, so the balance of the linear bond (trapezoidal work exact) stays at round-off.
TEST(DemEngine, KineticDampingStopsTheSwingAtTheEquilibriumAndKeepsTheBalanceExact) {
  const Oscillator o;
  const double period = 2.0 * kPi / o.omega(), amplitude = 1e-5, dt = period / 200.0;
  Engine engine = o.make(dt, amplitude);
  double previous = 0.0;
  int arrests = 0;
  while (engine.time() < 3.0 * period) arrests += step_with_kinetic_damping(engine, previous);
  ASSERT_GE(arrests, 1);
  engine.step();
  EXPECT_LT(std::abs(engine.position(1).x() - o.length), o.omega() * dt * amplitude);
  const EnergySplit& e = engine.energy();
  EXPECT_GT(e.damping, 0.99 * e.external() - e.link_elastic);  // what the arrests took out
  EXPECT_LT(std::abs(e.balance_error()), 1e-9 * e.external());

  Engine free_swing = o.make(dt, amplitude);  // without the arrests: the amplitude stays
  double largest = 0.0;
  while (free_swing.time() < 3.0 * period) {
    free_swing.step();
    if (free_swing.time() > 2.0 * period) largest = std::max(largest, std::abs(free_swing.position(1).x() - o.length));
  }
  EXPECT_GT(largest, 0.99 * amplitude);
}

// The settle's kinetic damping on a swing of few steps a period (omega dt = 0.7, 9 steps): with
// the arrest one step past the detected peak (x left at x_{n+1}), the arrests lock to a 5-step
// cycle and each one gives the swing 6 % more amplitude (the 3 x 3 m beam-spring punch's settle
// that ran away at 55 s, docs/dem_engine.md "Settling to rest"). Barnes' reset to the peak
// (1999, Int. J. Space Struct. 14(2) 89-104) takes amplitude out at every omega dt < 2.
TEST(DemEngine, KineticDampingDoesNotPumpASwingOfFewStepsAPeriod) {
  const Oscillator o;
  const double amplitude = 1e-5;
  for (double omega_dt : {0.3, 0.7, 0.9, 1.2, 1.8}) {
    Engine engine = o.make(omega_dt / o.omega(), amplitude);
    double previous = 0.0, largest_late = 0.0;
    int arrests = 0;
    for (int n = 0; n < 400; ++n) {
      arrests += step_with_kinetic_damping(engine, previous);
      if (n >= 300) largest_late = std::max(largest_late, std::abs(engine.position(1).x() - o.length));
    }
    EXPECT_GE(arrests, 1) << "omega dt " << omega_dt;
    EXPECT_LT(largest_late, 1e-3 * amplitude) << "omega dt " << omega_dt << ": the arrests pump the swing";
    const EnergySplit& e = engine.energy();
    EXPECT_LT(std::abs(e.balance_error()), 1e-9 * e.external()) << "omega dt " << omega_dt;
  }
}

// YADE's unbalanced-force ratio on one hanging link at a known position: the link pulls k u up,
// gravity m g down; the ratio is |k u - m g| / (k u), and 0 for the chain relaxed.
TEST(DemEngine, UnbalancedForceRatioIsYadesMeanRatio) {
  const double mass = 0.004, length = 0.05, g = 9.81, k = elastic_bond_stiffness(length), u = 2e-7;
  std::vector<NetNode> nodes{make_node(Vector3::Zero(), mass, NodeFixity::Pinned), make_node(Vector3(0, 0, -length), mass)};
  std::vector<EngineLink> links;
  links.push_back({{0, 1, LinkTag::SingleWire}, elastic_bond(length)});
  EngineOptions options;
  options.time_step = 1e-7;
  Engine engine(nodes, std::move(links), options);
  EXPECT_TRUE(std::isinf(engine.unbalanced_force_ratio()));  // no link force yet
  engine.impose_positions({Vector3::Zero(), Vector3(0, 0, -length - u)});
  engine.step();
  EXPECT_NEAR(engine.unbalanced_force_ratio(), std::abs(k * u - mass * g) / (k * u), 1e-6);
  EXPECT_GT(engine.unbalanced_force_ratio(), 0.1);
  options.time_step = 0.0;
  options.local_damping = 0.7;
  std::vector<EngineLink> relaxed_links;
  relaxed_links.push_back({{0, 1, LinkTag::SingleWire}, elastic_bond(length)});
  Engine relaxed(nodes, std::move(relaxed_links), options);
  ASSERT_TRUE(relaxed.relax(1e-7, 2000000).converged);
  EXPECT_LT(relaxed.unbalanced_force_ratio(), 1e-7);
  EXPECT_THROW(relaxed.set_local_damping(1.0), std::invalid_argument);
}

// A wall's contact is an interaction as a link is (YADE counts both): a free node pressed 1.5 m g
// / k_n into a wall, its link unstretched, has the unbalanced force 0.5 m g; over the mean of the
// link's 0 and the two nodes' contacts (1.5 m g each) the ratio is 1/2 (the mean link force alone
// would make it infinite).
TEST(DemEngine, UnbalancedForceRatioCountsTheWallsContactsAsInteractions) {
  const double mass = 0.004, length = 0.05, g = 9.81, kn = 1e5, radius = 0.0054;
  std::vector<NetNode> nodes{make_node(Vector3::Zero(), mass, NodeFixity::Pinned), make_node(Vector3(length, 0, 0), mass)};
  std::vector<EngineLink> links;
  links.push_back({{0, 1, LinkTag::SingleWire}, elastic_bond(length)});
  EngineOptions options;
  options.time_step = 1e-7;
  options.local_damping = 0.0;
  Engine engine(nodes, std::move(links), options);
  auto wall = std::make_unique<PlaneWall>(Vector3::UnitZ());
  const double depth = 1.5 * mass * g / kn;
  wall->position = Vector3(0.0, 0.0, -radius + depth);
  wall->contact.normal_stiffness = kn;
  wall->contact.shear_stiffness = 0.0;
  engine.add_tool(std::move(wall));
  engine.step();
  ASSERT_EQ(engine.tool_contacts(0), 2u);  // the pinned node touches it too (held: no unbalanced force)
  // Interactions: the link (0) and two contacts (the free node's 1.5 m g, the pinned node's the same).
  EXPECT_NEAR(engine.unbalanced_force_ratio(), 0.5 * mass * g / ((0.0 + 2.0 * 1.5 * mass * g) / 3.0), 1e-6);
}

}  // namespace
}  // namespace dtwire::dem
