#pragma once
// Mesh files: gmsh MSH 2.2 ASCII (through the gmsh API; what deal.II's GridIn::read_msh reads
// with physical ids as material and boundary ids) and a VTU preview for ParaView.
// Coordinates are written in metres.
#include <filesystem>

#include "dtwire/meshes/wire_mesh.hpp"

namespace dtwire::meshes {

// The mesh as discrete gmsh entities, one per region, with one physical group each (tag =
// region id, name from HexMesh). Written under a temporary name, then renamed into place.
void write_msh(const HexMesh& mesh, const std::filesystem::path& path);

// VTU (XML, ASCII) with the hexahedra and the boundary quads; cell data `region_id`
// (material or boundary id) and `dimension` (3 or 2).
void write_vtu(const HexMesh& mesh, const std::filesystem::path& path);

}  // namespace dtwire::meshes
