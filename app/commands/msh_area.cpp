#include "msh_area.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <unordered_map>

#include "dtwire/core/error.hpp"

namespace dtwire::app {
namespace {

using Point = std::array<double, 3>;

Point sub(const Point& a, const Point& b) { return {{a[0] - b[0], a[1] - b[1], a[2] - b[2]}}; }
double cross_norm(const Point& a, const Point& b) {
  return std::hypot(a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]);
}

// Bilinear quadrilateral x(xi, eta) over [0, 1]^2 (nodes counter-clockwise): area = int |x_xi x x_eta|.
double quad_area(const std::array<Point, 4>& x) {
  const double g[2] = {0.5 - 0.5 / std::sqrt(3.0), 0.5 + 0.5 / std::sqrt(3.0)};
  double area = 0.0;
  for (double xi : g)
    for (double eta : g) {
      Point d_xi{}, d_eta{};
      for (unsigned c = 0; c < 3; ++c) {
        d_xi[c] = (1 - eta) * (x[1][c] - x[0][c]) + eta * (x[2][c] - x[3][c]);
        d_eta[c] = (1 - xi) * (x[3][c] - x[0][c]) + xi * (x[2][c] - x[1][c]);
      }
      area += 0.25 * cross_norm(d_xi, d_eta);
    }
  return area;
}

}  // namespace

double msh_surface_area(const std::filesystem::path& msh, const std::vector<unsigned>& physical_ids) {
  std::ifstream in(msh);
  if (!in) throw InputError(msh.string(), "cannot read the mesh file");
  std::unordered_map<long, Point> nodes;
  double area = 0.0;
  std::string line;
  const auto fail = [&](const std::string& what) { throw InputError(msh.string(), what); };
  while (std::getline(in, line)) {
    if (line == "$MeshFormat") {
      std::getline(in, line);
      if (line.rfind("2.2 0", 0) != 0) fail("expected an ASCII MSH 2.2 file (`dtwire mesh`), found '" + line + "'");
    } else if (line == "$Nodes") {
      long count = 0;
      in >> count;
      for (long k = 0; k < count; ++k) {
        long id = 0;
        Point x{};
        if (!(in >> id >> x[0] >> x[1] >> x[2])) fail("bad $Nodes section");
        nodes[id] = x;
      }
    } else if (line == "$Elements") {
      long count = 0;
      in >> count;
      std::getline(in, line);
      for (long k = 0; k < count; ++k) {
        std::getline(in, line);
        std::istringstream element(line);
        long id = 0, type = 0, tags = 0, physical = 0, skip = 0;
        if (!(element >> id >> type >> tags >> physical)) fail("bad element line");
        for (long t = 1; t < tags; ++t) element >> skip;
        if (type != 3 && type != 2) continue;  // only quadrilaterals and triangles are surfaces
        if (std::find(physical_ids.begin(), physical_ids.end(), static_cast<unsigned>(physical)) == physical_ids.end())
          continue;
        std::array<Point, 4> x{};
        for (int n = 0; n < (type == 3 ? 4 : 3); ++n) {
          long node = 0;
          if (!(element >> node) || !nodes.count(node)) fail("element " + std::to_string(id) + ": unknown node");
          x[n] = nodes.at(node);
        }
        area += type == 3 ? quad_area(x) : 0.5 * cross_norm(sub(x[1], x[0]), sub(x[2], x[0]));
      }
    }
  }
  return area;
}

}  // namespace dtwire::app
