#include "dtwire/gap/curve_metrics.hpp"

#include <algorithm>
#include <cmath>

namespace dtwire::gap {
namespace {

double travel_tolerance(const std::vector<double>& u) {
  const auto [lo, hi] = std::minmax_element(u.begin(), u.end());
  return 1e-3 * (*hi - *lo);
}

// A branch of the model with u non-decreasing: a view of the model's own points where they are
// (a loading branch that never steps back, the common case), else of a copy made monotone.
struct BranchView {
  const double* u = nullptr;
  const double* f = nullptr;
  std::size_t n = 0;
};

struct MonotoneCopy {
  std::vector<double> u, f;
};

// The model's branches as views (into the model or into `copies`, whose storage is reused: the
// fits evaluate this for every trial curve, and allocating and copying cost more than the
// interpolation).
void monotone_branches(const ForceCurve& model, std::vector<MonotoneCopy>& copies, std::vector<BranchView>& out) {
  const std::vector<Branch> branches = split_monotone_branches(model.u, travel_tolerance(model.u));
  copies.resize(branches.size());
  out.assign(branches.size(), BranchView{});
  for (std::size_t k = 0; k < branches.size(); ++k) {
    const Branch& b = branches[k];
    const bool loading = b.direction == BranchDirection::Loading;
    if (loading && std::is_sorted(model.u.begin() + static_cast<std::ptrdiff_t>(b.begin),
                                  model.u.begin() + static_cast<std::ptrdiff_t>(b.end))) {
      out[k] = {model.u.data() + b.begin, model.f.data() + b.begin, b.end - b.begin};
      continue;
    }
    MonotoneCopy& m = copies[k];
    m.u.clear();
    m.f.clear();
    for (std::size_t i = b.begin; i < b.end; ++i) {
      const double u = loading ? model.u[i] : -model.u[i];
      m.u.push_back(m.u.empty() ? u : std::max(u, m.u.back()));
      m.f.push_back(model.f[i]);
    }
    if (!loading) {
      for (double& u : m.u) u = -u;
      std::reverse(m.u.begin(), m.u.end());
      std::reverse(m.f.begin(), m.f.end());
    }
    out[k] = {m.u.data(), m.f.data(), m.u.size()};
  }
}

// interpolate_clamped on a view, with the search started at `cursor` (the index of the first u
// above the previous, smaller query): the lab's points come in order along a branch, so the walk
// is short.
double interpolate_from(const BranchView& b, double xq, std::size_t& cursor) {
  if (xq <= b.u[0]) return b.f[0];
  if (xq >= b.u[b.n - 1]) return b.f[b.n - 1];
  if (cursor == 0 || cursor >= b.n || b.u[cursor - 1] > xq)
    cursor = static_cast<std::size_t>(std::upper_bound(b.u, b.u + b.n, xq) - b.u);
  else
    while (b.u[cursor] <= xq) ++cursor;
  const std::size_t i = cursor;
  const double t = (xq - b.u[i - 1]) / (b.u[i] - b.u[i - 1]);
  return b.f[i - 1] + t * (b.f[i] - b.f[i - 1]);
}

}  // namespace

double interpolate_clamped(const std::vector<double>& x, const std::vector<double>& y, double xq) {
  std::size_t cursor = 0;  // no previous query: a binary search
  return interpolate_from({x.data(), y.data(), x.size()}, xq, cursor);
}

Comparison make_comparison(const ForceCurve& lab) {
  Comparison c;
  c.lab = lab;
  const std::size_t n = lab.size();
  double travel = 0.0, peak = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    if (i > 0) travel += std::abs(lab.u[i] - lab.u[i - 1]);
    peak = std::max(peak, std::abs(lab.f[i]));
  }
  c.u_scale = travel > 0 ? travel : 1.0;
  c.f_scale = peak > 0 ? peak : 1.0;
  c.weight.assign(n, 0.0);
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const double half = 0.5 * std::abs(lab.u[i + 1] - lab.u[i]) / c.u_scale;
    c.weight[i] += half;
    c.weight[i + 1] += half;
  }
  c.branches = split_monotone_branches(lab.u, travel_tolerance(lab.u));
  c.branch_of.assign(n, 0);
  for (std::size_t b = 0; b < c.branches.size(); ++b)
    for (std::size_t i = c.branches[b].begin; i < c.branches[b].end; ++i) c.branch_of[i] = b;
  return c;
}

std::vector<double> model_forces_at_lab(const ForceCurve& model, const Comparison& comparison) {
  thread_local std::vector<MonotoneCopy> copies;
  thread_local std::vector<BranchView> branches;
  monotone_branches(model, copies, branches);
  std::vector<double> out(comparison.lab.size());
  std::size_t branch = branches.size(), cursor = 0;
  for (std::size_t i = 0; i < out.size(); ++i) {
    const std::size_t b = std::min(comparison.branch_of[i], branches.size() - 1);
    if (b != branch) {
      branch = b;
      cursor = 0;
    }
    out[i] = interpolate_from(branches[b], comparison.lab.u[i], cursor);
  }
  return out;
}

std::vector<double> normalised_residual(const std::vector<double>& model_forces,
                                        const Comparison& comparison) {
  std::vector<double> r(model_forces.size());
  for (std::size_t i = 0; i < r.size(); ++i)
    r[i] = (model_forces[i] - comparison.lab.f[i]) / comparison.f_scale;
  return r;
}

double normalised_area(const std::vector<double>& model_forces, const Comparison& comparison) {
  double area = 0.0;
  for (std::size_t i = 0; i < model_forces.size(); ++i)
    area += comparison.weight[i] * std::abs(model_forces[i] - comparison.lab.f[i]);
  return area / comparison.f_scale;
}

double normalised_area(const ForceCurve& model, const Comparison& comparison) {
  return normalised_area(model_forces_at_lab(model, comparison), comparison);
}

double frechet_distance(const ForceCurve& model, const Comparison& comparison,
                        std::size_t max_points) {
  auto thin = [&](const ForceCurve& c) {
    std::vector<std::pair<double, double>> p;
    const std::size_t stride = std::max<std::size_t>(1, (c.size() + max_points - 1) / max_points);
    for (std::size_t i = 0; i < c.size(); i += stride)
      p.emplace_back(c.u[i] / comparison.u_scale, c.f[i] / comparison.f_scale);
    if ((c.size() - 1) % stride != 0)
      p.emplace_back(c.u.back() / comparison.u_scale, c.f.back() / comparison.f_scale);
    return p;
  };
  // Only the part of the model inside the laboratory's displacement range: a test that ended
  // early is not a gap.
  const auto [lo, hi] = std::minmax_element(comparison.lab.u.begin(), comparison.lab.u.end());
  ForceCurve inside;
  for (std::size_t i = 0; i < model.size(); ++i)
    if (model.u[i] >= *lo && model.u[i] <= *hi) {
      inside.u.push_back(model.u[i]);
      inside.f.push_back(model.f[i]);
    }
  if (inside.size() < 2) inside = model;
  const auto a = thin(inside), b = thin(comparison.lab);
  auto dist = [&](std::size_t i, std::size_t j) {
    return std::hypot(a[i].first - b[j].first, a[i].second - b[j].second);
  };
  std::vector<double> previous(b.size()), current(b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    for (std::size_t j = 0; j < b.size(); ++j) {
      const double d = dist(i, j);
      if (i == 0 && j == 0) current[j] = d;
      else if (i == 0) current[j] = std::max(current[j - 1], d);
      else if (j == 0) current[j] = std::max(previous[j], d);
      else current[j] = std::max(std::min({previous[j], previous[j - 1], current[j - 1]}), d);
    }
    std::swap(previous, current);
  }
  return previous.back();
}

double partial_curve_mapping(const ForceCurve& model, const Comparison& comparison,
                             std::size_t samples, std::size_t offsets) {
  struct Path {
    std::vector<double> s, x, y;
  };
  auto path = [&](const ForceCurve& c) {
    Path p;
    p.x.resize(c.size());
    p.y.resize(c.size());
    for (std::size_t i = 0; i < c.size(); ++i) {
      p.x[i] = c.u[i] / comparison.u_scale;
      p.y[i] = c.f[i] / comparison.f_scale;
    }
    p.s = arc_length(p.x, p.y, 1.0, 1.0);
    return p;
  };
  Path a = path(model), b = path(comparison.lab);
  if (a.s.back() < b.s.back()) std::swap(a, b);  // a is the longer curve
  const double slack = a.s.back() - b.s.back();
  const std::vector<double> along = linspace(0.0, b.s.back(), std::max<std::size_t>(samples, 2));
  double best = INFINITY;
  for (std::size_t k = 0; k < std::max<std::size_t>(offsets, 1); ++k) {
    const double shift = offsets > 1 ? slack * static_cast<double>(k) / static_cast<double>(offsets - 1) : 0.0;
    double sum = 0.0;
    for (double s : along) {
      const double dx = interpolate_clamped(a.s, a.x, s + shift) - interpolate_clamped(b.s, b.x, s);
      const double dy = interpolate_clamped(a.s, a.y, s + shift) - interpolate_clamped(b.s, b.y, s);
      sum += std::hypot(dx, dy);
    }
    best = std::min(best, sum / static_cast<double>(along.size()));
  }
  return best;
}

}  // namespace dtwire::gap
