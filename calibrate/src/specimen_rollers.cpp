// Placing dem_specimen's bending rollers (specimen_rollers.hpp).
#include "specimen_rollers.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace dtwire::calibrate {
namespace {

// Smallest gap between the roller and a wire [m], and where on that link.
struct Gap {
  double gap = 1e300;
  int link = -1;
  double s = 0.0;
};

Gap nearest_gap(const dem::Roller& roller, const std::vector<dem::NetNode>& nodes, const std::vector<dem::NetLink>& links,
                const std::vector<double>& radius) {
  Gap best;
  for (std::size_t l = 0; l < links.size(); ++l) {
    const dem::SegmentPoint p = dem::nearest_to_axis(roller, nodes[links[l].a].position, nodes[links[l].b].position);
    const double gap = p.distance - roller.radius - radius[l];
    if (gap < best.gap) best = {gap, static_cast<int>(l), p.s};
  }
  return best;
}

}  // namespace

BendingRollers place_bending_rollers(const RollerRig& rig, const std::vector<dem::NetNode>& nodes,
                                     const std::vector<dem::NetLink>& links) {
  BendingRollers out;
  for (const dem::NetLink& link : links)
    out.link_radius.push_back(link.tag == dem::LinkTag::DoubleTwist ? rig.dt_contact_radius_m : rig.sw_contact_radius_m);
  const double c = std::cos(rig.support_tilt_rad), s = std::sin(rig.support_tilt_rad);
  const double far = rig.radius_m + 0.1;  // m, clear of the specimen
  struct Placement {
    double z, side;  // side: -1 below the mesh plane (a support), +1 above (the loading roller)
    Eigen::Vector3d axis;
  };
  const Placement placements[3] = {{rig.support_z_m[0], -1.0, {c, -s, 0.0}},
                                   {rig.support_z_m[1], -1.0, {c, s, 0.0}},
                                   {rig.loading_z_m, 1.0, {1.0, 0.0, 0.0}}};
  for (const Placement& p : placements) {
    dem::Roller roller;
    roller.point = Eigen::Vector3d(0.0, p.side * far, p.z);
    roller.axis = p.axis.normalized();
    roller.radius = rig.radius_m;
    roller.contact.normal_stiffness = rig.normal_stiffness_N_per_m;
    roller.contact.shear_stiffness = rig.normal_stiffness_N_per_m;
    roller.contact.friction = rig.friction;
    // The gap shrinks at most as fast as the roller moves: steps of the gap approach from outside.
    Gap g = nearest_gap(roller, nodes, links, out.link_radius);
    for (int k = 0; k < 200 && g.gap > 1e-13; ++k) {
      roller.point.y() -= p.side * g.gap;
      g = nearest_gap(roller, nodes, links, out.link_radius);
    }
    std::vector<int> touched;
    bool between_nodes = false;
    for (std::size_t l = 0; l < links.size(); ++l) {
      const dem::SegmentPoint q = dem::nearest_to_axis(roller, nodes[links[l].a].position, nodes[links[l].b].position);
      if (q.distance - roller.radius - out.link_radius[l] > 1e-9) continue;
      touched.push_back(static_cast<int>(l));
      between_nodes = between_nodes || (q.s > 1e-9 && q.s < 1.0 - 1e-9);
    }
    if (!between_nodes)
      throw std::invalid_argument("dem_specimen: the roller at z = " + std::to_string(p.z * 1e3) +
                                  " mm touches the specimen only at a node (expected a z within a link's span)");
    out.rollers.push_back(roller);
    out.touched.push_back(touched);
  }
  return out;
}

}  // namespace dtwire::calibrate
