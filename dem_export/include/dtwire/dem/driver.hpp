#pragma once
// The two-node driver: one node fixed, the other moved along a load path (or left to oscillate
// freely); the bond's law turns the relative displacement into forces. Histories of
// displacement, force, moment and energy come back as a Curve:
//   time_s, axial_displacement_mm, shear_displacement_y_mm, shear_displacement_z_mm,
//   rotation_x_rad, rotation_y_rad, rotation_z_rad, axial_force_N, shear_force_y_N,
//   shear_force_z_N, torque_Nm, moment_y_Nm, moment_z_Nm, external_work_J, elastic_energy_J,
//   plastic_work_J, damage_work_J, broken_1
#include <filesystem>
#include <string>
#include <vector>

#include "dtwire/core/curve.hpp"
#include "dtwire/core/provenance.hpp"
#include "dtwire/dem/contact_law.hpp"
#include "dtwire/dem/paths.hpp"

namespace dtwire::dem {

// Free vibration of the moving node (mass m, rotational inertia I) on the bond, integrated with
// the symplectic (semi-implicit) Euler scheme. The time step is a fraction of the period from
// the law's initial stiffness (probed on a copy of the law).
struct FreeOscillationOptions {
  double mass = 4.3e-3;                // Thoeni 2013 net particle [kg]
  double rotational_inertia = 5.0e-8;  // 2/5 m r^2 with r = 5.4 mm [kg m^2]
  double initial_axial_velocity = 1.0; // [m/s], > 0 stretches the bond
  double initial_angular_velocity = 0.0;  // about y [rad/s]
  double periods = 5.0;
  std::size_t steps = 1000;            // whole run
};

// Path magnitudes for a law: l0 from reference_length_m; for WirePM the pulls go to 1.1 times the
// breaking elongation so that every path with a pull ends past the break.
PathOptions default_path_options(const std::string& law_name, const ParameterMap& parameters);

// Replays the path on `law` (advanced in place), one increment per sample.
Curve replay_path(ContactLaw& law, const LoadPath& path);
// Throws ComputationError if the law has no initial stiffness to set the time step.
Curve run_free_oscillation(ContactLaw& law, const FreeOscillationOptions& options);

struct DriverRun {
  std::string path_name;
  Curve history;
};

// `path_spec`: a prescribed path name, "free_oscillation", "all" (every prescribed path and the
// free oscillation, each on a fresh law) or a path CSV file. Throws std::invalid_argument for
// bad law parameters or an unknown path name, InputError for a bad CSV.
std::vector<DriverRun> run_driver(const std::string& law_name, const ParameterMap& parameters,
                                  const std::string& path_spec, const PathOptions& path_options,
                                  const FreeOscillationOptions& oscillation_options);

// Writes <out>/<path>.csv for every run and <out>/driver.h5 with all runs and the parameters.
void write_driver_results(const std::vector<DriverRun>& runs, const std::string& law_name,
                          const ParameterMap& parameters, const std::filesystem::path& out,
                          const Provenance& provenance);

}  // namespace dtwire::dem
