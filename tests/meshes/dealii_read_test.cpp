// deal.II reads the meshes (GridIn::read_msh, MSH 2.2) with the documented material and
// boundary ids and positive Jacobians at every quadrature point.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <unistd.h>

#include "dealii_reader.hpp"

#include "dtwire/meshes/mesh_check.hpp"
#include "dtwire/meshes/mesh_io.hpp"
#include "dtwire/meshes/wire_geometry.hpp"

using namespace dtwire::meshes;

namespace {

struct Case {
  WireKind kind;
  int level;
  double coating_mm;
};

void PrintTo(const Case& c, std::ostream* out) {
  *out << (c.kind == WireKind::Single ? "SW" : "DT") << " level " << c.level << " coating " << c.coating_mm << " mm";
}

std::string case_name(const ::testing::TestParamInfo<Case>& info) {
  return std::string(info.param.kind == WireKind::Single ? "SW" : "DT") + "level" +
         std::to_string(info.param.level) + (info.param.coating_mm > 0 ? "coated" : "");
}

}  // namespace

class DealIIRead : public ::testing::TestWithParam<Case> {};

TEST_P(DealIIRead, CellsIdsAndJacobiansAsWritten) {
  MeshParameters p = default_parameters(GetParam().kind);
  p.level = GetParam().level;
  p.coating = GetParam().coating_mm * 1e-3;
  const WireMesh mesh = build_wire_mesh(p);
  const auto file = std::filesystem::temp_directory_path() /
                    ("dtwire_dealii_" + std::to_string(::getpid()) + "_" + std::to_string(p.level) + ".msh");
  write_msh(mesh.mesh, file);

  const DealIIView view = read_with_dealii(file.string());
  std::filesystem::remove(file);

  EXPECT_EQ(view.cells, mesh.mesh.hexes.size());
  std::set<int> expected_materials, expected_boundaries;
  for (const auto& [id, name] : mesh.mesh.volume_names) expected_materials.insert(id);
  for (const auto& [id, name] : mesh.mesh.surface_names) expected_boundaries.insert(id);
  EXPECT_EQ(view.material_ids, expected_materials);
  EXPECT_EQ(view.boundary_ids, expected_boundaries);  // every boundary face carries a documented id (none 0)

  EXPECT_GT(view.min_jxw, 0.0);
  const MeshCheck check = check_mesh(mesh);
  EXPECT_NEAR(view.volume, check.steel_volume + check.coating_volume, 1e-9 * view.volume);
}

INSTANTIATE_TEST_SUITE_P(Levels, DealIIRead,
                         ::testing::Values(Case{WireKind::Single, 0, 0}, Case{WireKind::Single, 1, 0},
                                           Case{WireKind::Single, 2, 0}, Case{WireKind::Single, 3, 0},
                                           Case{WireKind::DoubleTwist, 0, 0}, Case{WireKind::DoubleTwist, 1, 0},
                                           Case{WireKind::DoubleTwist, 2, 0}, Case{WireKind::DoubleTwist, 3, 0},
                                           Case{WireKind::DoubleTwist, 1, 0.5}),
                         case_name);
