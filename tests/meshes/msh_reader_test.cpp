// The MSH 2.2 reader of meshes/ (no gmsh, no deal.II): a written SW mesh reads back with every
// node, hexahedron and boundary face, and the grips' lateral area is the faceted cylinder's.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "dtwire/core/error.hpp"
#include "dtwire/core/region_ids.hpp"
#include "dtwire/meshes/mesh_io.hpp"
#include "dtwire/meshes/msh_reader.hpp"
#include "dtwire/meshes/wire_geometry.hpp"

using namespace dtwire::meshes;

namespace {

std::filesystem::path temporary(const std::string& stem) {
  return std::filesystem::temp_directory_path() / (stem + std::to_string(::getpid()) + ".msh");
}

TEST(MshReader, WrittenMeshReadsBackWithItsGripArea) {
  MeshParameters p = default_parameters(WireKind::Single);
  p.level = 1;
  const WireMesh built = build_wire_mesh(p);
  const auto file = temporary("dtwire_reader_sw");
  write_msh(built.mesh, file);
  const MshFile read = read_msh(file);
  std::filesystem::remove(file);
  EXPECT_EQ(read.nodes.size(), built.mesh.nodes.size());
  std::size_t hexes = 0, quads = 0;
  for (const auto& e : read.elements) {
    if (e.type == 5) ++hexes;
    if (e.type == 3) ++quads;
  }
  EXPECT_EQ(hexes, built.mesh.hexes.size());
  EXPECT_EQ(quads, built.mesh.quads.size());
  // Lateral grip surface: the section is a polygon of N = 16 edges (level 1) whose nodes sit on
  // r sqrt(x / sin x), x = 2 pi / N, so that its area is the circle's (docs/meshes.md); its side
  // faces are flat rectangles, so the area is N 2 R' sin(pi / N) L_grip exactly (0.65 % above
  // pi d L_grip).
  const double n = 16, x = 2 * M_PI / n, node_radius = 0.5 * p.diameter * std::sqrt(x / std::sin(x));
  const double polygon = n * 2 * node_radius * std::sin(M_PI / n) * p.grip_length;
  EXPECT_NEAR(surface_area(read, {dtwire::regions::kWireAEndGrip}), polygon, 1e-9 * polygon);
  EXPECT_NEAR(surface_area(read, {dtwire::regions::kWireAStartGrip, dtwire::regions::kWireAEndGrip}), 2 * polygon,
              2e-9 * polygon);
  EXPECT_EQ(surface_area(read, {99}), 0.0);
}

TEST(MshReader, BadFilesAreErrorsNamingTheFile) {
  EXPECT_THROW(read_msh("/nonexistent/dtwire.msh"), dtwire::InputError);
  const auto file = temporary("dtwire_reader_bad");
  std::ofstream(file) << "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n";
  try {
    read_msh(file);
    ADD_FAILURE() << "an MSH 4 file was read";
  } catch (const dtwire::InputError& e) {
    EXPECT_EQ(e.source(), file.string());
  }
  std::ofstream(file) << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n1\n1 0 0 0\n$EndNodes\n"
                         "$Elements\n1\n1 3 2 4 4 1 2 3 4\n$EndElements\n";
  EXPECT_THROW(read_msh(file), dtwire::InputError);  // nodes 2-4 missing
  std::filesystem::remove(file);
}

TEST(MshCellCount, CountsTheVolumeCellsOfBothFormatsWithoutKeepingThem) {
  const auto v2 = temporary("dtwire_count_v2");
  std::ofstream(v2) << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Elements\n3\n"
                       "1 3 2 1 1 1 2 3 4\n2 5 2 1 1 1 2 3 4 5 6 7 8\n3 5 2 1 1 5 6 7 8 9 10 11 12\n$EndElements\n";
  EXPECT_EQ(count_msh_volume_cells(v2), 2u);  // the quadrilateral face is no cell
  const auto v4 = temporary("dtwire_count_v4");
  std::ofstream(v4) << "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Elements\n2 3 1 3\n"
                       "2 1 3 1\n1 1 2 3 4\n3 1 5 2\n2 1 2 3 4 5 6 7 8\n3 5 6 7 8 9 10 11 12\n$EndElements\n";
  EXPECT_EQ(count_msh_volume_cells(v4), 2u);
  // A mesh `dtwire mesh` writes: every hexahedron it built.
  MeshParameters p = default_parameters(WireKind::Single);
  const WireMesh built = build_wire_mesh(p);
  const auto written = temporary("dtwire_count_written");
  write_msh(built.mesh, written);
  EXPECT_EQ(count_msh_volume_cells(written), built.mesh.hexes.size());
  for (const auto& file : {v2, v4, written}) std::filesystem::remove(file);
}

TEST(MshCellCount, UnreadableFilesAreNamedWithTheirLine) {
  const auto truncated = temporary("dtwire_count_truncated");
  std::ofstream(truncated) << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Elements\n5\n1 5 2 1 1 1 2 3 4 5 6 7 8\n";
  try {
    count_msh_volume_cells(truncated);
    ADD_FAILURE() << "a truncated element section was accepted";
  } catch (const dtwire::InputError& e) {
    EXPECT_EQ(e.source(), truncated.string());
    EXPECT_EQ(e.line(), 6);
    EXPECT_NE(std::string(e.what()).find("element line"), std::string::npos) << e.what();
  }
  const auto binary = temporary("dtwire_count_binary");
  std::ofstream(binary) << "$MeshFormat\n2.2 1 8\n";
  try {
    count_msh_volume_cells(binary);
    ADD_FAILURE() << "a binary file was accepted";
  } catch (const dtwire::InputError& e) {
    EXPECT_EQ(e.line(), 2);
    EXPECT_NE(std::string(e.what()).find("binary"), std::string::npos) << e.what();
  }
  const auto empty = temporary("dtwire_count_empty");
  std::ofstream(empty) << "";
  EXPECT_THROW(count_msh_volume_cells(empty), dtwire::InputError);
  EXPECT_THROW(count_msh_volume_cells("/nonexistent/dtwire.msh"), dtwire::InputError);
  for (const auto& file : {truncated, binary, empty}) std::filesystem::remove(file);
}

}  // namespace
