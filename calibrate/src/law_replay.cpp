#include "dtwire/calibrate/law_replay.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "dtwire/core/csv.hpp"
#include "dtwire/core/error.hpp"
#include "dtwire/dem/driver.hpp"
#include "dtwire/dem/law_schema.hpp"
#include "dtwire/dem/paths.hpp"

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

LoadPath path_from_target(Curve& target, int increments_per_leg) {
  if (target.size() == 0) throw std::invalid_argument("no rows");
  if (!target.has("displacement") && !target.has("rotation"))
    throw std::invalid_argument("neither a displacement nor a rotation channel to follow");
  if (target.has("time")) throw std::invalid_argument("already has a 'time' channel (path_from_target makes its own)");
  const std::size_t rows = target.size();
  const std::vector<double> u = target.has("displacement") ? target.si("displacement") : std::vector<double>(rows, 0.0);
  const std::vector<double> theta = target.has("rotation") ? target.si("rotation") : std::vector<double>(rows, 0.0);
  LoadPath path;
  path.increments_per_leg = increments_per_leg;
  const bool starts_at_origin = u.front() == 0.0 && theta.front() == 0.0;
  if (!starts_at_origin) {
    path.displacement_m.push_back(0.0);
    path.rotation_rad.push_back(0.0);
  }
  path.displacement_m.insert(path.displacement_m.end(), u.begin(), u.end());
  path.rotation_rad.insert(path.rotation_rad.end(), theta.begin(), theta.end());
  if (path.displacement_m.size() < 2) throw std::invalid_argument("one row at the origin: no path to follow");
  std::vector<double> time(rows);
  for (std::size_t k = 0; k < rows; ++k) time[k] = static_cast<double>(k + (starts_at_origin ? 0 : 1));
  target.add_channel_si("time", Dimension::Time, time, *find_unit("s"));
  validate(path);
  return path;
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
  // The waypoints as a sampled path for dem_export's two-node driver (dem::replay_path), one
  // sample per increment; time is the pseudo-time of the legs.
  const auto& u = path_.displacement_m;
  const auto& w = path_.rotation_rad;
  const int steps = path_.increments_per_leg;
  dem::LoadPath sampled;
  sampled.name = "fit_path";
  sampled.samples.push_back(dem::PathSample{});
  for (std::size_t leg = 1; leg < u.size(); ++leg)
    for (int i = 1; i <= steps; ++i) {
      const double t = static_cast<double>(i) / steps;
      dem::PathSample sample;
      sample.time = static_cast<double>(leg - 1) + t;
      sample.displacement(0) = u[leg - 1] + (u[leg] - u[leg - 1]) * t;
      sample.displacement(4) = w[leg - 1] + (w[leg] - w[leg - 1]) * t;
      sampled.samples.push_back(sample);
    }
  const Curve history = dem::replay_path(*bond, sampled);
  Curve curve;
  const auto copy = [&](const char* from, const char* to) {
    const Channel& c = history.channel(from);
    for (double v : c.values)
      if (!std::isfinite(v)) throw ComputationError(law_ + ": non-finite " + from);
    curve.add_channel(to, c.unit, c.values);
  };
  copy("time", "time");
  copy("axial_displacement", "displacement");
  copy("rotation_y", "rotation");
  copy("axial_force", "force");
  copy("moment_y", "moment");
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

std::vector<std::pair<std::string, Dimension>> LawReplaySimulator::channels() const {
  return {{"time", Dimension::Time},
          {"displacement", Dimension::Length},
          {"rotation", Dimension::Angle},
          {"force", Dimension::Force},
          {"moment", Dimension::Moment}};
}

std::vector<std::string> LawReplaySimulator::parameter_names() const {
  std::vector<std::string> names = dem::law_parameter_names(law_);
  for (const auto& [name, value] : fixed_)  // WirePM's backbone points, named by pattern
    if (dem::is_law_parameter(law_, name) && std::find(names.begin(), names.end(), name) == names.end())
      names.push_back(name);
  return names;
}

}  // namespace dtwire::calibrate
