#pragma once
// Reading gmsh MSH 2.2 ASCII meshes (as `dtwire mesh` writes them) without gmsh or deal.II:
// nodes, and elements with their physical id (the region id, core/region_ids.hpp). For tools
// that do not link the FE solver, e.g. `dtwire gap --model` measuring the grips' bonded area.
#include <array>
#include <filesystem>
#include <unordered_map>
#include <vector>

namespace dtwire::meshes {

struct MshElement {
  int type = 0;      // gmsh element type: 2 triangle, 3 quadrilateral, 5 hexahedron, ...
  int physical = 0;  // first tag: the physical group (region id)
  std::vector<long> nodes;
};

struct MshFile {
  std::unordered_map<long, std::array<double, 3>> nodes;  // gmsh node id -> coordinates (m)
  std::vector<MshElement> elements;
};

// Throws InputError naming the file (and the section or element) for a file it cannot read,
// another format version, or an element whose node is not in $Nodes.
MshFile read_msh(const std::filesystem::path& msh);

// Area (m^2) of the quadrilateral and triangle faces that carry one of `physical_ids`:
// bilinear quadrilaterals integrated by 2 x 2 Gauss points, the area the FE solver integrates
// on them (deal.II's Q1 mapping).
double surface_area(const MshFile& mesh, const std::vector<int>& physical_ids);

// read_msh + surface_area.
double msh_surface_area(const std::filesystem::path& msh, const std::vector<int>& physical_ids);

}  // namespace dtwire::meshes
