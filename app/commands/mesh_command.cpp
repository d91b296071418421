#include <CLI/CLI.hpp>

#include "../cli.hpp"
#include "../commands.hpp"

namespace dtwire::app {

void add_mesh_command(CLI::App& root, CommandSet& commands) {
  commands.add_unavailable(root, "mesh", "Build parametric gmsh meshes of single wires and double twists", "the meshes module (issue #3)");
}

}  // namespace dtwire::app
