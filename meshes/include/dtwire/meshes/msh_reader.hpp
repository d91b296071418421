#pragma once
// Reading gmsh MSH 2.2 ASCII meshes (as `dtwire mesh` writes them) without gmsh or deal.II:
// nodes, and elements with their physical id (the region id, core/region_ids.hpp). For tools
// that do not link the FE solver, e.g. `dtwire gap --model` measuring the grips' bonded area.
#include <array>
#include <cstdint>
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

// The 3D cells (tetrahedra, hexahedra, prisms, pyramids; order 1 or 2) of an ASCII gmsh file,
// MSH 2.x or 4.x as deal.II's GridIn reads them, counted line by line without keeping the mesh
// (the FE run's memory estimate, before it builds a mesh of unknown size). Throws InputError
// naming the file and line where the format or the element section cannot be read; a binary
// file is refused by name.
std::uint64_t count_msh_volume_cells(const std::filesystem::path& msh);

// read_msh + surface_area.
double msh_surface_area(const std::filesystem::path& msh, const std::vector<int>& physical_ids);

}  // namespace dtwire::meshes
