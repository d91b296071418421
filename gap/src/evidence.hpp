#pragma once
// Evidence shared by the single-mode and the combined (several loading modes) diagnosis:
// the information criterion, the score and whether a candidate qualifies as the cause.
#include <string>
#include <vector>

#include "dtwire/gap/diagnosis.hpp"

namespace dtwire::gap::evidence {

double aicc(double mse, double n_eff, int k);

// Names joined with '+' in alphabetical order ("a+b" for a pair).
std::string joined_name(std::vector<std::string> names);

// Shares of non-negative `values`; uniform when they sum to zero.
std::vector<double> shares(const std::vector<double>& values);

struct Thresholds {
  double gap_before = 0.0;
  double floor = 0.0;
  double noise_area = 0.0;  // expected area of the noise alone
};

struct FitStatistics {
  double weighted_sse = 0.0;
  std::vector<double> residual;
};

// AICc and BIC with one effective sample size (from the residual of the best fit), Akaike
// weights among the candidates and the bare simulation, score and qualification. Writes the
// lag-1 autocorrelation and n_eff it used.
void score(std::vector<RankedEffect>& ranking, const std::vector<FitStatistics>& fits, double curves,
           double baseline_mse, const Thresholds& t, double* lag1, double* n_eff);

// Pairs (entries from `first_pair` on) that do not cut the best single's gap by 20 % are a
// refinement, not a second cause: they do not qualify and their score is divided by 10.
void demote_weak_pairs(std::vector<RankedEffect>& ranking, std::size_t first_pair, double single_gap);

}  // namespace dtwire::gap::evidence
