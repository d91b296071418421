// Fit (3): the thesis macro-element's parameters recovered from synthetic curves made by the
// same law at the thesis values on the 12 load paths of tests/calibrate/data/macro_fit_synthetic.toml
// (1 % Gaussian noise), read through that fit file. The targets are generated here, so the test
// follows the law's implementation.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "coverage.hpp"
#include "dtwire/calibrate/fit_file.hpp"
#include "dtwire/calibrate/fitter.hpp"
#include "dtwire/calibrate/synthesize.hpp"

namespace dtwire::calibrate {
namespace {

constexpr double kNoise = 0.01;  // fraction of each channel's range

FitDefinition synthetic_macro_fit(std::uint64_t seed) {
  FitReadOptions options;
  options.read_targets = false;
  FitDefinition def =
      read_fit_file(std::filesystem::path(DTWIRE_SOURCE_DIR) / "tests/calibrate/data/macro_fit_synthetic.toml", options);
  ParameterValues thesis;
  for (const auto& p : def.parameters) thesis[p.name] = p.reference.value();
  std::mt19937_64 generator(seed);
  for (auto& e : def.experiments) e.target = synthesize_target(e, thesis, kNoise, generator, 81);
  def.fit.loss = LossKind::Squared;  // the covariance is exact for least squares
  def.fit.starts = 1;
  return def;
}

// Over 10 noise realisations (70 estimates): >= 85 % within 2 sigma of the thesis value
// (95 % expected; 85 % is 3.6 binomial standard deviations below), RMS of z in [0.6, 1.5],
// no estimate beyond 4 sigma, sigma < 10 % of the value (k_F, active only over the first
// ~0.1 mm of plastic elongation: < 50 %), and every curve fitted to the noise level
// (NRMSE 0.007-0.015 for 1 % noise).
TEST(MacroElementFit, RecoversThesisParametersWithinTwoSigma) {
  test::Coverage coverage;
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    FitDefinition def = synthetic_macro_fit(seed);
    ASSERT_EQ(def.experiments.size(), 12u);
    ProblemEvaluator evaluator(def.experiments, def.parameters, def.evaluation);
    const FitResult result = run_fit(evaluator, def.fit);
    ASSERT_TRUE(result.completed);
    ASSERT_FALSE(result.sigma.empty());
    for (std::size_t i = 0; i < result.values.size(); ++i) {
      const auto& p = result.parameters[i];
      const double z = (result.values[i] - *p.reference) / result.sigma[i];
      coverage.z.push_back(z);
      EXPECT_LT(std::abs(z), 4.0) << "seed " << seed << ": " << p.name << " = " << result.values[i]
                                  << " +- " << result.sigma[i] << ", thesis " << *p.reference;
      EXPECT_LT(result.sigma[i], (p.name == "k_F" ? 0.5 : 0.1) * *p.reference) << p.name;
    }
    for (const auto& q : result.quality) {
      EXPECT_GT(q.nrmse, 0.007) << q.experiment << " " << q.quantity;
      EXPECT_LT(q.nrmse, 0.015) << q.experiment << " " << q.quantity;
    }
  }
  EXPECT_GE(coverage.fraction_within(2.0), 0.85);
  EXPECT_GT(coverage.rms(), 0.6);
  EXPECT_LT(coverage.rms(), 1.5);
  std::cout << "macro-element fit: " << coverage.z.size() << " estimates, fraction within 2 sigma "
            << coverage.fraction_within(2.0) << ", RMS z " << coverage.rms() << "\n";
}

}  // namespace
}  // namespace dtwire::calibrate
