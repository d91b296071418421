#include "wire_mesh.hpp"

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_in.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/manifold_lib.h>

#include <cmath>
#include <fstream>
#include <stdexcept>

#include "dtwire/core/error.hpp"
#include "dtwire/core/region_ids.hpp"

namespace dtwire::fem {

double wire_radius(const GeometryParameters& g, double z) {
  const double R = 0.5 * g.diameter;
  const double s = (z - g.imperfection_centre) / g.imperfection_half_width;
  if (g.imperfection <= 0.0 || std::abs(s) >= 1.0) return R;
  return R * (1.0 - 0.5 * g.imperfection * (1.0 + std::cos(M_PI * s)));
}

namespace {

void read_wire_mesh(GeometryParameters& g, dealii::Triangulation<3>& target) {
  using namespace dealii;
  Triangulation<3> wire;
  GridIn<3> in;
  in.attach_triangulation(wire);
  std::ifstream file(g.mesh_file);
  in.read_msh(file);
  g.double_twist = false;
  for (const auto& cell : wire.active_cell_iterators()) g.double_twist = g.double_twist || cell->material_id() >= regions::kFirstWireBMaterial;
  double z_min = 0.0, z_max = 0.0, r_max = 0.0;
  for (const auto& v : wire.get_vertices()) {
    z_min = std::min(z_min, v[2]);
    z_max = std::max(z_max, v[2]);
    r_max = std::max(r_max, std::hypot(v[0], v[1]));
  }
  g.length = z_max - z_min;
  if (g.double_twist) {  // two wires: keep every id; the diameter stays the .prm's
    target.copy_triangulation(wire);
    return;
  }
  // The end face is a section of the wire wherever the axis runs (a bent segment's vertices lie
  // far from the z axis, so their distance to it is no radius).
  Point<3> face_centre;
  std::vector<Point<3>> face_vertices;
  for (const auto& cell : wire.active_cell_iterators())
    for (const auto f : cell->face_indices())
      if (cell->face(f)->at_boundary() && cell->face(f)->boundary_id() == kBottom)
        for (const auto v : cell->face(f)->vertex_indices()) face_vertices.push_back(cell->face(f)->vertex(v));
  for (const auto& v : face_vertices) face_centre += v / static_cast<double>(face_vertices.size());
  double r_face = 0.0;
  for (const auto& v : face_vertices) r_face = std::max(r_face, v.distance(face_centre));
  g.straight_axis = face_vertices.empty() || r_max < 1.5 * r_face;
  g.diameter = 2.0 * (g.straight_axis ? r_max : r_face);
  // A quarter-section mesh (x >= 0, y >= 0) has plane boundary faces on x = 0 and y = 0: they
  // become the symmetry planes and the model a quarter section. A full wire has none (its
  // lateral faces lie on the circle).
  const double tol = 1e-9 * r_max;
  const auto on_plane = [&](const auto& face, unsigned axis) {
    for (const auto v : face->vertex_indices())
      if (std::abs(face->vertex(v)[axis]) > tol) return false;
    return true;
  };
  bool symmetry_x = false, symmetry_y = false;
  for (const auto& cell : wire.active_cell_iterators())
    for (const auto f : cell->face_indices())
      if (cell->face(f)->at_boundary() && cell->face(f)->boundary_id() != kBottom &&
          cell->face(f)->boundary_id() != kTop) {
        symmetry_x = symmetry_x || on_plane(cell->face(f), 0);
        symmetry_y = symmetry_y || on_plane(cell->face(f), 1);
      }
  if (symmetry_x != symmetry_y)
    throw InputError(g.mesh_file.string(), "a quarter-section mesh needs boundary faces on both planes x = 0 and y = 0");
  g.quarter = symmetry_x;
  for (const auto& cell : wire.active_cell_iterators())
    for (const auto f : cell->face_indices()) {
      const auto face = cell->face(f);
      const auto id = face->boundary_id();
      if (!face->at_boundary() || id == kBottom || id == kTop) continue;
      // A full wire keeps its grips' lateral surfaces (`dtwire mesh sw --grip-length`), which
      // Bottom / Top boundary ids can then hold.
      if (!g.quarter && (id == kStartGrip || id == kEndGrip)) continue;
      face->set_boundary_id(on_plane(face, 0) ? kSymmetryX : on_plane(face, 1) ? kSymmetryY : kHull);
    }
  target.copy_triangulation(wire);
}

}  // namespace

void make_wire_mesh(GeometryParameters& g, dealii::Triangulation<3>& target) {
  using namespace dealii;
  if (!g.mesh_file.empty()) {
    read_wire_mesh(g, target);
    return;
  }
  const double R = 0.5 * g.diameter;
  Triangulation<2> disc;
  if (g.quarter) GridGenerator::quarter_hyper_ball(disc, Point<2>(), R);
  else GridGenerator::hyper_ball(disc, Point<2>(), R);
  // Circle on the curved boundary, transfinite interpolation inside (as hyper_ball does).
  disc.reset_all_manifolds();
  disc.set_all_manifold_ids(1);
  for (const auto& cell : disc.active_cell_iterators())
    for (const auto f : cell->face_indices())
      if (cell->face(f)->at_boundary() &&
          std::abs(cell->face(f)->vertex(0).norm() - R) < 1e-9 * R &&
          std::abs(cell->face(f)->vertex(1).norm() - R) < 1e-9 * R)
        cell->face(f)->set_manifold_id(0);
  disc.set_manifold(0, SphericalManifold<2>(Point<2>()));
  TransfiniteInterpolationManifold<2> interior;
  interior.initialize(disc);
  disc.set_manifold(1, interior);
  disc.refine_global(g.radial_refinements);

  Triangulation<2> flat;
  GridGenerator::flatten_triangulation(disc, flat);
  Triangulation<3> wire;
  GridGenerator::extrude_triangulation(flat, g.axial_cells + 1, g.length, wire);
  const double sides = (g.quarter ? 8.0 : 4.0) * std::pow(2.0, g.radial_refinements);
  const double area_scale = std::sqrt(2.0 * M_PI / (sides * std::sin(2.0 * M_PI / sides)));
  GridTools::transform(
      [&](const Point<3>& p) {
        const double s = area_scale * wire_radius(g, p[2]) / R;
        const double bow = 0.5 * g.bow * (1.0 - std::cos(2.0 * M_PI * p[2] / g.length));
        return Point<3>(p[0] * s + bow, p[1] * s, p[2]);
      },
      wire);
  if (g.mesh_distortion > 0.0) GridTools::distort_random(g.mesh_distortion, wire, true, 20261122);

  const double tol = 1e-9 * R;
  for (const auto& cell : wire.active_cell_iterators())
    for (const auto f : cell->face_indices()) {
      if (!cell->face(f)->at_boundary()) continue;
      const Point<3> c = cell->face(f)->center();
      types::boundary_id id = kHull;
      if (std::abs(c[2]) < tol) id = kBottom;
      else if (std::abs(c[2] - g.length) < tol) id = kTop;
      else if (g.quarter && std::abs(c[0]) < tol) id = kSymmetryX;
      else if (g.quarter && std::abs(c[1]) < tol) id = kSymmetryY;
      cell->face(f)->set_boundary_id(id);
    }
  target.copy_triangulation(wire);
}

}  // namespace dtwire::fem
