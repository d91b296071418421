// Radial sections of a punched net (membrane_sections.hpp) against the closed form of a spoked
// membrane: n straight spokes from a hub at height h to a ring of radius a, each at tension T,
// cut by a cylinder of radius r < a: n crossings, vertical force n T h / L, radial force
// n T a / L (L = sqrt(a^2 + h^2)), mean tension n T a / (L 2 pi r), slope atan(h / a).
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "dtwire/dem/membrane_sections.hpp"

namespace dtwire::dem {
namespace {

constexpr double kPi = 3.14159265358979323846;

struct Spokes {
  std::vector<Vector3> positions;
  std::vector<SectionLink> links;
};

// Spoke k has tension tension[k]; odd spokes name the ring node first (the sign convention of
// force_on_a must not matter).
Spokes spokes(double a, double h, const std::vector<double>& tension, double hub_x = 0.0) {
  Spokes net;
  const Vector3 hub(hub_x, 0.0, h);
  net.positions.push_back(hub);
  for (std::size_t k = 0; k < tension.size(); ++k) {
    const double angle = 2.0 * kPi * k / tension.size();
    const Vector3 ring(hub_x + a * std::cos(angle), a * std::sin(angle), 0.0);
    net.positions.push_back(ring);
    const Vector3 hub_to_ring = (ring - hub).normalized();
    const std::size_t node = net.positions.size() - 1;
    if (k % 2 == 0)
      net.links.push_back({0, node, tension[k] * hub_to_ring});  // tension pulls the hub toward the ring
    else
      net.links.push_back({node, 0, -tension[k] * hub_to_ring});
  }
  return net;
}

TEST(MembraneSections, SpokedMembraneMatchesTheClosedForm) {
  const double a = 1.2, h = 0.4, t = 1500.0, r = 0.7;
  const Spokes net = spokes(a, h, std::vector<double>(8, t), 0.3);
  const auto sections = membrane_sections(net.positions, net.links, Vector3(0.3, 0.0, -5.0), {r, 1.3});
  ASSERT_EQ(sections.size(), 2u);
  const double length = std::hypot(a, h);
  const MembraneSection& s = sections[0];
  EXPECT_EQ(s.crossing_links, 8u);
  EXPECT_NEAR(s.vertical_force, 8 * t * h / length, 1e-9);
  EXPECT_NEAR(s.radial_force, 8 * t * a / length, 1e-9);
  EXPECT_NEAR(s.radial_tension, 8 * t * a / length / (2 * kPi * r), 1e-9);
  EXPECT_NEAR(s.largest_sector_tension, s.radial_tension, 1e-9);
  EXPECT_NEAR(s.smallest_sector_tension, s.radial_tension, 1e-9);
  EXPECT_NEAR(s.slope, std::atan(h / a), 1e-12);
  // Beyond the ring nothing crosses.
  EXPECT_EQ(sections[1].crossing_links, 0u);
  EXPECT_EQ(sections[1].vertical_force, 0.0);
}

TEST(MembraneSections, SectorsShowAnUnevenCircumference) {
  // Spoke 2 (along +y) at twice the others' tension: its sector carries 2 T a / L per 1/8 of the
  // circumference, the others T a / L.
  std::vector<double> tension(8, 1000.0);
  tension[2] = 2000.0;
  const double a = 1.0, h = 0.5, r = 0.5;
  const Spokes net = spokes(a, h, tension);
  const auto s = membrane_sections(net.positions, net.links, Vector3::Zero(), {r}).front();
  const double per_spoke = 1000.0 * a / std::hypot(a, h);
  EXPECT_NEAR(s.largest_sector_tension, 2 * per_spoke / (2 * kPi * r / 8), 1e-9);
  EXPECT_NEAR(s.largest_sector_angle, kPi / 2, 1e-12);
  EXPECT_NEAR(s.smallest_sector_tension, per_spoke / (2 * kPi * r / 8), 1e-9);
  EXPECT_NEAR(s.radial_tension, 9 * per_spoke / (2 * kPi * r), 1e-9);
}

TEST(MembraneSections, RejectsBadRadiiSectorsAndNodes) {
  const Spokes net = spokes(1.0, 0.2, std::vector<double>(4, 10.0));
  EXPECT_THROW(membrane_sections(net.positions, net.links, Vector3::Zero(), {0.0}), std::invalid_argument);
  EXPECT_THROW(membrane_sections(net.positions, net.links, Vector3::Zero(), {0.5}, 0), std::invalid_argument);
  std::vector<SectionLink> links = net.links;
  links.push_back({0, 99, Vector3::Zero()});
  EXPECT_THROW(membrane_sections(net.positions, links, Vector3::Zero(), {0.5}), std::invalid_argument);
}

}  // namespace
}  // namespace dtwire::dem
