#include "dtwire/gap/dt_features.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <regex>

namespace dtwire::gap {

double toe_length(const ForceCurve& curve) {
  double peak = 0.0;
  std::size_t peak_index = 0;
  for (std::size_t i = 0; i < curve.size(); ++i)
    if (curve.f[i] > peak) peak = curve.f[i], peak_index = i;
  double steepest = 0.0, toe = 0.0;
  for (std::size_t i = 1; i <= peak_index; ++i) {
    if (curve.f[i] > 0.5 * peak) break;
    const double du = curve.u[i] - curve.u[i - 1];
    if (du <= 0.0) continue;
    const double slope = (curve.f[i] - curve.f[i - 1]) / du;
    if (slope > steepest) {
      steepest = slope;
      toe = curve.u[i] - curve.f[i] / slope;
    }
  }
  return std::max(0.0, toe);
}

std::string zone_name(FailureZone zone) {
  switch (zone) {
    case FailureZone::twist: return "twist";
    case FailureZone::junction: return "junction";
    case FailureZone::arm: return "arm";
    case FailureZone::unknown: break;
  }
  return "unknown";
}

FailureZone failure_zone(double z, const std::vector<std::pair<double, double>>& stations) {
  if (stations.empty()) return FailureZone::unknown;
  double largest = 0.0;
  for (const auto& s : stations) largest = std::max(largest, s.second);
  // The helix curvature: the most frequent non-zero curvature (rounded to 1 %).
  std::map<long, int> counts;
  for (const auto& s : stations)
    if (s.second > 0.01 * largest) ++counts[std::lround(std::log(s.second) * 100.0)];
  if (counts.empty()) return FailureZone::arm;
  const auto mode = std::max_element(counts.begin(), counts.end(),
                                     [](const auto& a, const auto& b) { return a.second < b.second; });
  const double helix = std::exp(mode->first / 100.0);
  const auto nearest = std::min_element(stations.begin(), stations.end(), [z](const auto& a, const auto& b) {
    return std::abs(a.first - z) < std::abs(b.first - z);
  });
  if (nearest->second <= 0.01 * largest) return FailureZone::arm;
  return nearest->second <= 1.1 * helix ? FailureZone::twist : FailureZone::junction;
}

std::optional<ReportedFailure> parse_reported_failure(const std::string& text) {
  static const std::regex pattern(
      R"(^\s*(?:in the [A-Za-z -]+, )?([A-Za-z-]+(?: [A-Za-z-]+)*) at displacement ([-+0-9.eE]+) mm.*\bz = ([-+0-9.eE]+) mm)");
  std::smatch m;
  if (!std::regex_search(text, m, pattern)) return std::nullopt;
  try {
    return ReportedFailure{m[1].str(), 1e-3 * std::stod(m[2].str()), 1e-3 * std::stod(m[3].str())};
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

FeatureVerdict explain_features(const std::vector<FeatureRun>& runs, const LabFeatures& lab) {
  FeatureVerdict verdict;
  if (runs.empty() || runs.front().failed) return verdict;
  const bool peak_stated = lab.peak_sd > 0.0;
  const auto gap_sd = [&](const FeatureRun& r) {
    return peak_stated ? std::abs(r.peak_force - lab.peak_force) / lab.peak_sd : 0.0;
  };
  verdict.gap_before_sd = verdict.gap_after_sd = gap_sd(runs.front());
  const FeatureRun* best = nullptr;
  for (std::size_t k = 1; k < runs.size(); ++k) {
    const FeatureRun& r = runs[k];
    if (r.failed || (lab.zone && r.zone != *lab.zone)) continue;
    if (peak_stated && gap_sd(r) >= verdict.gap_before_sd) continue;
    if (!lab.zone && !peak_stated) continue;  // nothing stated to explain
    verdict.candidates.push_back(r.effect);
    if (!best || gap_sd(r) < gap_sd(*best)) best = &r;
  }
  if (!best) return verdict;
  verdict.effect = best->effect;
  verdict.gap_after_sd = gap_sd(*best);
  verdict.shrink = verdict.gap_before_sd > 0.0 ? 1.0 - verdict.gap_after_sd / verdict.gap_before_sd : 0.0;
  verdict.within_scatter = verdict.gap_after_sd <= 1.0;
  return verdict;
}

}  // namespace dtwire::gap
