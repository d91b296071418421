#pragma once
// The three-point bending rig of dem_specimen (dem_specimen.hpp, RollerRig): the rollers placed
// so that each just touches the specimen, and the links each one touches at the start.
#include <vector>

#include "dtwire/calibrate/dem_specimen.hpp"
#include "dtwire/dem/net.hpp"
#include "dtwire/dem/roller.hpp"

namespace dtwire::calibrate {

struct BendingRollers {
  std::vector<dem::Roller> rollers;       // 0, 1: the supports at rig.support_z_m, 2: the loading roller
  std::vector<double> link_radius;        // per link: its wire radius against the rollers [m]
  std::vector<std::vector<int>> touched;  // per roller: the links it touches at the start
};

// The supports come up along +y and the loading roller down along -y until each touches the
// nearest link. Throws std::invalid_argument if a roller touches the specimen only at a node
// (its z beyond the links that should carry it).
BendingRollers place_bending_rollers(const RollerRig& rig, const std::vector<dem::NetNode>& nodes,
                                     const std::vector<dem::NetLink>& links);

}  // namespace dtwire::calibrate
