#pragma once
// DEM-bond simulator for fit (3), macro-element parameters from curves without FE in the loop:
// replays a load path (axial displacement u and bending rotation theta_y of the bond's moving
// node, piecewise linear between waypoints) on a dtwire::dem::ContactLaw through dem_export's
// two-node driver (dem::replay_path) and returns the force and moment curves.
// Curve channels, in the driver's units: time (pseudo-time: leg k runs from k-1 to k s, a
// monotone abscissa for paths along which neither u nor theta_y is monotone), displacement,
// rotation, force, moment (the driver's axial_displacement, rotation_y, axial_force, moment_y).
#include <string>
#include <vector>

#include "dtwire/calibrate/simulator.hpp"
#include "dtwire/dem/contact_law.hpp"

namespace dtwire::calibrate {

struct LoadPath {
  std::vector<double> displacement_m;  // waypoints, starting at 0
  std::vector<double> rotation_rad;    // same length
  int increments_per_leg = 100;
};

// Throws std::invalid_argument if the waypoint lists differ in length, have < 2 entries or
// increments_per_leg < 1.
void validate(const LoadPath& path);

// A path that follows a target's own kinematics (e.g. an FE run's measured link elongation and
// rotation, which no waypoint list can state in advance): its waypoints are the target's rows'
// displacement and rotation (zero where the target has no such channel), preceded by the origin
// unless the first row is there. Adds the target's `time` channel, each row at the pseudo-time of
// its waypoint, so that abscissa = "time" compares the forces row by row. Throws
// std::invalid_argument if the target has neither channel, no row, or a `time` channel already.
LoadPath path_from_target(Curve& target, int increments_per_leg);

class LawReplaySimulator final : public Simulator {
 public:
  // `fixed` holds the law parameters that are not fitted; fitted ones override them.
  LawReplaySimulator(std::string law, dem::ParameterMap fixed, LoadPath path);
  // Throws ComputationError if the law rejects the parameters or produces non-finite forces.
  Curve simulate(const ParameterValues& parameters) const override;
  std::string identity() const override;
  std::vector<std::pair<std::string, Dimension>> channels() const override;
  std::vector<std::string> parameter_names() const override;

  const std::string& law() const { return law_; }
  const dem::ParameterMap& fixed() const { return fixed_; }
  const LoadPath& path() const { return path_; }

 private:
  std::string law_;
  dem::ParameterMap fixed_;
  LoadPath path_;
};

}  // namespace dtwire::calibrate
