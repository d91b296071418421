// The .msh file carries every physical group (each wire, arm end, lateral surface, grip),
// read back through the gmsh API.
#include <gmsh.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <unistd.h>

#include "dtwire/meshes/mesh_io.hpp"
#include "dtwire/meshes/wire_geometry.hpp"

using namespace dtwire::meshes;

namespace {

std::map<std::pair<int, int>, std::string> groups_in(const std::filesystem::path& file) {
  gmsh::initialize(0, nullptr, false);
  gmsh::option::setNumber("General.Terminal", 0);
  gmsh::open(file.string());
  gmsh::vectorpair dim_tags;
  gmsh::model::getPhysicalGroups(dim_tags);
  std::map<std::pair<int, int>, std::string> groups;
  for (const auto& [dim, tag] : dim_tags) {
    std::string name;
    gmsh::model::getPhysicalName(dim, tag, name);
    groups[{dim, tag}] = name;
  }
  gmsh::finalize();
  return groups;
}

std::filesystem::path temporary(const std::string& stem) {
  return std::filesystem::temp_directory_path() / (stem + std::to_string(::getpid()) + ".msh");
}

}  // namespace

TEST(MshGroups, DoubleTwistHasEveryWireArmEndLateralSurfaceAndGrip) {
  MeshParameters p = default_parameters(WireKind::DoubleTwist);
  p.coating = 0.5e-3;
  p.level = 0;
  const auto file = temporary("dtwire_groups_dt");
  write_msh(build_wire_mesh(p).mesh, file);
  const auto groups = groups_in(file);
  std::filesystem::remove(file);
  std::map<std::pair<int, int>, std::string> expected;
  for (const char* w : {"A", "B"}) {
    const int base = w[0] == 'A' ? 0 : 10;
    const std::string wire = std::string("wire_") + w;
    expected[{3, base + 1}] = wire;
    expected[{3, base + 2}] = wire + "_start_grip";
    expected[{3, base + 3}] = wire + "_end_grip";
    expected[{3, base + 4}] = wire + "_coating";
    expected[{3, base + 5}] = wire + "_start_grip_coating";
    expected[{3, base + 6}] = wire + "_end_grip_coating";
    expected[{2, base + 1}] = wire + "_start_face";  // arm ends
    expected[{2, base + 2}] = wire + "_end_face";
    expected[{2, base + 3}] = wire + "_lateral";     // contact candidates
    expected[{2, base + 4}] = wire + "_start_grip_lateral";
    expected[{2, base + 5}] = wire + "_end_grip_lateral";
  }
  EXPECT_EQ(groups, expected);
}

TEST(MshGroups, SingleWireHasWireGripsEndsAndLateralSurface) {
  MeshParameters p = default_parameters(WireKind::Single);
  p.level = 0;
  const auto file = temporary("dtwire_groups_sw");
  write_msh(build_wire_mesh(p).mesh, file);
  const auto groups = groups_in(file);
  std::filesystem::remove(file);
  const std::map<std::pair<int, int>, std::string> expected = {
      {{3, 1}, "wire"},           {{3, 2}, "wire_start_grip"},         {{3, 3}, "wire_end_grip"},
      {{2, 1}, "wire_start_face"}, {{2, 2}, "wire_end_face"},           {{2, 3}, "wire_lateral"},
      {{2, 4}, "wire_start_grip_lateral"}, {{2, 5}, "wire_end_grip_lateral"}};
  EXPECT_EQ(groups, expected);
}

TEST(MshGroups, NoGripsWhenGripLengthIsZero) {
  MeshParameters p = default_parameters(WireKind::Single);
  p.level = 0;
  p.grip_length = 0;
  const WireMesh mesh = build_wire_mesh(p);
  EXPECT_EQ(mesh.mesh.volume_names.size(), 1u);
  EXPECT_EQ(mesh.mesh.surface_names.size(), 3u);
}
