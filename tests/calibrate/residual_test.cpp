// Residuals on a common abscissa, per monotone branch; fit quality; Latin hypercube.
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "dtwire/calibrate/experiment.hpp"
#include "dtwire/calibrate/sampling.hpp"
#include "dtwire/core/error.hpp"

namespace dtwire::calibrate {
namespace {

class FixedCurve final : public Simulator {
 public:
  explicit FixedCurve(Curve c) : curve_(std::move(c)) {}
  Curve simulate(const ParameterValues&) const override { return curve_; }
  std::string identity() const override { return "fixed"; }

 private:
  Curve curve_;
};

Curve curve(const std::vector<double>& x_mm, const std::vector<double>& f_kN) {
  Curve c;
  c.add_channel("displacement", *find_unit("mm"), x_mm);
  c.add_channel("force", *find_unit("kN"), f_kN);
  return c;
}

Experiment experiment(const Curve& target) {
  Experiment e;
  e.name = "e";
  e.target = target;
  e.simulator = std::make_shared<FixedCurve>(target);
  e.channels = {{"force", 1.0, 0.0}};
  return e;
}

// A load-unload-reload target compared with a simulation on a finer grid and in other units:
// the unloading branch is matched to the simulated unloading branch (not the loading one at
// the same displacement), so the residual is zero up to interpolation of straight segments.
TEST(Residuals, MatchBranchByBranch) {
  const Curve target = curve({0, 1, 2, 1.5, 1, 2, 3}, {0, 1, 2, 1.5, 1, 2, 2.5});
  Curve fine;
  std::vector<double> x_m, f_N;
  const std::vector<double> xs{0, 1, 2, 1.5, 1, 2, 3}, fs{0, 1, 2, 1.5, 1, 2, 2.5};
  for (std::size_t k = 1; k < xs.size(); ++k)
    for (int i = (k == 1 ? 0 : 1); i <= 10; ++i) {
      x_m.push_back(1e-3 * (xs[k - 1] + (xs[k] - xs[k - 1]) * i / 10.0));
      f_N.push_back(1e3 * (fs[k - 1] + (fs[k] - fs[k - 1]) * i / 10.0));
    }
  fine.add_channel("displacement", *find_unit("m"), x_m);
  fine.add_channel("force", *find_unit("N"), f_N);
  const auto r = residuals(experiment(target), fine);
  ASSERT_EQ(r.size(), target.size());
  for (double v : r) EXPECT_NEAR(v, 0.0, 1e-12);
}

// Offsetting the simulated force by 0.1 kN gives residuals sqrt(1/n) * 0.1 / range (range 2.5 kN)
// and RMSE 0.1 kN, R^2 = 1 - n 0.01 / SS_tot.
TEST(Residuals, OffsetGivesClosedFormValuesAndQuality) {
  const Curve target = curve({0, 1, 2, 3}, {0, 1, 2, 2.5});
  const Curve shifted = curve({0, 1, 2, 3}, {0.1, 1.1, 2.1, 2.6});
  const auto e = experiment(target);
  const auto r = residuals(e, shifted);
  for (double v : r) EXPECT_NEAR(v, std::sqrt(1.0 / 4.0) * 0.1 / 2.5, 1e-12);
  const auto q = fit_quality(e, shifted);
  ASSERT_EQ(q.size(), 1u);
  EXPECT_NEAR(q[0].rmse, 0.1, 1e-12);  // in kN, the target's unit
  EXPECT_EQ(q[0].unit, "kN");
  EXPECT_NEAR(q[0].nrmse, 0.1 / 2.5, 1e-12);
  const double mean = 5.5 / 4, ss_tot = mean * mean + (1 - mean) * (1 - mean) + (2 - mean) * (2 - mean) +
                                        (2.5 - mean) * (2.5 - mean);
  EXPECT_NEAR(q[0].r_squared, 1.0 - 4 * 0.01 / ss_tot, 1e-12);
}

TEST(Residuals, BranchCountMismatchIsAComputationError) {
  const Curve target = curve({0, 2, 1}, {0, 2, 1});
  const Curve monotone = curve({0, 1, 2}, {0, 1, 2});
  EXPECT_THROW(residuals(experiment(target), monotone), ComputationError);
}

TEST(Residuals, NormalizedArcLengthOfIdenticalShapeIsZero) {
  const Curve target = curve({0, 1, 2, 3}, {0, 2, 3, 3.5});
  auto e = experiment(target);
  e.kind = AbscissaKind::NormalizedArcLength;
  for (double v : residuals(e, target)) EXPECT_NEAR(v, 0.0, 1e-12);
}

// A leg along which the abscissa does not move (a pull at zero rotation before the bending, with
// rotation as the abscissa): its target points are compared with the simulated leg at equal
// progress along the channel's own rise, not all with the first simulated point.
TEST(Residuals, StalledLegIsComparedAlongItsOwnProgress) {
  const Curve target = curve({0, 0, 0, 0, 0.5, 1, 2}, {0, 1, 2, 3, 2.75, 2.5, 2});
  const double w = std::sqrt(1.0 / 7.0) / 3.0;  // sqrt(1/n) / range
  // The same path sampled otherwise: six points on the stalled leg, four on the moving one.
  const Curve same = curve({0, 0, 0, 0, 0, 0, 0.5, 1, 1.5, 2}, {0, 0.6, 1.2, 1.8, 2.4, 3, 2.75, 2.5, 2.25, 2});
  for (double v : residuals(experiment(target), same)) EXPECT_NEAR(v, 0.0, 1e-12);
  // A leg that rises to 80 % of the target's: the stalled points differ by 20 % of their own
  // value; the moving leg starts where the stall ends (2.4 at abscissa 0, 2.45 at 0.5).
  const Curve weaker = curve({0, 0, 0, 1, 2}, {0, 1.2, 2.4, 2.5, 2});
  const auto r = residuals(experiment(target), weaker);
  const std::vector<double> f{0, 1, 2, 3};
  for (std::size_t i = 0; i < 4; ++i) EXPECT_NEAR(r[i], w * (-0.2 * f[i]), 1e-12) << i;
  EXPECT_NEAR(r[4], w * (2.45 - 2.75), 1e-12);
  EXPECT_NEAR(r[5], 0.0, 1e-12);
  EXPECT_NEAR(r[6], 0.0, 1e-12);
  // A simulation that does not stall there is interpolated at the abscissa, as before.
  const Curve moving = curve({0, 1, 2}, {0, 2.5, 2});
  const auto m = residuals(experiment(target), moving);
  for (std::size_t i = 0; i < 4; ++i) EXPECT_NEAR(m[i], w * (0 - f[i]), 1e-12) << i;
  EXPECT_NEAR(m[4], w * (1.25 - 2.75), 1e-12);
}

TEST(Residuals, MissingTargetChannelIsRejected) {
  auto e = experiment(curve({0, 1, 2}, {0, 1, 2}));
  e.channels = {{"moment", 1.0, 0.0}};
  EXPECT_THROW(validate(e), std::invalid_argument);
}

// Every stratum of every dimension holds exactly one point; same seed -> same design.
// A target that ends where the specimen breaks (peak 2.5 kN at 3 mm, last point 2.0 kN) and a
// simulation that follows it to 3.2 mm and then goes on rising to 3.4 kN past the target's end:
// the points alone see 0.08 kN of difference at the last point; the peak row sees the 0.9 kN
// the set is too strong, over the whole simulated path, and sits after its channel's rows.
TEST(Residuals, APeakRowComparesTheSimulatedPeakOverTheWholePath) {
  const Curve target = curve({0, 1, 2, 3, 3.2}, {0, 1, 2, 2.5, 2.0});
  const Curve simulated = curve({0, 1, 2, 3, 3.2, 4, 6}, {0, 1, 2, 2.5, 2.08, 2.9, 3.4});
  Experiment e = experiment(target);
  e.channels.push_back({"displacement", 1.0, 0.0});
  e.peaks = {{"force", 2.0, 0.0}};
  ASSERT_EQ(residual_count(e), 2 * target.size() + 1);
  EXPECT_EQ(residual_groups(e), (std::vector<std::size_t>{target.size() + 1, target.size()}));
  const auto r = residuals(e, simulated);
  ASSERT_EQ(r.size(), residual_count(e));
  EXPECT_NEAR(r[4], std::sqrt(1.0 / 5.0) * 0.08 / 2.5, 1e-12) << "the last point, as before";
  EXPECT_NEAR(r[5], std::sqrt(2.0) * (3.4 - 2.5) / 2.5, 1e-12) << "the peak row follows the force's points";
  const auto q = peak_quality(e, simulated);
  ASSERT_EQ(q.size(), 1u);
  EXPECT_DOUBLE_EQ(q[0].target, 2.5);
  EXPECT_DOUBLE_EQ(q[0].simulated, 3.4);
  EXPECT_DOUBLE_EQ(q[0].target_abscissa, 3.0);
  EXPECT_DOUBLE_EQ(q[0].simulated_abscissa, 6.0);
  // A set that breaks early is too weak by its own peak; a peak of a channel not compared point
  // by point is a group of its own at the end.
  const Curve weak = curve({0, 1, 2, 3, 3.2, 6}, {0, 1, 1.8, 0.5, 0.2, 0});
  e.channels = {{"displacement", 1.0, 0.0}};
  EXPECT_EQ(residual_groups(e), (std::vector<std::size_t>{target.size(), 1}));
  EXPECT_NEAR(residuals(e, weak).back(), std::sqrt(2.0) * (1.8 - 2.5) / 2.5, 1e-12);
}

// Peaks of compression curves are their largest magnitude, sign kept.
TEST(Residuals, APeakIsTheValueOfLargestMagnitude) {
  const Curve target = curve({0, 1, 2}, {0, -2, -1});
  Experiment e = experiment(target);
  e.peaks = {{"force", 1.0, 0.0}};
  const auto r = residuals(e, curve({0, 1, 2}, {0, -2.5, -1}));
  EXPECT_NEAR(r.back(), -0.5 / 2.0, 1e-12);
  e.peaks = {{"missing", 1.0, 0.0}};
  EXPECT_THROW(validate(e), std::invalid_argument);
  e.peaks = {{"force", 1.0, 0.0}, {"force", 2.0, 0.0}};
  EXPECT_THROW(validate(e), std::invalid_argument) << "a peak compared twice";
}

TEST(LatinHypercube, OnePointPerStratumAndDeterministic) {
  const std::vector<double> lo{0.0, -1.0}, hi{1.0, 3.0};
  const auto a = latin_hypercube(8, lo, hi, 42);
  const auto b = latin_hypercube(8, lo, hi, 42);
  EXPECT_EQ(a, b);
  for (std::size_t d = 0; d < 2; ++d) {
    std::set<int> strata;
    for (const auto& p : a) {
      const double u = (p[d] - lo[d]) / (hi[d] - lo[d]);
      ASSERT_GE(u, 0.0);
      ASSERT_LT(u, 1.0);
      strata.insert(static_cast<int>(u * 8));
    }
    EXPECT_EQ(strata.size(), 8u);
  }
  EXPECT_NE(latin_hypercube(8, lo, hi, 43), a);
}

// Logarithmic dimensions: one point per stratum of log(value), i.e. one per decade for bounds
// 1e1-1e9 with 8 points; a linear dimension beside it is unchanged by the other's mapping.
TEST(LatinHypercube, LogarithmicDimensionsHaveOnePointPerDecade) {
  const std::vector<double> lo{10.0, 0.0}, hi{1e9, 1.0};
  const auto a = latin_hypercube(8, lo, hi, {true, false}, 42);
  EXPECT_EQ(a, latin_hypercube(8, lo, hi, {true, false}, 42));
  std::set<int> decades;
  for (const auto& p : a) {
    ASSERT_GE(p[0], 10.0);
    ASSERT_LT(p[0], 1e9);
    decades.insert(static_cast<int>(std::floor(std::log10(p[0]))));
  }
  EXPECT_EQ(decades.size(), 8u);  // 1, 2, ..., 8
  const auto linear = latin_hypercube(8, lo, hi, 42);
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a[i][1], linear[i][1]);
  EXPECT_THROW(latin_hypercube(2, {0.0}, {1.0}, {true}, 1), std::invalid_argument);
}

}  // namespace
}  // namespace dtwire::calibrate
