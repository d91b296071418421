#pragma once
// Which fitted parameters the data identify, and why the others are not (docs/calibrate.md,
// "Identifiability"). A parameter is identified to a relative tolerance tol when none of these
// holds:
//  1. the covariance could not be computed (rank-deficient Jacobian);
//  2. it ended at a bound (the data push it out of the box; its sigma is not meaningful), or at
//     the edge of the region where the simulator runs: a finite-difference step from the answer
//     failed (e.g. the law rejects Nult < N0, a constraint the box bounds cannot express), so the
//     answer presses against that edge and the linearisation does not hold there;
//  3. linearised: 2 sigma > tol |value|, sigma from the Jacobian's covariance (J^T J)^-1 s^2,
//     i.e. its 95 % confidence interval is wider than the tolerance (a flat direction of the
//     cost shows as a small singular value of J and a large sigma of the parameters along it);
//     judged with the larger of the sigma from the finite-difference Jacobian and from a
//     secant Jacobian whose steps change each parameter by tol / 2 of its value: the question is
//     asked at that scale, and where the residuals have kinks between it and the tangent's step
//     (an elastic-plastic onset moving across a sample point), the tangent can be many times
//     too steep (the DT specimen fit: sigma 0.5 % against a valley 8 % wide, docs/calibrate.md);
//  4. likelihood ratio: another start ended inside the 95 % likelihood region of the best
//     answer, cost - best cost <= chi2(1, 0.95) / 2 s^2 = 1.92 s^2 (s^2 the residual variance
//     2 cost / (m - n)), with this parameter more than tol away from its best value. That end
//     fits the data as well (a point of the parameter's profile likelihood below the 95 %
//     threshold), so the data do not fix the parameter to tol even where the linearisation says
//     they do (a curved valley, another minimum of equal depth). Venzon & Moolgavkar (1988),
//     Raue et al. (2009), Bioinformatics 25:1923, for the profile-likelihood definition;
//  5. the covariance cannot vouch for it (`covariance_doubts`): its Jacobian column is zero, or
//     the covariance is only semi-definite (the pseudo-inverse drops a null direction of J^T J
//     and reports a variance of about zero for the parameters along it) and this parameter has a
//     variance of zero or a correlation above 0.95 with another.
#include <cstddef>
#include <string>
#include <vector>

#include "dtwire/calibrate/parameter.hpp"

namespace dtwire::calibrate {

struct Identification {
  bool identified = false;
  double relative_sigma = 0.0;  // sigma / |value|; +inf without a covariance or at value 0
  std::string reason;           // why not identified (empty when identified)
};

// The likelihood-ratio threshold of rule 4 in units of the residual variance: chi2(1, 0.95) / 2.
inline constexpr double kLikelihoodRatioCost = 0.5 * 3.841458820694124;

struct StartEnd {
  std::vector<double> values;  // empty: the start failed
  double cost = 0.0;
};

// `values` and the starts' values: the fitted values (an offset parameter's offset, to which its
// bounds apply; rule 2); rules 1, 3 and 4 judge the parameters' own values (offsets resolved,
// parameter.hpp), with `sigma` their standard deviations (empty: no covariance). `failed_steps`:
// per parameter the failure of its first finite-difference step at the answer (empty string:
// none; empty vector: not known). `tolerance` relative, > 0. `secant_sigma`: of the parameters'
// own values from the secant Jacobian (empty: not computed).
// `covariance_doubts`: per parameter why its sigma cannot be trusted (empty string: no doubt;
// empty vector: none known), see covariance_doubts() below.
std::vector<Identification> identify(const std::vector<ParameterDefinition>& parameters,
                                     const std::vector<double>& values, const std::vector<double>& sigma,
                                     const std::vector<std::string>& failed_steps,
                                     double cost, double residual_variance, const std::vector<StartEnd>& starts,
                                     double tolerance, const std::vector<double>& secant_sigma = {},
                                     const std::vector<std::string>& covariance_doubts = {});

// Rule 5's reasons from the fit's covariance facts: `insensitive` the parameters whose Jacobian
// column is zero; when `positive_definite` is false, a variance of zero (or not finite) and a
// correlation above 0.95 (row-major n x n `correlation`) are doubts too.
std::vector<std::string> covariance_doubts(const std::vector<ParameterDefinition>& parameters,
                                           const std::vector<std::size_t>& insensitive, bool positive_definite,
                                           const std::vector<double>& sigma, const std::vector<double>& correlation);

}  // namespace dtwire::calibrate
