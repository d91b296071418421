// Fits of the analytic Voce bar: recovery of known parameters from noisy synthetic curves,
// bounds, failure handling, cache, checkpoint/resume.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>

#include "dtwire/calibrate/fitter.hpp"
#include "dtwire/calibrate/voce_bar.hpp"
#include "dtwire/core/error.hpp"
#include "coverage.hpp"
#include "synthetic.hpp"

namespace dtwire::calibrate {
namespace {

const ParameterValues kTruth{{"E_Pa", 200e9}, {"sigma_y0_Pa", 300e6}, {"Q_Pa", 150e6}, {"b_1", 20.0}};
constexpr double kNoisePa = 2e6;  // standard deviation of the synthetic stress noise

std::vector<ParameterDefinition> voce_parameters() {
  return {{"E_Pa", "Pa", 150e9, 50e9, 400e9, 0.0, std::nullopt},
          {"sigma_y0_Pa", "Pa", 250e6, 50e6, 800e6, 0.0, std::nullopt},
          {"Q_Pa", "Pa", 100e6, 0.0, 500e6, 0.0, std::nullopt},
          {"b_1", "1", 10.0, 0.5, 200.0, 0.0, std::nullopt}};
}

std::vector<Experiment> voce_experiments(std::shared_ptr<const Simulator> override_simulator = nullptr,
                                         std::uint64_t seed = 100) {
  std::vector<Experiment> out;
  const std::vector<std::vector<double>> paths{{0.0, 0.04}, {0.0, 0.01, 0.004, 0.03}, {0.0, 0.005, -0.005}};
  for (std::size_t i = 0; i < paths.size(); ++i) {
    auto simulator = std::make_shared<VoceBarSimulator>(paths[i], 60);
    Experiment e;
    e.name = "path" + std::to_string(i);
    e.simulator = override_simulator ? override_simulator : simulator;
    e.target = test::noisy(simulator->simulate(kTruth), "stress", kNoisePa, seed + i);
    e.abscissa = "strain";
    e.channels = {{"stress", 1.0, 0.0}};
    out.push_back(e);
  }
  return out;
}

EvaluationOptions serial_evaluation() {
  EvaluationOptions o;
  o.threads = 1;
  o.relative_step = 1e-6;
  return o;
}

// Known parameters recovered within 2 sigma of the reported covariance; the sigmas are small
// enough that this is a real check (relative sigma < 10 %), and the per-curve RMSE matches the
// injected noise (within 25 %: the RMSE of n >= 60 points scatters by about 1/sqrt(2n) = 9 %).
TEST(VoceFit, RecoversKnownParametersWithinTwoSigma) {
  ProblemEvaluator evaluator(voce_experiments(), voce_parameters(), serial_evaluation());
  const FitResult result = run_fit(evaluator, FitOptions{});
  ASSERT_TRUE(result.completed);
  ASSERT_TRUE(result.covariance.has_value());
  EXPECT_EQ(result.covariance_status, "positive definite");
  for (std::size_t i = 0; i < result.values.size(); ++i) {
    const std::string& name = result.parameters[i].name;
    const double truth = kTruth.at(name);
    EXPECT_LT(std::abs(result.values[i] - truth), 2.0 * result.sigma[i]) << name;
    EXPECT_LT(result.sigma[i], 0.1 * truth) << name;
  }
  ASSERT_EQ(result.quality.size(), 3u);
  for (const auto& q : result.quality) {
    EXPECT_NEAR(q.rmse, kNoisePa, 0.25 * kNoisePa) << q.experiment;
    EXPECT_GT(q.r_squared, 0.99) << q.experiment;
  }
}

// The Voce bar declaring one more parameter that it never reads: the curves cannot identify it.
class IgnoresOneParameter final : public Simulator {
 public:
  Curve simulate(const ParameterValues& parameters) const override { return bar_.simulate(parameters); }
  std::string identity() const override { return "ignores unused_1: " + bar_.identity(); }
  std::vector<std::pair<std::string, Dimension>> channels() const override { return bar_.channels(); }
  std::vector<std::string> parameter_names() const override {
    std::vector<std::string> names = bar_.parameter_names();
    names.push_back("unused_1");
    return names;
  }

 private:
  VoceBarSimulator bar_{{0.0, 0.04}, 60};
};

// A covariance that is only semi-definite (issue 37: the pseudo-inverse gives the unread
// parameter a variance of zero) is reported as such, with a warning, not as standard errors.
TEST(VoceFit, CovarianceThatIsNotPositiveDefiniteIsReported) {
  auto simulator = std::make_shared<IgnoresOneParameter>();
  std::vector<Experiment> experiments = voce_experiments(simulator);
  experiments.resize(1);  // the monotonic pull, the wrapped bar's path
  std::vector<ParameterDefinition> parameters = voce_parameters();
  parameters.push_back({"unused_1", "1", 0.5, 0.0, 1.0, 0.0, std::nullopt});
  ProblemEvaluator evaluator(experiments, parameters, serial_evaluation());
  const FitResult result = run_fit(evaluator, FitOptions{});
  ASSERT_TRUE(result.completed);
  EXPECT_NE(result.covariance_status, "positive definite");
  EXPECT_EQ(result.covariance_status.rfind("not ", 0), 0u) << result.covariance_status;
  const bool warned = std::any_of(result.warnings.begin(), result.warnings.end(), [](const std::string& w) {
    return w.find("the sigma are not standard errors") != std::string::npos ||
           w.find("covariance could not be computed") != std::string::npos;
  });
  EXPECT_TRUE(warned);
}

// The covariance is honest: over 40 noise realisations, the fraction of the 160 estimates
// within 2 sigma of the truth is >= 0.88 (0.95 expected; 0.88 is 4 binomial standard deviations
// below) and the RMS of z = (estimate - truth) / sigma lies in [0.8, 1.4] (1 expected). Measured:
// 0.93 and 1.22: the linearisation around the elastic-plastic kink of this coarsely sampled
// model under-estimates sigma by about 20 % (the classical pooled s^2 (J^T J)^-1 gave 0.75 and
// 1.77 here, because the three curves have different residual variances).
TEST(VoceFit, TwoSigmaCoverageOverNoiseRealisations) {
  test::Coverage coverage;
  for (std::uint64_t seed = 1; seed <= 40; ++seed) {
    ProblemEvaluator evaluator(voce_experiments(nullptr, 1000 * seed), voce_parameters(), serial_evaluation());
    const FitResult result = run_fit(evaluator, FitOptions{});
    ASSERT_TRUE(result.completed);
    ASSERT_FALSE(result.sigma.empty());
    for (std::size_t i = 0; i < result.values.size(); ++i)
      coverage.z.push_back((result.values[i] - kTruth.at(result.parameters[i].name)) / result.sigma[i]);
  }
  std::cout << "voce fit: " << coverage.z.size() << " estimates, fraction within 2 sigma "
            << coverage.fraction_within(2.0) << ", RMS z " << coverage.rms() << "\n";
  EXPECT_GE(coverage.fraction_within(2.0), 0.88);
  EXPECT_GT(coverage.rms(), 0.8);
  EXPECT_LT(coverage.rms(), 1.4);
}

// A robust loss resists outliers: 5 points of the monotonic curve shifted by +150 MPa (75
// noise sigmas) bias sigma_y0 under least squares by more than 1 % (measured 1.6 %); with the
// Huber loss (bend at 3 noise sigmas) and with the Cauchy loss the estimate stays within
// 0.2 % of the truth (measured 0.04 % and 0.01 %).
TEST(VoceFit, RobustLossResistsOutliers) {
  auto experiments = voce_experiments();
  std::vector<double> stress = experiments[0].target.channel("stress").values;
  for (std::size_t i = 20; i < 60; i += 8) stress[i] += 150e6;
  Curve target;
  target.add_channel("strain", *find_unit("1"), experiments[0].target.channel("strain").values);
  target.add_channel("stress", *find_unit("Pa"), stress);
  experiments[0].target = target;
  // Residual of one point: sqrt(1/n) * error / range; the loss bends at 3 noise sigmas.
  const double range = *std::max_element(stress.begin(), stress.end()) - *std::min_element(stress.begin(), stress.end());
  const double noise_residual = std::sqrt(1.0 / static_cast<double>(stress.size())) * kNoisePa / range;
  const double truth = kTruth.at("sigma_y0_Pa");
  std::vector<double> errors;
  for (LossKind loss : {LossKind::Squared, LossKind::Huber, LossKind::Cauchy}) {
    ProblemEvaluator evaluator(experiments, voce_parameters(), serial_evaluation());
    FitOptions options;
    options.loss = loss;
    options.loss_scale = 3.0 * noise_residual;
    const FitResult result = run_fit(evaluator, options);
    errors.push_back(std::abs(result.values[1] - truth));
  }
  std::cout << "sigma_y0 error: squared " << errors[0] << ", huber " << errors[1] << ", cauchy " << errors[2] << " Pa\n";
  EXPECT_GT(errors[0], 0.01 * truth);
  EXPECT_LT(errors[1], 0.002 * truth);
  EXPECT_LT(errors[2], 0.002 * truth);
}

// With an upper bound on sigma_y0 below the truth, the estimate stays inside the bounds and
// the fit says the parameter ended at a bound.
TEST(VoceFit, BoundsAreRespected) {
  auto parameters = voce_parameters();
  parameters[1].upper = 280e6;
  ProblemEvaluator evaluator(voce_experiments(), parameters, serial_evaluation());
  const FitResult result = run_fit(evaluator, FitOptions{});
  ASSERT_TRUE(result.completed);
  for (std::size_t i = 0; i < parameters.size(); ++i) {
    EXPECT_GE(result.values[i], parameters[i].lower);
    EXPECT_LE(result.values[i], parameters[i].upper);
  }
  EXPECT_NEAR(result.values[1], 280e6, 1.0);  // active bound
  const bool warned = std::any_of(result.warnings.begin(), result.warnings.end(), [](const std::string& w) {
    return w.find("sigma_y0_Pa' ended at a bound") != std::string::npos;
  });
  EXPECT_TRUE(warned);
}

// A simulator that throws ComputationError on chosen calls (serial evaluation: call order is
// deterministic), standing in for an FE run that does not converge.
class FailingSimulator final : public Simulator {
 public:
  FailingSimulator(std::shared_ptr<const Simulator> inner, std::vector<int> failing_calls)
      : inner_(std::move(inner)), failing_(std::move(failing_calls)) {}
  Curve simulate(const ParameterValues& p) const override {
    const int call = ++calls_;
    if (std::find(failing_.begin(), failing_.end(), call) != failing_.end()) {
      ++thrown_;
      throw ComputationError("injected failure on call " + std::to_string(call));
    }
    return inner_->simulate(p);
  }
  std::string identity() const override { return "failing " + inner_->identity(); }
  int thrown() const { return thrown_; }

 private:
  std::shared_ptr<const Simulator> inner_;
  std::vector<int> failing_;
  mutable std::atomic<int> calls_{0}, thrown_{0};
};

// Calls 3 (a finite-difference run) and 6 (the first trial step: 1 base + 4 perturbed before
// it) fail: the Jacobian retries the opposite step, the trial step is rejected, and the fit
// still reaches the same optimum as without failures.
TEST(VoceFit, FailingEvaluationIsSurvived) {
  auto experiments = voce_experiments();
  experiments.resize(1);
  ProblemEvaluator reference(experiments, voce_parameters(), serial_evaluation());
  const FitResult expected = run_fit(reference, FitOptions{});

  auto failing = std::make_shared<FailingSimulator>(experiments[0].simulator, std::vector<int>{3, 6});
  experiments[0].simulator = failing;
  ProblemEvaluator evaluator(experiments, voce_parameters(), serial_evaluation());
  const FitResult result = run_fit(evaluator, FitOptions{});
  EXPECT_EQ(failing->thrown(), 2);
  EXPECT_EQ(result.statistics.failures, 2u);
  ASSERT_TRUE(result.completed);
  for (std::size_t i = 0; i < result.values.size(); ++i)  // same optimum to 1e-6 relative
    EXPECT_NEAR(result.values[i], expected.values[i], 1e-6 * std::abs(expected.values[i]));
}

// A start whose very first evaluation fails is recorded as failed; the other starts carry on.
TEST(VoceFit, FailedStartDoesNotStopMultiStart) {
  auto experiments = voce_experiments();
  experiments.resize(1);
  experiments[0].simulator = std::make_shared<FailingSimulator>(experiments[0].simulator, std::vector<int>{1});
  ProblemEvaluator evaluator(experiments, voce_parameters(), serial_evaluation());
  FitOptions options;
  options.starts = 3;
  const FitResult result = run_fit(evaluator, options);
  ASSERT_TRUE(result.completed);
  EXPECT_EQ(result.starts[0].state, "failed");
  EXPECT_NE(result.best_start, 0u);
  EXPECT_NEAR(result.values[0], kTruth.at("E_Pa"), 0.02 * kTruth.at("E_Pa"));
}

// Identical evaluations are served by the cache: the same fit run twice on one evaluator
// runs no new simulation the second time.
TEST(VoceFit, CacheAvoidsRepeatedRuns) {
  ProblemEvaluator evaluator(voce_experiments(), voce_parameters(), serial_evaluation());
  run_fit(evaluator, FitOptions{});
  const auto first = evaluator.statistics();
  run_fit(evaluator, FitOptions{});
  const auto second = evaluator.statistics();
  EXPECT_GT(first.simulations, 0u);
  EXPECT_EQ(second.simulations, first.simulations);
  EXPECT_GT(second.cache_hits, first.cache_hits);
}

// Interrupted after k iterations (checkpoint written), resumed by a fresh evaluator (empty
// cache, as after a restart): ends bit-for-bit where the uninterrupted fit ends, for several k
// and with multi-start.
TEST(VoceFit, InterruptedAndResumedFitEndsWhereUninterruptedEnds) {
  const auto dir = std::filesystem::temp_directory_path() / "dtwire_calibrate_resume_test";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  FitOptions base;
  base.starts = 2;
  ProblemEvaluator reference(voce_experiments(), voce_parameters(), serial_evaluation());
  const FitResult expected = run_fit(reference, base);
  ASSERT_TRUE(expected.completed);

  for (int stop_after : {1, 3, 8}) {
    FitOptions options = base;
    options.checkpoint = dir / ("checkpoint_" + std::to_string(stop_after) + ".json");
    options.stop_after_iterations = stop_after;
    {
      ProblemEvaluator evaluator(voce_experiments(), voce_parameters(), serial_evaluation());
      const FitResult partial = run_fit(evaluator, options);
      EXPECT_FALSE(partial.completed) << stop_after;
    }
    options.stop_after_iterations = -1;
    options.resume = true;
    ProblemEvaluator evaluator(voce_experiments(), voce_parameters(), serial_evaluation());
    const FitResult resumed = run_fit(evaluator, options);
    ASSERT_TRUE(resumed.completed);
    for (std::size_t i = 0; i < expected.values.size(); ++i)
      EXPECT_EQ(resumed.values[i], expected.values[i]) << "stop after " << stop_after << ", " << i;
    EXPECT_EQ(resumed.cost, expected.cost);
    for (std::size_t s = 0; s < expected.starts.size(); ++s)
      EXPECT_EQ(resumed.starts[s].iterations, expected.starts[s].iterations);
  }
  std::filesystem::remove_all(dir);
}

// Parallel perturbed runs give the same Jacobian as serial ones.
TEST(VoceFit, ParallelJacobianEqualsSerial) {
  auto parallel_options = serial_evaluation();
  parallel_options.threads = 4;
  ProblemEvaluator serial(voce_experiments(), voce_parameters(), serial_evaluation());
  ProblemEvaluator parallel(voce_experiments(), voce_parameters(), parallel_options);
  const auto z = serial.to_scaled({170e9, 280e6, 120e6, 15.0});
  std::vector<double> r1, j1, r2, j2;
  serial.residuals_and_jacobian(z, r1, j1);
  parallel.residuals_and_jacobian(z, r2, j2);
  EXPECT_EQ(r1, r2);
  EXPECT_EQ(j1, j2);
}

// The Voce bar whose stress moves in jumps of `quantum` Pa (the stand-in for a DEM specimen,
// whose links yield and break one load increment apart): between jumps the response is flat.
class QuantizedStress final : public Simulator {
 public:
  QuantizedStress(std::shared_ptr<const Simulator> smooth, double quantum) : smooth_(std::move(smooth)), quantum_(quantum) {}
  Curve simulate(const ParameterValues& parameters) const override {
    const Curve smooth = smooth_->simulate(parameters);
    Curve out;
    for (const Channel& c : smooth.channels()) {
      std::vector<double> si = c.si();
      if (c.quantity == "stress")
        for (double& value : si) value = quantum_ * std::round(value / quantum_);
      out.add_channel_si(c.quantity, c.unit.dimension, si, c.unit);
    }
    return out;
  }
  std::string identity() const override { return "quantized " + std::to_string(quantum_) + ": " + smooth_->identity(); }
  std::vector<std::pair<std::string, Dimension>> channels() const override { return smooth_->channels(); }
  std::vector<std::string> parameter_names() const override { return smooth_->parameter_names(); }

 private:
  std::shared_ptr<const Simulator> smooth_;
  double quantum_;
};

// On a response that moves in jumps of 5 MPa, a finite-difference step far below the jumps
// (1e-6) sees zero or spikes and Levenberg-Marquardt stops short of the truth; the polish with
// a step wider than the jumps (2 %: about 4 GPa of E, 5-30 MPa of stress) follows the trend:
// its cost is lower, it is taken, and E and sigma_y0 (the parameters the three paths identify
// sharply) come within 5 % of the truth. Measured: without the polish the fit does not leave
// its start (E 150 GPa, cost 0.029); with it E 200.1 GPa, sigma_y0 303.8 MPa, cost 4.3e-5.
TEST(VoceFit, PolishWithACoarseStepPassesTheJumpsOfAQuantizedResponse) {
  auto experiments = voce_experiments();
  for (Experiment& e : experiments) e.simulator = std::make_shared<QuantizedStress>(e.simulator, 5e6);
  ProblemEvaluator fine(experiments, voce_parameters(), serial_evaluation());
  const FitResult unpolished = run_fit(fine, FitOptions{});
  ASSERT_TRUE(unpolished.completed);
  EXPECT_FALSE(unpolished.polish.run);

  ProblemEvaluator evaluator(experiments, voce_parameters(), serial_evaluation());
  FitOptions options;
  options.polish_relative_step = 0.02;
  const FitResult polished = run_fit(evaluator, options);
  ASSERT_TRUE(polished.completed);
  ASSERT_TRUE(polished.polish.run);
  EXPECT_TRUE(polished.polish.taken);
  EXPECT_DOUBLE_EQ(polished.polish.cost_before, unpolished.cost);
  EXPECT_LT(polished.cost, 0.5 * unpolished.cost);
  EXPECT_EQ(evaluator.relative_step(), 1e-6);  // the fine step is back for the covariance
  for (const char* name : {"E_Pa", "sigma_y0_Pa"}) {
    const auto i = static_cast<std::size_t>(std::find_if(polished.parameters.begin(), polished.parameters.end(),
                                                         [&](const auto& p) { return p.name == name; }) -
                                            polished.parameters.begin());
    EXPECT_LT(std::abs(polished.values[i] - kTruth.at(name)), 0.05 * kTruth.at(name)) << name;
  }
  std::cout << "quantized Voce bar: cost " << unpolished.cost << " -> " << polished.cost << " (polish "
            << polished.polish.iterations << " iterations); E " << unpolished.values[0] << " -> " << polished.values[0]
            << ", sigma_y0 " << unpolished.values[1] << " -> " << polished.values[1] << "\n";
}

}  // namespace
}  // namespace dtwire::calibrate
