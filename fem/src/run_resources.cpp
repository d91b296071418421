#include "run_resources.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "dtwire/core/resources.hpp"
#include "dtwire/meshes/msh_reader.hpp"

namespace dtwire::fem {
namespace {

constexpr double kKiB = 1024.0;
constexpr double kMiB = 1024.0 * kKiB;
// deal.II, PETSc and MPI of one rank before the mesh: 190 MiB measured, with a margin.
constexpr double kBaseBytesPerRank = 200.0 * kMiB;
// Generated single wire, Q1: 14 KiB + 2.2 KiB sqrt(cells of a section) a cell fits the measured
// 21.2 KiB (12 cells a section) and 28.7 KiB (48): the LU's fill grows with the section.
double generated_bytes_per_cell(std::uint64_t section_cells) {
  return (14.0 + 2.2 * std::sqrt(static_cast<double>(section_cells))) * kKiB;
}
// Mesh files, Q1 (their section is not known before the mesh is built): the double twist took
// 38.6 KiB a cell at level 0 (1488 cells), 58.8 at level 1 (11 712) and 62.1 at level 2 (78 720):
// the fill levels off, 64 KiB covers all three; single-wire mesh files take it too, erring high.
constexpr double kMeshFileBytesPerCell = 64.0 * kKiB;
// Q2 against Q1, same mesh: 330 against 21 KiB a cell (3600 cells).
constexpr double kQuadraticFactor = 16.0;
// A compressed VTU frame: 76 (SW) to 97 (DT) bytes a Q1 cell measured.
constexpr double kFrameBytesPerCell = 128.0;

}  // namespace

std::uint64_t refined_cells(std::uint64_t cells, std::uint64_t near, std::uint64_t ring, unsigned cycles) {
  if (cycles == 0 || near == 0) return cells;
  double added = static_cast<double>(near) * (std::pow(8.0, cycles) - 1.0);
  for (unsigned k = 1; k < cycles; ++k) added += static_cast<double>(ring) * (std::pow(8.0, cycles - k) - 1.0);
  return cells + static_cast<std::uint64_t>(std::ceil(added));
}

namespace {
// Whether a cell with centre z and z extent dz is near a junction plane (1), in the ring next to
// the near cells (2), or neither (0).
int junction_zone(const GeometryParameters& g, double z, double dz) {
  int zone = 0;
  for (const double plane : g.junction_planes) {
    const double distance = std::abs(z - plane);
    if (distance < g.junction_half_width) return 1;
    if (distance < g.junction_half_width + dz) zone = 2;
  }
  return zone;
}
}  // namespace

MeshSize generated_mesh_size(const GeometryParameters& g) {
  const std::uint64_t disc = g.quarter ? 3 : 5;  // quarter_hyper_ball / hyper_ball cells
  MeshSize size;
  size.section_cells = disc << (2 * g.radial_refinements);
  size.cells = size.section_cells * g.axial_cells;
  if (g.junction_cycles > 0) {  // layers whose centre lies near a junction plane
    std::uint64_t layers[3] = {0, 0, 0};
    const double dz = g.length / g.axial_cells;
    for (unsigned k = 0; k < g.axial_cells; ++k) ++layers[junction_zone(g, (k + 0.5) * dz, dz)];
    size.cells = refined_cells(size.cells, layers[1] * size.section_cells, layers[2] * size.section_cells,
                               g.junction_cycles);
  }
  return size;
}

MeshSize msh_file_size(const std::filesystem::path& file, const GeometryParameters& g) {
  MeshSize size;
  size.cells = meshes::count_msh_volume_cells(file);
  if (g.junction_cycles == 0) return size;
  const meshes::MshFile mesh = meshes::read_msh(file);
  std::uint64_t zones[3] = {0, 0, 0};
  for (const auto& e : mesh.elements) {
    if (e.type != 5) continue;  // hexahedra, the only cells deal.II reads in 3D
    double z = 0.0, low = std::numeric_limits<double>::max(), high = -low;
    for (const long node : e.nodes) {
      const double zn = mesh.nodes.at(node)[2];
      z += zn / static_cast<double>(e.nodes.size());
      low = std::min(low, zn);
      high = std::max(high, zn);
    }
    ++zones[junction_zone(g, z, high - low)];
  }
  size.cells = refined_cells(size.cells, zones[1], zones[2], g.junction_cycles);
  return size;
}

double run_memory_estimate(const MeshSize& mesh, unsigned degree, unsigned ranks) {
  const double per_cell =
      mesh.section_cells > 0 ? generated_bytes_per_cell(mesh.section_cells) : kMeshFileBytesPerCell;
  return kBaseBytesPerRank * std::max(1u, ranks) +
         static_cast<double>(mesh.cells) * per_cell * (degree >= 2 ? kQuadraticFactor : 1.0);
}

double field_output_estimate(const MeshSize& mesh, unsigned degree, const Parameters& p) {
  if (!p.output.fields) return 0.0;
  double end = 0.0;
  for (const auto* path : {&p.load.path, &p.load.force_path, &p.load.rotation_path})
    if (!path->empty()) end = std::max(end, path->back().first);
  const double fewest_steps = p.stepping.maximum_step > 0.0 ? std::floor(end / p.stepping.maximum_step) : 0.0;
  const double frames = 1.0 + (p.output.field_interval > 0 ? std::floor(fewest_steps / p.output.field_interval) : 0.0);
  return frames * static_cast<double>(mesh.cells) * kFrameBytesPerCell * std::pow(static_cast<double>(degree), 3);
}

void check_run_resources(const Parameters& p, unsigned ranks, const std::optional<std::uint64_t>& max_memory,
                         const std::optional<std::uint64_t>& available, const std::optional<std::uint64_t>& free_disk,
                         const std::string& source, const std::filesystem::path& out) {
  const MeshSize mesh = p.geometry.mesh_file.empty() ? generated_mesh_size(p.geometry) : msh_file_size(p.geometry.mesh_file, p.geometry);
  const unsigned degree = p.formulation.degree;
  std::ostringstream what;
  what << mesh.cells << (p.geometry.mesh_file.empty() ? " cells" : " cells of " + p.geometry.mesh_file.string())
       << ", Q" << degree << ", " << std::max(1u, ranks) << " rank(s); measured figures: docs/fem.md, Memory and disk";
  check_memory(run_memory_estimate(mesh, degree, ranks), max_memory, source, what.str(), available);
  std::ostringstream frames;
  frames << "VTU frames of " << mesh.cells << " cells every " << p.output.field_interval
         << " steps at the least; Output/Fields = false writes none";
  check_disk(field_output_estimate(mesh, degree, p), out, source, frames.str(), free_disk);
}

}  // namespace dtwire::fem
