// The factory knows the laws by name and reports unknown names and missing fields.
#include <gtest/gtest.h>

#include "dtwire/dem/contact_law.hpp"
#include "law_test_support.hpp"

namespace dtwire::dem {
namespace {

TEST(LawFactory, CreatesTheMacroElementsAndTheParallelBond) {
  const ParameterMap thesis = test::thesis_parameters("double_twist");
  EXPECT_EQ(make_contact_law("thesis", thesis)->name(), "thesis");
  EXPECT_EQ(make_contact_law("macro3d", thesis)->name(), "macro3d");
  const ParameterMap bond = {{"E_Pa", 2e11}, {"diameter_m", 2.7e-3}, {"length_m", 0.04}};
  EXPECT_EQ(make_contact_law("parallel_bond", bond)->name(), "parallel_bond");
  // clone() keeps the state
  auto law = make_contact_law("macro3d", thesis);
  law->update(test::generalised(1e-5, 0.01));
  const auto copy = law->clone();
  EXPECT_EQ(copy->forces(), law->forces());
}

TEST(LawFactory, NamesTheMissingField) {
  ParameterMap thesis = test::thesis_parameters("single_wire");
  thesis.erase("m_g");
  try {
    make_contact_law("thesis", thesis);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("m_g"), std::string::npos);
  }
  EXPECT_THROW(make_contact_law("nonexistent", {}), std::invalid_argument);
}

}  // namespace
}  // namespace dtwire::dem
