#include "dtwire/calibrate/identifiability.hpp"

#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace dtwire::calibrate {
namespace {

std::string percent(double fraction) {
  std::ostringstream out;
  out << std::setprecision(3) << 100.0 * fraction << " %";
  return out.str();
}

std::string number(double v) {
  std::ostringstream out;
  out << std::setprecision(4) << v;
  return out.str();
}

}  // namespace

std::vector<Identification> identify(const std::vector<ParameterDefinition>& parameters,
                                     const std::vector<double>& values, const std::vector<double>& sigma,
                                     const std::vector<std::string>& failed_steps,
                                     double cost, double residual_variance, const std::vector<StartEnd>& starts,
                                     double tolerance, const std::vector<double>& secant_sigma,
                                     const std::vector<std::string>& covariance_doubts) {
  const std::size_t n = parameters.size();
  if (values.size() != n || (!sigma.empty() && sigma.size() != n) || (!failed_steps.empty() && failed_steps.size() != n) ||
      (!secant_sigma.empty() && (sigma.empty() || secant_sigma.size() != n)) ||
      (!covariance_doubts.empty() && covariance_doubts.size() != n))
    throw std::invalid_argument("identify: sizes of parameters, values and sigma differ");
  if (!(tolerance > 0.0)) throw std::invalid_argument("identify: tolerance must be > 0");
  const double inf = std::numeric_limits<double>::infinity();
  // Rules 1, 3 and 4 judge the parameters' own values; rule 2 the box of the fitted values.
  const std::vector<double> resolved = resolve_offsets(parameters, values);
  std::vector<StartEnd> resolved_ends;
  for (const StartEnd& s : starts)
    resolved_ends.push_back({s.values.size() == n ? resolve_offsets(parameters, s.values) : std::vector<double>{}, s.cost});
  std::vector<Identification> out(n);
  for (std::size_t i = 0; i < n; ++i) {
    const ParameterDefinition& p = parameters[i];
    Identification& id = out[i];
    const double magnitude = std::abs(resolved[i]);
    const bool secant_wider = !secant_sigma.empty() && secant_sigma[i] > sigma[i];
    const double judged = sigma.empty() ? inf : secant_wider ? secant_sigma[i] : sigma[i];
    id.relative_sigma = sigma.empty() || magnitude == 0.0 ? inf : judged / magnitude;
    std::vector<std::string> reasons;
    if (sigma.empty()) reasons.push_back("no covariance (rank-deficient Jacobian)");
    const double at = 1e-6 * (p.upper - p.lower);
    const std::string its = p.offset_from.empty() ? "its" : "its offset " + coordinate_name(p) + " at the offset's";
    if (values[i] <= p.lower + at) reasons.push_back("ended at " + its + " lower bound " + number(p.lower));
    if (values[i] >= p.upper - at) reasons.push_back("ended at " + its + " upper bound " + number(p.upper));
    if (!failed_steps.empty() && !failed_steps[i].empty())
      reasons.push_back("at the edge of the region where the simulator runs (a finite-difference step failed: " +
                        failed_steps[i] + ")");
    if (!covariance_doubts.empty() && !covariance_doubts[i].empty()) reasons.push_back(covariance_doubts[i]);
    if (!sigma.empty() && !(2.0 * id.relative_sigma <= tolerance))
      reasons.push_back("2 sigma = " + percent(2.0 * id.relative_sigma) + " of the value " +
                        (secant_wider ? "(secant over +-" + percent(0.5 * tolerance) + "; the Jacobian's " +
                                            percent(2.0 * sigma[i] / magnitude) + "; "
                                      : "(Jacobian; ") +
                        "tolerance " + percent(tolerance) + ")");
    // The other end inside the 95 % likelihood region farthest from this value.
    double farthest = 0.0;
    const StartEnd* witness = nullptr;
    for (const StartEnd& s : resolved_ends) {
      if (s.values.size() != n || !(s.cost - cost <= kLikelihoodRatioCost * residual_variance)) continue;
      const double away = magnitude > 0.0 ? std::abs(s.values[i] - resolved[i]) / magnitude : inf;
      if (away > tolerance && away > farthest) farthest = away, witness = &s;
    }
    if (witness)
      reasons.push_back("another start ends at " + number(witness->values[i]) + " (" + percent(farthest) +
                        " away) with a cost within the 95 % likelihood region (+" +
                        number(witness->cost - cost) + ", threshold " +
                        number(kLikelihoodRatioCost * residual_variance) + ")");
    id.identified = reasons.empty();
    for (std::size_t k = 0; k < reasons.size(); ++k) id.reason += (k ? "; " : "") + reasons[k];
  }
  return out;
}

std::vector<std::string> covariance_doubts(const std::vector<ParameterDefinition>& parameters,
                                           const std::vector<std::size_t>& insensitive, bool positive_definite,
                                           const std::vector<double>& sigma, const std::vector<double>& correlation) {
  const std::size_t n = parameters.size();
  if ((!sigma.empty() && sigma.size() != n) || (!correlation.empty() && correlation.size() != n * n))
    throw std::invalid_argument("covariance_doubts: sizes of parameters, sigma and correlation differ");
  std::vector<std::string> doubts(n);
  for (std::size_t j : insensitive)
    if (j < n) doubts[j] = "does not affect the residuals at the answer (a zero Jacobian column)";
  if (positive_definite || sigma.empty()) return doubts;
  for (std::size_t i = 0; i < n; ++i) {
    if (!doubts[i].empty()) continue;
    if (!(sigma[i] > 0.0) || !std::isfinite(sigma[i])) {
      doubts[i] = "a variance of zero or not finite in a covariance that is not positive definite";
      continue;
    }
    if (correlation.empty()) continue;
    for (std::size_t j = 0; j < n; ++j)
      if (j != i && std::abs(correlation[i * n + j]) > 0.95) {
        doubts[i] = "correlated with '" + parameters[j].name + "' (r = " + number(correlation[i * n + j]) +
                    ") in a covariance that is not positive definite: the sigma is not a standard error";
        break;
      }
  }
  return doubts;
}

}  // namespace dtwire::calibrate
