// The non-local average (fem/src/nonlocal_average.hpp) against closed forms: a uniform field is
// its own average everywhere (the renormalisation); a linear field is its own average where the
// ball lies inside the body (the bell weight is even); at a flat free surface a linear field's
// average is its value at the weight's centroid over the half ball,
//   z_bar = (1/2) int_0^R w r^3 dr / int_0^R w r^2 dr = (1/2) (R/24) / (8/105) = 105 R / 384,
// approached at second order by a lattice with trapezoidal volumes; other groups never enter.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "nonlocal_average.hpp"

namespace dtwire::fem {
namespace {

struct Lattice {
  std::vector<std::array<double, 3>> positions;
  std::vector<double> volumes;
  std::vector<int> groups;
};

// Points k h for |i|, |j| <= n and 0 <= k <= n (z >= 0: the body's surface is z = 0), the
// surface layer with half a cell's volume (the trapezoidal rule along z).
Lattice half_space(int n, double h, int group = 0) {
  Lattice l;
  for (int i = -n; i <= n; ++i)
    for (int j = -n; j <= n; ++j)
      for (int k = 0; k <= n; ++k) {
        l.positions.push_back({{i * h, j * h, k * h}});
        l.volumes.push_back(k == 0 ? 0.5 * h * h * h : h * h * h);
        l.groups.push_back(group);
      }
  return l;
}

std::size_t index_of(const Lattice& l, double x, double y, double z) {
  for (std::size_t p = 0; p < l.positions.size(); ++p)
    if (std::abs(l.positions[p][0] - x) + std::abs(l.positions[p][1] - y) + std::abs(l.positions[p][2] - z) < 1e-12)
      return p;
  throw std::logic_error("no lattice point there");
}

TEST(NonlocalAverage, AUniformFieldIsItsOwnAverageAlsoAtTheSurface) {
  const double R = 1e-3;
  const Lattice l = half_space(6, R / 3.0);
  std::vector<std::size_t> all(l.positions.size());
  for (std::size_t p = 0; p < all.size(); ++p) all[p] = p;
  const NonlocalAverage average(l.positions, l.volumes, l.groups, R, all);
  const std::vector<double> field(l.positions.size(), 0.7);
  for (double value : average.apply(field)) EXPECT_NEAR(value, 0.7, 1e-6);  // single-precision weights
}

TEST(NonlocalAverage, ALinearFieldIsItsOwnAverageInsideTheBody) {
  const double R = 1e-3, h = R / 4.0;
  const Lattice l = half_space(10, h);
  const std::size_t inside = index_of(l, 0.0, 0.0, 5 * h);  // the ball (radius 4 h) inside z >= 0
  const NonlocalAverage average(l.positions, l.volumes, l.groups, R, {inside});
  EXPECT_GT(average.neighbours(0), 200u);
  std::vector<double> field(l.positions.size());
  for (std::size_t p = 0; p < field.size(); ++p)
    field[p] = 0.3 + 100.0 * l.positions[p][0] - 250.0 * l.positions[p][1] + 400.0 * l.positions[p][2];
  EXPECT_NEAR(average.apply(field)[0], field[inside], 1e-6);
}

TEST(NonlocalAverage, ALinearFieldAtAFreeSurfaceAveragesToTheHalfBallsCentroid) {
  const double R = 1e-3, centroid = 105.0 * R / 384.0;
  double previous_error = std::numeric_limits<double>::max();
  for (const int per_radius : {4, 8, 16}) {
    const double h = R / per_radius;
    const Lattice l = half_space(per_radius + 1, h);
    const NonlocalAverage average(l.positions, l.volumes, l.groups, R, {index_of(l, 0.0, 0.0, 0.0)});
    std::vector<double> depth(l.positions.size());
    for (std::size_t p = 0; p < depth.size(); ++p) depth[p] = l.positions[p][2];
    const double error = std::abs(average.apply(depth)[0] - centroid) / centroid;
    EXPECT_LT(error, previous_error) << per_radius << " points per radius";
    previous_error = error;
  }
  EXPECT_LT(previous_error, 0.01);  // 16 points per radius
}

TEST(NonlocalAverage, AnotherGroupNeverEntersTheAverage) {
  const double R = 1e-3;
  Lattice l = half_space(4, R / 3.0, 0);
  const Lattice other = half_space(4, R / 3.0, 1);  // the same places: another wire in contact
  const std::size_t n = l.positions.size();
  l.positions.insert(l.positions.end(), other.positions.begin(), other.positions.end());
  l.volumes.insert(l.volumes.end(), other.volumes.begin(), other.volumes.end());
  l.groups.insert(l.groups.end(), other.groups.begin(), other.groups.end());
  std::vector<std::size_t> all(l.positions.size());
  for (std::size_t p = 0; p < all.size(); ++p) all[p] = p;
  const NonlocalAverage average(l.positions, l.volumes, l.groups, R, all);
  std::vector<double> field(l.positions.size(), 0.0);
  for (std::size_t p = n; p < field.size(); ++p) field[p] = 1.0;
  const std::vector<double> out = average.apply(field);
  for (std::size_t p = 0; p < out.size(); ++p) {
    if (p < n)
      EXPECT_EQ(out[p], 0.0) << p;
    else
      EXPECT_NEAR(out[p], 1.0, 1e-6) << p;
  }
}

// The count the solver checks against the memory before it stores the weights: every pair within
// R, by brute force, and the rows the average then holds.
TEST(NonlocalAverage, CountsThePairsItWillStore) {
  const double R = 1e-3;
  const Lattice l = half_space(3, 0.4e-3);
  std::vector<std::size_t> own;
  for (std::size_t p = 0; p < l.positions.size(); p += 7) own.push_back(p);
  std::size_t brute = 0, stored = 0;
  for (std::size_t p : own)
    for (const auto& y : l.positions) {
      const double d2 = std::pow(l.positions[p][0] - y[0], 2) + std::pow(l.positions[p][1] - y[1], 2) +
                        std::pow(l.positions[p][2] - y[2], 2);
      brute += d2 < R * R ? 1 : 0;
    }
  const NonlocalAverage average(l.positions, l.volumes, l.groups, R, own);
  for (std::size_t i = 0; i < average.size(); ++i) stored += average.neighbours(i);
  EXPECT_EQ(NonlocalAverage::count_pairs(l.positions, l.groups, R, own), brute);
  EXPECT_EQ(stored, brute);
}

TEST(NonlocalAverage, RefusesARadiusThatIsNoLengthAndMismatchedInput) {
  const Lattice l = half_space(1, 1e-3);
  for (const double radius : {0.0, -1e-3, std::nan(""), std::numeric_limits<double>::infinity()})
    EXPECT_THROW(NonlocalAverage(l.positions, l.volumes, l.groups, radius, {0}), std::invalid_argument) << radius;
  EXPECT_THROW(NonlocalAverage(l.positions, {1.0}, l.groups, 1e-3, {0}), std::invalid_argument);
  EXPECT_THROW(NonlocalAverage(l.positions, l.volumes, l.groups, 1e-3, {l.positions.size()}), std::invalid_argument);
  std::vector<double> zero_volume = l.volumes;
  zero_volume[0] = 0.0;
  EXPECT_THROW(NonlocalAverage(l.positions, zero_volume, l.groups, 1e-3, {0}), std::invalid_argument);
  const NonlocalAverage average(l.positions, l.volumes, l.groups, 1e-3, {0});
  EXPECT_THROW(average.apply({1.0, 2.0}), std::invalid_argument);
}

}  // namespace
}  // namespace dtwire::fem
