#include "junction_refinement.hpp"

#include <deal.II/base/mpi.h>
#include <deal.II/dofs/dof_tools.h>

#include <cmath>
#include <stdexcept>
#include <vector>

namespace dtwire::fem {

using namespace dealii;

bool near_junction(const GeometryParameters& g, const Point<3>& x) {
  for (const double z : g.junction_planes)
    if (std::abs(x[2] - z) < g.junction_half_width) return true;
  return false;
}

void refine_junctions(const GeometryParameters& g, Triangulation<3>& tria) {
  for (unsigned cycle = 0; cycle < g.junction_cycles; ++cycle) {
    for (const auto& cell : tria.active_cell_iterators())
      if (cell->is_locally_owned() && near_junction(g, cell->center())) cell->set_refine_flag();
    tria.execute_coarsening_and_refinement();
  }
}

void make_shared_hanging_node_constraints(const DoFHandler<3>& dof_handler, const IndexSet& relevant,
                                          const IndexSet& shared, MPI_Comm comm, AffineConstraints<double>& hanging) {
  hanging.clear();
  hanging.reinit(relevant);
  DoFTools::make_hanging_node_constraints(dof_handler, hanging);
  // Packed lines of the shared dofs this rank knows: index, entry count, (column, weight) pairs.
  std::vector<double> packed;
  for (const auto& line : hanging.get_lines()) {
    if (!shared.is_element(line.index)) continue;
    packed.push_back(static_cast<double>(line.index));
    packed.push_back(static_cast<double>(line.entries.size()));
    for (const auto& [column, weight] : line.entries) {
      packed.push_back(static_cast<double>(column));
      packed.push_back(weight);
    }
  }
  for (const auto& block : Utilities::MPI::all_gather(comm, packed))
    for (std::size_t k = 0; k < block.size();) {
      const auto i = static_cast<types::global_dof_index>(block[k]);
      const auto n = static_cast<std::size_t>(block[k + 1]);
      const bool add = relevant.is_element(i) && !hanging.is_constrained(i);
      if (add) hanging.add_line(i);
      for (std::size_t e = 0; e < n; ++e)
        if (add) hanging.add_entry(i, static_cast<types::global_dof_index>(block[k + 2 + 2 * e]), block[k + 3 + 2 * e]);
      k += 2 + 2 * n;
    }
  hanging.close();
}

double cell_order_key(const CellId& id) {
  const auto children = id.get_child_indices();
  if (children.size() > kMaxKeyLevels)
    throw std::invalid_argument("cell_order_key: a cell " + std::to_string(children.size()) + " levels below its coarse cell");
  double key = static_cast<double>(id.get_coarse_cell_id());
  for (unsigned level = 0; level < kMaxKeyLevels; ++level)
    key = 8.0 * key + (level < children.size() ? static_cast<double>(children[level]) : 0.0);
  return key;  // exact in a double below 2^53 / 8^6, about 3.4e10 coarse cells
}

}  // namespace dtwire::fem
