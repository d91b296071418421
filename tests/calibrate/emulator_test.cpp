// The Gaussian-process emulator of `dtwire dem propagate --emulator` (emulator.hpp): its
// leave-one-out algebra against refits without the point, and the band it gives from a few dozen
// runs against bands known exactly (a lognormal response: closed-form quantiles) or computed from
// the response itself (a one-sided response with inert parameters: 10^6 direct evaluations),
// and a noisy response whose scatter it must read as noise.
//
// Tolerance of a band end: 5 % of the exact band's width, half of the propagation's default
// band tolerance (0.1 of the width, band_statistics.hpp), so that an emulated band leaves the
// other half to the Monte Carlo error of the runs it replaces.
#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <cmath>
#include <random>
#include <stdexcept>

#include "dtwire/calibrate/band_statistics.hpp"
#include "dtwire/calibrate/emulator.hpp"

namespace dtwire::calibrate {
namespace {

std::vector<std::vector<double>> normal_points(std::size_t n, std::size_t d, std::uint64_t seed) {
  std::mt19937_64 generator(seed);
  std::normal_distribution<double> normal;
  std::vector<std::vector<double>> points(n, std::vector<double>(d));
  for (auto& p : points)
    for (double& v : p) v = normal(generator);
  return points;
}

TEST(Emulator, LeaveOneOutResidualsAreThoseOfARefitWithoutThePoint) {
  const auto x = normal_points(25, 3, 7);
  std::vector<double> f;
  for (const auto& p : x) f.push_back(std::sin(p[0]) + 0.3 * p[1] * p[1] + 0.1 * p[2]);
  const GaussianProcessEmulator emulator(x, f);
  double mean = 0.0, square = 0.0;
  for (double v : f) mean += v / 25.0;
  for (double v : f) square += (v - mean) * (v - mean);
  const double scale = std::sqrt(square / 24.0);
  for (std::size_t left = 0; left < x.size(); left += 6) {
    // Simple kriging on the other 24 points with the emulator's own correlation.
    Eigen::MatrixXd a(24, 24);
    Eigen::VectorXd t(24), r(24);
    std::vector<std::size_t> kept;
    for (std::size_t j = 0; j < x.size(); ++j)
      if (j != left) kept.push_back(j);
    for (Eigen::Index i = 0; i < 24; ++i) {
      t(i) = (f[kept[static_cast<std::size_t>(i)]] - mean) / scale;
      r(i) = matern52(x[kept[static_cast<std::size_t>(i)]], x[left], emulator.length_scales());
      for (Eigen::Index j = 0; j < 24; ++j)
        a(i, j) = matern52(x[kept[static_cast<std::size_t>(i)]], x[kept[static_cast<std::size_t>(j)]], emulator.length_scales()) +
                  (i == j ? emulator.nugget_ratio() : 0.0);
    }
    const double predicted = mean + scale * r.dot(a.llt().solve(t));
    EXPECT_NEAR(emulator.loo_residuals()[left], f[left] - predicted, 1e-8 * scale) << "point " << left;
  }
}

TEST(Emulator, ALognormalBandFromFortyRunsMatchesItsClosedForm) {
  // f = exp(0.4 z1), z1 and an inert z2 standard normal: f is lognormal, its 5-95 % band
  // exp(-+0.4 x 1.6449).
  const auto x = normal_points(40, 2, 11);
  std::vector<double> f;
  for (const auto& p : x) f.push_back(std::exp(0.4 * p[0]));
  const GaussianProcessEmulator emulator(x, f);
  const EmulatedBand band = emulated_band(emulator, normal_points(20000, 2, 12), 3);
  const double q05 = std::exp(-0.4 * kNormal95), q95 = std::exp(0.4 * kNormal95);
  const double tolerance = 0.05 * (q95 - q05);
  EXPECT_NEAR(band.with_error.q05, q05, tolerance);
  EXPECT_NEAR(band.with_error.q95, q95, tolerance);
  EXPECT_NEAR(band.of_means.q05, q05, tolerance);
  EXPECT_NEAR(band.of_means.q95, q95, tolerance);
  EXPECT_GT(emulator.q_squared(), 0.99);
  EXPECT_GT(emulator.length_scales()[1], 3.0 * emulator.length_scales()[0]) << "the inert coordinate reads as inert";

  // The same figure emulated as ln f (a positive magnitude, as dem propagate does): ln f is
  // linear in z1, and the band comes back through exp.
  std::vector<double> logarithm;
  for (double v : f) logarithm.push_back(std::log(v));
  const EmulatedBand back = emulated_band(GaussianProcessEmulator(x, logarithm), normal_points(20000, 2, 12), 3, true);
  EXPECT_NEAR(back.with_error.q05, q05, tolerance);
  EXPECT_NEAR(back.with_error.q95, q95, tolerance);
  EXPECT_GT(back.with_error.q05, 0.0);
}

TEST(Emulator, AOneSidedResponseWithInertParametersGivesTheBandOfTheResponseItself) {
  // The strip strength's shape in the propagation record: a figure that falls, never rises, as
  // one parameter moves (softplus), a weak linear one, four inert ones; 60 runs in 6 dimensions.
  const auto response = [](const std::vector<double>& p) {
    return 70.0 - 8.0 * std::log1p(std::exp(2.0 * p[1])) + 1.5 * p[0];
  };
  const auto x = normal_points(60, 6, 21);
  std::vector<double> f;
  for (const auto& p : x) f.push_back(response(p));
  const GaussianProcessEmulator emulator(x, f);
  std::vector<double> direct;
  for (const auto& p : normal_points(1000000, 6, 22)) direct.push_back(response(p));
  const BandStatistics exact = band_statistics(direct, 1, 2);
  const EmulatedBand band = emulated_band(emulator, normal_points(20000, 6, 23), 5);
  const double tolerance = 0.05 * (exact.q95 - exact.q05);
  EXPECT_NEAR(band.with_error.q05, exact.q05, tolerance);
  EXPECT_NEAR(band.with_error.q95, exact.q95, tolerance);
  EXPECT_GT(emulator.q_squared(), 0.95);
}

TEST(Emulator, RunToRunScatterIsReadAsNoiseAndTheTrendIsKept) {
  // f = z1 + 0.3 e, e standard normal per run: noise sd 0.3, slope 1.
  const auto x = normal_points(80, 2, 31);
  std::mt19937_64 generator(32);
  std::normal_distribution<double> normal;
  std::vector<double> f;
  for (const auto& p : x) f.push_back(p[0] + 0.3 * normal(generator));
  const GaussianProcessEmulator emulator(x, f);
  const EmulatorPrediction at0 = emulator.predict({0.0, 0.0});
  // The noise sd estimated from 80 runs: relative standard error about 1 / sqrt(2 x 80) = 8 %;
  // the check allows 4 of them.
  EXPECT_NEAR(at0.noise_sd, 0.3, 0.3 * 4 * 0.08);
  EXPECT_NEAR(emulator.predict({1.0, 0.0}).mean - emulator.predict({-1.0, 0.0}).mean, 2.0, 0.2);
  EXPECT_GT(emulator.share_within_two_sd(), 0.85);
}

TEST(Emulator, AConstantFigureGivesAConstantEmulator) {
  const auto x = normal_points(10, 2, 41);
  const GaussianProcessEmulator emulator(x, std::vector<double>(10, 4.5));
  const EmulatorPrediction p = emulator.predict({0.3, -1.0});
  EXPECT_EQ(p.mean, 4.5);
  EXPECT_EQ(p.latent_sd, 0.0);
  EXPECT_EQ(p.noise_sd, 0.0);
}

TEST(Emulator, RefusesTooFewPointsAndNonFiniteValues) {
  EXPECT_THROW(GaussianProcessEmulator({{0.0}, {1.0}}, {1.0, 2.0}), std::invalid_argument);
  EXPECT_THROW(GaussianProcessEmulator({{0.0}, {1.0}, {2.0}}, {1.0, std::nan(""), 2.0}), std::invalid_argument);
  EXPECT_THROW(GaussianProcessEmulator({{0.0}, {1.0, 2.0}, {2.0}}, {1.0, 2.0, 3.0}), std::invalid_argument);
}

}  // namespace
}  // namespace dtwire::calibrate
