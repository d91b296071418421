#pragma once
// The wire axes of a mesh as CSV (`X.axis.csv` beside `X.msh`): one row per station, in mm, with
// the tangent and the curvature vector. fem/ reads it to put the forming history of a double
// twist (bending a straight wire into its axis) into the mesh (docs/fem_dt.md, "As made").
#include <filesystem>

#include "dtwire/meshes/wire_mesh.hpp"

namespace dtwire::meshes {

// X.msh -> X.axis.csv
std::filesystem::path axis_file_for(const std::filesystem::path& mesh_file);

// Written under a temporary name, then renamed into place.
void write_axis_csv(const WireMesh& mesh, const std::filesystem::path& path);

}  // namespace dtwire::meshes
