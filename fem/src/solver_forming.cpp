#include <deal.II/base/timer.h>
#include <deal.II/fe/fe_values.h>

#include <algorithm>
#include <cmath>

#include "dtwire/core/error.hpp"
#include "dtwire/core/region_ids.hpp"
#include "forming_history.hpp"
#include "solver_impl.hpp"

namespace dtwire::fem {

using namespace dealii;

void WireSolver::Impl::visit_steel_points(
    const WireAxes& axes, const std::function<void(unsigned, const AxisLocation&, QuadraturePointRecord&)>& visit) {
  FEValues<3> values(fe, quadrature, update_quadrature_points);
  const unsigned n_q = quadrature.size();
  for (const auto& cell : dof_handler.active_cell_iterators()) {
    if (!cell->is_locally_owned() || is_coating(cell->material_id())) continue;
    values.reinit(cell);
    const unsigned wire = prm.geometry.double_twist ? static_cast<unsigned>(regions::wire_of_id(cell->material_id())) : 0;
    for (unsigned q = 0; q < n_q; ++q)
      visit(wire, axes.locate(wire, values.quadrature_point(q)), points[cell->active_cell_index() * n_q + q]);
  }
}

// Every steel quadrature point gets the state of its fibre bent from straight wire into the
// wire's axis (forming_history.hpp); with a twisted pair state, the twist's points take the
// state the twisting run left instead (twisted_pair_state.hpp).
void WireSolver::Impl::apply_forming_history() {
  Timer timer;
  const WireAxes axes(prm.forming.axes);
  visit_steel_points(axes, [&](unsigned, const AxisLocation& at, QuadraturePointRecord& point) {
    const double strain = prm.forming.scale * at.bending_strain;
    if (std::abs(strain) > 1e-12) point.committed = formed_state(material, at.tangent, strain, prm.forming.increments);
    point.trial = point.committed;
  });
  log << "as made: forming history of " << prm.forming.axis_file.filename().string() << " (scale "
      << prm.forming.scale << ") in " << timer.wall_time() << " s\n";
  if (!prm.forming.twisted_pair_state.empty()) apply_twisted_pair_state(prm.forming.twisted_pair_state);
}

void WireSolver::Impl::set_top_released(bool released) {
  top_released = released;
  make_constraints(homogeneous, 0.0, 0.0);
  make_constraints(predictor, 0.0, 0.0);
  make_matrix();
}

// The current positions of the top end's support points (one per vertex), this rank's.
std::vector<Point<3>> WireSolver::Impl::top_end_positions() const {
  std::vector<Point<3>> x;
  for (const auto& d : top_end_dofs)
    if (d.component == 0) {
      Point<3> p = d.reference;
      for (unsigned c = 0; c < 3; ++c) p[c] += ghosted[d.vertex_dofs[c]];
      x.push_back(p);
    }
  return x;
}

namespace {
// The rotation about the unit `axis` that best carries the point set `from` onto `to` (least
// squares, each about its own centroid): atan2(sum a.(r0 x r1), sum r0.r1) with r the offsets
// from the centroid normal to the axis. Summed over the ranks.
double rotation_about(const Tensor<1, 3>& axis, const std::vector<Point<3>>& from, const std::vector<Point<3>>& to,
                      MPI_Comm comm) {
  Tensor<1, 3> sum0, sum1;
  for (std::size_t i = 0; i < from.size(); ++i) sum0 += from[i], sum1 += to[i];
  const double n = Utilities::MPI::sum(static_cast<double>(from.size()), comm);
  if (n == 0.0) return 0.0;
  sum0 = Utilities::MPI::sum(sum0, comm) / n;
  sum1 = Utilities::MPI::sum(sum1, comm) / n;
  double sine = 0.0, cosine = 0.0;
  for (std::size_t i = 0; i < from.size(); ++i) {
    Tensor<1, 3> r0 = from[i] - sum0, r1 = to[i] - sum1;
    r0 -= (r0 * axis) * axis;
    r1 -= (r1 * axis) * axis;
    sine += axis * cross_product_3d(r0, r1);
    cosine += r0 * r1;
  }
  return std::atan2(Utilities::MPI::sum(sine, comm), Utilities::MPI::sum(cosine, comm));
}
}  // namespace

// Springback of the as-made wires: released, then the top end is clamped where it came to rest
// and the load path starts from there.
void WireSolver::Impl::release_forming() {
  release_top_end();
  set_top_released(false);
  StepRecord reset;  // the top end's work counts from where it came to rest
  record_end(reset);
  end_work = tool_work = 0.0;
}

// The top end lets go: the forces that held it (the internal forces of the held mesh: the
// forming tools' after a forming, the twisting head's after a twisting run) fall to zero in load
// steps with cut-back, the bottom grips held and the top end free.
void WireSolver::Impl::release_top_end() {
  Timer timer;
  auto& f = stats.forming;
  set_top_released(true);
  holding_factor = 0.0;
  assemble(false, homogeneous);
  holding_force = rhs;
  holding_force *= -1.0;
  f.initial_elastic_energy = elastic_energy;
  const double dissipation_before = dissipation;
  const auto friction = [&]() {
    StepRecord r;
    record_contact_parts(r, false);
    return r.wire_contact.friction_dissipation;
  };
  const double friction_before = friction();
  const PETScWrappers::MPI::Vector formed = solution;
  const std::vector<Point<3>> top_before = top_end_positions();
  PETScWrappers::MPI::Vector start(owned, comm), change(owned, comm);
  const auto& stepping = prm.stepping;
  double released = 0.0, step = prm.forming.initial_release_step;
  while (released < 1.0 - 1e-12) {
    const double next = std::min(1.0, released + step);
    holding_factor = 1.0 - next;
    start = solution;
    unsigned iterations = 0;
    std::string reason;
    log << "springback: released " << released << " -> " << next << "\n";
    if (solve_contact_step(0.0, 0.0, nullptr, start, iterations, reason)) {
      commit();
      change = solution;
      change -= start;
      // The holding force falls linearly over the step: trapezoidal rule.
      f.holding_work += (1.0 - 0.5 * (released + next)) * (holding_force * change);
      released = next;
      ++f.steps;
      f.newton_iterations += iterations;
      if (iterations <= stepping.easy_iterations) step = std::min(1.0, step * stepping.growth_factor);
    } else {
      solution = start;
      ++f.cutbacks;
      step *= stepping.cutback_factor;
      log << "  springback step failed (" << reason << "): cut back to " << step << "\n";
      if (step < stepping.minimum_step)
        throw ComputationError("springback of the as-made wires did not converge at released fraction " +
                               std::to_string(released) + " (" + reason + ")");
    }
  }
  holding_factor = 0.0;
  assemble(false, homogeneous);  // the released state's energies and stresses
  f.elastic_energy = elastic_energy;
  f.plastic_work = dissipation - dissipation_before;
  f.friction_work = friction() - friction_before;
  f.energy_balance = std::abs(f.initial_elastic_energy + f.holding_work - f.elastic_energy - f.plastic_work -
                              f.friction_work) /
                     std::max(f.initial_elastic_energy, 1e-300);
  change = solution;
  change -= formed;
  f.largest_displacement = change.linfty_norm();
  if (wire_contact) {
    const auto c = wire_contact->clearance();
    f.clearance_points = c.points;
    f.points_in_contact = c.in_contact;
    f.clearance_mean = c.mean;
    f.clearance_largest = c.largest;
  }
  Tensor<1, 3> axis;
  for (unsigned c = 0; c < 3; ++c) axis[c] = prm.load.rotation_axis[c];
  f.top_rotation = rotation_about(axis / axis.norm(), top_before, top_end_positions(), comm);
  record_forming_profile();
  f.seconds = timer.wall_time();
  f.done = true;
  log << "springback: " << f.steps << " steps, " << f.newton_iterations << " Newton iterations, " << f.cutbacks
      << " cut-backs, " << f.seconds << " s; elastic energy " << f.initial_elastic_energy << " -> " << f.elastic_energy
      << " J, plastic work " << f.plastic_work << " J, friction " << f.friction_work << " J, holding forces "
      << f.holding_work << " J: balance " << 100.0 * f.energy_balance << " %; largest displacement "
      << f.largest_displacement * 1e3 << " mm, top end turned " << f.top_rotation * 180 / M_PI
      << " deg; clearance mean " << f.clearance_mean * 1e3 << " mm, largest "
      << f.clearance_largest * 1e3 << " mm (" << f.points_in_contact << " of " << f.clearance_points
      << " points in contact)\n";
}

// Per wire and axis station: von Mises stress, equivalent plastic strain and damage over the
// section's quadrature points (nearest station), gathered over the ranks.
void WireSolver::Impl::record_forming_profile() {
  const WireAxes axes(prm.forming.axes);
  std::vector<unsigned> first(axes.wires() + 1, 0);
  for (unsigned w = 0; w < axes.wires(); ++w) first[w + 1] = first[w] + axes.stations(w);
  const unsigned n = first.back();
  std::vector<double> count(n), vm_sum(n), vm_max(n), ep_sum(n), ep_max(n), d_max(n);
  visit_steel_points(axes, [&](unsigned wire, const AxisLocation& at, QuadraturePointRecord& point) {
    const unsigned k = first[wire] + at.station;
    const double vm = stress_invariants(point.cauchy).von_mises, ep = point.committed.equivalent_plastic_strain;
    count[k] += 1.0;
    vm_sum[k] += vm;
    ep_sum[k] += ep;
    vm_max[k] = std::max(vm_max[k], vm);
    ep_max[k] = std::max(ep_max[k], ep);
    d_max[k] = std::max(d_max[k], point.committed.damage);
  });
  Utilities::MPI::sum(count, comm, count);
  Utilities::MPI::sum(vm_sum, comm, vm_sum);
  Utilities::MPI::sum(ep_sum, comm, ep_sum);
  Utilities::MPI::max(vm_max, comm, vm_max);
  Utilities::MPI::max(ep_max, comm, ep_max);
  Utilities::MPI::max(d_max, comm, d_max);
  auto& profile = stats.forming.profile;
  profile.clear();
  for (unsigned w = 0; w < axes.wires(); ++w)
    for (unsigned s = 0; s < axes.stations(w); ++s) {
      const unsigned k = first[w] + s;
      if (count[k] == 0.0) continue;
      profile.push_back({w, axes.arc_length(w, s), axes.height(w, s), vm_sum[k] / count[k], vm_max[k],
                         ep_sum[k] / count[k], ep_max[k], d_max[k]});
    }
}

}  // namespace dtwire::fem
