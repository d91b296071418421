#include <deal.II/base/timer.h>
#include <deal.II/base/work_stream.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/filtered_iterator.h>
#include <deal.II/lac/full_matrix.h>

#include <cmath>

#include "fbar_element.hpp"
#include "solver_impl.hpp"

namespace dtwire::fem {

using namespace dealii;

namespace {

struct ScratchData {
  ScratchData(const FiniteElement<3>& fe, const Quadrature<3>& q)
      : values(fe, q, update_gradients | update_JxW_values) {}
  ScratchData(const ScratchData& other)
      : values(other.values.get_fe(), other.values.get_quadrature(), other.values.get_update_flags()) {}
  FEValues<3> values;
  ElementGeometry geometry;
  std::vector<double> u;
  std::vector<PlasticState> history;
  ElementResult result;
};

struct CopyData {
  FullMatrix<double> matrix;
  Vector<double> rhs;
  std::vector<double> internal_force;
  std::vector<types::global_dof_index> dofs;
  double elastic_energy = 0.0, dissipation = 0.0;
  bool failed = false;
};

}  // namespace

AssemblyOutcome WireSolver::Impl::assemble(bool with_matrix, const AffineConstraints<double>& constraints) {
  Timer timer;
  refresh_relevant_values();
  if (with_matrix) matrix = 0.0;
  rhs = 0.0;
  internal_force = 0.0;
  elastic_energy = dissipation = 0.0;
  bool failed = false;
  const unsigned n_q = quadrature.size();
  const unsigned n_dofs = fe.n_dofs_per_cell();
  const bool fbar = prm.formulation.fbar;

  auto worker = [&](const typename DoFHandler<3>::active_cell_iterator& cell, ScratchData& scratch, CopyData& copy) {
    scratch.values.reinit(cell);
    copy.dofs.resize(n_dofs);
    cell->get_dof_indices(copy.dofs);
    auto& geo = scratch.geometry;
    geo.component.resize(n_dofs);
    for (unsigned i = 0; i < n_dofs; ++i) geo.component[i] = fe.system_to_component_index(i).first;
    geo.shape_grad.resize(n_q);
    geo.weight.resize(n_q);
    for (unsigned q = 0; q < n_q; ++q) {
      geo.shape_grad[q].resize(n_dofs);
      for (unsigned i = 0; i < n_dofs; ++i) geo.shape_grad[q][i] = scratch.values.shape_grad(i, q);
      geo.weight[q] = scratch.values.JxW(q);
    }
    scratch.u.resize(n_dofs);
    for (unsigned i = 0; i < n_dofs; ++i) scratch.u[i] = relevant_values[relevant.index_within_set(copy.dofs[i])];
    const std::size_t first = cell->active_cell_index() * n_q;
    scratch.history.resize(n_q);
    for (unsigned q = 0; q < n_q; ++q) scratch.history[q] = points[first + q].committed;
    copy.failed = false;
    try {
      evaluate_element(material, geo, scratch.u, scratch.history, fbar, with_matrix, scratch.result);
    } catch (const std::domain_error&) {
      copy.failed = true;
      return;
    }
    const auto& r = scratch.result;
    copy.elastic_energy = copy.dissipation = 0.0;
    for (unsigned q = 0; q < n_q; ++q) {
      auto& record = points[first + q];
      record.trial = r.points[q].state;
      // Cauchy stress: tau / det(Fbar), det(Fbar) = exp(tr eps_e) since det(Fp) = 1.
      const double K = material.elastic().bulk();
      record.cauchy = r.points[q].kirchhoff / std::exp(trace(r.points[q].kirchhoff) / (3.0 * K));
      copy.elastic_energy += r.points[q].elastic_energy * geo.weight[q];
      copy.dissipation += r.points[q].state.plastic_dissipation * geo.weight[q];
    }
    copy.internal_force = r.residual;
    copy.rhs.reinit(n_dofs);
    for (unsigned i = 0; i < n_dofs; ++i) copy.rhs[i] = -r.residual[i];
    if (with_matrix) {
      copy.matrix.reinit(n_dofs, n_dofs);
      for (unsigned i = 0; i < n_dofs; ++i)
        for (unsigned j = 0; j < n_dofs; ++j) copy.matrix(i, j) = r.tangent[i * n_dofs + j];
    }
  };
  auto copier = [&](const CopyData& copy) {
    if (copy.failed) {
      failed = true;
      return;
    }
    if (with_matrix) constraints.distribute_local_to_global(copy.matrix, copy.rhs, copy.dofs, matrix, rhs);
    else constraints.distribute_local_to_global(copy.rhs, copy.dofs, rhs);
    if (hanging.n_constraints() > 0) {  // a hanging node's share goes to the nodes it follows
      const Vector<double> local(copy.internal_force.begin(), copy.internal_force.end());
      hanging.distribute_local_to_global(local, copy.dofs, internal_force);
    } else {
      internal_force.add(copy.dofs, copy.internal_force);
    }
    elastic_energy += copy.elastic_energy;
    dissipation += copy.dissipation;
  };
  using CellFilter = FilteredIterator<typename DoFHandler<3>::active_cell_iterator>;
  WorkStream::run(CellFilter(IteratorFilters::LocallyOwnedCell(), dof_handler.begin_active()),
                  CellFilter(IteratorFilters::LocallyOwnedCell(), dof_handler.end()), worker, copier,
                  ScratchData(fe, quadrature), CopyData());
  const contact::AssemblyTarget target{relevant, relevant_values, with_matrix, constraints, matrix, rhs, internal_force};
  for (const auto& part : contact_parts)
    if (!part->assemble(target)) failed = true;
  if (force_dof != numbers::invalid_dof_index && owned.is_element(force_dof)) rhs(force_dof) += applied_force;
  if (with_matrix) matrix.compress(VectorOperation::add);
  rhs.compress(VectorOperation::add);
  if (holding_factor != 0.0) rhs.add(holding_factor, holding_force);
  internal_force.compress(VectorOperation::add);
  elastic_energy = Utilities::MPI::sum(elastic_energy, comm);
  dissipation = Utilities::MPI::sum(dissipation, comm);
  ++stats.assemblies;

  AssemblyOutcome outcome;
  outcome.ok = Utilities::MPI::max(failed ? 1 : 0, comm) == 0;
  if (outcome.ok) {
    outcome.residual = rhs.l2_norm();
    outcome.force_scale = internal_force.l2_norm();
    // Force control: near zero load the internal forces vanish and a purely relative criterion
    // would chase round-off; the largest force of the path sets the scale.
    if (prm.load.force_control)
      for (const auto& knot : prm.load.force_path)
        outcome.force_scale = std::max(outcome.force_scale, std::abs(knot.second) / force_multiplier());
    outcome.ok = std::isfinite(outcome.residual) && std::isfinite(outcome.force_scale);
  }
  stats.assembly_seconds += timer.wall_time();
  return outcome;
}

void WireSolver::Impl::commit() {
  for (auto& p : points) p.committed = p.trial;
  update_nonlocal_indicator();
  for (const auto& part : contact_parts) part->commit();
}

}  // namespace dtwire::fem
