#pragma once
// The memory and disk a `dtwire run` would take, estimated from its .prm before the mesh is built
// (issue 37): a typo in `Axial cells` or a mesh file far finer than meant is refused by name
// (exit 2, nothing written) instead of allocating until the kernel kills the machine's jobs.
//
// The estimate is measured, not derived (docs/fem.md, "Memory"): peak resident memory of one rank
// with the direct solver (MUMPS), 50 load steps, Fields off, 2026-11-28 on this project's machine:
//   generated SW, quarter section, Q1: 193 MiB at 360 cells, 931 MiB at 36 000 (12 cells a
//     section), 232 MiB at 1440 and 1193 MiB at 36 000 (48 cells a section): 21 and 29 KiB a
//     cell, the LU's fill growing with the section;
//   the same with Q2: 304 MiB at 360 cells, 1347 MiB at 3600: 330 KiB a cell (16 x Q1);
//   the double twist of `dtwire mesh dt` (wire contact) at levels 0, 1, 2: 242 MiB at 1488 cells,
//     858 MiB at 11 712, 4.84 GiB at 78 720 (the first load steps): 39, 59 and 62 KiB a cell.
// A cell's cost is taken at or above every measured figure of its kind, so the estimate errs
// towards refusing; `--max-memory` overrides it. No deal.II here: plain sizes in.
// Junction refinement (junction_refinement.hpp) adds the children of the cells near the junction
// planes, counted from the mesh before it is built (see refined_cells).
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "parameters.hpp"

namespace dtwire::fem {

struct MeshSize {
  std::uint64_t cells = 0;        // hexahedra (3D elements of a mesh file)
  std::uint64_t section_cells = 0;  // cells of one cross-section (generated meshes; 0: unknown)
};

// The size of the generated mesh of `g` (no mesh file): the quarter or full disc refined
// `radial_refinements` times, extruded into `axial_cells` layers, then refined at the junctions.
MeshSize generated_mesh_size(const GeometryParameters& g);
// The 3D elements of a gmsh .msh file (ASCII 2.x or 4.x), counted without building the mesh
// (meshes::count_msh_volume_cells: InputError naming the file and line it cannot read). With
// junction refinement (g.junction_cycles > 0) the file is read (meshes::read_msh, a few hundred
// bytes a cell against the run's tens of KiB) to find the hexahedra near the junction planes.
MeshSize msh_file_size(const std::filesystem::path& file, const GeometryParameters& g = {});

// Active cells after `cycles` junction refinements of a mesh of `cells` cells of which `near`
// have their centre within the half-width of a junction plane and `ring` (the others) within the
// half-width plus their own z extent (their neighbours along the wire): each cycle splits the near
// cells and their children into 8, and p4est's 2:1 balance keeps the k-th ring of neighbours at
// most k levels coarser, counted as `ring` cells for every k (the first ring's size).
std::uint64_t refined_cells(std::uint64_t cells, std::uint64_t near, std::uint64_t ring, unsigned cycles);

// Peak resident memory (bytes) of a run on `ranks` ranks with elements of `degree`.
double run_memory_estimate(const MeshSize& mesh, unsigned degree, unsigned ranks);

// Bytes of the VTU frames a run writes at the least: one frame every `field_interval` steps of
// the fewest steps the load path allows (its end over Maximum step), and the last step.
double field_output_estimate(const MeshSize& mesh, unsigned degree, const Parameters& p);

// Refuses (InputError naming `source`) a run whose memory estimate exceeds `max_memory`, or the
// available memory when none is given (`available`: MemAvailable, decided once for every rank),
// and one whose frames exceed `free_disk` (bytes free on the file system of `out`; none: unknown).
void check_run_resources(const Parameters& p, unsigned ranks, const std::optional<std::uint64_t>& max_memory,
                         const std::optional<std::uint64_t>& available, const std::optional<std::uint64_t>& free_disk,
                         const std::string& source, const std::filesystem::path& out);

}  // namespace dtwire::fem
