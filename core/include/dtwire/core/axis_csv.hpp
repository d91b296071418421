#pragma once
// The wire axes of a mesh (`X.axis.csv`, written by `dtwire mesh ... -o X.msh`): one row per
// station, `wire,arc_length_mm,x_mm,y_mm,z_mm,tangent_x,tangent_y,tangent_z,curvature_x_per_mm,
// curvature_y_per_mm,curvature_z_per_mm` ('#' lines are comments). Read here in SI.
#include <array>
#include <filesystem>
#include <vector>

namespace dtwire {

struct AxisStation {
  unsigned wire = 0;                 // 0 or 1
  double arc_length = 0.0;           // m from the wire's first station
  std::array<double, 3> point{}, tangent{};  // m; unit
  std::array<double, 3> curvature{};         // 1/m, d(tangent)/ds towards the centre of curvature
};

// Per wire (index = wire), in file order. Throws InputError naming the file and line of a bad row
// (not 11 numbers, a wire other than 0 or 1 or out of order, a tangent that is not a unit
// vector), a missing header, or a wire with fewer than two stations.
std::vector<std::vector<AxisStation>> read_axis_csv(const std::filesystem::path& file);

}  // namespace dtwire
