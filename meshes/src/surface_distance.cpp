// Minimum signed distance between the lateral surfaces of two wires, from the nodes of each
// to the triangles of the other, with a uniform bucket grid.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <unordered_map>
#include <unordered_set>

#include "dtwire/meshes/mesh_check.hpp"

namespace dtwire::meshes {
namespace {

struct Triangle {
  Vec3 a, b, c;
  Vec3 normal;  // outward (unit)
};

// Closest point on triangle abc to p (Ericson, Real-Time Collision Detection, 5.1.5).
Vec3 closest_point(const Vec3& p, const Triangle& t) {
  const Vec3 ab = t.b - t.a, ac = t.c - t.a, ap = p - t.a;
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return t.a;
  const Vec3 bp = p - t.b;
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return t.b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return t.a + (d1 / (d1 - d3)) * ab;
  const Vec3 cp = p - t.c;
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return t.c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return t.a + (d2 / (d2 - d6)) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return t.b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (t.c - t.b);
  const double denominator = 1 / (va + vb + vc);
  return t.a + (vb * denominator) * ab + (vc * denominator) * ac;
}

class TriangleGrid {
 public:
  TriangleGrid(std::vector<Triangle> triangles, double cell) : triangles_(std::move(triangles)), cell_(cell) {
    for (std::size_t i = 0; i < triangles_.size(); ++i) {
      const Triangle& t = triangles_[i];
      const Vec3 lo{std::min({t.a.x, t.b.x, t.c.x}), std::min({t.a.y, t.b.y, t.c.y}), std::min({t.a.z, t.b.z, t.c.z})};
      const Vec3 hi{std::max({t.a.x, t.b.x, t.c.x}), std::max({t.a.y, t.b.y, t.c.y}), std::max({t.a.z, t.b.z, t.c.z})};
      for_cells(lo, hi, [&](std::int64_t key) { buckets_[key].push_back(i); });
    }
  }

  // Signed distance from p to the nearest triangle within `radius`, or +infinity.
  double signed_distance(const Vec3& p, double radius) const {
    double best = std::numeric_limits<double>::infinity(), sign = 1;
    for_cells(p - Vec3{radius, radius, radius}, p + Vec3{radius, radius, radius}, [&](std::int64_t key) {
      const auto found = buckets_.find(key);
      if (found == buckets_.end()) return;
      for (std::size_t i : found->second) {
        const Vec3 q = closest_point(p, triangles_[i]);
        const double d = distance(p, q);
        if (d < best) {
          best = d;
          sign = dot(p - q, triangles_[i].normal) < 0 ? -1 : 1;
        }
      }
    });
    return best <= radius ? sign * best : std::numeric_limits<double>::infinity();
  }

 private:
  template <class Visit>
  void for_cells(const Vec3& lo, const Vec3& hi, Visit visit) const {
    auto index = [&](double x) { return static_cast<std::int64_t>(std::floor(x / cell_)); };
    for (auto i = index(lo.x); i <= index(hi.x); ++i)
      for (auto j = index(lo.y); j <= index(hi.y); ++j)
        for (auto k = index(lo.z); k <= index(hi.z); ++k)
          visit(((i & 0x1fffff) << 42) | ((j & 0x1fffff) << 21) | (k & 0x1fffff));
  }

  std::vector<Triangle> triangles_;
  double cell_;
  std::unordered_map<std::int64_t, std::vector<std::size_t>> buckets_;
};

void lateral_faces(const HexMesh& mesh, int wire, std::vector<Triangle>& triangles,
                   std::unordered_set<std::size_t>& nodes) {
  for (std::size_t f = 0; f < mesh.quads.size(); ++f) {
    const int id = mesh.quad_boundary[f];
    if (wire_of_id(id) != wire || !is_lateral_boundary(id)) continue;
    const auto& q = mesh.quads[f];
    const Vec3 p[4] = {mesh.nodes[q[0]], mesh.nodes[q[1]], mesh.nodes[q[2]], mesh.nodes[q[3]]};
    // Both diagonals: the bilinear face lies between the two splits.
    for (const auto& t : {std::array<int, 3>{0, 1, 2}, {0, 2, 3}, {0, 1, 3}, {1, 2, 3}}) {
      const Vec3 n = cross(p[t[1]] - p[t[0]], p[t[2]] - p[t[0]]);
      triangles.push_back({p[t[0]], p[t[1]], p[t[2]], normalized(n)});
    }
    nodes.insert(q.begin(), q.end());
  }
}

}  // namespace

double min_surface_distance(const HexMesh& mesh, int wire_a, int wire_b, double search_radius) {
  std::vector<Triangle> triangles[2];
  std::unordered_set<std::size_t> nodes[2];
  lateral_faces(mesh, wire_a, triangles[0], nodes[0]);
  lateral_faces(mesh, wire_b, triangles[1], nodes[1]);
  double result = std::numeric_limits<double>::infinity();
  for (int side = 0; side < 2; ++side) {
    const TriangleGrid grid(std::move(triangles[1 - side]), search_radius);
    for (std::size_t n : nodes[side]) result = std::min(result, grid.signed_distance(mesh.nodes[n], search_radius));
  }
  return result;
}

}  // namespace dtwire::meshes
