// Thoeni et al. 2013 distortion (distortion.hpp): the shift decorator against closed forms (a
// linear bond pulled through its slack, the thesis macro-element against itself shifted), its
// energy balance, and YADE's random stream (minstd_rand + boost triangle_distribution) against
// std::minstd_rand and the triangular distribution's moments and CDF. The draws against YADE
// itself: tests/dem/distortion_yade_test.cpp (slow).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "dtwire/dem/distortion.hpp"
#include "dtwire/dem/parallel_bond.hpp"
#include "law_test_support.hpp"

namespace dtwire::dem {
namespace {

const ParameterMap steel_wire = {{"E_Pa", 2.0e11}, {"poisson_1", 0.3}, {"diameter_m", 2.7e-3}, {"length_m", 0.06}};

Vector6 axial(double u) {
  Vector6 q = Vector6::Zero();
  q(0) = u;
  return q;
}

TEST(Distortion, LinearBondCarriesNothingUntilTheSlackThenTheShiftedLine) {
  const double length = 0.06, lambda_u = 0.05, slack = lambda_u * length;  // 3 mm
  const double k = 2.0e11 * test::pi * 1.35e-3 * 1.35e-3 / length;
  DistortedLaw law(make_contact_law("parallel_bond", steel_wire), slack);
  const double step = 1e-5;
  double u = 0.0;
  for (int i = 1; i <= 400; ++i) {  // to 4 mm: 3 mm of slack, then 1 mm of stretch
    law.update(axial(step));
    u += step;
    const double expected = u < slack ? 0.0 : k * (u - slack);
    ASSERT_NEAR(law.forces()(0), expected, 1e-9 * k * 1e-3) << "u = " << u;  // tol: round-off of the sum of steps
    const double stored = 0.5 * k * std::pow(std::max(u - slack, 0.0), 2);
    ASSERT_NEAR(law.energy().external, stored, 1e-9 * 0.5 * k * 1e-6) << "u = " << u;  // work = 1/2 k (u - dL)^2
  }
  // Back below the slack (the wire waves again): no force, all stored energy given back.
  law.update(axial(-2e-3));
  EXPECT_EQ(law.forces()(0), 0.0);
  EXPECT_NEAR(law.energy().external, 0.0, 1e-12);
  EXPECT_NEAR(law.energy().elastic, 0.0, 1e-12);
  // Other components pass through unchanged.
  Vector6 bend = Vector6::Zero();
  bend(4) = 1e-3;
  law.update(bend);
  ParallelBondLaw reference(steel_wire);
  reference.update(bend);
  EXPECT_EQ(law.forces()(4), reference.forces()(4));
}

TEST(Distortion, OneIncrementAcrossTheSlackGivesTheSameForceAndWork) {
  const double slack = 2e-3;
  DistortedLaw law(make_contact_law("parallel_bond", steel_wire), slack);
  const double k = 2.0e11 * test::pi * 1.35e-3 * 1.35e-3 / 0.06;
  law.update(axial(2.5e-3));  // 2 mm slack and 0.5 mm stretch in one step
  EXPECT_NEAR(law.forces()(0), k * 0.5e-3, 1e-9 * k * 0.5e-3);               // tol round-off
  EXPECT_NEAR(law.energy().external, 0.5 * k * 0.25e-6, 1e-9 * k * 0.25e-6);  // tol round-off
}

TEST(Distortion, ThesisMacroElementPulledIsItsOwnCurveShiftedByTheSlack) {
  const ParameterMap thesis = test::thesis_parameters("single_wire");
  const double slack = 1.2e-3, step = 2e-6;
  const int slack_steps = 600, pulled_steps = 6000;  // slack = 600 steps exactly
  DistortedLaw distorted(make_contact_law("thesis", thesis), slack);
  auto plain = make_contact_law("thesis", thesis);
  double peak = 0.0, worst = 0.0;
  for (int i = 1; i <= slack_steps; ++i) {
    distorted.update(axial(step));
    if (i < slack_steps) {  // the last one ends at it
      ASSERT_EQ(distorted.forces()(0), 0.0) << "inside the slack, step " << i;
    }
  }
  for (int i = 1; i <= pulled_steps && !plain->broken(); ++i) {
    distorted.update(axial(step));
    plain->update(axial(step));
    peak = std::max(peak, std::abs(plain->forces()(0)));
    worst = std::max(worst, std::abs(distorted.forces()(0) - plain->forces()(0)));
    ASSERT_EQ(distorted.broken(), plain->broken()) << "step " << i;
  }
  ASSERT_GT(peak, 100.0);
  EXPECT_LT(worst, 1e-9 * peak);  // tol: the fed increments differ from `step` by round-off only
  const EnergyAccount a = distorted.energy(), b = plain->energy();
  EXPECT_NEAR(a.external, b.external, 1e-9 * b.external);  // no work is done inside the slack
  EXPECT_NEAR(a.external, a.elastic + a.plastic + a.damage, 1e-9 * a.external);
}

TEST(Distortion, EnergyBalanceOnAPathThatCrossesTheSlackBothWays) {
  const ParameterMap thesis = test::thesis_parameters("single_wire");
  DistortedLaw law(make_contact_law("thesis", thesis), 1e-3);
  double work = 0.0;  // trapezoid rule of N du, exact on the slack (N = 0)
  test::PathBuilder path;
  path.to(test::generalised(3e-3, 0.0), 300).to(test::generalised(0.2e-3, 0.02), 300).to(test::generalised(4e-3, -0.01), 300);
  for (const Vector6& increment : path.increments) {
    const Vector6 before = law.forces();
    law.update(increment);
    work += 0.5 * (before + law.forces()).dot(increment);
    const EnergyAccount e = law.energy();
    ASSERT_NEAR(e.external, e.elastic + e.plastic + e.damage, 1e-9 * std::max(1.0, e.external));  // tol round-off
  }
  // The trapezoid sum is not exact where the law yields within a step: 1 % of the work.
  EXPECT_NEAR(law.energy().external, work, 1e-2 * work);
}

TEST(Distortion, RejectsANegativeSlackAndUnknownModes) {
  EXPECT_THROW(DistortedLaw(make_contact_law("parallel_bond", steel_wire), -1e-3), std::invalid_argument);
  EXPECT_THROW(distortion_mode_from_name("wavy"), std::invalid_argument);
  EXPECT_EQ(distortion_mode_from_name("random"), DistortionMode::Random);
  EXPECT_THROW(yade_triangular_variate(0, 0), std::invalid_argument);  // YADE: seed 0 = clock
  EXPECT_THROW(yade_triangular_variate(kLargestDistortionSeed + 1, 0), std::invalid_argument);
}

TEST(DistortionStream, JumpAheadEqualsTheSequentialMinstdStream) {
  for (std::int64_t seed : {1L, 12345L, 2013L, kLargestDistortionSeed}) {
    std::minstd_rand engine(static_cast<std::minstd_rand::result_type>(seed));  // a = 48271, m = 2^31 - 1
    for (std::uint64_t k = 0; k < 2000; ++k) {
      const double u = static_cast<double>(engine() - 1) * (1.0 / 2147483646.0);
      const double r = u <= 0.5 ? std::sqrt(0.5) * std::sqrt(u) : 1.0 - std::sqrt(0.5) * std::sqrt(u - 0.5);
      ASSERT_EQ(yade_triangular_variate(seed, k), r) << "seed " << seed << " draw " << k;
    }
  }
  // First draw of seed 1 by hand: x = 48271, u = 48270 / (2^31 - 2), r = sqrt(u / 2).
  EXPECT_DOUBLE_EQ(yade_triangular_variate(1, 0), std::sqrt(48270.0 / 2147483646.0 / 2.0));
}

TEST(DistortionStream, DrawsAreTriangularOnZeroOneWithModeOneHalf) {
  const std::size_t n = 200000;
  std::vector<double> r(n);
  double mean = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    r[k] = yade_triangular_variate(777, k);
    ASSERT_GE(r[k], 0.0);
    ASSERT_LE(r[k], 1.0);
    mean += r[k] / n;
  }
  double variance = 0.0;
  for (double x : r) variance += (x - mean) * (x - mean) / (n - 1);
  // Mean 1/2, variance 1/24; standard errors 4.6e-4 and 1.1e-4 for n = 2e5: 5 sigma.
  EXPECT_NEAR(mean, 0.5, 2.3e-3);
  EXPECT_NEAR(variance, 1.0 / 24.0, 5.5e-4);
  // Kolmogorov-Smirnov against F(x) = 2x^2 (x <= 1/2), 1 - 2 (1 - x)^2: 1.63 / sqrt(n) is the 1 % level.
  std::sort(r.begin(), r.end());
  double d = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    const double x = r[k];
    const double cdf = x <= 0.5 ? 2.0 * x * x : 1.0 - 2.0 * (1.0 - x) * (1.0 - x);
    d = std::max({d, std::abs(cdf - static_cast<double>(k) / n), std::abs(cdf - static_cast<double>(k + 1) / n)});
  }
  EXPECT_LT(d, 1.63 / std::sqrt(static_cast<double>(n)));
  // Reproducible from the seed, different for another seed.
  EXPECT_EQ(yade_triangular_variate(777, 12345), yade_triangular_variate(777, 12345));
  EXPECT_NE(yade_triangular_variate(777, 5), yade_triangular_variate(778, 5));
  const Distortion constant{DistortionMode::Constant, 0.2, 0};
  EXPECT_EQ(distortion_variate(constant, 99), 1.0);
}

}  // namespace
}  // namespace dtwire::dem
