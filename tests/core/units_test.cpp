#include <gtest/gtest.h>

#include <cmath>

#include "dtwire/core/units.hpp"

namespace dtwire {
namespace {

TEST(Units, EveryRequiredUnitIsKnownWithItsSiFactor) {
  const std::vector<std::pair<std::string, double>> expected = {
      {"m", 1.0},  {"mm", 1e-3},  {"um", 1e-6},        {"N", 1.0},
      {"kN", 1e3}, {"MPa", 1e6},  {"Pa", 1.0},         {"s", 1.0},
      {"rad", 1.0}, {"deg", M_PI / 180.0}};
  for (const auto& [symbol, factor] : expected) {
    const auto unit = find_unit(symbol);
    ASSERT_TRUE(unit) << symbol;
    EXPECT_DOUBLE_EQ(unit->to_si, factor) << symbol;
  }
}

TEST(Units, ConvertsWithinADimensionAndRefusesAcross) {
  EXPECT_DOUBLE_EQ(convert(2.5, *find_unit("kN"), *find_unit("N")), 2500.0);
  EXPECT_DOUBLE_EQ(convert(180.0, *find_unit("deg"), *find_unit("rad")), M_PI);
  EXPECT_DOUBLE_EQ(convert(1500.0, *find_unit("um"), *find_unit("mm")), 1.5);
  EXPECT_THROW(convert(1.0, *find_unit("mm"), *find_unit("N")), std::invalid_argument);
}

TEST(Units, ColumnNameSplitsAtTheLastUnderscore) {
  const ColumnName c = parse_column_name("plastic_dissipation_J");
  EXPECT_EQ(c.quantity, "plastic_dissipation");
  EXPECT_EQ(c.unit.symbol, "J");
  EXPECT_THROW(parse_column_name("force"), std::invalid_argument);
  EXPECT_THROW(parse_column_name("force_"), std::invalid_argument);
  EXPECT_THROW(parse_column_name("force_furlong"), std::invalid_argument);
}

}  // namespace
}  // namespace dtwire
