#pragma once
// Radial sections of a punched net (issue 35): how the platter's force leaves the loaded zone.
// A vertical cylinder of radius r about the platter's axis cuts the net; the part inside is held
// by the links that cross the cylinder, so (quasi-static, the inside's weight aside) the sum of
// their forces on the inside balances the platter's force. Per section:
//   1. a link crosses when the horizontal distance of one end node from the axis is below r and
//      the other's is not; its force on the inside end node is summed (the full force vector the
//      link applies: axial and shear);
//   2. vertical_force = minus the sum's component along the axis (the outer net pulling the
//      inside down; equals the platter's force minus the inside's weight at rest);
//   3. radial_force = the sum of each force's component along the outward horizontal unit
//      vector at the link's crossing point; radial_tension = radial_force / (2 pi r), the mean
//      membrane force per metre of circumference (N/m, comparable with a strip test's strength
//      per metre);
//   4. the same per sector (`sectors` equal angles, the first centred on the x axis: for a
//      square panel, the sectors toward the mid-sides and toward the corners) gives the largest
//      and smallest sector tension (and where the largest lies): how unevenly the circumference
//      carries;
//   5. slope = atan(vertical_force / radial_force), the membrane's mean inclination there.
// For an axisymmetric membrane F = 2 pi r T sin(slope) / cos(slope) (T the radial tension), the
// relation that ties a punch's peak to the mesh's tensile strength per metre (docs/dem_engine.md,
// "Where the punch's force goes").
#include <cstddef>
#include <vector>

#include "dtwire/dem/net.hpp"

namespace dtwire::dem {

struct SectionLink {
  std::size_t a = 0, b = 0;
  Vector3 force_on_a = Vector3::Zero();  // the link's force on node a [N]; on b it is the opposite
};

struct MembraneSection {
  double radius = 0.0;                   // [m]
  std::size_t crossing_links = 0;
  double vertical_force = 0.0;           // [N]
  double radial_force = 0.0;             // [N]
  double radial_tension = 0.0;           // [N/m]
  double largest_sector_tension = 0.0;   // [N/m]
  double smallest_sector_tension = 0.0;  // [N/m]
  double largest_sector_angle = 0.0;     // the largest sector's centre, from the x axis [rad]
  double slope = 0.0;                    // [rad]
};

// `axis` is a point on the vertical (z) axis of the sections. Throws std::invalid_argument for a
// radius <= 0, sectors < 1 or a link naming a node outside `positions`.
std::vector<MembraneSection> membrane_sections(const std::vector<Vector3>& positions,
                                               const std::vector<SectionLink>& links, const Vector3& axis,
                                               const std::vector<double>& radii, int sectors = 8);

}  // namespace dtwire::dem
