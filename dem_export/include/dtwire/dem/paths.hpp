#pragma once
// Load paths for the two-node driver: histories of the generalised relative displacement of a
// bond (see contact_law.hpp for the six components), prescribed in time.
#include <filesystem>
#include <string>
#include <vector>

#include "dtwire/dem/contact_law.hpp"

namespace dtwire::dem {

struct PathSample {
  double time = 0.0;                          // [s]
  Vector6 displacement = Vector6::Zero();     // total, not incremental [m, rad]
};

struct LoadPath {
  std::string name;
  std::vector<PathSample> samples;  // samples[0] is the undeformed start
};

// Magnitudes of the prescribed paths. Elongations scale with the bond's reference length.
struct PathOptions {
  double reference_length = 0.06;        // l0 [m]
  double max_axial_strain = 0.4;         // pull, pull + spin, cycles: peak elongation / l0
  double max_compression_strain = 0.1;   // compression: peak shortening / l0
  double max_rotation = 0.5;             // bending spin, pull + spin: peak theta_y [rad]
  double duration = 1.0;                 // time of a whole path [s]
  std::size_t steps = 2000;              // increments of a whole path
};

// A piecewise-linear history through breakpoints, sampled at a constant rate along its length
// (sum of |changes|, with rotations scaled by l0). The YADE script uses the same formula.
struct Breakpoint {
  double axial = 0.0;     // u [m]
  double rotation = 0.0;  // theta_y [rad]
};

// "axial_pull", "compression", "bending_spin", "pull_spin", "cycles". Free oscillation is not a
// prescribed path: see driver.hpp.
std::vector<std::string> prescribed_path_names();
// Throws std::invalid_argument for an unknown name or bad options.
LoadPath make_path(const std::string& name, const PathOptions& options);
std::vector<Breakpoint> path_breakpoints(const std::string& name, const PathOptions& options);
// Steps given to each leg of a breakpoint list (proportional to its length, at least 1).
std::vector<std::size_t> leg_steps(const std::vector<Breakpoint>& breakpoints, double reference_length,
                                   std::size_t steps);

// Reads a path CSV: time_s plus any of axial_displacement, shear_displacement_y,
// shear_displacement_z (length units), rotation_x, rotation_y, rotation_z (angle units); absent
// components stay zero. Time must increase. Throws InputError naming the file, line and column.
LoadPath read_path_csv(const std::filesystem::path& path);

}  // namespace dtwire::dem
