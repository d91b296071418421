#include "dealii_reader.hpp"

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/grid_in.h>
#include <deal.II/grid/tria.h>

#include <algorithm>
#include <fstream>

DealIIView read_with_dealii(const std::string& msh_file) {
  dealii::Triangulation<3> triangulation;
  dealii::GridIn<3> grid_in;
  grid_in.attach_triangulation(triangulation);
  std::ifstream in(msh_file);
  grid_in.read_msh(in);

  DealIIView view;
  view.cells = triangulation.n_active_cells();
  for (const auto& cell : triangulation.active_cell_iterators()) {
    view.material_ids.insert(static_cast<int>(cell->material_id()));
    for (const auto f : cell->face_indices())
      if (cell->face(f)->at_boundary()) view.boundary_ids.insert(static_cast<int>(cell->face(f)->boundary_id()));
  }
  dealii::FE_Q<3> fe(1);
  dealii::QGauss<3> quadrature(2);
  dealii::FEValues<3> values(fe, quadrature, dealii::update_JxW_values);
  view.min_jxw = 1e300;
  for (const auto& cell : triangulation.active_cell_iterators()) {
    values.reinit(cell);
    for (unsigned q = 0; q < quadrature.size(); ++q) {
      view.min_jxw = std::min(view.min_jxw, values.JxW(q));
      view.volume += values.JxW(q);
    }
  }
  return view;
}
