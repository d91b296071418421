// The hexagonal DT mesh generator: counts, link lengths, opening, mass per area, boundary sides.
#include <gtest/gtest.h>

#include <algorithm>

#include <cmath>
#include <set>
#include <tuple>

#include "dtwire/dem/hex_mesh.hpp"

namespace dtwire::dem {
namespace {

constexpr double kPi = 3.14159265358979323846;

TEST(DemHexMesh, EightByTenPanelCountsAndLinkLengths) {
  HexMeshSpec spec = hex_pattern("8x10_2.7mm");
  const HexMesh mesh = generate_hex_mesh(spec);  // 3 x 3 m
  // 76 columns 40 mm apart; 22 twists in even columns (0.14 k + 0.04 <= 3), 21 in odd ones.
  EXPECT_EQ(mesh.columns, 76);
  std::size_t twists = 0, wires = 0;
  for (const NetLink& link : mesh.net.links) {
    const double length = (mesh.net.nodes[link.b].position - mesh.net.nodes[link.a].position).norm();
    if (link.tag == LinkTag::DoubleTwist) {
      ++twists;
      EXPECT_NEAR(length, 0.04, 1e-12);
      EXPECT_EQ(link.b, link.a + 1);  // consecutive ids (YADE's double-twist rule)
    } else {
      ++wires;
      EXPECT_NEAR(length, 0.05, 1e-12);  // 30 mm along, 40 mm across the twists
      EXPECT_NE(std::abs(link.b - link.a), 1);
    }
  }
  EXPECT_EQ(twists, 38u * 22u + 38u * 21u);
  EXPECT_EQ(mesh.net.nodes.size(), 2 * twists);
  // Every twist top has two SW links up except in the last row/columns: count them exactly.
  std::size_t expected_wires = 0;
  for (int i = 0; i < 76; ++i)
    for (int k = 0; k < (i % 2 ? 21 : 22); ++k) {
      const double top = (i % 2) * 0.07 + 0.14 * k + 0.04;
      for (int j : {i - 1, i + 1})
        if (j >= 0 && j < 76 && top + 0.03 + 0.04 <= 3.0 + 1e-9) ++expected_wires;
    }
  EXPECT_EQ(wires, expected_wires);
}

TEST(DemHexMesh, OpeningGeometryAndMassPerArea) {
  HexMeshSpec spec = hex_pattern("8x10_2.7mm");
  spec.width = 1.0;
  spec.height = 1.0;
  const HexMesh mesh = generate_hex_mesh(spec);
  // Opening: the twists of columns i and i + 2 are 80 mm apart; from the top of a twist of column
  // i+1 to the bottom of its next twist is the opening height 100 mm less the 40 mm twist... i.e.
  // 0.14 - 0.04 = 0.10 m.
  std::set<double> xs;
  for (const NetNode& node : mesh.net.nodes) xs.insert(std::round(node.position.x() * 1e6) / 1e6);
  EXPECT_NEAR(*std::next(xs.begin(), 2) - *xs.begin(), 0.08, 1e-12);
  const NetNode& top = mesh.net.nodes[1];
  const NetNode& next_bottom = mesh.net.nodes[2];
  EXPECT_NEAR(next_bottom.position.y() - top.position.y(), 0.10, 1e-12);
  // Mass per area from the wire: 4 SW of 50 mm and 2 twists of 2 wires x 40 mm x helix factor per
  // 80 x 140 mm cell; helix of 3 half turns: factor sqrt(1 + (pi d / (0.04/1.5))^2).
  const double area = kPi * 0.0027 * 0.0027 / 4.0;
  const double helix = std::sqrt(1.0 + std::pow(kPi * 0.0027 / (0.04 / 1.5), 2));
  EXPECT_NEAR(mesh.twist_wire_factor, helix, 1e-14);
  const double per_area = 7850.0 * area * (4 * 0.05 + 4 * 0.04 * helix) / (0.08 * 0.14);
  EXPECT_NEAR(mesh.mass_per_area, per_area, 1e-12);
  EXPECT_NEAR(mesh.mass_per_area, 1.48, 0.01);  // kg/m^2 of 8x10 / 2.7 mm mesh
  // An interior node carries half a twist and two half SW segments: 4.13 g, within 5 % of the
  // 4.3 g particle of Thoeni et al. (2013).
  double interior = 0.0;
  for (std::size_t n = 0; n < mesh.net.nodes.size(); ++n)
    if (mesh.sides[n] == 0) interior = mesh.net.nodes[n].mass;
  EXPECT_NEAR(interior, 7850.0 * area * (0.04 * helix + 0.05), 1e-15);
  EXPECT_NEAR(interior / 0.0043, 1.0, 0.05);
  // The lumped masses add up to the steel of all links.
  double steel = 0.0;
  for (const NetLink& link : mesh.net.links)
    steel += 7850.0 * area * (link.tag == LinkTag::DoubleTwist ? 2.0 * 0.04 * helix : 0.05);
  EXPECT_NEAR(mesh.net_mass, steel, 1e-12);
}

TEST(DemHexMesh, BoundarySidesSelvedgeGabionAndErrors) {
  HexMeshSpec spec = hex_pattern("8x10_2.7mm");
  spec.width = 0.5;
  spec.height = 0.6;
  spec.selvedge = true;
  const HexMesh mesh = generate_hex_mesh(spec);
  std::size_t selvedge = 0;
  for (const NetLink& link : mesh.net.links)
    if (link.tag == LinkTag::Selvedge) {
      ++selvedge;
      EXPECT_NEAR((mesh.net.nodes[link.b].position - mesh.net.nodes[link.a].position).norm(), 0.10, 1e-12);
      EXPECT_TRUE(mesh.sides[link.a] & (kLeft | kRight));
    }
  EXPECT_GT(selvedge, 0u);
  for (std::size_t n = 0; n < mesh.net.nodes.size(); ++n) {
    const double x = mesh.net.nodes[n].position.x();
    if (x < 1e-9) {
      EXPECT_TRUE(mesh.sides[n] & kLeft);
    }
    if (mesh.sides[n] == 0) {
      EXPECT_GT(x, 1e-9);
    }
  }
  // Bottom and top are the first and last rows only: an edge column's nodes inside the panel
  // are left or right, not bottom or top (they once were, so that "two edges" pinned four).
  double low = 1e300, high = -1e300;
  for (const NetNode& node : mesh.net.nodes) {
    low = std::min(low, node.position.y());
    high = std::max(high, node.position.y());
  }
  const double period = 2.0 * (spec.twist_length + 0.5 * (spec.opening_height - spec.twist_length));
  std::size_t bottom = 0, top = 0;
  for (std::size_t n = 0; n < mesh.net.nodes.size(); ++n) {
    const double y = mesh.net.nodes[n].position.y();
    if (mesh.sides[n] & kBottom) {
      ++bottom;
      EXPECT_LT(y, low + period) << "node " << n;
    }
    if (mesh.sides[n] & kTop) {
      ++top;
      EXPECT_GT(y, high - period) << "node " << n;
    }
    if (y > low + period && y < high - period) {
      EXPECT_FALSE(mesh.sides[n] & (kBottom | kTop)) << "node " << n << " inside the panel";
    }
  }
  EXPECT_GT(bottom, 0u);
  EXPECT_GT(top, 0u);
  const HexMeshSpec gabion = hex_pattern("8x10_3.1mm");
  EXPECT_DOUBLE_EQ(gabion.twist_length, 0.035);
  EXPECT_DOUBLE_EQ(gabion.wire_diameter, 0.0031);
  spec.width = 0.05;
  try {
    generate_hex_mesh(spec);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("width_m"), std::string::npos);
  }
  EXPECT_THROW(hex_pattern("6x8"), std::invalid_argument);
}

// Three nodes per wire: every SW and DT link of the two-node mesh becomes two half-links through
// a node at its midpoint; the twist-end nodes, their sides and the selvedge links are those of
// the two-node mesh; the steel is shared among the wire's nodes, so the mass per area and the
// net's mass are unchanged.
TEST(DemHexMesh, ThreeNodesPerWireSplitsEachWireAndKeepsTheMassPerArea) {
  HexMeshSpec spec = hex_pattern("8x10_2.7mm");
  spec.width = 1.0;
  spec.height = 1.0;
  spec.selvedge = true;
  const HexMesh two = generate_hex_mesh(spec);
  spec.nodes_per_wire = 3;
  const HexMesh three = generate_hex_mesh(spec);
  const std::size_t ends = two.net.nodes.size();
  ASSERT_EQ(three.twist_end_nodes, ends);
  EXPECT_EQ(two.twist_end_nodes, ends);
  for (std::size_t n = 0; n < ends; ++n) {
    EXPECT_EQ(three.net.nodes[n].position, two.net.nodes[n].position);
    EXPECT_EQ(three.sides[n], two.sides[n]) << "node " << n;
  }
  std::size_t wires = 0, selvedge = 0;
  std::vector<int> halves_of(two.net.links.size(), 0);
  for (std::size_t l = 0; l < three.net.links.size(); ++l) {
    const NetLink& link = three.net.links[l];
    ASSERT_GE(link.wire, 0);
    const NetLink& whole = two.net.links[static_cast<std::size_t>(link.wire)];
    EXPECT_EQ(link.tag, whole.tag);
    if (link.tag == LinkTag::Selvedge) {
      ++selvedge;
      EXPECT_EQ(link.parts, 1);
      EXPECT_EQ(link.a, whole.a);
      EXPECT_EQ(link.b, whole.b);
      continue;
    }
    EXPECT_EQ(link.parts, 2);
    ++halves_of[static_cast<std::size_t>(link.wire)];
    // a -> middle, then middle -> b; the middle node at the wire's midpoint, on no boundary.
    const bool first = link.a == whole.a;
    const int middle = first ? link.b : link.a;
    EXPECT_EQ(first ? link.a : link.b, first ? whole.a : whole.b);
    if (!first) {
      EXPECT_EQ(link.b, whole.b);
    }
    ASSERT_GE(static_cast<std::size_t>(middle), ends);
    const Vector3 midpoint = 0.5 * (two.net.nodes[whole.a].position + two.net.nodes[whole.b].position);
    EXPECT_LT((three.net.nodes[middle].position - midpoint).norm(), 1e-15);
    EXPECT_EQ(three.sides[middle], 0u);
    EXPECT_EQ(three.net.nodes[middle].radius, spec.node_radius);
    ++wires;
  }
  std::size_t whole_wires = 0;
  for (std::size_t l = 0; l < two.net.links.size(); ++l)
    if (two.net.links[l].tag != LinkTag::Selvedge) {
      ++whole_wires;
      EXPECT_EQ(halves_of[l], 2) << "wire " << l;
    }
  EXPECT_GT(selvedge, 0u);
  EXPECT_EQ(wires, 2 * whole_wires);
  EXPECT_EQ(three.net.nodes.size(), ends + whole_wires);

  // Mass: a middle node carries half its wire, a twist end a quarter of each wire it ends
  // (half its two-node mass inside the panel); the totals are the two-node mesh's.
  const double area = kPi * 0.0027 * 0.0027 / 4.0;
  const double helix = three.twist_wire_factor;
  for (std::size_t l = 0; l < three.net.links.size(); ++l) {
    const NetLink& link = three.net.links[l];
    if (link.tag == LinkTag::Selvedge || link.a < static_cast<int>(ends)) continue;  // the half from the middle node
    const double steel = 7850.0 * area * (link.tag == LinkTag::DoubleTwist ? 2.0 * 0.04 * helix : 0.05);
    EXPECT_NEAR(three.net.nodes[link.a].mass, 0.5 * steel, 1e-15) << "middle node " << link.a;
  }
  for (std::size_t n = 0; n < ends; ++n)
    if (two.sides[n] == 0) {
      EXPECT_NEAR(three.net.nodes[n].mass, 0.5 * two.net.nodes[n].mass, 1e-15) << "node " << n;
    }
  EXPECT_NEAR(three.net_mass, two.net_mass, 1e-12 * two.net_mass);
  EXPECT_DOUBLE_EQ(three.mass_per_area, two.mass_per_area);
  EXPECT_NEAR(three.mass_per_area, 1.48, 0.01);

  for (const int bad : {1, 4}) {
    spec.nodes_per_wire = bad;
    try {
      generate_hex_mesh(spec);
      FAIL() << bad;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("nodes_per_wire"), std::string::npos);
    }
  }
}

// The counts the memory check uses (issue 37) without building the mesh: with two nodes per
// wire the nodes exactly, the links as an upper bound, within 5 % on the 3 x 3 m punch panel
// (edge twists have fewer wires); with three, the middle nodes as the links, an upper bound.
TEST(DemHexMesh, SizeWithoutBuildingMatchesTheMesh) {
  for (const auto& [width, height, selvedge] : {std::tuple{3.0, 3.0, false}, std::tuple{0.6, 0.45, false},
                                                std::tuple{1.0, 0.99, true}, std::tuple{0.08, 0.1, false}}) {
    for (const int nodes_per_wire : {2, 3}) {
      HexMeshSpec spec;
      spec.width = width;
      spec.height = height;
      spec.selvedge = selvedge;
      spec.nodes_per_wire = nodes_per_wire;
      const HexMesh mesh = generate_hex_mesh(spec);
      const HexMeshSize size = hex_mesh_size(spec);
      const auto nodes = static_cast<double>(mesh.net.nodes.size()), links = static_cast<double>(mesh.net.links.size());
      if (nodes_per_wire == 2) {
        EXPECT_EQ(size.nodes, nodes) << width << " x " << height;
      }
      EXPECT_GE(size.nodes, nodes) << width << " x " << height;
      EXPECT_GE(size.links, links) << width << " x " << height;
      if (width >= 3.0) {
        EXPECT_LT(size.nodes, 1.05 * nodes);
        EXPECT_LT(size.links, 1.05 * links);
      }
    }
  }
}

}  // namespace
}  // namespace dtwire::dem
