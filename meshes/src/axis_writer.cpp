#include "dtwire/meshes/axis_io.hpp"

#include <iomanip>

#include "dtwire/core/atomic_file.hpp"

namespace dtwire::meshes {

std::filesystem::path axis_file_for(const std::filesystem::path& mesh_file) {
  auto axis = mesh_file;
  axis.replace_extension(".axis.csv");
  return axis;
}

void write_axis_csv(const WireMesh& mesh, const std::filesystem::path& path) {
  write_file_atomically(path, [&](std::ostream& out) {
    out << "# wire axes of the mesh beside this file (`dtwire mesh`): stations the section was swept along;\n"
           "# curvature = d(tangent)/ds towards the centre of curvature (what bending a straight wire into\n"
           "# this axis takes; fem's As made/Forming history reads it)\n";
    out << "wire,arc_length_mm,x_mm,y_mm,z_mm,tangent_x,tangent_y,tangent_z,curvature_x_per_mm,curvature_y_per_mm,"
           "curvature_z_per_mm\n";
    out << std::setprecision(12);
    for (std::size_t wire = 0; wire < mesh.axes.size(); ++wire)
      for (const AxisSample& s : mesh.axes[wire])
        out << wire << ',' << 1e3 * s.arc_length << ',' << 1e3 * s.point.x << ',' << 1e3 * s.point.y << ','
            << 1e3 * s.point.z << ',' << s.tangent.x << ',' << s.tangent.y << ',' << s.tangent.z << ','
            << 1e-3 * s.curvature.x << ',' << 1e-3 * s.curvature.y << ',' << 1e-3 * s.curvature.z << '\n';
  });
}

}  // namespace dtwire::meshes
