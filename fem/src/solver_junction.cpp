// The junction's state for the junction-refinement convergence study (issue 50; docs/fem_dt.md,
// "Junction refinement"): over the cells whose centre lies within the refinement half-width of
// a junction plane, the quadrature point of the largest equivalent plastic strain, with its
// stress state (triaxiality, Lode parameter), place and failure indicator.
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/mapping_q1.h>

#include <cmath>
#include <map>

#include "junction_refinement.hpp"
#include "solver_impl.hpp"

namespace dtwire::fem {

using namespace dealii;

void WireSolver::Impl::log_junction_state() const {
  if (prm.geometry.junction_planes.empty()) return;
  const auto near = [&](const Triangulation<3>::active_cell_iterator& cell) {
    return !is_coating(cell->material_id()) && near_junction(prm.geometry, cell->center());
  };
  const LargestPoint strain =
      largest_point(near, [](const PlasticState& state) { return state.equivalent_plastic_strain; });
  if (strain.value < 0.0) return;  // no steel cell near a junction plane
  const LargestPoint damage = largest_point(
      near, [this](const PlasticState& state) { return prm.material.failure.initiation_indicator(state); });
  log << "  junction: largest equivalent plastic strain " << strain.value << " at z = " << strain.z * 1e3
      << " mm, r = " << strain.r * 1e3 << " mm (triaxiality " << strain.triaxiality << ", Lode parameter "
      << strain.lode_parameter << ", failure indicator " << strain.damage << "); largest failure indicator there "
      << std::max(damage.value, 0.0) << "\n";
}

WireSolver::HangingNodeCheck WireSolver::hanging_node_check() {
  Impl& s = *impl_;
  AffineConstraints<double> fresh;
  fresh.reinit(s.relevant);
  DoFTools::make_hanging_node_constraints(s.dof_handler, fresh);
  fresh.close();
  std::map<types::global_dof_index, Point<3>> support;
  DoFTools::map_dofs_to_support_points(MappingQ1<3>(), s.dof_handler, support);
  s.refresh_relevant_values();
  const auto value = [&](types::global_dof_index i) { return s.relevant_values[s.relevant.index_within_set(i)]; };
  HangingNodeCheck check;
  double reference = 0.0, displaced = 0.0, nodes = 0.0;
  for (const auto& line : fresh.get_lines()) {
    if (!s.owned.is_element(line.index)) continue;
    nodes += 1.0 / 3.0;  // one line per component
    Point<3> X;
    double u = 0.0;
    for (const auto& [j, w] : line.entries) {
      X += w * support.at(j);
      u += w * value(j);
    }
    reference = std::max(reference, X.distance(support.at(line.index)));
    displaced = std::max(displaced, std::abs(u - value(line.index)));
  }
  check.nodes = static_cast<std::size_t>(std::lround(Utilities::MPI::sum(nodes, s.comm)));
  check.reference_gap = Utilities::MPI::max(reference, s.comm);
  check.displaced_gap = Utilities::MPI::max(displaced, s.comm);
  return check;
}

}  // namespace dtwire::fem
