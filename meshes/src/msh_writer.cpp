#include <gmsh.h>

#include <set>
#include <stdexcept>
#include <unistd.h>

#include "dtwire/meshes/mesh_io.hpp"

namespace dtwire::meshes {
namespace {

// gmsh keeps global state: one initialisation per write, always finalised.
class GmshSession {
 public:
  GmshSession() {
    gmsh::initialize(0, nullptr, false);
    gmsh::option::setNumber("General.Terminal", 0);
  }
  ~GmshSession() { gmsh::finalize(); }
  GmshSession(const GmshSession&) = delete;
  GmshSession& operator=(const GmshSession&) = delete;
};

template <std::size_t N>
void add_region(int dim, int id, const std::string& name, const std::vector<std::array<std::size_t, N>>& elements,
                const std::vector<int>& ids, std::size_t& next_tag) {
  std::vector<std::size_t> tags, nodes;
  for (std::size_t e = 0; e < elements.size(); ++e) {
    if (ids[e] != id) continue;
    tags.push_back(next_tag++);
    for (std::size_t n : elements[e]) nodes.push_back(n + 1);
  }
  gmsh::model::addDiscreteEntity(dim, id);
  gmsh::model::mesh::addElementsByType(id, dim == 3 ? 5 : 3, tags, nodes);  // 5: hex8, 3: quad4
  gmsh::model::addPhysicalGroup(dim, {id}, id);
  gmsh::model::setPhysicalName(dim, id, name);
}

}  // namespace

void write_msh(const HexMesh& mesh, const std::filesystem::path& path) {
  const auto parent = path.parent_path();
  if (!parent.empty() && !std::filesystem::is_directory(parent))
    throw std::runtime_error(path.string() + ": output directory '" + parent.string() + "' does not exist");
  // gmsh picks the format from the extension, so the temporary name keeps ".msh".
  std::filesystem::path temporary = path;
  temporary.replace_filename("." + path.stem().string() + ".tmp" + std::to_string(::getpid()) + ".msh");
  try {
    GmshSession session;
    gmsh::model::add("dtwire");
    // All nodes live on a node-only carrier entity (tag 1000): regions share nodes.
    constexpr int kCarrier = 1000;
    gmsh::model::addDiscreteEntity(3, kCarrier);
    std::vector<std::size_t> node_tags(mesh.nodes.size());
    std::vector<double> coordinates;
    coordinates.reserve(3 * mesh.nodes.size());
    for (std::size_t n = 0; n < mesh.nodes.size(); ++n) {
      node_tags[n] = n + 1;
      coordinates.insert(coordinates.end(), {mesh.nodes[n].x, mesh.nodes[n].y, mesh.nodes[n].z});
    }
    gmsh::model::mesh::addNodes(3, kCarrier, node_tags, coordinates);
    std::size_t next_tag = 1;
    for (const auto& [id, name] : mesh.volume_names) add_region(3, id, name, mesh.hexes, mesh.hex_material, next_tag);
    for (const auto& [id, name] : mesh.surface_names) add_region(2, id, name, mesh.quads, mesh.quad_boundary, next_tag);
    gmsh::option::setNumber("Mesh.MshFileVersion", 2.2);
    gmsh::option::setNumber("Mesh.Binary", 0);
    gmsh::option::setNumber("Mesh.SaveAll", 0);
    gmsh::write(temporary.string());
  } catch (...) {
    // The gmsh API reports errors as exceptions of its own types (std::string in 4.8).
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    throw std::runtime_error(path.string() + ": gmsh could not write the mesh file");
  }
  std::error_code error;
  std::filesystem::rename(temporary, path, error);
  if (error) {
    std::filesystem::remove(temporary, error);
    throw std::runtime_error(path.string() + ": cannot write the mesh file");
  }
}

}  // namespace dtwire::meshes
