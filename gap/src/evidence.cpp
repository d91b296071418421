#include "evidence.hpp"

#include <algorithm>
#include <cmath>

#include "dtwire/gap/noise.hpp"

namespace dtwire::gap::evidence {

double aicc(double mse, double n_eff, int k) {
  const double kk = k;
  const double correction = n_eff - kk - 1 > 0 ? 2 * kk * (kk + 1) / (n_eff - kk - 1) : 1e9;
  return n_eff * std::log(std::max(mse, 1e-300)) + 2 * kk + correction;
}

std::string joined_name(std::vector<std::string> names) {
  std::sort(names.begin(), names.end());
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : "+") + n;
  return out;
}

std::vector<double> shares(const std::vector<double>& values) {
  double total = 0.0;
  for (double v : values) total += v;
  std::vector<double> out(values.size(), values.empty() ? 0.0 : 1.0 / static_cast<double>(values.size()));
  if (total > 0)
    for (std::size_t i = 0; i < values.size(); ++i) out[i] = values[i] / total;
  return out;
}

void score(std::vector<RankedEffect>& ranking, const std::vector<FitStatistics>& fits, double curves,
           double baseline_mse, const Thresholds& t, double* lag1, double* n_eff_out) {
  // One effective sample size for every candidate: from the residual of the best fit, whose
  // autocorrelation is closest to that of the noise.
  std::size_t best = 0;
  for (std::size_t i = 1; i < fits.size(); ++i)
    if (fits[i].weighted_sse < fits[best].weighted_sse) best = i;
  *lag1 = fits.empty() ? 0.0 : lag1_autocorrelation(fits[best].residual);
  const std::size_t n = fits.empty() ? 0 : fits[best].residual.size();
  *n_eff_out = effective_sample_size(n, *lag1, 8.0);
  const double n_eff = *n_eff_out;
  const double baseline = aicc(baseline_mse, n_eff, 0);
  double lowest = baseline;
  for (std::size_t i = 0; i < ranking.size(); ++i) {
    const double mse = fits[i].weighted_sse / curves;
    ranking[i].aicc = aicc(mse, n_eff, ranking[i].parameters);
    ranking[i].bic = n_eff * std::log(std::max(mse, 1e-300)) + ranking[i].parameters * std::log(n_eff);
    ranking[i].delta_aicc = ranking[i].aicc - baseline;
    lowest = std::min(lowest, ranking[i].aicc);
  }
  double total = std::exp(-0.5 * (baseline - lowest));
  for (const RankedEffect& r : ranking) total += std::exp(-0.5 * (r.aicc - lowest));
  for (RankedEffect& r : ranking) {
    const double weight = std::exp(-0.5 * (r.aicc - lowest)) / total;
    r.score = weight * r.plausibility * 0.5 * (1.0 + r.region_match);
    r.qualifies = t.gap_before > t.floor && t.gap_before - r.gap_after > kMinimumReduction * t.noise_area &&
                  r.delta_aicc < -kInformationMargin;
  }
}

void demote_weak_pairs(std::vector<RankedEffect>& ranking, std::size_t first_pair, double single_gap) {
  for (std::size_t i = first_pair; i < ranking.size(); ++i)
    if (!(ranking[i].gap_after < kPairGapRatio * single_gap)) {
      ranking[i].qualifies = false;
      ranking[i].score *= 0.1;
    }
}

}  // namespace dtwire::gap::evidence
