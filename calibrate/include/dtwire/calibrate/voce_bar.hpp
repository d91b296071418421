#pragma once
// An analytic simulator for developing and testing fits without FE or DEM: a uniaxial bar,
// rate-independent elastoplastic with isotropic Voce hardening
//   sigma_y(p) = sigma_y0 + Q (1 - exp(-b p))      (Voce 1948)
// driven along a strain path (waypoints, linear legs). Parameters: E_Pa, sigma_y0_Pa, Q_Pa, b_1.
// Curve channels: strain_1, stress_Pa.
#include <vector>

#include "dtwire/calibrate/simulator.hpp"

namespace dtwire::calibrate {

class VoceBarSimulator final : public Simulator {
 public:
  // strain_waypoints start at 0; increments_per_leg >= 1.
  VoceBarSimulator(std::vector<double> strain_waypoints, int increments_per_leg);
  Curve simulate(const ParameterValues& parameters) const override;
  std::string identity() const override;
  std::vector<std::pair<std::string, Dimension>> channels() const override;
  std::vector<std::string> parameter_names() const override;

 private:
  std::vector<double> waypoints_;
  int increments_;
};

}  // namespace dtwire::calibrate
