#include "dtwire/gap/regions.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "dtwire/gap/noise.hpp"

namespace dtwire::gap {
namespace {

// Thresholds on the tangent stiffness relative to the elastic one: the toe ends once the
// curve reaches half the elastic stiffness, yield starts when it falls below half again and
// ends below a tenth; the peak region is where the force is within 1 % of its maximum.
constexpr double kToeEnd = 0.5;
constexpr double kYieldStart = 0.5;
constexpr double kYieldEnd = 0.1;
constexpr double kPeakBand = 0.99;

void name_first_loading(const ForceCurve& lab, std::size_t begin, std::size_t end,
                        std::vector<RegionSpan>& out) {
  ForceCurve branch;
  branch.u.assign(lab.u.begin() + static_cast<std::ptrdiff_t>(begin),
                  lab.u.begin() + static_cast<std::ptrdiff_t>(end));
  branch.f.assign(lab.f.begin() + static_cast<std::ptrdiff_t>(begin),
                  lab.f.begin() + static_cast<std::ptrdiff_t>(end));
  const std::size_t n = branch.size();
  if (n < 5) {
    out.push_back({"hardening", begin, end});
    return;
  }
  const Smoothed s = smooth_curve(branch, default_half_window(n));
  const std::size_t peak = static_cast<std::size_t>(
      std::max_element(s.value.begin(), s.value.end()) - s.value.begin());
  const double fmax = s.value[peak];
  std::vector<double> rising;
  for (std::size_t i = 0; i <= peak; ++i)
    if (s.value[i] < 0.8 * fmax) rising.push_back(s.slope[i]);
  double k_el = 0.0;
  if (!rising.empty()) {
    std::sort(rising.begin(), rising.end());
    k_el = rising[static_cast<std::size_t>(0.95 * static_cast<double>(rising.size() - 1))];
  }
  std::size_t toe_end = 0, yield_start = 0, yield_end = 0;
  if (k_el > 0) {
    while (toe_end < peak && s.slope[toe_end] < kToeEnd * k_el) ++toe_end;
    if (toe_end < 3 || s.value[toe_end] > 0.5 * fmax) toe_end = 0;  // no real toe
    yield_start = toe_end;
    while (yield_start < peak && (s.slope[yield_start] >= kYieldStart * k_el ||
                                  s.value[yield_start] < 0.2 * fmax))
      ++yield_start;
    yield_end = yield_start;
    while (yield_end < peak && s.slope[yield_end] >= kYieldEnd * k_el) ++yield_end;
  }
  std::size_t peak_begin = peak, peak_end = peak + 1;
  while (peak_begin > yield_end && s.value[peak_begin - 1] >= kPeakBand * fmax) --peak_begin;
  while (peak_end < n && s.value[peak_end] >= kPeakBand * fmax) ++peak_end;
  const std::vector<std::pair<const char*, std::size_t>> cuts = {
      {"toe", toe_end},         {"elastic", yield_start}, {"yield", yield_end},
      {"hardening", peak_begin}, {"peak", peak_end},      {"post_peak", n}};
  std::size_t from = 0;
  for (const auto& [name, to] : cuts) {
    const std::size_t upto = std::max(from, std::min(to, n));
    if (upto > from) out.push_back({name, begin + from, begin + upto});
    from = upto;
  }
}

struct PrefixSums {
  std::vector<double> n, x, xx, y, xy, yy;
  PrefixSums(const std::vector<double>& xs, const std::vector<double>& ys) {
    const std::size_t m = xs.size() + 1;
    for (auto* v : {&n, &x, &xx, &y, &xy, &yy}) v->assign(m, 0.0);
    for (std::size_t i = 0; i < xs.size(); ++i) {
      n[i + 1] = n[i] + 1;
      x[i + 1] = x[i] + xs[i];
      xx[i + 1] = xx[i] + xs[i] * xs[i];
      y[i + 1] = y[i] + ys[i];
      xy[i + 1] = xy[i] + xs[i] * ys[i];
      yy[i + 1] = yy[i] + ys[i] * ys[i];
    }
  }
  // Residual sum of squares of a straight-line fit to points [a, b).
  double line_sse(std::size_t a, std::size_t b) const {
    const double sn = n[b] - n[a], sx = x[b] - x[a], sxx = xx[b] - xx[a];
    const double sy = y[b] - y[a], sxy = xy[b] - xy[a], syy = yy[b] - yy[a];
    const double syy_c = syy - sy * sy / sn;
    const double sxx_c = sxx - sx * sx / sn;
    const double sxy_c = sxy - sx * sy / sn;
    const double sse = sxx_c > 1e-300 ? syy_c - sxy_c * sxy_c / sxx_c : syy_c;
    return std::max(0.0, sse);
  }
};

std::string classify_direction(const std::vector<double>& x, const std::vector<double>& r,
                               const std::vector<double>& slope, std::size_t a, std::size_t b) {
  double sr = 0, srr = 0, sk = 0, skk = 0, srk = 0;
  const double m = static_cast<double>(b - a);
  for (std::size_t i = a; i < b; ++i) {
    sr += r[i];
    srr += r[i] * r[i];
    sk += slope[i];
    skk += slope[i] * slope[i];
    srk += r[i] * slope[i];
  }
  const double sse_vertical = srr - sr * sr / m;
  const double sse_horizontal = skk > 0 ? srr - srk * srk / skk : srr;
  const PrefixSums sums(std::vector<double>(x.begin() + static_cast<std::ptrdiff_t>(a),
                                            x.begin() + static_cast<std::ptrdiff_t>(b)),
                        std::vector<double>(r.begin() + static_cast<std::ptrdiff_t>(a),
                                            r.begin() + static_cast<std::ptrdiff_t>(b)));
  const double sse_slope = sums.line_sse(0, b - a);
  if (sse_slope < 0.5 * std::min(sse_vertical, sse_horizontal)) return "slope";
  return sse_horizontal < 0.8 * sse_vertical ? "horizontal offset" : "vertical offset";
}

}  // namespace

std::vector<RegionSpan> name_regions(const ForceCurve& lab) {
  std::vector<RegionSpan> out;
  const double tol = 1e-3 * (*std::max_element(lab.u.begin(), lab.u.end()) -
                             *std::min_element(lab.u.begin(), lab.u.end()));
  const auto branches = split_monotone_branches(lab.u, tol);
  bool first_loading_done = false, unloaded = false;
  std::size_t from = 0;
  for (const Branch& b : branches) {
    const std::size_t begin = std::max(from, b.begin);
    if (b.end <= begin) continue;
    if (b.direction == BranchDirection::Loading && !first_loading_done) {
      name_first_loading(lab, begin, b.end, out);
      first_loading_done = true;
    } else if (b.direction == BranchDirection::Unloading) {
      out.push_back({"unloading", begin, b.end});
      unloaded = true;
    } else {
      out.push_back({unloaded ? "reloading" : "hardening", begin, b.end});
    }
    from = b.end;
  }
  return out;
}

std::vector<std::size_t> residual_change_points(const std::vector<double>& x,
                                                const std::vector<double>& r,
                                                double noise_variance) {
  const std::size_t n = r.size();
  const PrefixSums sums(x, r);
  const std::size_t min_length = std::max<std::size_t>(5, n / 50);
  constexpr std::size_t kMaxSegments = 10;
  // Each extra segment adds a change point, an intercept and a slope (BIC: 3 ln n sigma^2).
  const double penalty = 3.0 * std::log(static_cast<double>(n)) * std::max(noise_variance, 1e-10);
  std::vector<std::size_t> starts = {0};
  while (starts.size() < kMaxSegments) {
    double best_gain = 0.0;
    std::size_t best_cut = 0;
    for (std::size_t s = 0; s < starts.size(); ++s) {
      const std::size_t a = starts[s];
      const std::size_t b = s + 1 < starts.size() ? starts[s + 1] : n;
      if (b - a < 2 * min_length) continue;
      const double whole = sums.line_sse(a, b);
      for (std::size_t c = a + min_length; c + min_length <= b; ++c) {
        const double gain = whole - sums.line_sse(a, c) - sums.line_sse(c, b);
        if (gain > best_gain) {
          best_gain = gain;
          best_cut = c;
        }
      }
    }
    if (best_gain <= penalty) break;
    starts.insert(std::upper_bound(starts.begin(), starts.end(), best_cut), best_cut);
  }
  return starts;
}

std::vector<GapSegment> locate_gap(const Comparison& comparison,
                                   const std::vector<double>& model_forces,
                                   const std::vector<RegionSpan>& regions, double noise_sigma_N) {
  const ForceCurve& lab = comparison.lab;
  const std::size_t n = lab.size();
  const std::vector<double> r = normalised_residual(model_forces, comparison);
  std::vector<double> travel(n, 0.0);
  for (std::size_t i = 1; i < n; ++i)
    travel[i] = travel[i - 1] + std::abs(lab.u[i] - lab.u[i - 1]) / comparison.u_scale;
  const double sigma = noise_sigma_N / comparison.f_scale;
  auto starts = residual_change_points(travel, r, sigma * sigma);
  // Region boundaries are change points too, so a segment never straddles two named regions.
  for (const RegionSpan& region : regions)
    if (region.begin > 0 && region.begin < n) starts.push_back(region.begin);
  std::sort(starts.begin(), starts.end());
  starts.erase(std::unique(starts.begin(), starts.end()), starts.end());

  std::vector<std::string> region_of(n, regions.empty() ? "hardening" : regions.front().name);
  for (const RegionSpan& region : regions)
    for (std::size_t i = region.begin; i < region.end && i < n; ++i) region_of[i] = region.name;

  const Smoothed smoothed = smooth_curve(lab, default_half_window(n));
  std::vector<double> slope(n);
  for (std::size_t i = 0; i < n; ++i)
    slope[i] = smoothed.slope[i] * comparison.u_scale / comparison.f_scale;
  // Neighbouring pieces merge when they share the region name and the direction.
  std::vector<GapSegment> segments;
  for (std::size_t s = 0; s < starts.size(); ++s) {
    const std::size_t a = starts[s];
    const std::size_t b = s + 1 < starts.size() ? starts[s + 1] : n;
    std::map<std::string, std::size_t> votes;
    for (std::size_t i = a; i < b; ++i) ++votes[region_of[i]];
    const std::string name =
        std::max_element(votes.begin(), votes.end(),
                         [](const auto& p, const auto& q) { return p.second < q.second; })->first;
    const std::string direction = classify_direction(travel, r, slope, a, b);
    if (!segments.empty() && segments.back().region == name &&
        segments.back().direction == direction) {
      segments.back().end = b;
    } else {
      GapSegment g;
      g.region = name;
      g.begin = a;
      g.end = b;
      g.direction = direction;
      segments.push_back(g);
    }
  }
  const auto gaps = segment_gaps(segments, comparison, model_forces);
  double total = 0.0;
  for (double g : gaps) total += g;
  for (std::size_t k = 0; k < segments.size(); ++k) {
    GapSegment& g = segments[k];
    g.from_m = lab.u[g.begin];
    g.to_m = lab.u[g.end - 1];
    g.gap = gaps[k];
    g.share = total > 0 ? gaps[k] / total : 1.0 / static_cast<double>(segments.size());
  }
  return segments;
}

std::vector<double> segment_gaps(const std::vector<GapSegment>& segments,
                                 const Comparison& comparison,
                                 const std::vector<double>& model_forces) {
  std::vector<double> out;
  for (const GapSegment& g : segments) {
    double area = 0.0;
    for (std::size_t i = g.begin; i < g.end; ++i)
      area += comparison.weight[i] * std::abs(model_forces[i] - comparison.lab.f[i]);
    out.push_back(area / comparison.f_scale);
  }
  return out;
}

}  // namespace dtwire::gap
