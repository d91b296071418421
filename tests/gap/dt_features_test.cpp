// The features of a DT tension test (issue 17): the toe by the standards' toe compensation, the
// failure zone from the wires' axis stations, the failure an FE curve reports.
#include <gtest/gtest.h>

#include <cmath>

#include "dtwire/gap/dt_features.hpp"

namespace {

using namespace dtwire::gap;

// A curve that carries nothing until u0, then rises linearly and hardens: the toe is u0 exactly
// (the steepest chord is the linear part); without the slack it is 0.
TEST(DtFeatures, ToeIsTheInterceptOfTheSteepestChord) {
  for (const double u0 : {0.0, 0.4e-3, 1.5e-3}) {
    ForceCurve c;
    for (int i = 0; i <= 400; ++i) {
      const double u = 1e-5 * i * 2.0, s = std::max(0.0, u - u0);
      c.u.push_back(u);
      c.f.push_back(s < 1e-3 ? 4e6 * s : 4000.0 + 1e6 * (s - 1e-3) - 2e8 * (s - 1e-3) * (s - 1e-3));
    }
    EXPECT_NEAR(toe_length(c), u0, 1e-9) << u0;
  }
  // A soft toe that stiffens gradually (F ~ u^2 then linear): the intercept lies inside the toe.
  ForceCurve soft;
  for (int i = 0; i <= 200; ++i) {
    const double u = 1e-5 * i;
    soft.u.push_back(u);
    soft.f.push_back(u < 1e-3 ? 2e9 * u * u : 2000.0 + 4e6 * (u - 1e-3));
  }
  EXPECT_NEAR(toe_length(soft), 0.5e-3, 1e-5);  // the tangent at 1 mm (slope 4e6) meets F = 0 at 0.5 mm
}

TEST(DtFeatures, FailureZoneFollowsTheAxisCurvature) {
  std::vector<std::pair<double, double>> stations;
  for (int i = 0; i <= 10; ++i) stations.emplace_back(-0.02 + 0.0015 * i, 0.0);  // lower arm to z = -5 mm
  for (int i = 1; i <= 3; ++i) stations.emplace_back(-0.005 + 0.0015 * i, 185.0);  // bend to z = -0.5 mm
  for (int i = 0; i <= 20; ++i) stations.emplace_back(0.002 * i, 68.3);  // helix 0..40 mm
  EXPECT_EQ(failure_zone(0.0274, stations), FailureZone::twist);
  EXPECT_EQ(failure_zone(-0.0021, stations), FailureZone::junction);
  EXPECT_EQ(failure_zone(-0.012, stations), FailureZone::arm);
  EXPECT_EQ(failure_zone(0.0, {}), FailureZone::unknown);
  EXPECT_EQ(zone_name(FailureZone::junction), "junction");
}

TEST(DtFeatures, ReportedFailureIsReadFromTheCurveMetadata) {
  const auto f = parse_reported_failure(
      "necking-driven at displacement 32.9713 mm, force 5156.42 N, z = 27.454 mm, r = 1.23382 mm, triaxiality 0.54");
  ASSERT_TRUE(f);
  EXPECT_EQ(f->mode, "necking-driven");
  EXPECT_NEAR(f->displacement, 32.9713e-3, 1e-12);
  EXPECT_NEAR(f->z, 27.454e-3, 1e-12);
  EXPECT_FALSE(parse_reported_failure("no failure"));
}

}  // namespace
