#include "dtwire/calibrate/experiment.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "dtwire/core/curve_ops.hpp"
#include "dtwire/core/error.hpp"

namespace dtwire::calibrate {
namespace {

double range_of(const std::vector<double>& v) {
  const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
  return *hi - *lo;
}

std::vector<Branch> branches_of(const std::vector<double>& x, double relative_tolerance) {
  return split_monotone_branches(x, relative_tolerance * range_of(x));
}

// Round-off on an abscissa that does not move, as a fraction of its range (a stall, below).
constexpr double kStallTolerance = 1e-9;

// Indices of a branch whose abscissa strictly advances (points that step back are skipped), so
// that interpolation is well defined. Of a stall (points at one abscissa within `stall`) the
// last point is kept: where the abscissa moves on, the curve leaves from the stall's end.
std::vector<std::size_t> strictly_monotone(const std::vector<double>& x, const Branch& b, double stall) {
  std::vector<std::size_t> kept{b.begin};
  const bool up = b.direction == BranchDirection::Loading;
  for (std::size_t i = b.begin + 1; i < b.end; ++i) {
    const double last = x[kept.back()];
    if (std::abs(x[i] - last) <= stall)
      kept.back() = i;
    else if (up ? x[i] > last : x[i] < last)
      kept.push_back(i);
  }
  return kept;
}

std::vector<double> pick(const std::vector<double>& v, const std::vector<std::size_t>& idx) {
  std::vector<double> out;
  out.reserve(idx.size());
  for (std::size_t i : idx) out.push_back(v[i]);
  return out;
}

// Indices of a non-decreasing sequence (an arc length, a progress) without its repeated values,
// for interpolation.
std::vector<std::size_t> increasing(const std::vector<double>& s) {
  std::vector<std::size_t> keep{0};
  for (std::size_t i = 1; i < s.size(); ++i)
    if (s[i] > s[keep.back()]) keep.push_back(i);
  return keep;
}

// A run of consecutive points whose abscissa stays within `tolerance` of the run's first value:
// a leg of the path along which the abscissa does not move (a pull before bending at fixed
// rotation, a hold). [begin, end) index the curve; at least two points. The tolerance is round-off
// (kStallTolerance x the abscissa's range), not the branch tolerance: finely sampled curves have
// neighbours closer than that everywhere, and a measured hold with noise on its abscissa is
// interpolated as before.
struct Stall {
  std::size_t begin = 0;
  std::size_t end = 0;
};

std::vector<Stall> stalls_in(const std::vector<double>& x, const Branch& b, double tolerance) {
  std::vector<Stall> out;
  std::size_t start = b.begin;
  for (std::size_t i = b.begin + 1; i <= b.end; ++i)
    if (i == b.end || std::abs(x[i] - x[start]) > tolerance) {
      if (i - start >= 2) out.push_back({start, i});
      start = i;
    }
  return out;
}

// Progress along a stall: the normalised arc length of the channel itself (the abscissa does not
// move), so that a pull from 0 to 716 N is compared at equal fractions of its own rise; the
// points' position in the run where the channel does not move at all.
std::vector<double> stall_progress(const std::vector<double>& y, const Stall& s) {
  std::vector<double> p{0.0};
  for (std::size_t i = s.begin + 1; i < s.end; ++i) p.push_back(p.back() + std::abs(y[i] - y[i - 1]));
  const double length = p.back();
  for (std::size_t k = 0; k < p.size(); ++k)
    p[k] = length > 0 ? p[k] / length : static_cast<double>(k) / static_cast<double>(p.size() - 1);
  return p;
}

// Target points on a stall are compared with the simulated stall at the same abscissa (if the
// simulation has one there) at equal progress; interpolation at one abscissa value would compare
// them all with a single simulated point (issue 36: half the rows of a bend at held tension are
// its pull at zero rotation).
void compare_stalls_by_progress(const std::vector<double>& tx, const std::vector<double>& ty, const Branch& tb,
                                const std::vector<double>& sx, const std::vector<double>& sy, const Branch& sb,
                                double tolerance, std::vector<double>& out) {
  const auto simulated = stalls_in(sx, sb, tolerance);
  for (const Stall& t : stalls_in(tx, tb, tolerance)) {
    const auto match = std::find_if(simulated.begin(), simulated.end(), [&](const Stall& s) {
      return std::abs(sx[s.begin] - tx[t.begin]) <= tolerance;
    });
    if (match == simulated.end()) continue;
    const std::vector<double> sp = stall_progress(sy, *match);
    std::vector<double> syv(sy.begin() + static_cast<std::ptrdiff_t>(match->begin),
                            sy.begin() + static_cast<std::ptrdiff_t>(match->end));
    const auto keep = increasing(sp);
    const std::vector<double> tp = stall_progress(ty, t);
    const std::vector<double> values =
        keep.size() < 2 ? std::vector<double>(tp.size(), syv.front()) : interpolate(pick(sp, keep), pick(syv, keep), tp);
    for (std::size_t i = t.begin; i < t.end; ++i) out[i] = values[i - t.begin];
  }
}

// Simulated values of channel `quantity` at every target point, branch by branch.
std::vector<double> simulated_values(const Experiment& e, const Curve& simulated,
                                     const std::string& quantity) {
  if (!simulated.has(e.abscissa) || !simulated.has(quantity))
    throw ComputationError("experiment '" + e.name + "': the simulated curve lacks channel '" +
                           (simulated.has(e.abscissa) ? quantity : e.abscissa) + "'");
  if (simulated.size() < 2)
    throw ComputationError("experiment '" + e.name + "': the simulated curve has < 2 points");
  for (const std::string& q : {e.abscissa, quantity})
    if (simulated.channel(q).unit.dimension != e.target.channel(q).unit.dimension)
      throw ComputationError("experiment '" + e.name + "': the simulated " + q + " is a " +
                             std::string(dimension_name(simulated.channel(q).unit.dimension)) +
                             ", the target's a " + std::string(dimension_name(e.target.channel(q).unit.dimension)));
  const std::vector<double> tx = e.target.si(e.abscissa);
  const std::vector<double> ty = e.target.si(quantity);
  const std::vector<double> sx = simulated.si(e.abscissa);
  const std::vector<double> sy = simulated.si(quantity);
  for (double v : sy)
    if (!std::isfinite(v))
      throw ComputationError("experiment '" + e.name + "': the simulated " + quantity +
                             " is not finite");
  const auto target_branches = branches_of(tx, e.branch_tolerance);
  const auto sim_branches = branches_of(sx, e.branch_tolerance);
  if (sim_branches.size() != target_branches.size())
    throw ComputationError("experiment '" + e.name + "': the simulated curve has " +
                           std::to_string(sim_branches.size()) + " monotone branch(es), the target " +
                           std::to_string(target_branches.size()));
  std::vector<double> out(tx.size(), 0.0);
  for (std::size_t b = 0; b < target_branches.size(); ++b) {
    const Branch& tb = target_branches[b];
    const auto sidx = strictly_monotone(sx, sim_branches[b], kStallTolerance * range_of(sx));
    if (sidx.size() < 2)
      throw ComputationError("experiment '" + e.name + "': simulated branch " +
                             std::to_string(b + 1) + " has < 2 distinct points");
    std::vector<double> query, values;
    if (e.kind == AbscissaKind::Channel) {
      query.assign(tx.begin() + tb.begin, tx.begin() + tb.end);
      values = interpolate(pick(sx, sidx), pick(sy, sidx), query);
    } else {
      // Both branches parametrised by their own normalised arc length in the (x, y) plane.
      const std::vector<double> tbx(tx.begin() + tb.begin, tx.begin() + tb.end);
      const std::vector<double> tby(ty.begin() + tb.begin, ty.begin() + tb.end);
      query = normalized_arc_length(tbx, tby);
      std::vector<double> s = normalized_arc_length(pick(sx, sidx), pick(sy, sidx));
      const auto keep = increasing(s);
      values = interpolate(pick(s, keep), pick(pick(sy, sidx), keep), query);
    }
    for (std::size_t i = tb.begin; i < tb.end; ++i) out[i] = values[i - tb.begin];
    if (e.kind == AbscissaKind::Channel)
      compare_stalls_by_progress(tx, ty, tb, sx, sy, sim_branches[b], kStallTolerance * range_of(tx), out);
  }
  return out;
}

double channel_scale(const Experiment& e, const std::string& quantity, double scale) {
  if (scale > 0) return scale;
  const double r = range_of(e.target.si(quantity));
  return r > 0 ? r : 1.0;
}

// Index of the value of largest magnitude (the first, if several).
std::size_t peak_index(const std::vector<double>& v) {
  return static_cast<std::size_t>(
      std::max_element(v.begin(), v.end(), [](double a, double b) { return std::abs(a) < std::abs(b); }) - v.begin());
}

// The simulated curve's peak of `quantity` over its whole path, with its abscissa (SI).
std::pair<double, double> simulated_peak(const Experiment& e, const Curve& simulated, const std::string& quantity) {
  if (!simulated.has(quantity) || !simulated.has(e.abscissa) || simulated.size() == 0)
    throw ComputationError("experiment '" + e.name + "': the simulated curve lacks channel '" + quantity +
                           "' for its peak");
  const std::vector<double> y = simulated.si(quantity);
  for (double v : y)
    if (!std::isfinite(v))
      throw ComputationError("experiment '" + e.name + "': the simulated " + quantity + " is not finite");
  const std::size_t i = peak_index(y);
  return {y[i], simulated.si(e.abscissa)[i]};
}

}  // namespace

void validate(const Experiment& e) {
  const std::string where = "experiment '" + e.name + "': ";
  if (!e.simulator) throw std::invalid_argument(where + "no simulator");
  if (!(e.weight > 0)) throw std::invalid_argument(where + "weight must be > 0");
  if (e.channels.empty()) throw std::invalid_argument(where + "no channel to compare");
  if (!e.target.has(e.abscissa))
    throw std::invalid_argument(where + "the target has no abscissa channel '" + e.abscissa + "'");
  for (const auto& c : e.channels) {
    if (!e.target.has(c.quantity))
      throw std::invalid_argument(where + "the target has no channel '" + c.quantity + "'");
    if (!(c.weight > 0)) throw std::invalid_argument(where + "channel weights must be > 0");
  }
  for (const auto* list : {&e.channels, &e.peaks})
    for (std::size_t i = 0; i < list->size(); ++i)
      for (std::size_t j = 0; j < i; ++j)
        if ((*list)[i].quantity == (*list)[j].quantity)
          throw std::invalid_argument(where + "'" + (*list)[i].quantity + "' is compared twice");
  for (const auto& p : e.peaks) {
    if (!e.target.has(p.quantity))
      throw std::invalid_argument(where + "the target has no channel '" + p.quantity + "' for its peak");
    if (!(p.weight > 0)) throw std::invalid_argument(where + "peak weights must be > 0");
  }
  const auto x = e.target.si(e.abscissa);
  if (!(range_of(x) > 0)) throw std::invalid_argument(where + "the target abscissa is constant");
  for (const Branch& b : branches_of(x, e.branch_tolerance))
    if (strictly_monotone(x, b, kStallTolerance * range_of(x)).size() < 2)
      throw std::invalid_argument(where + "a target branch has < 2 distinct abscissa values");
}

bool compares_channel(const Experiment& e, const std::string& quantity) {
  return std::any_of(e.channels.begin(), e.channels.end(), [&](const ChannelWeight& c) { return c.quantity == quantity; });
}

std::vector<std::size_t> residual_groups(const Experiment& e) {
  std::vector<std::size_t> groups;
  for (const auto& c : e.channels)
    groups.push_back(e.target.size() + static_cast<std::size_t>(std::count_if(
                                           e.peaks.begin(), e.peaks.end(),
                                           [&](const PeakWeight& p) { return p.quantity == c.quantity; })));
  const auto alone = static_cast<std::size_t>(
      std::count_if(e.peaks.begin(), e.peaks.end(), [&](const PeakWeight& p) { return !compares_channel(e, p.quantity); }));
  if (alone > 0) groups.push_back(alone);
  return groups;
}

std::size_t residual_count(const Experiment& e) { return e.channels.size() * e.target.size() + e.peaks.size(); }

std::vector<double> residuals(const Experiment& e, const Curve& simulated) {
  std::vector<double> r;
  r.reserve(residual_count(e));
  const double n = static_cast<double>(e.target.size());
  const auto peak_row = [&](const PeakWeight& p) {
    const std::vector<double> target = e.target.si(p.quantity);
    const double factor = std::sqrt(e.weight * p.weight) / channel_scale(e, p.quantity, p.scale);
    r.push_back(factor * (simulated_peak(e, simulated, p.quantity).first - target[peak_index(target)]));
  };
  for (const auto& c : e.channels) {
    const auto sim = simulated_values(e, simulated, c.quantity);
    const auto target = e.target.si(c.quantity);
    const double factor = std::sqrt(e.weight * c.weight / n) / channel_scale(e, c.quantity, c.scale);
    for (std::size_t i = 0; i < sim.size(); ++i) r.push_back(factor * (sim[i] - target[i]));
    for (const auto& p : e.peaks)
      if (p.quantity == c.quantity) peak_row(p);
  }
  for (const auto& p : e.peaks)
    if (!compares_channel(e, p.quantity)) peak_row(p);
  return r;
}

Curve simulated_at_target(const Experiment& e, const Curve& simulated) {
  Curve out;
  const Channel& x = e.target.channel(e.abscissa);
  out.add_channel(x.quantity, x.unit, x.values);
  for (const auto& c : e.channels) {
    const Unit unit = e.target.channel(c.quantity).unit;
    std::vector<double> values = simulated_values(e, simulated, c.quantity);
    for (double& v : values) v /= unit.to_si;
    out.add_channel(c.quantity, unit, std::move(values));
  }
  out.set_metadata("experiment", e.name);
  return out;
}

std::vector<ChannelQuality> fit_quality(const Experiment& e, const Curve& simulated) {
  std::vector<ChannelQuality> out;
  for (const auto& c : e.channels) {
    const Channel& target = e.target.channel(c.quantity);
    std::vector<double> sim = simulated_values(e, simulated, c.quantity);
    const std::vector<double> t = target.si();
    double mean = 0;
    for (double v : t) mean += v;
    mean /= static_cast<double>(t.size());
    double ss_res = 0, ss_tot = 0;
    for (std::size_t i = 0; i < t.size(); ++i) {
      ss_res += (sim[i] - t[i]) * (sim[i] - t[i]);
      ss_tot += (t[i] - mean) * (t[i] - mean);
    }
    ChannelQuality q;
    q.experiment = e.name;
    q.quantity = c.quantity;
    q.unit = target.unit.symbol;
    q.points = t.size();
    q.rmse = std::sqrt(ss_res / static_cast<double>(t.size())) / target.unit.to_si;
    const double r = range_of(t);
    q.nrmse = r > 0 ? q.rmse * target.unit.to_si / r : 0.0;
    q.r_squared = ss_tot > 0 ? 1.0 - ss_res / ss_tot : 0.0;
    out.push_back(q);
  }
  return out;
}

std::vector<PeakQuality> peak_quality(const Experiment& e, const Curve& simulated) {
  std::vector<PeakQuality> out;
  const Unit x_unit = e.target.channel(e.abscissa).unit;
  for (const auto& p : e.peaks) {
    const Channel& target = e.target.channel(p.quantity);
    const std::vector<double> t = target.si();
    const std::size_t i = peak_index(t);
    const auto [peak, at] = simulated_peak(e, simulated, p.quantity);
    out.push_back({e.name, p.quantity, target.unit.symbol, t[i] / target.unit.to_si, peak / target.unit.to_si,
                   e.target.si(e.abscissa)[i] / x_unit.to_si, at / x_unit.to_si});
  }
  return out;
}

}  // namespace dtwire::calibrate
