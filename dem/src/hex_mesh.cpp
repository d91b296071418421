// The hexagonal DT mesh generator (layout in hex_mesh.hpp).
#include "dtwire/dem/hex_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

namespace dtwire::dem {
namespace {

constexpr double kPi = 3.14159265358979323846;

void require_positive(double value, const std::string& field) {
  if (!(value > 0.0) || !std::isfinite(value)) throw std::invalid_argument(field + ": must be a positive number");
}

}  // namespace

std::string link_tag_name(LinkTag tag) {
  switch (tag) {
    case LinkTag::SingleWire: return "sw";
    case LinkTag::DoubleTwist: return "dt";
    case LinkTag::Selvedge: return "selvedge";
  }
  return "?";
}

HexMeshSpec hex_pattern(const std::string& name) {
  HexMeshSpec spec;  // 8x10 rockfall net, 2.7 mm (wire_2.7mm_literature.md)
  if (name == "8x10_2.7mm") return spec;
  if (name == "8x10_3.1mm") {  // gabion: 3.1 mm wire, 35 mm twists
    spec.wire_diameter = 0.0031;
    spec.twist_length = 0.035;
    return spec;
  }
  throw std::invalid_argument("pattern: unknown pattern '" + name + "', expected 8x10_2.7mm or 8x10_3.1mm");
}

HexMeshSize hex_mesh_size(const HexMeshSpec& spec) {
  const double t = spec.twist_length, rise = 0.5 * (spec.opening_height - t), period = 2.0 * (t + rise);
  const double eps = 1e-9;
  const double columns = std::floor(spec.width / (0.5 * spec.opening_width) + eps) + 1.0;
  // Twists of a column of parity p start at p (t + rise) + k period and must end inside.
  auto twists = [&](int parity) { return std::max(0.0, std::floor((spec.height + eps - t - parity * (t + rise)) / period) + 1.0); };
  const double even = std::ceil(0.5 * columns), odd = columns - even;
  const double total = even * twists(0) + odd * twists(1);
  HexMeshSize size;
  const double wire_links = 3.0 * total;  // an upper bound: a twist and two SW links per twist
  const double selvedge_links = spec.selvedge ? 2.0 * std::max(twists(0), twists(1)) : 0.0;
  const bool split = spec.nodes_per_wire == 3;
  size.nodes = 2.0 * total + (split ? wire_links : 0.0);
  size.links = (split ? 2.0 : 1.0) * wire_links + selvedge_links;
  return size;
}

HexMesh generate_hex_mesh(const HexMeshSpec& spec) {
  require_positive(spec.width, "width_m");
  require_positive(spec.height, "height_m");
  require_positive(spec.opening_width, "opening_width_m");
  require_positive(spec.opening_height, "opening_height_m");
  require_positive(spec.twist_length, "twist_length_m");
  require_positive(spec.wire_diameter, "wire_diameter_m");
  require_positive(spec.node_radius, "node_radius_m");
  if (spec.nodes_per_wire != 2 && spec.nodes_per_wire != 3)
    throw std::invalid_argument("nodes_per_wire: expected 2 or 3, found " + std::to_string(spec.nodes_per_wire));
  if (spec.twist_length >= spec.opening_height)
    throw std::invalid_argument("twist_length_m: must be shorter than the opening height");
  if (spec.width < spec.opening_width)
    throw std::invalid_argument("width_m: the panel (" + std::to_string(spec.width) +
                                " m) is narrower than one mesh opening (" + std::to_string(spec.opening_width) + " m)");
  if (spec.height < spec.opening_height)
    throw std::invalid_argument("height_m: the panel (" + std::to_string(spec.height) +
                                " m) is shorter than one mesh opening (" + std::to_string(spec.opening_height) + " m)");

  const double t = spec.twist_length;
  const double rise = 0.5 * (spec.opening_height - t);
  const double period = 2.0 * (t + rise);
  const double spacing = 0.5 * spec.opening_width;
  const double eps = 1e-9;
  HexMesh mesh;
  mesh.columns = static_cast<int>(std::floor(spec.width / spacing + eps)) + 1;

  // Twists, column by column; the bottom node of each is found by (column, row).
  std::map<std::pair<int, long>, int> bottom_of;  // (column, row of 'period / 2' units) -> node
  std::vector<int> column_of;
  auto add_node = [&](double x, double y, int column) {
    NetNode node;
    node.position = Vector3(x, y, 0.0);
    node.radius = spec.node_radius;
    mesh.net.nodes.push_back(node);
    column_of.push_back(column);
    return static_cast<int>(mesh.net.nodes.size()) - 1;
  };
  for (int i = 0; i < mesh.columns; ++i) {
    const double x = i * spacing;
    const int parity = i % 2;
    for (long k = 0;; ++k) {
      const double y0 = parity * (t + rise) + k * period;
      if (y0 + t > spec.height + eps) break;
      const int bottom = add_node(x, y0, i);
      const int top = add_node(x, y0 + t, i);
      mesh.net.links.push_back({bottom, top, LinkTag::DoubleTwist});
      bottom_of[{i, 2 * k + parity}] = bottom;
    }
  }
  // Single-wire segments: top of twist (i, row) -> bottoms of (i +- 1, row + 1).
  const std::size_t twist_links = mesh.net.links.size();
  for (std::size_t l = 0; l < twist_links; ++l) {
    const int bottom = mesh.net.links[l].a, top = mesh.net.links[l].b;
    const int i = column_of[bottom];
    const long row = std::lround((mesh.net.nodes[bottom].position.y() - (i % 2) * (t + rise)) / period) * 2 + i % 2;
    for (int j : {i - 1, i + 1}) {
      const auto found = bottom_of.find({j, row + 1});
      if (found != bottom_of.end()) mesh.net.links.push_back({top, found->second, LinkTag::SingleWire});
    }
    if (spec.selvedge && (i == 0 || i == mesh.columns - 1)) {
      const auto next = bottom_of.find({i, row + 2});
      if (next != bottom_of.end()) mesh.net.links.push_back({top, next->second, LinkTag::Selvedge});
    }
  }

  for (std::size_t l = 0; l < mesh.net.links.size(); ++l) mesh.net.links[l].wire = static_cast<int>(l);
  mesh.twist_end_nodes = mesh.net.nodes.size();
  if (spec.nodes_per_wire == 3) {
    // Each SW and DT link becomes two half-links through a node at its midpoint.
    std::vector<NetLink> split;
    split.reserve(2 * mesh.net.links.size());
    for (const NetLink& link : mesh.net.links) {
      if (link.tag == LinkTag::Selvedge) {
        split.push_back(link);
        continue;
      }
      const Vector3 middle = 0.5 * (mesh.net.nodes[link.a].position + mesh.net.nodes[link.b].position);
      const int m = add_node(middle.x(), middle.y(), -1);
      split.push_back({link.a, m, link.tag, link.wire, 2});
      split.push_back({m, link.b, link.tag, link.wire, 2});
    }
    mesh.net.links = std::move(split);
  }

  // Masses from the wire steel (half of each link to each of its two nodes).
  const double area = kPi * spec.wire_diameter * spec.wire_diameter / 4.0;
  const double selvedge_area = kPi * spec.selvedge_diameter * spec.selvedge_diameter / 4.0;
  const double turns = 0.5 * spec.twist_half_turns;
  const double pitch = t / turns;
  mesh.twist_wire_factor = std::sqrt(1.0 + std::pow(kPi * spec.wire_diameter / pitch, 2));
  const double sw_length = std::hypot(spacing, rise);
  mesh.mass_per_area = spec.steel_density * area * (4.0 * sw_length + 2.0 * 2.0 * t * mesh.twist_wire_factor) /
                       (spec.opening_width * period);
  std::vector<int> degree(mesh.net.nodes.size(), 0);
  std::vector<double> lumped(mesh.net.nodes.size(), 0.0);
  for (const NetLink& link : mesh.net.links) {
    const double length = (mesh.net.nodes[link.b].position - mesh.net.nodes[link.a].position).norm();
    double steel = spec.steel_density * area * length;
    if (link.tag == LinkTag::DoubleTwist) steel *= 2.0 * mesh.twist_wire_factor;
    if (link.tag == LinkTag::Selvedge) steel = spec.steel_density * selvedge_area * length;
    else {
      ++degree[link.a];
      ++degree[link.b];
    }
    lumped[link.a] += 0.5 * steel;
    lumped[link.b] += 0.5 * steel;
  }
  mesh.sides.assign(mesh.net.nodes.size(), 0u);
  for (std::size_t n = 0; n < mesh.net.nodes.size(); ++n) {
    NetNode& node = mesh.net.nodes[n];
    node.mass = spec.node_mass > 0.0 ? spec.node_mass : lumped[n];
    node.rotational_inertia = 0.4 * node.mass * spec.node_radius * spec.node_radius;
    mesh.net_mass += node.mass;
    if (n >= mesh.twist_end_nodes) continue;  // a middle node: inside its wire, on no boundary
    unsigned sides = 0;
    if (column_of[n] == 0) sides |= kLeft;
    if (column_of[n] == mesh.columns - 1) sides |= kRight;
    // A node misses wires below or above it (bottom or top row) when it has fewer than a node of
    // its column has inside the panel: 3 (a twist and two wires), 2 in the first and last
    // columns (one neighbouring column), 1 in a panel one column wide.
    const bool edge_column = column_of[n] == 0 || column_of[n] == mesh.columns - 1;
    const int inside_degree = mesh.columns == 1 ? 1 : (edge_column ? 2 : 3);
    if (degree[n] < inside_degree) sides |= node.position.y() < 0.5 * spec.height ? kBottom : kTop;
    mesh.sides[n] = sides;
  }
  return mesh;
}

}  // namespace dtwire::dem
