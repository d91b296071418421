#include "dtwire/meshes/cross_section.hpp"

#include <algorithm>
#include <cmath>

namespace dtwire::meshes {
namespace {

constexpr double kPi = 3.14159265358979323846;
// Core half-width as a fraction of the radius: core, block and ring cells of similar size.
constexpr double kCoreFraction = 0.45;

class PointSet {
 public:
  explicit PointSet(double tolerance) : tolerance_(tolerance) {}
  std::size_t add(double u, double v) {
    for (std::size_t i = 0; i < points_.size(); ++i)
      if (std::abs(points_[i][0] - u) < tolerance_ && std::abs(points_[i][1] - v) < tolerance_)
        return i;
    points_.push_back({u, v});
    return points_.size() - 1;
  }
  std::vector<std::array<double, 2>> release() { return std::move(points_); }

 private:
  double tolerance_;
  std::vector<std::array<double, 2>> points_;
};

}  // namespace

Resolution resolution(int level, double diameter) {
  const int block = 2 << level;  // 2, 4, 8, 16
  return {block, std::max(1, block / 2), std::max(1, block / 4), 1.5 * diameter / block, level == 0 ? 0.3 : 0.15};
}

double area_preserving_radius_factor(int boundary_segments) {
  const double x = 2 * kPi / boundary_segments;
  return std::sqrt(x / std::sin(x));
}

CrossSection make_o_grid_section(double steel_radius, double coating, const Resolution& res) {
  const int n = res.block_cells;
  const int m = res.radial_cells;
  const int mc = coating > 0 ? res.coating_cells : 0;
  const double factor = area_preserving_radius_factor(4 * n);
  const double a = kCoreFraction * steel_radius;
  const double turn = kPi / (4 * n);  // half a boundary segment
  const double ct = std::cos(turn), st = std::sin(turn);
  PointSet set(1e-9 * steel_radius);
  auto add = [&](double u, double v) { return set.add(ct * u - st * v, st * u + ct * v); };

  CrossSection section;
  // Core: (n+1)^2 grid on [-a, a]^2.
  std::vector<std::size_t> core((n + 1) * (n + 1));
  for (int k = 0; k <= n; ++k)
    for (int i = 0; i <= n; ++i)
      core[k * (n + 1) + i] = add(-a + 2 * a * i / n, -a + 2 * a * k / n);
  for (int k = 0; k < n; ++k)
    for (int i = 0; i < n; ++i) {
      section.quads.push_back({core[k * (n + 1) + i], core[k * (n + 1) + i + 1],
                               core[(k + 1) * (n + 1) + i + 1], core[(k + 1) * (n + 1) + i]});
      section.quad_in_coating.push_back(false);
    }
  // Four curved blocks, block b is the right block (-45..45 deg) turned by b * 90 deg.
  const int layers = m + mc;
  for (int b = 0; b < 4; ++b) {
    const double cb = std::cos(b * kPi / 2), sb = std::sin(b * kPi / 2);
    std::vector<std::size_t> block((n + 1) * (layers + 1));
    for (int i = 0; i <= n; ++i) {
      const double phi = -kPi / 4 + (kPi / 2) * i / n;
      const double inner_u = a, inner_v = -a + 2 * a * i / n;
      const double steel_u = factor * steel_radius * std::cos(phi);
      const double steel_v = factor * steel_radius * std::sin(phi);
      for (int j = 0; j <= layers; ++j) {
        double u, v;
        if (j <= m) {
          const double s = double(j) / m;
          u = (1 - s) * inner_u + s * steel_u;
          v = (1 - s) * inner_v + s * steel_v;
        } else {
          const double radius = factor * (steel_radius + coating * double(j - m) / mc);
          u = radius * std::cos(phi);
          v = radius * std::sin(phi);
        }
        block[i * (layers + 1) + j] = add(cb * u - sb * v, sb * u + cb * v);
      }
    }
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < layers; ++j) {
        section.quads.push_back({block[i * (layers + 1) + j], block[i * (layers + 1) + j + 1],
                                 block[(i + 1) * (layers + 1) + j + 1],
                                 block[(i + 1) * (layers + 1) + j]});
        section.quad_in_coating.push_back(j >= m);
      }
    for (int i = 0; i < n; ++i)
      section.outer_edges.push_back(
          {block[i * (layers + 1) + layers], block[(i + 1) * (layers + 1) + layers]});
  }
  section.points = set.release();
  return section;
}

}  // namespace dtwire::meshes
