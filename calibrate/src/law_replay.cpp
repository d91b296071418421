#include "dtwire/calibrate/law_replay.hpp"

#include <cmath>
#include <stdexcept>

#include "dtwire/core/csv.hpp"
#include "dtwire/core/error.hpp"

namespace dtwire::calibrate {

void validate(const LoadPath& path) {
  if (path.displacement_m.size() < 2 || path.displacement_m.size() != path.rotation_rad.size())
    throw std::invalid_argument("load path: displacement and rotation waypoints must have the same "
                                "length, at least 2");
  if (path.increments_per_leg < 1) throw std::invalid_argument("load path: increments per leg >= 1");
  for (std::size_t i = 0; i < path.displacement_m.size(); ++i)
    if (!std::isfinite(path.displacement_m[i]) || !std::isfinite(path.rotation_rad[i]))
      throw std::invalid_argument("load path: waypoints must be finite");
}

LawReplaySimulator::LawReplaySimulator(std::string law, dem::ParameterMap fixed, LoadPath path)
    : law_(std::move(law)), fixed_(std::move(fixed)), path_(std::move(path)) {
  validate(path_);
}

Curve LawReplaySimulator::simulate(const ParameterValues& parameters) const {
  dem::ParameterMap all = fixed_;
  for (const auto& [name, value] : parameters) all[name] = value;
  std::unique_ptr<dem::ContactLaw> bond;
  try {
    bond = dem::make_contact_law(law_, all);
  } catch (const std::invalid_argument& error) {
    throw ComputationError(std::string("law rejected the parameters: ") + error.what());
  }
  const auto& u = path_.displacement_m;
  const auto& w = path_.rotation_rad;
  std::vector<double> time{0.0}, du{u.front()}, rot{w.front()}, force{0.0}, moment{0.0};
  const int steps = path_.increments_per_leg;
  for (std::size_t leg = 1; leg < u.size(); ++leg) {
    dem::Vector6 increment = dem::Vector6::Zero();
    increment(0) = (u[leg] - u[leg - 1]) / steps;
    increment(4) = (w[leg] - w[leg - 1]) / steps;
    for (int i = 1; i <= steps; ++i) {
      bond->update(increment);
      const dem::Vector6 f = bond->forces();
      if (!f.allFinite()) throw ComputationError(law_ + ": non-finite forces");
      time.push_back(static_cast<double>(leg - 1) + static_cast<double>(i) / steps);
      du.push_back(u[leg - 1] + (u[leg] - u[leg - 1]) * i / steps);
      rot.push_back(w[leg - 1] + (w[leg] - w[leg - 1]) * i / steps);
      force.push_back(f(0));
      moment.push_back(f(4));
    }
  }
  Curve curve;
  curve.add_channel("time", *find_unit("s"), time);
  curve.add_channel("displacement", *find_unit("m"), du);
  curve.add_channel("rotation", *find_unit("rad"), rot);
  curve.add_channel("force", *find_unit("N"), force);
  curve.add_channel("moment", *find_unit("Nm"), moment);
  return curve;
}

std::string LawReplaySimulator::identity() const {
  std::string text = "law_replay law=" + law_ + " increments=" + std::to_string(path_.increments_per_leg);
  text += "\nfixed:";
  for (const auto& [name, value] : fixed_) text += " " + name + "=" + format_number(value);
  text += "\npath:";
  for (std::size_t i = 0; i < path_.displacement_m.size(); ++i)
    text += " (" + format_number(path_.displacement_m[i]) + "," + format_number(path_.rotation_rad[i]) + ")";
  return text;
}

}  // namespace dtwire::calibrate
