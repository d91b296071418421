// Recovery by the FE fit's own file (issue 36): experiments/dt_fe_fit/dt_specimen_fit.toml fits
// the thesis macro-element's SW and DT sets jointly (8 parameters) to whole-specimen curves of the
// dem_specimen simulator (tension and the 47 deg pull, to 34 and 42 mm). Here its targets are
// curves synthesized at its own `reference` values (the published sets,
// experiments/data/macroelement_thesis_params.json) with Gaussian noise of 0.5 % of each
// channel's range, and the fit runs from the file's own start, as a new user would run it, with
// the file's 32 starts (below).
// The file fits each Nult as the hardening reserve over its N0 (offset_from): the law's order
// Nult >= N0 is a bound, so no run is refused by it; the truth is the same (Nult = N0 + reserve).
// INVERSE CRIME: the targets are made by the same simulator (same engine, law, geometry,
// quasi-static settings and increments) as the fit, so the only model error is the noise. The
// test shows that the machinery no longer loses runs to the law's order, that the multi-start
// improves on the single start and on the fit before the reserve, and that every parameter the
// data do not identify is named, as the Jacobian, its secant at the tolerance's scale and the
// other starts say (every identified one within 5 % of the truth); it does NOT find the global
// minimum (the cost of the noise; docs/calibrate.md, "Recovery by dt_specimen_fit.toml"), and it
// says nothing about how well the element represents the FE or a laboratory specimen (the file's
// fit against the FE curves, docs/calibrate.md, Fit (4)).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <random>
#include <stdexcept>
#include <string>

#include "dtwire/calibrate/fit_file.hpp"
#include "dtwire/calibrate/fitter.hpp"
#include "dtwire/calibrate/synthesize.hpp"

namespace dtwire::calibrate {
namespace {

constexpr double kNoise = 0.005;  // x each channel's range

FitDefinition synthetic_fit(std::uint64_t seed) {
  FitReadOptions options;
  options.read_targets = false;
  FitDefinition def = read_fit_file(
      std::filesystem::path(DTWIRE_SOURCE_DIR) / "experiments/dt_fe_fit/dt_specimen_fit.toml", options);
  for (const auto& p : def.parameters) EXPECT_TRUE(p.reference) << p.name;
  // The references as the simulator reads them (dt.Nult_N = dt.N0_N + the reserve's reference).
  const ParameterValues truth = to_values(def.parameters, reference_point(def.parameters));
  std::mt19937_64 generator(seed);
  for (auto& e : def.experiments) e.target = synthesize_target(e, truth, kNoise, generator, 81);
  def.evaluation.threads = 2;
  // The file's own 32 starts (start 1 at `initial`, a Latin hypercube of the rest, seed 1). With
  // its peak rows 8 starts no longer reach the region of the truth: the best of them (cost
  // 7.4e-4) ends with dt.N0 at dt.Nult, 79 % from the truth and named identified; 32 end at
  // 3.0e-4 (323 s beside a campaign, 2026-11-29). Another count: DTWIRE_RECOVERY_STARTS=N.
  if (const char* starts = std::getenv("DTWIRE_RECOVERY_STARTS")) {
    char* end = nullptr;
    const long count = std::strtol(starts, &end, 10);
    if (end == starts || *end != '\0' || count < 1 || count > 1024)
      throw std::invalid_argument("DTWIRE_RECOVERY_STARTS: expected a whole number of starts in [1, 1024], found '" +
                                  std::string(starts) + "'");
    def.fit.starts = static_cast<int>(count);
  }
  return def;
}

// Relative standard deviations of the parameters' own values (dt.Nult_N, not its reserve) from
// the Jacobian at the fitted values, computed here independently of the fit's covariance:
// S = d r / d x from the evaluator's finite differences in the optimiser's coordinate z
// (d x / d z = x for a logarithmic parameter, its scale for a linear one), Cov(x) = s^2 (S^T S)^-1
// with the pooled residual variance s^2 = 2 cost / (m - n) (the fit uses each channel's own
// variance: the two differ somewhat), carried to the parameters' own values (A Cov A^T,
// parameter.hpp) and divided by them.
std::vector<double> jacobian_relative_sigma(ProblemEvaluator& evaluator, const std::vector<double>& fitted_values,
                                            double residual_variance) {
  const std::vector<double> z = evaluator.to_scaled(fitted_values);
  std::vector<double> r, J;
  evaluator.residuals_and_jacobian(z, r, J);
  const auto m = static_cast<Eigen::Index>(r.size()), n = static_cast<Eigen::Index>(z.size());
  Eigen::MatrixXd S(m, n);
  const auto& parameters = evaluator.parameters();
  for (Eigen::Index j = 0; j < n; ++j) {
    const auto k = static_cast<std::size_t>(j);
    const double dz_dx = 1.0 / parameters[k].derivative(z[k]);
    for (Eigen::Index i = 0; i < m; ++i) S(i, j) = J[static_cast<std::size_t>(i * n + j)] * dz_dx;
  }
  const Eigen::MatrixXd covariance = resolve_covariance(
      parameters, residual_variance * (S.transpose() * S).completeOrthogonalDecomposition().pseudoInverse());
  const std::vector<double> values = resolve_offsets(parameters, fitted_values);
  std::vector<double> out;
  for (Eigen::Index j = 0; j < n; ++j)
    out.push_back(std::sqrt(std::max(covariance(j, j), 0.0)) / std::abs(values[static_cast<std::size_t>(j)]));
  return out;
}

TEST(DtSpecimenFit, RecoversTheIdentifiedParametersAndNamesTheOthers) {
  FitDefinition def = synthetic_fit(1);
  ProblemEvaluator evaluator(def.experiments, def.parameters, def.evaluation);
  const FitResult result = run_fit(evaluator, def.fit);
  ASSERT_TRUE(result.completed);
  const double tolerance = def.fit.identification_tolerance;
  ASSERT_EQ(tolerance, 0.05);  // "within 5 % of the truth" below is this tolerance
  std::cout << "wall " << result.wall_seconds << " s, " << result.statistics.simulations << " runs ("
            << result.statistics.failures << " failed), " << result.starts.size() << " starts (best "
            << result.best_start + 1 << "), cost " << result.cost << "\n";
  for (const auto& [kind, count] : result.statistics.failure_kinds) std::cout << "  failed: " << count << " x " << kind << "\n";
  for (const auto& s : result.starts) std::cout << "  start: " << s.state << ", cost " << s.cost << ", " << s.iterations << " iterations\n";

  // The cost of the noise alone is 1/2 x 4 channels x noise^2 = 5e-5 (each channel's residuals
  // are divided by its range and weighted by 1/points), plus the two peak rows' (the largest of
  // 81 noisy points lies about 2.5 noise above the peak: 1/2 x 2 x (2.5 noise)^2 = 1.6e-4).
  // NOT REACHED (docs/calibrate.md, "Recovery by dt_specimen_fit.toml"): the best start ends at
  // 6.1 times the points' share (before the peak rows, 8 starts: 4.6 times), in a local minimum of
  // the kinked cost (the elastic-plastic onsets between the curves' points). What is required:
  // better than the one start of the issue (0.0037) and than eight starts before the reserve
  // (5.36e-4, 541 of 6230 runs refused by the law), no run refused for Nult < N0, and almost no
  // failed run at all (a specimen that breaks before the path's end).
  const double noise_cost = 0.5 * 4 * kNoise * kNoise;
  std::cout << "cost " << result.cost << " = " << result.cost / noise_cost << " x the noise's\n";
  EXPECT_LT(result.cost, 0.0037 / 2);
  EXPECT_LT(result.cost, 5.36e-4);
  EXPECT_LT(result.statistics.failures, result.statistics.simulations / 100);
  for (const auto& [kind, count] : result.statistics.failure_kinds)
    EXPECT_EQ(kind.find("Nult_N must be >= N"), std::string::npos) << count << " x " << kind;

  const std::vector<double> sigma = jacobian_relative_sigma(evaluator, result.fitted_values, result.residual_variance);
  const std::vector<std::optional<double>> truth = resolved_references(result.parameters);
  std::size_t identified = 0;
  for (std::size_t i = 0; i < result.values.size(); ++i) {
    const auto& p = result.parameters[i];
    const Identification& id = result.identification.at(i);
    const double error = result.values[i] / truth[i].value() - 1.0;
    std::cout << "  " << p.name << ": " << result.values[i] << " +- " << result.sigma[i] << " (truth " << *truth[i]
              << ", error " << 100 * error << " %, 2 sigma " << 200 * sigma[i] << " % by the Jacobian here) "
              << (id.identified ? "identified" : "NOT IDENTIFIED: " + id.reason) << "\n";
    // The naming follows the Jacobian: clearly wide (2 sigma > 1.5 x tolerance) is named; clearly
    // narrow (< tolerance / 1.5) is not named by the Jacobian, though a bound, another start's
    // equally good end or the secant at the tolerance's scale may name it (where the cost has
    // kinks the tangent is too steep: the secant names dt.EA_N, dt.N0_N, sw.N0_N and sw.Nult_N,
    // whose grouped tangent 2 sigma are 3.1-4.6 %, 9-73 % from the truth; sw.Nult_N by 5.01 %
    // against 5 %). Between the two the fit's grouped covariance decides.
    if (2 * sigma[i] > 1.5 * tolerance) {
      EXPECT_FALSE(id.identified) << p.name;
    }
    if (2 * sigma[i] < tolerance / 1.5 && !id.identified) {
      EXPECT_EQ(id.reason.find("(Jacobian"), std::string::npos) << p.name << ": " << id.reason;
    }
    if (id.identified) {
      ++identified;
      EXPECT_LT(std::abs(error), tolerance) << p.name;
    } else {
      const bool named = std::any_of(result.warnings.begin(), result.warnings.end(), [&](const std::string& w) {
        return w.find("'" + p.name + "' is NOT IDENTIFIED") != std::string::npos;
      });
      EXPECT_TRUE(named) << p.name;
    }
  }
  // Not a test that passes by naming everything: the DT's strength, which every start that gets
  // below 0.003 finds within 1 %, is identified.
  EXPECT_GE(identified, 1u);
  const auto nult = std::find_if(result.parameters.begin(), result.parameters.end(),
                                 [](const ParameterDefinition& p) { return p.name == "dt.Nult_N"; });
  ASSERT_NE(nult, result.parameters.end());
  EXPECT_TRUE(result.identification.at(static_cast<std::size_t>(nult - result.parameters.begin())).identified);
  for (const auto& q : result.quality) std::cout << "  " << q.experiment << " " << q.quantity << ": NRMSE " << q.nrmse << ", R^2 " << q.r_squared << "\n";
}

}  // namespace
}  // namespace dtwire::calibrate
