#include "dtwire/dem/membrane_sections.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace dtwire::dem {
namespace {
constexpr double kPi = 3.14159265358979323846;

double horizontal_distance(const Vector3& p, const Vector3& axis) { return std::hypot(p.x() - axis.x(), p.y() - axis.y()); }
}  // namespace

std::vector<MembraneSection> membrane_sections(const std::vector<Vector3>& positions,
                                               const std::vector<SectionLink>& links, const Vector3& axis,
                                               const std::vector<double>& radii, int sectors) {
  if (sectors < 1) throw std::invalid_argument("membrane sections: sectors must be >= 1, got " + std::to_string(sectors));
  for (const SectionLink& link : links)
    if (link.a >= positions.size() || link.b >= positions.size())
      throw std::invalid_argument("membrane sections: a link names node " + std::to_string(std::max(link.a, link.b)) +
                                  " of " + std::to_string(positions.size()));
  std::vector<MembraneSection> sections;
  for (double r : radii) {
    if (!(r > 0.0)) throw std::invalid_argument("membrane sections: a radius must be > 0, got " + std::to_string(r));
    MembraneSection section;
    section.radius = r;
    std::vector<double> sector_force(static_cast<std::size_t>(sectors), 0.0);
    for (const SectionLink& link : links) {
      const double ra = horizontal_distance(positions[link.a], axis);
      const double rb = horizontal_distance(positions[link.b], axis);
      if ((ra < r) == (rb < r)) continue;
      const bool a_inside = ra < r;
      const Vector3& inside = a_inside ? positions[link.a] : positions[link.b];
      const Vector3& outside = a_inside ? positions[link.b] : positions[link.a];
      const Vector3 force = a_inside ? link.force_on_a : Vector3(-link.force_on_a);
      // Where the link's horizontal projection crosses the circle (linear between its ends).
      const double r_in = std::min(ra, rb), r_out = std::max(ra, rb);
      const double s = (r - r_in) / (r_out - r_in);
      const Vector3 crossing = inside + s * (outside - inside);
      const double angle = std::atan2(crossing.y() - axis.y(), crossing.x() - axis.x());
      const double radial = force.x() * std::cos(angle) + force.y() * std::sin(angle);
      ++section.crossing_links;
      section.vertical_force -= force.z();
      section.radial_force += radial;
      // Sector 0 is centred on the x axis.
      const double width = 2.0 * kPi / sectors;
      const double shifted = std::fmod(angle + 0.5 * width + 4.0 * kPi, 2.0 * kPi);
      sector_force[std::min(static_cast<std::size_t>(shifted / width), sector_force.size() - 1)] += radial;
    }
    const double circumference = 2.0 * kPi * r;
    section.radial_tension = section.radial_force / circumference;
    const auto [smallest, largest] = std::minmax_element(sector_force.begin(), sector_force.end());
    section.largest_sector_tension = *largest / (circumference / sectors);
    section.smallest_sector_tension = *smallest / (circumference / sectors);
    section.largest_sector_angle = 2.0 * kPi / sectors * static_cast<double>(largest - sector_force.begin());
    section.slope = section.crossing_links ? std::atan2(section.vertical_force, section.radial_force) : 0.0;
    sections.push_back(section);
  }
  return sections;
}

}  // namespace dtwire::dem
