#pragma once
// Area of the boundary faces of a gmsh MSH 2.2 ASCII mesh (as `dtwire mesh` writes it) that carry
// given physical ids: bilinear quadrilaterals integrated by 2 x 2 Gauss points, the same area the
// FE solver integrates on them (deal.II's Q1 mapping). For `dtwire gap --model`, which does not
// link the FE solver.
#include <filesystem>
#include <vector>

namespace dtwire::app {

// m^2 (the file is in metres). Throws InputError naming the file for a file it cannot read.
double msh_surface_area(const std::filesystem::path& msh, const std::vector<unsigned>& physical_ids);

}  // namespace dtwire::app
