// Curve metrics, noise estimate and region naming against closed-form values.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "dtwire/gap/curve_metrics.hpp"
#include "dtwire/gap/noise.hpp"
#include "dtwire/gap/regions.hpp"
#include "dtwire/gap/synthetic_curves.hpp"

namespace dtwire::gap {
namespace {

ForceCurve line(double slope, double offset, double end, std::size_t n) {
  ForceCurve c;
  c.source = "line";
  for (std::size_t i = 0; i < n; ++i) {
    const double u = end * static_cast<double>(i) / static_cast<double>(n - 1);
    c.u.push_back(u);
    c.f.push_back(offset + slope * u);
  }
  return c;
}

TEST(GapMetrics, AreaOfAConstantOffsetIsTheOffsetOverThePeak) {
  const ForceCurve lab = line(1000.0, 0.0, 0.01, 101);  // peak 10 N at 10 mm
  const ForceCurve model = line(1000.0, 0.5, 0.01, 37);
  // Closed form: |offset| / peak force = 0.5 / 10, exact for piecewise-linear curves.
  EXPECT_NEAR(normalised_area(model, make_comparison(lab)), 0.05, 1e-12);
}

TEST(GapMetrics, FrechetDistanceOfAShiftedCurveIsTheShift) {
  const ForceCurve lab = line(1000.0, 0.0, 0.01, 201);
  const ForceCurve model = line(1000.0, 1.0, 0.01, 201);
  // A vertical shift of 1 N is 0.1 on axes normalised by the 10 N peak; the coupling cannot
  // do better than the shift at the end points (tolerance: round-off).
  EXPECT_NEAR(frechet_distance(model, make_comparison(lab)), 0.1, 1e-9);
  EXPECT_NEAR(frechet_distance(lab, make_comparison(lab)), 0.0, 1e-12);
}

TEST(GapMetrics, UnloadingBranchIsComparedWithTheUnloadingBranch) {
  ForceCurve lab;
  lab.source = "loop";
  for (int i = 0; i <= 50; ++i) { lab.u.push_back(i * 1e-4); lab.f.push_back(i * 10.0); }
  for (int i = 49; i >= 20; --i) { lab.u.push_back(i * 1e-4); lab.f.push_back(i * 10.0 - 200.0); }
  // The model equal to the lab on both branches has zero gap even though the branches overlap
  // in displacement (a single-valued comparison would see a 200 N gap on unloading).
  EXPECT_NEAR(normalised_area(lab, make_comparison(lab)), 0.0, 1e-12);
}

TEST(GapNoise, EstimatedSigmaMatchesInjectedWhiteNoise) {
  ForceCurve c = voce_tension_curve();
  std::mt19937 rng(5);
  LabSampling s;
  s.points = 1000;
  s.noise_sigma_N = 12.0;
  const ForceCurve lab = sample_lab_curve(c, s, rng);
  // MAD-based estimate: its sampling error for n = 1000 is about 3 %; 10 % tolerance.
  EXPECT_NEAR(estimate_noise_sigma(lab), 12.0, 1.2);
}

TEST(GapNoise, EffectiveSampleSizeOfAr1) {
  // n (1 - rho) / (1 + rho): 1000 * 0.5 / 1.5.
  EXPECT_NEAR(effective_sample_size(1000, 0.5, 8.0), 1000.0 / 3.0, 1e-9);
  EXPECT_DOUBLE_EQ(effective_sample_size(10, 0.95, 8.0), 8.0);
  std::vector<double> alternating;
  for (int i = 0; i < 100; ++i) alternating.push_back(i % 2 ? 1.0 : -1.0);
  EXPECT_NEAR(lag1_autocorrelation(alternating), -0.99, 0.011);
}

TEST(GapRegions, VoceCurveHasElasticYieldHardeningPeakPostPeakInOrder) {
  const ForceCurve c = voce_tension_curve();
  const auto regions = name_regions(c);
  std::vector<std::string> names;
  for (const auto& r : regions) names.push_back(r.name);
  EXPECT_EQ(names, (std::vector<std::string>{"elastic", "yield", "hardening", "peak", "post_peak"}));
  EXPECT_EQ(regions.front().begin, 0u);
  EXPECT_EQ(regions.back().end, c.size());
  for (std::size_t i = 1; i < regions.size(); ++i) EXPECT_EQ(regions[i].begin, regions[i - 1].end);
}

TEST(GapRegions, ChangePointFoundAtAStepInTheResidual) {
  std::vector<double> x, r;
  for (int i = 0; i < 200; ++i) {
    x.push_back(i / 199.0);
    r.push_back(i < 120 ? 0.0 : 0.1);
  }
  const auto starts = residual_change_points(x, r, 1e-6);
  ASSERT_GE(starts.size(), 2u);
  EXPECT_NE(std::find(starts.begin(), starts.end(), 120u), starts.end());
}

TEST(GapRegions, ShiftedCurveGapIsAHorizontalOffsetInHardening) {
  const ForceCurve lab = voce_tension_curve();
  ForceCurve model = lab;
  for (double& u : model.u) u += 0.002;  // 2 mm horizontal shift
  const Comparison c = make_comparison(lab);
  const auto where = locate_gap(c, model_forces_at_lab(model, c), name_regions(lab), 1.0);
  double share_sum = 0.0;
  bool horizontal_in_hardening = false;
  for (const auto& g : where) {
    share_sum += g.share;
    horizontal_in_hardening |= g.region == "hardening" && g.direction == "horizontal offset";
  }
  EXPECT_NEAR(share_sum, 1.0, 1e-12);
  EXPECT_TRUE(horizontal_in_hardening);
}

}  // namespace
}  // namespace dtwire::gap

namespace dtwire::gap {
namespace {

TEST(GapMetrics, PartialCurveMappingIgnoresTheTestEnd) {
  const ForceCurve full = line(1000.0, 0.0, 0.01, 201);
  ForceCurve part;
  part.source = "part";
  for (std::size_t i = 0; i < 121; ++i) {  // the first 60 % of the same line
    part.u.push_back(full.u[i]);
    part.f.push_back(full.f[i]);
  }
  // Exact sub-curve: 0 up to interpolation round-off.
  EXPECT_NEAR(partial_curve_mapping(full, make_comparison(part)), 0.0, 1e-9);
  // A 0.5 N vertical offset is 0.5/6 on axes normalised by the 6 N peak of the part; sliding
  // forward along the 45-degree line only moves the points apart, so the best match is the
  // unshifted one at exactly the offset (round-off tolerance).
  ForceCurve shifted = full;
  for (double& f : shifted.f) f += 0.5;
  EXPECT_NEAR(partial_curve_mapping(shifted, make_comparison(part)), 0.5 / 6.0, 1e-9);
}

}  // namespace
}  // namespace dtwire::gap
