#include "dtwire/meshes/msh_reader.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

#include "dtwire/core/error.hpp"

namespace dtwire::meshes {
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

// Nodes per element of the gmsh types `dtwire mesh` writes (lines, triangles, quads, hexahedra, points).
int node_count(int type) {
  switch (type) {
    case 1: return 2;
    case 2: return 3;
    case 3: return 4;
    case 4: return 4;
    case 5: return 8;
    case 15: return 1;
    default: return -1;
  }
}

bool is_volume_element(int type) {
  static const std::set<int> types{4, 5, 6, 7, 11, 12, 13, 14, 17, 18, 19};
  return types.count(type) > 0;
}

std::string msh_error(const std::string& expected, const std::string& found) {
  return "cannot read the mesh: expected " + expected + (found.empty() ? "" : ", found '" + found.substr(0, 60) + "'");
}

}  // namespace

MshFile read_msh(const std::filesystem::path& msh) {
  std::ifstream in(msh);
  if (!in) throw InputError(msh.string(), "cannot read the mesh file");
  const auto fail = [&](const std::string& what) { throw InputError(msh.string(), what); };
  MshFile mesh;
  bool format_seen = false;
  for (std::string line; std::getline(in, line);) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line == "$MeshFormat") {
      std::getline(in, line);
      if (line.rfind("2.2 0", 0) != 0) fail("expected an ASCII MSH 2.2 file (`dtwire mesh`), found '" + line + "'");
      format_seen = true;
    } else if (line == "$Nodes") {
      long count = 0;
      if (!(in >> count) || count < 0) fail("$Nodes: expected the node count");
      for (long k = 0; k < count; ++k) {
        long id = 0;
        Point x{};
        if (!(in >> id >> x[0] >> x[1] >> x[2])) fail("$Nodes: node " + std::to_string(k + 1) + " of " +
                                                      std::to_string(count) + " is not 'id x y z'");
        mesh.nodes[id] = x;
      }
    } else if (line == "$Elements") {
      long count = 0;
      if (!(in >> count) || count < 0) fail("$Elements: expected the element count");
      std::getline(in, line);
      for (long k = 0; k < count; ++k) {
        std::getline(in, line);
        std::istringstream element(line);
        long id = 0, tags = 0, skip = 0;
        MshElement e;
        if (!(element >> id >> e.type >> tags >> e.physical) || tags < 1)
          fail("$Elements: line " + std::to_string(k + 1) + " is not 'id type tags physical ...'");
        for (long t = 1; t < tags; ++t) element >> skip;
        const int nodes = node_count(e.type);
        if (nodes < 0) fail("element " + std::to_string(id) + ": gmsh type " + std::to_string(e.type) + " not read");
        for (int n = 0; n < nodes; ++n) {
          long node = 0;
          if (!(element >> node) || !mesh.nodes.count(node))
            fail("element " + std::to_string(id) + ": node " + std::to_string(node) + " is not in $Nodes");
          e.nodes.push_back(node);
        }
        mesh.elements.push_back(std::move(e));
      }
    }
  }
  if (!format_seen) fail("no $MeshFormat section: not a gmsh mesh file");
  return mesh;
}

std::uint64_t count_msh_volume_cells(const std::filesystem::path& msh) {
  const std::string name = msh.string();
  std::ifstream in(msh);
  if (!in) throw InputError(name, "cannot read the mesh: the file does not open");
  std::string line;
  int line_number = 0;
  const auto next = [&](const std::string& expected) {
    if (!std::getline(in, line)) throw InputError(name, line_number, 0, msh_error(expected, "the end of the file"));
    ++line_number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
  };
  double version = 0.0;
  while (std::getline(in, line)) {
    ++line_number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line == "$MeshFormat") {
      next("the format line 'version file-type data-size'");
      std::istringstream format(line);
      int file_type = -1;
      if (!(format >> version >> file_type) || version < 2.0 || version >= 5.0)
        throw InputError(name, line_number, 0, msh_error("a gmsh format 2.x or 4.x", line));
      if (file_type != 0)
        throw InputError(name, line_number, 0,
                         "cannot read the mesh: it is a binary .msh, deal.II reads ASCII gmsh files only (gmsh -bin 0)");
    } else if (line == "$Elements" || line == "$ELM") {
      const bool v4 = version >= 4.0;
      next(v4 ? "'numEntityBlocks numElements minTag maxTag'" : "the number of elements");
      std::istringstream header(line);
      std::uint64_t count = 0, cells = 0;
      if (!(header >> count)) throw InputError(name, line_number, 0, msh_error("a count", line));
      for (std::uint64_t k = 0; k < count; ++k) {
        if (v4) {  // a block: 'entityDim entityTag elementType numElementsInBlock', then its elements
          next("an element block 'entityDim entityTag elementType numElementsInBlock'");
          std::istringstream block(line);
          int dim = 0, tag = 0, type = 0;
          std::uint64_t elements = 0;
          if (!(block >> dim >> tag >> type >> elements))
            throw InputError(name, line_number, 0, msh_error("'entityDim entityTag elementType numElementsInBlock'", line));
          if (dim == 3) cells += elements;
          for (std::uint64_t e = 0; e < elements; ++e) next("an element line");
        } else {
          next("an element line 'id type ntags tags... nodes...'");
          std::istringstream element(line);
          long id = 0;
          int type = 0;
          if (!(element >> id >> type)) throw InputError(name, line_number, 0, msh_error("'id type ntags ...'", line));
          if (is_volume_element(type)) ++cells;
        }
      }
      return cells;
    }
  }
  throw InputError(name, "cannot read the mesh: no $Elements section (expected a gmsh .msh file with its cells)");
}

double surface_area(const MshFile& mesh, const std::vector<int>& physical_ids) {
  double area = 0.0;
  for (const MshElement& e : mesh.elements) {
    if (e.type != 3 && e.type != 2) continue;  // only quadrilaterals and triangles are surfaces
    if (std::find(physical_ids.begin(), physical_ids.end(), e.physical) == physical_ids.end()) continue;
    std::array<Point, 4> x{};
    for (std::size_t n = 0; n < e.nodes.size(); ++n) x[n] = mesh.nodes.at(e.nodes[n]);
    area += e.type == 3 ? quad_area(x) : 0.5 * cross_norm(sub(x[1], x[0]), sub(x[2], x[0]));
  }
  return area;
}

double msh_surface_area(const std::filesystem::path& msh, const std::vector<int>& physical_ids) {
  return surface_area(read_msh(msh), physical_ids);
}

}  // namespace dtwire::meshes
