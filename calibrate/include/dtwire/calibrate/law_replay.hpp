#pragma once
// DEM-bond simulator: replays a load path (axial displacement u and bending rotation theta_y
// of the bond's moving node, piecewise linear between waypoints) on a dtwire::dem::ContactLaw
// and returns the force and moment curves. This is the fit (3) simulator: macro-element
// parameters from curves, without FE in the loop.
// Curve channels: time_s (pseudo-time: leg k runs from k-1 to k s, a monotone abscissa for paths
// along which neither displacement nor rotation is monotone), displacement_m, rotation_rad,
// force_N, moment_Nm.
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

class LawReplaySimulator final : public Simulator {
 public:
  // `fixed` holds the law parameters that are not fitted; fitted ones override them.
  LawReplaySimulator(std::string law, dem::ParameterMap fixed, LoadPath path);
  // Throws ComputationError if the law rejects the parameters or produces non-finite forces.
  Curve simulate(const ParameterValues& parameters) const override;
  std::string identity() const override;

  const std::string& law() const { return law_; }
  const dem::ParameterMap& fixed() const { return fixed_; }

 private:
  std::string law_;
  dem::ParameterMap fixed_;
  LoadPath path_;
};

}  // namespace dtwire::calibrate
