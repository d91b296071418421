// The junction's state for the junction-refinement convergence study (issue 50; docs/fem_dt.md,
// "Junction refinement"): over the cells whose centre lies within the refinement half-width of
// a junction plane, the quadrature point of the largest equivalent plastic strain, with its
// stress state (triaxiality, Lode parameter), place and failure indicator.
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/mapping_q1.h>
#include <mpi.h>

#include <cmath>
#include <map>

#include "junction_refinement.hpp"
#include "solver_impl.hpp"

namespace dtwire::fem {

using namespace dealii;

void WireSolver::Impl::log_junction_state() const {
  if (prm.geometry.junction_planes.empty()) return;
  const unsigned n_q = quadrature.size();
  struct {
    double value;
    int rank;
  } local{-1.0, static_cast<int>(Utilities::MPI::this_mpi_process(comm))}, global{};
  double where[5] = {0, 0, 0, 0, 0};  // triaxiality, Lode, z, r, failure indicator
  double largest_damage = 0.0;
  for (const auto& cell : triangulation.active_cell_iterators()) {
    if (!cell->is_locally_owned() || is_coating(cell->material_id()) || !near_junction(prm.geometry, cell->center()))
      continue;
    for (unsigned q = 0; q < n_q; ++q) {
      const auto& p = points[cell->active_cell_index() * n_q + q];
      largest_damage = std::max(largest_damage, p.committed.damage);
      if (p.committed.equivalent_plastic_strain <= local.value) continue;
      local.value = p.committed.equivalent_plastic_strain;
      const StressInvariants inv = stress_invariants(p.cauchy);
      const Point<3> x = cell->center();
      where[0] = inv.triaxiality;
      where[1] = inv.lode_parameter;
      where[2] = x[2];
      where[3] = std::hypot(x[0], x[1]);
      where[4] = p.committed.damage;
    }
  }
  MPI_Allreduce(&local, &global, 1, MPI_DOUBLE_INT, MPI_MAXLOC, comm);
  MPI_Bcast(where, 5, MPI_DOUBLE, global.rank, comm);
  largest_damage = Utilities::MPI::max(largest_damage, comm);
  if (global.value < 0.0) return;  // no steel cell near a junction plane
  log << "  junction: largest equivalent plastic strain " << global.value << " at z = " << where[2] * 1e3
      << " mm, r = " << where[3] * 1e3 << " mm (triaxiality " << where[0] << ", Lode parameter " << where[1]
      << ", failure indicator " << where[4] << "); largest failure indicator there " << largest_damage << "\n";
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
