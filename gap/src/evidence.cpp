#include "evidence.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

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

std::string at_edge_text(const std::vector<BeyondRange>& at_edge) {
  std::ostringstream edge;
  edge.precision(3);
  for (const BeyondRange& b : at_edge)
    edge << "; its " << b.parameter << " of " << b.value << " is the edge of [" << b.plausible_lower << ", "
         << b.plausible_upper << "] within what the data tell";
  return edge.str();
}

void mark_implausible(std::vector<RankedEffect>& ranking, const std::vector<CurveScale>& scales,
                      const std::function<bool(std::size_t index)>& edge_fits) {
  for (std::size_t i = 0; i < ranking.size(); ++i) {
    RankedEffect& r = ranking[i];
    std::vector<BeyondRange> beyond;
    if (r.fitted_by_mode.empty()) {
      beyond = magnitudes_beyond_range(r.fitted, scales.at(0));
    } else {
      for (std::size_t m = 0; m < r.fitted_by_mode.size(); ++m)
        for (const BeyondRange& b : magnitudes_beyond_range(r.fitted_by_mode[m].second, scales.at(m)))
          beyond.push_back(b);
    }
    if (beyond.empty()) continue;
    if (edge_fits && edge_fits(i)) {
      r.at_range_edge = beyond;
      continue;
    }
    r.implausible = true;
    r.beyond_range = beyond;
    r.qualifies_but_implausible = r.qualifies;
    r.qualifies = false;
  }
}

namespace {

std::string percent(double share) {
  std::ostringstream s;
  s << static_cast<int>(std::lround(100.0 * std::max(0.0, share))) << " %";
  return s.str();
}

}  // namespace

void decide(Diagnosis& d, bool testable) {
  d.cause = "none";
  d.also_closes.clear();
  d.refused_effect.clear();
  const auto cause = std::find_if(d.ranking.begin(), d.ranking.end(), [](const RankedEffect& r) { return r.qualifies; });
  if (d.gap_before <= d.noise_floor) {
    d.verdict = "within_noise";
    d.reason = "the gap is within the noise floor";
    return;
  }
  if (!testable) {
    d.verdict = "nothing_tested";
    d.reason = "no effect could be tested on this curve (see not_tested)";
    return;
  }
  const auto refused = std::find_if(d.ranking.begin(), d.ranking.end(),
                                    [](const RankedEffect& r) { return r.qualifies_but_implausible; });
  // A plausible effect that leaves the gap above the floor and removes less than half of what an
  // implausible one removes is no cause: the verdict is the implausible one's (issue 51: a
  // plausible 8 % beside an implausible 99 % read "reduces the gap most").
  const bool outdone = cause != d.ranking.end() && refused != d.ranking.end() && cause->gap_after > d.noise_floor &&
                       cause->shrink < kOutdoneRatio * refused->shrink;
  if (cause != d.ranking.end() && !outdone) {
    d.verdict = "cause";
    d.cause = cause->effect;
    d.reason = cause->gap_after <= d.noise_floor ? "closes the gap to the noise floor"
                                                 : "reduces the gap most, but not to the noise floor";
    d.reason += at_edge_text(cause->at_range_edge);
    if (cause->gap_after <= d.noise_floor)
      d.reason += also_closing(d.ranking, *cause, d.noise_floor, "dAICc", [](const RankedEffect& r) { return r.aicc; },
                               &d.also_closes);
    return;
  }
  if (refused != d.ranking.end()) {
    d.verdict = "beyond_plausible_range";
    d.refused_effect = refused->effect;
    std::string needs;
    for (const BeyondRange& b : refused->beyond_range)
      needs += (needs.empty() ? "" : " and ") + b.text() + (refused->beyond_range.size() > 1 ? " (" + b.effect + ")" : "");
    d.reason = "no cause within the plausible ranges: " + refused->effect + " explains " + percent(refused->shrink) +
               " of the gap but needs " + needs;
    if (outdone) d.reason += "; the best plausible effect, " + cause->effect + ", explains " + percent(cause->shrink);
    return;
  }
  d.verdict = "no_effect_closes";
  const auto best = std::min_element(d.ranking.begin(), d.ranking.end(), [](const RankedEffect& a, const RankedEffect& b) {
    return a.gap_after < b.gap_after;
  });
  if (best == d.ranking.end() || !(best->shrink > 0)) {
    d.reason = "no effect reduces the gap";
  } else {
    std::ostringstream why;
    why.precision(3);
    if (best->implausible)
      why << "and needs " << best->beyond_range.front().text();
    else if (best->delta_aicc >= -kInformationMargin)
      why << "too little for the information criterion (dAICc " << best->delta_aicc << ", at least -"
          << kInformationMargin << " needed)";
    else
      why << "less than the noise explains";
    d.reason = "no effect closes the gap: the best, " + best->effect + ", removes " + percent(best->shrink) +
               " of it, " + why.str();
  }
}

}  // namespace dtwire::gap::evidence
