// Where and how a DT fails (failure_place.hpp): the bands of one diameter at the twist's ends,
// and the stress-state classes of the failure report.
#include <gtest/gtest.h>

#include "failure_place.hpp"

namespace dtwire::fem {
namespace {

TEST(FailurePlace, JunctionIsOneDiameterEitherSideOfATwistEnd) {
  const std::array<double, 2> ends{{0.0, 40e-3}};
  const double d = 2.7e-3;
  EXPECT_EQ(failure_place(20e-3, d, ends), FailurePlace::twist);
  EXPECT_EQ(failure_place(12.7e-3, d, ends), FailurePlace::twist);  // the level-0 necking point
  EXPECT_EQ(failure_place(2.8e-3, d, ends), FailurePlace::twist);
  EXPECT_EQ(failure_place(2.6e-3, d, ends), FailurePlace::junction);
  EXPECT_EQ(failure_place(-2.6e-3, d, ends), FailurePlace::junction);
  EXPECT_EQ(failure_place(42.6e-3, d, ends), FailurePlace::junction);
  EXPECT_EQ(failure_place(-2.8e-3, d, ends), FailurePlace::arm);
  EXPECT_EQ(failure_place(50.6e-3, d, ends), FailurePlace::arm);  // the as-made 47 deg pull's failure
  EXPECT_STREQ(to_string(FailurePlace::junction), "junction");
}

TEST(FailureMode, NeckingShearAndUniformTension) {
  EXPECT_EQ(failure_mode(0.5, 1.0), "necking-driven");
  EXPECT_EQ(failure_mode(0.33, 1.0), "uniform tension");
  EXPECT_EQ(failure_mode(0.1, 0.2), "shear-driven");
  EXPECT_EQ(failure_mode(0.58, -0.4), "shear-driven");
}

}  // namespace
}  // namespace dtwire::fem
