#include <gtest/gtest.h>

#include <cmath>

#include "dtwire/core/curve_ops.hpp"

namespace dtwire {
namespace {

TEST(CurveOps, InterpolatesLinearDataExactlyInEitherDirection) {
  const std::vector<double> x = {0, 1, 3, 6}, y = {1, 3, 7, 13};  // y = 2x + 1
  const auto up = interpolate(x, y, {0.5, 2.0, 5.9});
  EXPECT_DOUBLE_EQ(up[0], 2.0);
  EXPECT_DOUBLE_EQ(up[1], 5.0);
  EXPECT_DOUBLE_EQ(up[2], 12.8);
  const std::vector<double> xr(x.rbegin(), x.rend()), yr(y.rbegin(), y.rend());
  EXPECT_DOUBLE_EQ(interpolate(xr, yr, {2.0})[0], 5.0);
  EXPECT_DOUBLE_EQ(interpolate(x, y, {-1.0})[0], 1.0);  // clamped, no extrapolation
  EXPECT_THROW(interpolate({0, 1, 1}, {0, 1, 2}, {0.5}), std::invalid_argument);
}

TEST(CurveOps, ResampleKeepsUnitsAndMetadata) {
  Curve c;
  c.set_metadata("specimen", "A");
  c.add_channel("displacement", *find_unit("mm"), {0, 1, 2});
  c.add_channel("force", *find_unit("kN"), {0, 1, 4});
  const Curve r = resample(c, "displacement", linspace(0, 2, 5));
  EXPECT_EQ(r.size(), 5u);
  EXPECT_EQ(r.metadata("specimen"), "A");
  EXPECT_EQ(r.channel("force").unit.symbol, "kN");
  EXPECT_DOUBLE_EQ(r.channel("force").values[3], 2.5);
}

TEST(CurveOps, ArcLengthOfAQuarterCircleApproachesPiOverTwo) {
  std::vector<double> x, y;
  const int n = 2000;
  for (int i = 0; i <= n; ++i) {
    const double t = 0.5 * M_PI * i / n;
    x.push_back(std::cos(t));
    y.push_back(std::sin(t));
  }
  EXPECT_NEAR(arc_length(x, y, 1.0, 1.0).back(), 0.5 * M_PI, 1e-6);
  const auto s = normalized_arc_length(x, y);
  EXPECT_DOUBLE_EQ(s.front(), 0.0);
  EXPECT_DOUBLE_EQ(s.back(), 1.0);
}

TEST(CurveOps, SplitsLoadUnloadReloadIntoBranchesSharingTurningPoints) {
  const std::vector<double> x = {0, 1, 2, 3, 2.5, 2, 2.5, 3, 4};
  const auto b = split_monotone_branches(x);
  ASSERT_EQ(b.size(), 3u);
  EXPECT_EQ(b[0].direction, BranchDirection::Loading);
  EXPECT_EQ(b[0].begin, 0u);
  EXPECT_EQ(b[0].end, 4u);
  EXPECT_EQ(b[1].direction, BranchDirection::Unloading);
  EXPECT_EQ(b[1].begin, 3u);
  EXPECT_EQ(b[1].end, 6u);
  EXPECT_EQ(b[2].direction, BranchDirection::Loading);
  EXPECT_EQ(b[2].begin, 5u);
  EXPECT_EQ(b[2].end, x.size());
}

TEST(CurveOps, NoiseBelowToleranceDoesNotSplit) {
  const std::vector<double> x = {0, 1, 0.999, 2, 1.998, 3};
  EXPECT_EQ(split_monotone_branches(x, 0.01).size(), 1u);
  EXPECT_EQ(split_monotone_branches(x, 0.0).size(), 5u);
}

}  // namespace
}  // namespace dtwire
