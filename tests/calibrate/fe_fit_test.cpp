// Fit (1) with FE in the loop: E and Voce hardening of the 2.7 mm wire recovered from a
// single-wire tension curve made by the same coarse FE model (tests/calibrate/data/
// sw_steel_fit.toml: reference values, 0.5 % noise), every evaluation a `dtwire run`.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>

#include "dtwire/calibrate/fit_file.hpp"
#include "dtwire/calibrate/fitter.hpp"

namespace dtwire::calibrate {
namespace {

// Each parameter within 2 sigma of the value the target was made with, sigma < 10 % of it;
// the curve fitted to the noise level (NRMSE 0.003-0.008 for 0.5 % noise).
TEST(SteelFitWithFe, RecoversReferenceParametersWithinTwoSigma) {
  setenv("DTWIRE_EXECUTABLE", DTWIRE_EXECUTABLE_PATH, 1);
  FitDefinition def = read_fit_file(std::filesystem::path(DTWIRE_SOURCE_DIR) / "tests/calibrate/data/sw_steel_fit.toml");
  ProblemEvaluator evaluator(def.experiments, def.parameters, def.evaluation);
  const FitResult result = run_fit(evaluator, def.fit);
  ASSERT_TRUE(result.completed);
  ASSERT_FALSE(result.sigma.empty());
  for (std::size_t i = 0; i < result.values.size(); ++i) {
    const auto& p = result.parameters[i];
    EXPECT_LT(std::abs(result.values[i] - *p.reference), 2.0 * result.sigma[i])
        << p.name << " = " << result.values[i] << " +- " << result.sigma[i];
    EXPECT_LT(result.sigma[i], 0.1 * *p.reference) << p.name;
  }
  ASSERT_EQ(result.quality.size(), 1u);
  EXPECT_GT(result.quality[0].nrmse, 0.003);
  EXPECT_LT(result.quality[0].nrmse, 0.008);
  std::cout << "FE-in-the-loop fit: " << result.statistics.simulations << " FE runs, "
            << result.wall_seconds << " s\n";
}

}  // namespace
}  // namespace dtwire::calibrate
