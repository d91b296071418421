#pragma once
// Evidence shared by the single-mode and the combined (several loading modes) diagnosis:
// the information criterion, the score and whether a candidate qualifies as the cause.
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "dtwire/gap/diagnosis.hpp"

namespace dtwire::gap::evidence {

double aicc(double mse, double n_eff, int k);

// The single candidates other than `cause` that qualify and close the gap to `floor` too (a
// curve's RankedEffect or a summary's SummaryCandidate), appended to `names`; returns the reason's
// addition ("; so does X (dAICc +16): ..."), empty when there is none. `criterion` gives each
// candidate's information criterion, labelled `label` in the text.
template <class Candidate, class Criterion>
std::string also_closing(const std::vector<Candidate>& ranking, const Candidate& cause, double floor,
                         const char* label, Criterion criterion, std::vector<std::string>* names) {
  std::ostringstream others;
  others.precision(3);
  for (const Candidate& c : ranking)
    if (&c != &cause && c.qualifies && c.gap_after <= floor && c.effect.find('+') == std::string::npos) {
      names->push_back(c.effect);
      others << (names->size() > 1 ? ", " : "") << c.effect << " (" << label << " +"
             << criterion(c) - criterion(cause) << ")";
    }
  return names->empty() ? std::string() : "; so does " + others.str() + ": the laboratory's scatter does not tell them apart";
}

// The reason's addition for a cause whose magnitudes were fitted just past their ranges' edges
// ("; its damage_at_test_end_1 of 0.512 is the edge of [0.02, 0.5] within what the data tell").
std::string at_edge_text(const std::vector<BeyondRange>& at_edge);

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

// Marks the candidates whose magnitude is beyond its plausible range (issue 37: never the
// cause), keeping whether they met every other rule of a cause. `scales` are the problems'
// scales, one per mode of `fitted_by_mode` (or one for `fitted`).
// `edge_fits` (optional): whether candidate `index` with its beyond-range magnitudes held at the
// range's edge fits as well, within the noise; such a candidate is not implausible (its magnitude
// is the edge within what the data tell).
void mark_implausible(std::vector<RankedEffect>& ranking, const std::vector<CurveScale>& scales,
                      const std::function<bool(std::size_t index)>& edge_fits = {});

// The cause and the verdict's three cases (issue 51) from a ranking sorted by score: the
// top-scored qualifying candidate is the cause; else the top-scored candidate that met every
// rule but its magnitude is named with its figures ("gauge_length explains 83 % of the gap but
// needs a scale_1 of 0.64, outside [0.85, 1.3]"); else no effect closes the gap (the best
// reduction is stated). `testable`: whether any candidate was fitted.
void decide(Diagnosis& d, bool testable);

}  // namespace dtwire::gap::evidence
