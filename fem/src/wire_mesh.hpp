#pragma once
// Hexahedral mesh of a straight round wire along z (0..length): a 2D disc (or quarter disc)
// refined with its circular boundary, extruded, then scaled radially by the imperfection
// profile r(z) = R (1 - delta (1 + cos(pi (z - zc) / w)) / 2) for |z - zc| < w.
// The cross-section is a regular polygon (its vertices on the circle after refinement); it is
// scaled by sqrt(2 pi / (n sin(2 pi / n))) so that its area equals pi R^2 exactly (second
// moment of area then within 0.014 % of pi R^4 / 4 from n = 16 sides on).
// Optional lateral bow e (1 - cos(2 pi z / L)) / 2 along x (buckling imperfection) and random
// distortion of the interior vertices (patch tests).
// Boundary ids: 0 lateral surface, 1 bottom (z = 0), 2 top (z = length), 3 plane x = 0,
// 4 plane y = 0 (quarter section).
#include <deal.II/grid/tria.h>

#include "parameters.hpp"

namespace dtwire::fem {

enum BoundaryId : unsigned { kHull = 0, kBottom = 1, kTop = 2, kSymmetryX = 3, kSymmetryY = 4 };
// Lateral surfaces of the grips in a full SW mesh file (docs/meshes.md; not in quarter meshes).
enum GripBoundaryId : unsigned { kStartGrip = 4, kEndGrip = 5 };

// `target` must be empty; it may be a parallel::distributed::Triangulation (coarse copy).
// With geometry.mesh_file set, the SW mesh of the meshes/ module is read instead (gmsh .msh,
// metres; its boundary ids 1 (z = 0), 2 (z = L) and the grips' lateral surfaces 4 (start) and 5
// (end) are kept, the lateral id 3 becomes 0, coating and grip volumes are steel like the rest), and geometry.length and .diameter are set
// from it. A double-twist mesh (material ids >= 11 present) keeps all its ids, sets
// geometry.double_twist and the z extent as length; the diameter stays as given. A mesh of the
// quarter x >= 0, y >= 0 (boundary faces on both planes x = 0 and y = 0, e.g. the graded mesh of
// the crossed-cylinder Hertz test) sets geometry.quarter: those faces get the symmetry ids 3 and 4.
void make_wire_mesh(GeometryParameters& geometry, dealii::Triangulation<3>& target);

// The radius of the undeformed wire at height z.
double wire_radius(const GeometryParameters& geometry, double z);

}  // namespace dtwire::fem
