#include "dtwire/calibrate/voce_bar.hpp"

#include <cmath>
#include <stdexcept>

#include "dtwire/core/csv.hpp"
#include "dtwire/core/error.hpp"

namespace dtwire::calibrate {
namespace {

double get(const ParameterValues& p, const char* name) {
  const auto found = p.find(name);
  if (found == p.end()) throw std::invalid_argument(std::string("voce bar: missing parameter ") + name);
  return found->second;
}

}  // namespace

VoceBarSimulator::VoceBarSimulator(std::vector<double> strain_waypoints, int increments_per_leg)
    : waypoints_(std::move(strain_waypoints)), increments_(increments_per_leg) {
  if (waypoints_.size() < 2 || increments_ < 1)
    throw std::invalid_argument("voce bar: need >= 2 waypoints and >= 1 increment per leg");
}

Curve VoceBarSimulator::simulate(const ParameterValues& parameters) const {
  const double E = get(parameters, "E_Pa"), sy0 = get(parameters, "sigma_y0_Pa");
  const double Q = get(parameters, "Q_Pa"), b = get(parameters, "b_1");
  if (!(E > 0) || !(sy0 > 0) || Q < 0 || b < 0)
    throw ComputationError("voce bar: E, sigma_y0 must be > 0 and Q, b >= 0");
  const auto yield = [&](double p) { return sy0 + Q * (1.0 - std::exp(-b * p)); };
  double plastic_strain = 0, p = 0;
  std::vector<double> strain{waypoints_.front()}, stress{0.0};
  for (std::size_t leg = 1; leg < waypoints_.size(); ++leg) {
    for (int i = 1; i <= increments_; ++i) {
      const double eps = waypoints_[leg - 1] +
                         (waypoints_[leg] - waypoints_[leg - 1]) * i / static_cast<double>(increments_);
      const double trial = E * (eps - plastic_strain);
      double sigma = trial;
      if (std::abs(trial) > yield(p)) {
        // Return mapping: E dp + sigma_y(p + dp) = |trial|, Newton on dp.
        double dp = 0;
        for (int k = 0; k < 50; ++k) {
          const double g = E * dp + yield(p + dp) - std::abs(trial);
          const double dg = E + Q * b * std::exp(-b * (p + dp));
          dp -= g / dg;
          if (std::abs(g) < 1e-12 * std::abs(trial)) break;
        }
        const double sign = trial > 0 ? 1.0 : -1.0;
        plastic_strain += sign * dp;
        p += dp;
        sigma = trial - sign * E * dp;
      }
      strain.push_back(eps);
      stress.push_back(sigma);
    }
  }
  Curve curve;
  curve.add_channel("strain", *find_unit("1"), strain);
  curve.add_channel("stress", *find_unit("Pa"), stress);
  return curve;
}

std::string VoceBarSimulator::identity() const {
  std::string text = "voce_bar increments=" + std::to_string(increments_) + " path=";
  for (double w : waypoints_) text += format_number(w) + ";";
  return text;
}

std::vector<std::pair<std::string, Dimension>> VoceBarSimulator::channels() const {
  return {{"strain", Dimension::Dimensionless}, {"stress", Dimension::Stress}};
}

std::vector<std::string> VoceBarSimulator::parameter_names() const { return {"E_Pa", "sigma_y0_Pa", "Q_Pa", "b_1"}; }

}  // namespace dtwire::calibrate
