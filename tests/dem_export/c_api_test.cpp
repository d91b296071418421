// The C ABI: create, update, read, break, errors without exceptions.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "dtwire_contact.h"
#include "law_test_support.hpp"

namespace {

TEST(ContactCApi, DrivesABondThroughTheLifeCycle) {
  const auto parameters = dtwire::dem::test::thesis_parameters("single_wire");
  std::vector<const char*> names;
  std::vector<double> values;
  for (const auto& [name, value] : parameters) {
    names.push_back(name.c_str());
    values.push_back(value);
  }
  dtwire_bond* bond = dtwire_bond_create("macro3d", names.data(), values.data(), names.size());
  ASSERT_NE(bond, nullptr) << dtwire_contact_last_error();

  const double elastic_step[6] = {1e-5, 0, 0, 0, 0, 0};
  ASSERT_EQ(dtwire_bond_update(bond, elastic_step), 0);
  double forces[6];
  ASSERT_EQ(dtwire_bond_forces(bond, forces), 0);
  EXPECT_NEAR(forces[0], parameters.at("EA_N") * 1e-5, 1e-9 * forces[0]);  // elastic; tol round-off
  dtwire_energy energy;
  ASSERT_EQ(dtwire_bond_energy(bond, &energy), 0);
  EXPECT_NEAR(energy.elastic, 0.5 * forces[0] * 1e-5, 1e-12);  // tol round-off [J]
  EXPECT_EQ(dtwire_bond_broken(bond), 0);
  EXPECT_EQ(dtwire_bond_failure_mode(bond), DTWIRE_FAILURE_NONE);

  dtwire_bond* copy = dtwire_bond_clone(bond);
  ASSERT_NE(copy, nullptr);
  const double pull[6] = {1e-4, 0, 0, 0, 0, 0};
  int steps = 0;
  while (dtwire_bond_broken(bond) == 0 && steps < 2000) {
    ASSERT_EQ(dtwire_bond_update(bond, pull), 0);
    ++steps;
  }
  EXPECT_EQ(dtwire_bond_broken(bond), 1);
  EXPECT_EQ(dtwire_bond_failure_mode(bond), DTWIRE_FAILURE_NECKING);
  ASSERT_EQ(dtwire_bond_forces(bond, forces), 0);
  for (double f : forces) EXPECT_EQ(f, 0.0);
  // The clone kept the state of the moment it was made.
  ASSERT_EQ(dtwire_bond_forces(copy, forces), 0);
  EXPECT_NEAR(forces[0], parameters.at("EA_N") * 1e-5, 1e-9 * forces[0]);
  dtwire_bond_destroy(copy);
  dtwire_bond_destroy(bond);
}

TEST(ContactCApi, ReportsErrorsWithoutThrowing) {
  EXPECT_EQ(dtwire_bond_create("no_such_law", nullptr, nullptr, 0), nullptr);
  EXPECT_NE(std::string(dtwire_contact_last_error()).find("no_such_law"), std::string::npos);

  const char* names[] = {"E_Pa", "diameter_m"};
  const double values[] = {2e11, 2.7e-3};
  EXPECT_EQ(dtwire_bond_create("parallel_bond", names, values, 2), nullptr);
  EXPECT_NE(std::string(dtwire_contact_last_error()).find("length_m"), std::string::npos);

  const char* bond_names[] = {"E_Pa", "diameter_m", "length_m"};
  const double bond_values[] = {2e11, 2.7e-3, 0.06};
  dtwire_bond* bond = dtwire_bond_create("parallel_bond", bond_names, bond_values, 3);
  ASSERT_NE(bond, nullptr);
  const double not_finite[6] = {std::nan(""), 0, 0, 0, 0, 0};
  EXPECT_EQ(dtwire_bond_update(bond, not_finite), -1);
  EXPECT_NE(std::string(dtwire_contact_last_error()).find("finite"), std::string::npos);
  double forces[6];
  ASSERT_EQ(dtwire_bond_forces(bond, forces), 0);
  EXPECT_EQ(forces[0], 0.0);  // the rejected increment left the bond untouched
  dtwire_bond_destroy(bond);

  EXPECT_EQ(dtwire_bond_create(nullptr, nullptr, nullptr, 0), nullptr);
  EXPECT_EQ(dtwire_bond_update(nullptr, nullptr), -1);
  EXPECT_EQ(dtwire_bond_forces(nullptr, nullptr), -1);
  EXPECT_EQ(dtwire_bond_energy(nullptr, nullptr), -1);
  EXPECT_EQ(dtwire_bond_broken(nullptr), -1);
  EXPECT_EQ(dtwire_bond_failure_mode(nullptr), -1);
  EXPECT_NE(std::string(dtwire_contact_last_error()), "");
  dtwire_bond_destroy(nullptr);
}

}  // namespace
