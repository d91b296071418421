#include <ostream>

#include "dtwire/core/atomic_file.hpp"
#include "dtwire/meshes/mesh_io.hpp"

namespace dtwire::meshes {

void write_vtu(const HexMesh& mesh, const std::filesystem::path& path) {
  write_file_atomically(path, [&](std::ostream& out) {
    const std::size_t cells = mesh.hexes.size() + mesh.quads.size();
    out.precision(17);
    out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
        << "<UnstructuredGrid>\n<Piece NumberOfPoints=\"" << mesh.nodes.size() << "\" NumberOfCells=\"" << cells
        << "\">\n<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
    for (const Vec3& p : mesh.nodes) out << p.x << ' ' << p.y << ' ' << p.z << '\n';
    out << "</DataArray>\n</Points>\n<Cells>\n<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
    for (const auto& h : mesh.hexes) {
      for (std::size_t n : h) out << n << ' ';
      out << '\n';
    }
    for (const auto& q : mesh.quads) {
      for (std::size_t n : q) out << n << ' ';
      out << '\n';
    }
    out << "</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
    std::size_t offset = 0;
    for (std::size_t c = 0; c < mesh.hexes.size(); ++c) out << (offset += 8) << '\n';
    for (std::size_t c = 0; c < mesh.quads.size(); ++c) out << (offset += 4) << '\n';
    out << "</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
    for (std::size_t c = 0; c < mesh.hexes.size(); ++c) out << "12\n";  // VTK_HEXAHEDRON
    for (std::size_t c = 0; c < mesh.quads.size(); ++c) out << "9\n";   // VTK_QUAD
    out << "</DataArray>\n</Cells>\n<CellData Scalars=\"region_id\">\n"
        << "<DataArray type=\"Int32\" Name=\"region_id\" format=\"ascii\">\n";
    for (int id : mesh.hex_material) out << id << '\n';
    for (int id : mesh.quad_boundary) out << id << '\n';
    out << "</DataArray>\n<DataArray type=\"Int32\" Name=\"dimension\" format=\"ascii\">\n";
    for (std::size_t c = 0; c < mesh.hexes.size(); ++c) out << "3\n";
    for (std::size_t c = 0; c < mesh.quads.size(); ++c) out << "2\n";
    out << "</DataArray>\n</CellData>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n";
  });
}

}  // namespace dtwire::meshes
