#pragma once
// Hexagonal double-twist (DT) mesh generator, Node-Wire-Based discretisation of Bertrand et al.
// (2008) / Thoeni et al. (2013) as in the thesis macro-element's PFC7 punch example: one node
// at each end of every double twist, one link per twist (tag DT) and one link per single-wire
// segment (tag SW) between the top of a twist and the bottom of the twists of the two
// neighbouring columns. The panel lies in the xy-plane (z = 0) with the twists along y:
//   column i at x = i D/2 (D = opening width across the twists), twists of column i from
//   y = s_i + k P to s_i + k P + t (t twist length, P = 2 (t + r), r = (H - t)/2 the rise of a
//   SW segment along y, H the opening height, s_i = 0 for even and t + r for odd columns).
// For 8x10 mesh (D = 80 mm, H = 100 mm, t = 40 mm): SW links span 30 mm along and 40 mm across
// the twists (50 mm long). The two nodes of a twist get consecutive indices (YADE's WirePM finds
// double twists that way). Optional selvedge links join consecutive twists of the first and last
// columns (a thicker edge wire, tag selvedge).
// Three nodes per wire (Previtali ch. 3.4, study 1): every SW and DT link is split at its
// midpoint by a middle node into two half-links in series (the same tag; each keeps the whole
// link's index in `wire`, `parts` = 2), so that the wire bends between its ends; selvedge links
// stay whole. Middle nodes come after all twist-end nodes (the twist-end indices and their
// boundary sides are those of the two-node mesh; middle nodes are never on a boundary) and
// have the twist-end nodes' contact radius.
// Node mass: half the steel of every link ending at the node (a twist is two wires on a helix
// of three half turns): with three nodes per wire a middle node carries half its wire and each
// end a quarter, so the mass per area is that of the real mesh either way; or a given mass.
#include <string>
#include <vector>

#include "dtwire/dem/net.hpp"

namespace dtwire::dem {

struct HexMeshSpec {
  double width = 3.0;             // panel extent across the twists (x) [m]
  double height = 3.0;            // panel extent along the twists (y) [m]
  double opening_width = 0.08;    // D [m]
  double opening_height = 0.10;   // H [m]
  double twist_length = 0.04;     // t [m]
  int twist_half_turns = 3;       // EN 10223-3
  double wire_diameter = 0.0027;  // [m]
  bool selvedge = false;
  double selvedge_diameter = 0.0034;  // [m]
  double node_radius = 0.0054;        // contact radius (Thoeni et al. 2013) [m]
  double node_mass = 0.0;             // [kg]; 0: lumped from the wire
  double steel_density = 7850.0;      // [kg/m^3]
  int nodes_per_wire = 2;             // 2 (one link per wire) or 3 (split at the midpoint)
};

// "8x10_2.7mm" (rockfall net: 40 mm twists) or "8x10_3.1mm" (gabion: 35 mm twists);
// throws std::invalid_argument naming the known patterns.
HexMeshSpec hex_pattern(const std::string& name);

enum BoundarySide : unsigned { kLeft = 1, kRight = 2, kBottom = 4, kTop = 8 };

struct HexMesh {
  Net net;
  std::vector<unsigned> sides;  // per node, BoundarySide bits (0: interior)
  int columns = 0;
  double mass_per_area = 0.0;       // of the repeating cell (the real mesh) [kg/m^2]
  double net_mass = 0.0;            // sum of node masses [kg]
  double twist_wire_factor = 1.0;   // helix length / twist length
  std::size_t twist_end_nodes = 0;  // nodes [0, this) end twists; the rest are middle nodes
};

// The node and link counts generate_hex_mesh would give (links: an upper bound, edge twists
// have fewer wires), without building anything: the memory check of a run comes first. Counts
// as doubles: a typo in a width can exceed every integer type the mesh uses.
struct HexMeshSize {
  double nodes = 0.0, links = 0.0;
};
HexMeshSize hex_mesh_size(const HexMeshSpec& spec);

// Throws std::invalid_argument naming the field ("width_m", ...) for a panel smaller than one
// opening, non-positive dimensions or nodes_per_wire other than 2 or 3.
HexMesh generate_hex_mesh(const HexMeshSpec& spec);

}  // namespace dtwire::dem
