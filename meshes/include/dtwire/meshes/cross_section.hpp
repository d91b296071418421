#pragma once
// The structured O-grid cross-section of a round wire: a square core plus four curved blocks,
// optionally wrapped in a coating ring. All quads are counter-clockwise in the (u, v) plane.
#include <array>
#include <cstddef>
#include <vector>

namespace dtwire::meshes {

// Cells of one refinement level. Level l has 4 * block_cells boundary segments.
struct Resolution {
  int block_cells;    // cells along each core side = along each curved block
  int radial_cells;   // cells across each curved block (core side to the steel surface)
  int coating_cells;  // cells across the coating ring
  double axial_cell_length;  // target cell length along the wire axis
  // Largest turn of the section about the axis between two stations (rad): the twisted
  // cells of a helix lose about turn^2 / 6 of their volume.
  double max_section_turn;
};
Resolution resolution(int level, double diameter);

struct CrossSection {
  std::vector<std::array<double, 2>> points;        // (u, v) in metres
  std::vector<std::array<std::size_t, 4>> quads;     // counter-clockwise
  std::vector<bool> quad_in_coating;
  std::vector<std::array<std::size_t, 2>> outer_edges;  // counter-clockwise along the surface
};

// Boundary nodes sit on a circle of radius r * sqrt(x / sin x), x = 2 pi / N, so that the
// polygon has the exact area pi r^2 (axial stiffness EA and mass are exact). The section is
// turned by half a segment so that the direction u = +1 (towards the other wire of a DT)
// meets an edge midpoint, which lies inside the true circle.
CrossSection make_o_grid_section(double steel_radius, double coating, const Resolution& resolution);

// The node-radius factor sqrt(x / sin x) for N boundary segments.
double area_preserving_radius_factor(int boundary_segments);

}  // namespace dtwire::meshes
