#include "nonlocal_average.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <unordered_map>

namespace dtwire::fem {

namespace {

struct CellKey {
  long long i, j, k;
  int group;
  bool operator==(const CellKey& o) const { return i == o.i && j == o.j && k == o.k && group == o.group; }
};

struct CellKeyHash {
  std::size_t operator()(const CellKey& c) const {
    std::size_t h = std::hash<long long>()(c.i);
    h = h * 1000003u ^ std::hash<long long>()(c.j);
    h = h * 1000003u ^ std::hash<long long>()(c.k);
    return h * 1000003u ^ std::hash<int>()(c.group);
  }
};

}  // namespace

namespace {

void check_input(const std::vector<std::array<double, 3>>& positions, const std::vector<double>& volumes,
                 const std::vector<int>& groups, double radius, const std::vector<std::size_t>& own) {
  if (!(radius > 0.0) || !std::isfinite(radius))
    throw std::invalid_argument("non-local average: the radius must be a finite length > 0");
  if (volumes.size() != positions.size() || groups.size() != positions.size())
    throw std::invalid_argument("non-local average: " + std::to_string(positions.size()) + " positions, " +
                                std::to_string(volumes.size()) + " volumes and " + std::to_string(groups.size()) +
                                " groups (one each per point)");
  if (positions.size() > std::numeric_limits<std::uint32_t>::max())
    throw std::invalid_argument("non-local average: more points than a 32-bit index holds");
  for (std::size_t p = 0; p < volumes.size(); ++p)
    if (!(volumes[p] > 0.0)) throw std::invalid_argument("non-local average: point " + std::to_string(p) + " has volume <= 0");
  for (std::size_t p : own)
    if (p >= positions.size()) throw std::invalid_argument("non-local average: own point " + std::to_string(p) + " out of range");
}

// Calls visit(i, y, d2) for every point y of own point i's group within the radius (d2 < R^2),
// the own points in order: a hash grid of cell size R, so only the 27 cells around a point are searched.
template <typename Visit>
void visit_pairs(const std::vector<std::array<double, 3>>& positions, const std::vector<int>& groups, double radius,
                 const std::vector<std::size_t>& own, Visit visit) {
  const auto cell_of = [&](std::size_t p) {
    const auto& x = positions[p];
    return CellKey{static_cast<long long>(std::floor(x[0] / radius)), static_cast<long long>(std::floor(x[1] / radius)),
                   static_cast<long long>(std::floor(x[2] / radius)), groups[p]};
  };
  std::unordered_map<CellKey, std::vector<std::uint32_t>, CellKeyHash> grid;
  for (std::size_t p = 0; p < positions.size(); ++p) grid[cell_of(p)].push_back(static_cast<std::uint32_t>(p));
  const double r2 = radius * radius;
  for (std::size_t i = 0; i < own.size(); ++i) {
    const CellKey c = cell_of(own[i]);
    const auto& x = positions[own[i]];
    for (long long di = -1; di <= 1; ++di)
      for (long long dj = -1; dj <= 1; ++dj)
        for (long long dk = -1; dk <= 1; ++dk) {
          const auto found = grid.find(CellKey{c.i + di, c.j + dj, c.k + dk, c.group});
          if (found == grid.end()) continue;
          for (std::uint32_t y : found->second) {
            const auto& z = positions[y];
            const double d2 = (x[0] - z[0]) * (x[0] - z[0]) + (x[1] - z[1]) * (x[1] - z[1]) + (x[2] - z[2]) * (x[2] - z[2]);
            if (d2 < r2) visit(i, y, d2);
          }
        }
  }
}

}  // namespace

std::size_t NonlocalAverage::count_pairs(const std::vector<std::array<double, 3>>& positions,
                                         const std::vector<int>& groups, double radius,
                                         const std::vector<std::size_t>& own) {
  check_input(positions, std::vector<double>(positions.size(), 1.0), groups, radius, own);
  std::size_t pairs = 0;
  visit_pairs(positions, groups, radius, own, [&](std::size_t, std::uint32_t, double) { ++pairs; });
  return pairs;
}

NonlocalAverage::NonlocalAverage(const std::vector<std::array<double, 3>>& positions, const std::vector<double>& volumes,
                                 const std::vector<int>& groups, double radius, std::vector<std::size_t> own)
    : radius_(radius), own_(std::move(own)), point_count_(positions.size()) {
  check_input(positions, volumes, groups, radius, own_);
  // Two passes: the rows' lengths first, so that the arrays are allocated once at their size (a
  // growing vector would copy itself and need up to twice the memory the solver checked).
  row_start_.assign(own_.size() + 1, 0);
  visit_pairs(positions, groups, radius, own_, [&](std::size_t i, std::uint32_t, double) { ++row_start_[i + 1]; });
  for (std::size_t i = 0; i < own_.size(); ++i) row_start_[i + 1] += row_start_[i];
  column_.resize(row_start_.back());
  weight_.resize(row_start_.back());
  const double r2 = radius * radius;
  std::vector<double> total(own_.size(), 0.0);
  std::vector<std::size_t> next(row_start_.begin(), row_start_.end() - 1);
  visit_pairs(positions, groups, radius, own_, [&](std::size_t i, std::uint32_t y, double d2) {
    const double w = (1.0 - d2 / r2) * (1.0 - d2 / r2) * volumes[y];
    column_[next[i]] = y;
    weight_[next[i]++] = static_cast<float>(w);
    total[i] += w;  // > 0: the point itself is in its own ball (d = 0, w = 1)
  });
  for (std::size_t i = 0; i < own_.size(); ++i)
    for (std::size_t n = row_start_[i]; n < row_start_[i + 1]; ++n)
      weight_[n] = static_cast<float>(weight_[n] / total[i]);
}

std::vector<double> NonlocalAverage::apply(const std::vector<double>& values) const {
  if (values.size() != point_count_)
    throw std::invalid_argument("non-local average: " + std::to_string(values.size()) + " values for " +
                                std::to_string(point_count_) + " points");
  std::vector<double> out(own_.size(), 0.0);
  for (std::size_t i = 0; i < own_.size(); ++i) {
    double sum = 0.0;
    for (std::size_t n = row_start_[i]; n < row_start_[i + 1]; ++n) sum += weight_[n] * values[column_[n]];
    out[i] = sum;
  }
  return out;
}

}  // namespace dtwire::fem
