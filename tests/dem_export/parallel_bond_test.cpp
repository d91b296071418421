// Linear parallel bond (Potyondy & Cundall 2004): closed-form stiffness, energy and breakage.
#include <gtest/gtest.h>

#include <cmath>

#include "dtwire/dem/parallel_bond.hpp"
#include "law_test_support.hpp"

namespace dtwire::dem {
namespace {

const ParameterMap steel_wire = {{"E_Pa", 2.0e11}, {"poisson_1", 0.3}, {"diameter_m", 2.7e-3}, {"length_m", 0.06}};

TEST(ParallelBond, ElasticStiffnessMatchesClosedForm) {
  ParallelBondLaw bond(steel_wire);
  const double E = 2.0e11, G = E / 2.6, R = 1.35e-3, L = 0.06;
  const double A = test::pi * R * R, I = test::pi * std::pow(R, 4) / 4.0, J = 2.0 * I;
  Vector6 expected;
  expected << E * A / L, G * A / L, G * A / L, G * J / L, E * I / L, E * I / L;
  for (int k = 0; k < 6; ++k) EXPECT_NEAR(bond.stiffness()[k], expected[k], 1e-12 * expected[k]);  // tol round-off

  Vector6 increment;
  increment << 1e-6, -2e-6, 3e-6, 1e-3, -2e-3, 5e-4;
  Vector6 total = Vector6::Zero();
  for (int i = 0; i < 10; ++i) {
    bond.update(increment);
    total += increment;
  }
  const Vector6 forces = bond.forces();
  for (int k = 0; k < 6; ++k)
    EXPECT_NEAR(forces[k], expected[k] * total[k], 1e-12 * std::abs(expected[k] * total[k]));  // tol round-off
  // Stored energy 1/2 sum k q^2; the external work equals it on any path of a linear spring.
  const double stored = 0.5 * expected.dot(total.cwiseProduct(total));
  EXPECT_NEAR(bond.energy().elastic, stored, 1e-12 * stored);   // tol round-off
  EXPECT_NEAR(bond.energy().external, stored, 1e-12 * stored);  // tol round-off
  EXPECT_FALSE(bond.broken());
}

TEST(ParallelBond, BreaksInTensionAtTheTensileStrength) {
  ParameterMap p = steel_wire;
  p["tensile_strength_Pa"] = 5.0e8;
  ParallelBondLaw bond(p);
  const double A = test::pi * 1.35e-3 * 1.35e-3, kn = 2.0e11 * A / 0.06;
  double u = 0.0;
  while (!bond.broken() && u < 1e-3) {
    bond.update(test::generalised(1e-7, 0.0));
    u += 1e-7;
  }
  ASSERT_TRUE(bond.broken());
  EXPECT_EQ(bond.failure_mode(), FailureMode::Necking);
  // sigma = k_n u / A reaches 500 MPa within the last increment.
  EXPECT_GE(kn * u / A, 5.0e8 * (1.0 - 1e-12));
  EXPECT_LT(kn * (u - 1e-7) / A, 5.0e8);
  const EnergyAccount e = bond.energy();
  EXPECT_EQ(e.elastic, 0.0);
  EXPECT_NEAR(e.external, e.damage, 1e-12 * e.external);  // released at break; tol round-off
}

TEST(ParallelBond, BreaksInShearAtTheShearStrength) {
  ParameterMap p = steel_wire;
  p["shear_strength_Pa"] = 3.0e8;
  p["tensile_strength_Pa"] = 1.0e12;
  ParallelBondLaw bond(p);
  Vector6 twist = Vector6::Zero();
  twist[3] = 1e-3;
  while (!bond.broken()) bond.update(twist);
  EXPECT_EQ(bond.failure_mode(), FailureMode::Shear);
}

TEST(ParallelBond, RejectsBadParameters) {
  ParameterMap p = steel_wire;
  p["E_Pa"] = -1.0;
  EXPECT_THROW(ParallelBondLaw{p}, std::invalid_argument);
  p = steel_wire;
  p.erase("length_m");
  EXPECT_THROW(ParallelBondLaw{p}, std::invalid_argument);
}

}  // namespace
}  // namespace dtwire::dem
