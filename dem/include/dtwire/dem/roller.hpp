#pragma once
// A rigid cylindrical roller (the supports and the loading roller of a three-point bending rig)
// that touches the net's LINKS, not its nodes: a specimen whose nodes are only at the link ends
// is pressed between its nodes. Contact acts at the point of the link's axis segment nearest to
// the roller's axis (an infinite line): a linear penalty spring kn on the overlap of the roller
// (radius R) and the wire (radius r), an incremental shear spring ks capped by Coulomb friction
// (Cundall & Strack 1979, as the node tools in tools.hpp). The contact force F at s (0 at node
// a, 1 at node b) goes to the end nodes by the lever rule, (1 - s) F and s F: the same resultant
// and the same moment about any point as F at the axis point, and the power F . ((1 - s) v_a +
// s v_b) is that of F at the interpolated velocity, so the engine's work bookkeeping holds.
// Neglected: the moment of the friction force about the axis (arm r) and the rollers' spin (the
// FE rollers do not spin either).
#include <Eigen/Core>

#include "dtwire/dem/tools.hpp"

namespace dtwire::dem {

struct Roller {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();     // a point of the axis [m]
  Eigen::Vector3d axis = Eigen::Vector3d::UnitX();     // direction (normalised on use)
  double radius = 0.02;                                // [m]
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();  // prescribed translation [m/s]
  ToolContactLaw contact;
};

// The point of segment a-b nearest to the roller's axis: s in [0, 1] and the distance [m]. A
// segment parallel to the axis gives s = 1/2.
struct SegmentPoint {
  double s = 0.5;
  double distance = 0.0;
  Eigen::Vector3d normal = Eigen::Vector3d::UnitY();  // unit, from the axis towards the segment
};
SegmentPoint nearest_to_axis(const Roller& roller, const Eigen::Vector3d& a, const Eigen::Vector3d& b);

struct SegmentContact {
  bool touching = false;
  SegmentPoint where;
  double penetration = 0.0;                               // R + r - distance, > 0 in contact [m]
  Eigen::Vector3d force = Eigen::Vector3d::Zero();        // of the roller on the segment [N]
  Eigen::Vector3d on_a = Eigen::Vector3d::Zero(), on_b = Eigen::Vector3d::Zero();  // lever-rule shares
  double elastic_energy = 0.0;                            // in the normal and shear springs [J]
  double friction_work = 0.0;                             // dissipated by slip in this step [J]
};

// One step of the contact of `roller` with the wire segment a-b of radius `wire_radius`:
// `shear` is the contact's shear spring force, carried between steps (set to zero when apart),
// v_a and v_b the nodes' velocities over the step dt.
SegmentContact roller_segment_contact(const Roller& roller, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                      double wire_radius, const Eigen::Vector3d& v_a, const Eigen::Vector3d& v_b,
                                      double dt, Eigen::Vector3d& shear);

}  // namespace dtwire::dem
