// Identifiability rules (calibrate/include/dtwire/calibrate/identifiability.hpp), failure kinds
// and the logarithmic coordinate, on hand-made inputs whose answer is known.
#include <gtest/gtest.h>

#include <cmath>

#include "dtwire/calibrate/evaluation.hpp"
#include "dtwire/calibrate/identifiability.hpp"
#include "dtwire/core/error.hpp"

namespace dtwire::calibrate {
namespace {

std::vector<ParameterDefinition> two_parameters() {
  ParameterDefinition a;
  a.name = "a";
  a.initial = 100, a.lower = 10, a.upper = 1000;
  ParameterDefinition b = a;
  b.name = "b";
  return {a, b};
}

TEST(Identifiability, TwoSigmaAgainstTheTolerance) {
  // 2 sigma = 2 % and 6 % of the value: the first identified to 5 %, the second not.
  const auto ids = identify(two_parameters(), {100, 200}, {1, 6}, {}, 1.0, 0.01, {}, 0.05);
  EXPECT_TRUE(ids[0].identified) << ids[0].reason;
  EXPECT_DOUBLE_EQ(ids[0].relative_sigma, 0.01);
  EXPECT_FALSE(ids[1].identified);
  EXPECT_NE(ids[1].reason.find("2 sigma = 6 %"), std::string::npos) << ids[1].reason;
}

TEST(Identifiability, BoundsFailedStepsAndNoCovariance) {
  auto ids = identify(two_parameters(), {10, 1000}, {0.01, 0.01}, {}, 1.0, 0.01, {}, 0.05);
  EXPECT_NE(ids[0].reason.find("lower bound 10"), std::string::npos) << ids[0].reason;
  EXPECT_NE(ids[1].reason.find("upper bound 1000"), std::string::npos) << ids[1].reason;
  ids = identify(two_parameters(), {100, 100}, {0.01, 0.01}, {"", "law rejected: Nult_N must be >= N0_N"}, 1.0, 0.01,
                 {}, 0.05);
  EXPECT_TRUE(ids[0].identified);
  EXPECT_FALSE(ids[1].identified);
  EXPECT_NE(ids[1].reason.find("Nult_N must be >= N0_N"), std::string::npos) << ids[1].reason;
  ids = identify(two_parameters(), {100, 100}, {}, {}, 1.0, 0.01, {}, 0.05);
  EXPECT_FALSE(ids[0].identified);
  EXPECT_TRUE(std::isinf(ids[0].relative_sigma));
}

// Rule 3 with the secant sigma: the wider of the two decides, and the reason says which.
TEST(Identifiability, TheWiderOfTangentAndSecantSigmaDecides) {
  // b: 2 sigma = 1 % by the tangent, 6 % by the secant; a: the secant narrower, the tangent decides.
  const auto ids = identify(two_parameters(), {100, 200}, {1, 1}, {}, 1.0, 0.01, {}, 0.05, {0.5, 6});
  EXPECT_TRUE(ids[0].identified) << ids[0].reason;
  EXPECT_DOUBLE_EQ(ids[0].relative_sigma, 0.01);
  EXPECT_FALSE(ids[1].identified);
  EXPECT_DOUBLE_EQ(ids[1].relative_sigma, 0.03);
  EXPECT_NE(ids[1].reason.find("2 sigma = 6 % of the value (secant over +-2.5 %; the Jacobian's 1 %; tolerance 5 %)"),
            std::string::npos)
      << ids[1].reason;
  EXPECT_THROW(identify(two_parameters(), {100, 200}, {}, {}, 1.0, 0.01, {}, 0.05, {1, 1}), std::invalid_argument);
}

// force = max(a - 1, 0) x displacement: a kink at a = 1; refuses a < 0.9.
class KinkSimulator : public Simulator {
 public:
  Curve simulate(const ParameterValues& p) const override {
    const double a = p.at("a_1");
    if (a < 0.9) throw ComputationError("kink: a < 0.9");
    std::vector<double> d{0, 1, 2, 3, 4}, f;
    for (double x : d) f.push_back(std::max(a - 1.0, 0.0) * x);
    Curve c;
    c.add_channel("displacement", *find_unit("m"), d);
    c.add_channel("force", *find_unit("N"), f);
    return c;
  }
  std::string identity() const override { return "kink"; }
};

// The secant Jacobian: central over the kink (the mean slope), one-sided at a bound and where a
// side's run fails; the tangent sees one side's slope only.
TEST(SecantJacobian, CentralOverAKinkOneSidedAtABoundOrAFailedSide) {
  Experiment e;
  e.name = "kink";
  e.simulator = std::make_shared<KinkSimulator>();
  e.target = e.simulator->simulate({{"a_1", 1.5}});
  e.channels = {{"force", 1.0, 0.0}};
  ParameterDefinition a;
  a.name = "a_1";
  a.initial = 1.5, a.lower = 0.5, a.upper = 3.0, a.scale = 1.0;  // z = a
  ProblemEvaluator evaluator({e}, {a}, EvaluationOptions{});
  const auto slopes = [&](double z, double step) {
    std::vector<double> r, tangent, secant;
    evaluator.residuals_and_jacobian({z}, r, tangent);
    evaluator.residuals_and_secant_jacobian({z}, {step}, r, secant);
    std::vector<double> ratio;
    for (std::size_t i = 0; i < r.size(); ++i)
      if (tangent[i] != 0.0) ratio.push_back(secant[i] / tangent[i]);
    EXPECT_EQ(ratio.size(), 4u);  // every point but the origin
    return ratio;
  };
  for (double q : slopes(1.01, 0.1)) EXPECT_NEAR(q, 0.11 / 0.2, 1e-9);  // (0.11 - 0) / 0.2 against 1
  for (double q : slopes(2.95, 0.1)) EXPECT_NEAR(q, 1.0, 1e-9);         // + side beyond the upper bound
  for (double q : slopes(1.0001, 0.15)) EXPECT_NEAR(q, 1.0, 1e-9);      // - side refused (a < 0.9)
  std::vector<double> r, J;
  EXPECT_THROW(evaluator.residuals_and_secant_jacobian({1.0}, {0.5, 0.5}, r, J), std::invalid_argument);
}

// Another start's end inside the 95 % likelihood region (cost within 1.92 s^2) with a parameter
// 20 % away: that parameter is not identified, the other (1 % away) is; outside the region
// (cost + 2 s^2) the same end says nothing.
TEST(Identifiability, AnotherEqualFitFarAwayIsNotIdentified) {
  const double s2 = 0.01, cost = 1.0;
  auto ids = identify(two_parameters(), {100, 100}, {0.1, 0.1}, {}, cost, s2, {{{120, 101}, cost + 1.9 * s2}}, 0.05);
  EXPECT_FALSE(ids[0].identified);
  EXPECT_NE(ids[0].reason.find("another start ends at 120"), std::string::npos) << ids[0].reason;
  EXPECT_TRUE(ids[1].identified) << ids[1].reason;
  ids = identify(two_parameters(), {100, 100}, {0.1, 0.1}, {}, cost, s2, {{{120, 101}, cost + 2.0 * s2}}, 0.05);
  EXPECT_TRUE(ids[0].identified) << ids[0].reason;
  // A failed start (no values) is ignored.
  ids = identify(two_parameters(), {100, 100}, {0.1, 0.1}, {}, cost, s2, {{{}, cost}}, 0.05);
  EXPECT_TRUE(ids[0].identified);
}

TEST(FailureKind, NumbersBecomeHashesTheExperimentNameStays) {
  EXPECT_EQ(failure_kind("experiment 'pull_47deg': dem_specimen: not converged at grip displacement 3.31 mm "
                         "(leg 2, increment 1): unbalanced force 2.5e-05 of the largest"),
            "experiment 'pull_47deg': dem_specimen: not converged at grip displacement # mm (leg #, increment #): "
            "unbalanced force # of the largest");
  EXPECT_EQ(failure_kind("thesis: Nult_N must be >= N0_N (-1.5E+3)"), "thesis: Nult_N must be >= N#_N (#)");
}

TEST(LogarithmicParameter, CoordinateIsTheLogOfValueOverScale) {
  ParameterDefinition p;
  p.initial = 150, p.lower = 20, p.upper = 2e4, p.logarithmic = true;
  EXPECT_DOUBLE_EQ(p.to_coordinate(150), 0.0);
  EXPECT_NEAR(p.to_coordinate(1500), std::log(10.0), 1e-15);
  EXPECT_NEAR(p.from_coordinate(p.to_coordinate(4080)), 4080, 1e-9);
  EXPECT_NEAR(p.derivative(p.to_coordinate(4080)), 4080, 1e-9);  // d value / d ln(value)
  p.logarithmic = false;
  EXPECT_DOUBLE_EQ(p.to_coordinate(300), 2.0);
  EXPECT_DOUBLE_EQ(p.derivative(7.0), 150.0);
  ParameterDefinition bad = p;
  bad.name = "bad", bad.lower = 0, bad.logarithmic = true;
  EXPECT_THROW(validate({bad}), std::invalid_argument);
}

// Rule 5: a pseudo-inverse covariance (not positive definite) reports a variance of about zero
// along the null direction it drops; such sigmas vouch for nothing. Seen on the SW section fit's
// recovery: k_M with sigma 0 (its column zero) and k_F with a relative sigma of 1e-9 at r = -0.998
// with m_f were both called identified before.
TEST(Identifiability, ASemiDefiniteCovarianceVouchesForNothingAlongItsNullDirection) {
  const auto params = two_parameters();
  // Positive definite: the correlation alone is the 2-sigma rule's business.
  auto doubts = covariance_doubts(params, {}, true, {1e-6, 1e-6}, {1, 0.99, 0.99, 1});
  EXPECT_TRUE(doubts[0].empty() && doubts[1].empty());
  // A zero Jacobian column is a doubt whatever the covariance.
  doubts = covariance_doubts(params, {1}, true, {1e-6, 1e-6}, {1, 0, 0, 1});
  EXPECT_TRUE(doubts[0].empty());
  EXPECT_NE(doubts[1].find("zero Jacobian column"), std::string::npos) << doubts[1];
  // Semi-definite: a zero variance and a correlation above 0.95 are doubts, a weak one is not.
  doubts = covariance_doubts(params, {}, false, {0.0, 1e-7}, {1, 0.2, 0.2, 1});
  EXPECT_NE(doubts[0].find("variance of zero"), std::string::npos) << doubts[0];
  EXPECT_TRUE(doubts[1].empty()) << doubts[1];
  doubts = covariance_doubts(params, {}, false, {1e-7, 1e-7}, {1, -0.998, -0.998, 1});
  EXPECT_NE(doubts[0].find("correlated with 'b'"), std::string::npos) << doubts[0];
  const auto ids = identify(params, {100, 100}, {1e-7, 1e-7}, {}, 1.0, 0.01, {}, 0.05, {}, doubts);
  EXPECT_FALSE(ids[0].identified);
  EXPECT_FALSE(ids[1].identified);
  EXPECT_THROW(covariance_doubts(params, {}, false, {1.0}, {}), std::invalid_argument);
}

}  // namespace
}  // namespace dtwire::calibrate
