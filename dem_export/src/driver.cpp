// The two-node driver: replays load paths (or a free oscillation) on a contact law and records
// the generalised displacements, forces and energies.
#include "dtwire/dem/driver.hpp"

#include <cmath>
#include <stdexcept>

#include "dtwire/core/csv.hpp"
#include "dtwire/core/error.hpp"
#include "dtwire/core/results_store.hpp"
#include "dtwire/dem/export_params.hpp"
#include "dtwire/dem/wirepm.hpp"

namespace dtwire::dem {
namespace {

constexpr double kPi = 3.14159265358979323846;

class HistoryRecorder {
 public:
  void record(double time, const Vector6& displacement, const ContactLaw& law) {
    time_.push_back(time);
    const Vector6 force = law.forces();
    for (int i = 0; i < 6; ++i) {
      displacement_[i].push_back(displacement(i));
      force_[i].push_back(force(i));
    }
    const EnergyAccount energy = law.energy();
    external_.push_back(energy.external);
    elastic_.push_back(energy.elastic);
    plastic_.push_back(energy.plastic);
    damage_.push_back(energy.damage);
    broken_.push_back(law.broken() ? 1.0 : 0.0);
  }

  Curve curve(const std::string& law_name, const std::string& path_name) const {
    const Unit mm = *find_unit("mm"), rad = *find_unit("rad");
    const Unit newton = *find_unit("N"), newton_metre = *find_unit("Nm"), joule = *find_unit("J");
    const char* displacement_names[6] = {"axial_displacement", "shear_displacement_y", "shear_displacement_z",
                                         "rotation_x", "rotation_y", "rotation_z"};
    const char* force_names[6] = {"axial_force", "shear_force_y", "shear_force_z", "torque", "moment_y", "moment_z"};
    Curve curve;
    curve.add_channel("time", *find_unit("s"), time_);
    for (int i = 0; i < 6; ++i)
      curve.add_channel_si(displacement_names[i], i < 3 ? Dimension::Length : Dimension::Angle, displacement_[i],
                           i < 3 ? mm : rad);
    for (int i = 0; i < 6; ++i)
      curve.add_channel_si(force_names[i], i < 3 ? Dimension::Force : Dimension::Moment, force_[i],
                           i < 3 ? newton : newton_metre);
    curve.add_channel("external_work", joule, external_);
    curve.add_channel("elastic_energy", joule, elastic_);
    curve.add_channel("plastic_work", joule, plastic_);
    curve.add_channel("damage_work", joule, damage_);
    curve.add_channel("broken", *find_unit("1"), broken_);
    curve.set_metadata("law", law_name);
    curve.set_metadata("path", path_name);
    curve.set_metadata("source", "dtwire dem driver (two-node bond, node 1 fixed)");
    return curve;
  }

 private:
  std::vector<double> time_, external_, elastic_, plastic_, damage_, broken_;
  std::vector<double> displacement_[6], force_[6];
};

// Initial stiffness along one component from a small increment on a copy of the law.
double probe_stiffness(const ContactLaw& law, int component, double increment) {
  const std::unique_ptr<ContactLaw> copy = law.clone();
  Vector6 step = Vector6::Zero();
  step(component) = increment;
  const double before = copy->forces()(component);
  copy->update(step);
  return (copy->forces()(component) - before) / increment;
}

}  // namespace

PathOptions default_path_options(const std::string& law_name, const ParameterMap& parameters) {
  PathOptions options;
  if (const auto found = parameters.find("reference_length_m"); found != parameters.end())
    options.reference_length = found->second;
  if (law_name == "wirepm") {
    const WirePmBackbone backbone = make_wirepm_backbone(parameters);
    options.max_axial_strain = 1.1 * backbone.points.back().elongation / options.reference_length;
  }
  return options;
}

Curve replay_path(ContactLaw& law, const LoadPath& path) {
  HistoryRecorder recorder;
  Vector6 previous = Vector6::Zero();
  for (const PathSample& sample : path.samples) {
    law.update(sample.displacement - previous);
    previous = sample.displacement;
    recorder.record(sample.time, sample.displacement, law);
  }
  return recorder.curve(std::string(law.name()), path.name);
}

Curve run_free_oscillation(ContactLaw& law, const FreeOscillationOptions& o) {
  if (!(o.mass > 0.0 && o.rotational_inertia > 0.0 && o.periods > 0.0 && o.steps >= 1))
    throw std::invalid_argument("free oscillation: mass, inertia, periods and steps must be > 0");
  // Probe increments: far inside the elastic range of a wire bond.
  const double axial_stiffness = probe_stiffness(law, 0, 1e-9);
  const double bending_stiffness = probe_stiffness(law, 4, 1e-9);
  double period = 0.0;
  if (axial_stiffness > 0.0 && o.initial_axial_velocity != 0.0) period = 2.0 * kPi * std::sqrt(o.mass / axial_stiffness);
  if (bending_stiffness > 0.0 && o.initial_angular_velocity != 0.0) {
    const double bending_period = 2.0 * kPi * std::sqrt(o.rotational_inertia / bending_stiffness);
    period = period > 0.0 ? std::min(period, bending_period) : bending_period;
  }
  if (!(period > 0.0))
    throw ComputationError("free oscillation: the law has no initial stiffness along the excited "
                           "components (axial " + std::to_string(axial_stiffness) + " N/m, bending " +
                           std::to_string(bending_stiffness) + " N m/rad)");
  const double time_step = o.periods * period / static_cast<double>(o.steps);

  HistoryRecorder recorder;
  Vector6 displacement = Vector6::Zero();
  Vector6 velocity = Vector6::Zero();
  velocity(0) = o.initial_axial_velocity;
  velocity(4) = o.initial_angular_velocity;
  recorder.record(0.0, displacement, law);
  for (std::size_t step = 1; step <= o.steps; ++step) {
    // Symplectic Euler: the bond force pulls the moving node back (F > 0 is tension).
    const Vector6 force = law.forces();
    for (int i = 0; i < 6; ++i) velocity(i) -= force(i) / (i < 3 ? o.mass : o.rotational_inertia) * time_step;
    const Vector6 increment = velocity * time_step;
    law.update(increment);
    displacement += increment;
    recorder.record(static_cast<double>(step) * time_step, displacement, law);
  }
  Curve curve = recorder.curve(std::string(law.name()), "free_oscillation");
  curve.set_metadata("time_step_s", format_number(time_step));
  return curve;
}

std::vector<DriverRun> run_driver(const std::string& law_name, const ParameterMap& parameters,
                                  const std::string& path_spec, const PathOptions& path_options,
                                  const FreeOscillationOptions& oscillation_options) {
  const std::unique_ptr<ContactLaw> prototype = make_contact_law(law_name, parameters);
  std::vector<DriverRun> runs;
  const auto run_named = [&](const std::string& name) {
    const std::unique_ptr<ContactLaw> law = prototype->clone();
    if (name == "free_oscillation")
      runs.push_back({name, run_free_oscillation(*law, oscillation_options)});
    else
      runs.push_back({name, replay_path(*law, make_path(name, path_options))});
  };
  const std::filesystem::path as_file(path_spec);
  if (path_spec == "all") {
    for (const std::string& name : prescribed_path_names()) run_named(name);
    run_named("free_oscillation");
  } else if (as_file.extension() == ".csv") {
    const LoadPath path = read_path_csv(as_file);
    const std::unique_ptr<ContactLaw> law = prototype->clone();
    runs.push_back({path.name, replay_path(*law, path)});
  } else {
    run_named(path_spec);
  }
  return runs;
}

void write_driver_results(const std::vector<DriverRun>& runs, const std::string& law_name,
                          const ParameterMap& parameters, const std::filesystem::path& out,
                          const Provenance& provenance) {
  std::filesystem::create_directories(out);
  Results results;
  results.provenance = provenance;
  for (const DriverRun& run : runs) {
    write_csv(run.history, out / (run.path_name + ".csv"));
    results.curves.emplace_back(run.path_name, run.history);
  }
  for (const auto& [name, value] : parameters) results.parameters.push_back({name, value, parameter_unit(name), std::nullopt});
  results.fields.emplace_back("law", law_name);
  write_results(results, out / "driver.h5");
}

}  // namespace dtwire::dem
