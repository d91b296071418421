#include <deal.II/fe/fe_values.h>
#include <deal.II/numerics/data_out.h>

#include <cmath>
#include <fstream>
#include <limits>

#include "solver_impl.hpp"
#include "wire_mesh.hpp"

namespace dtwire::fem {

using namespace dealii;

void WireSolver::Impl::record_probes(StepRecord& record) {
  std::vector<double> values(3 * prm.output.probe_points.size(), 0.0);
  for (const auto& probe : probes) {
    FEValues<3> fe_values(fe, Quadrature<3>(probe.unit_point), update_values);
    fe_values.reinit(probe.cell);
    std::vector<Vector<double>> u(1, Vector<double>(3));
    fe_values.get_function_values(ghosted, u);
    for (unsigned c = 0; c < 3; ++c) values[3 * probe.index + c] = u[0][c];
  }
  Utilities::MPI::sum(ArrayView<const double>(values), comm, ArrayView<double>(values));
  record.probe_displacements.resize(prm.output.probe_points.size());
  for (std::size_t k = 0; k < record.probe_displacements.size(); ++k)
    for (unsigned c = 0; c < 3; ++c) record.probe_displacements[k][c] = values[3 * k + c];
}

// Force and moment of the specimen on the top end (about the moved centre), the centre's
// translation, and the external work by the trapezoidal rule over the step: sum over the end's
// dofs of (f_old + f_new) / 2 (u_new - u_old), plus the work of the rigid tools.
void WireSolver::Impl::record_end(StepRecord& record) {
  Tensor<1, 3> force, moment;
  const Tensor<1, 3> translation = path_displacement(prm.load, record.time) * load_direction;
  const Point<3> centre = rotation_centre + translation;
  double work = 0.0;
  if (bonded_grip) {  // the bond tractions, not reactions: the grip surfaces are free dofs
    bonded_grip->top_resultants(centre, force, moment);
    work = bonded_grip->external_work();  // accumulated over the steps by the bond
  } else {
    for (std::size_t k = 0; k < top_end_dofs.size(); ++k) {
      const auto& d = top_end_dofs[k];
      const double f = internal_force[d.index], u = solution[d.index];
      Tensor<1, 3> x = d.reference;
      for (unsigned c = 0; c < 3; ++c) x[c] += ghosted[d.vertex_dofs[c]];
      Tensor<1, 3> f_vector;
      f_vector[d.component] = f;
      force += f_vector;
      moment += cross_product_3d(x - centre, f_vector);
      work += 0.5 * (f + previous_end_force[k]) * (u - previous_end_displacement[k]);
      previous_end_force[k] = f;
      previous_end_displacement[k] = u;
    }
  }
  const double scale = force_multiplier(), energy_scale = force_multiplier() * length_multiplier();
  for (unsigned c = 0; c < 3; ++c) {
    record.end_force[c] = Utilities::MPI::sum(force[c], comm) * scale;
    record.end_moment[c] = Utilities::MPI::sum(moment[c], comm) * scale;
    record.end_translation[c] = translation[c] * length_multiplier();
    record.end_centre[c] = centre[c];
  }
  end_work = (bonded_grip ? 0.0 : end_work) + Utilities::MPI::sum(work, comm) * energy_scale;
  if (rigid_contact) {  // the tools push the wire: their work is -(force on the tool) . displacement
    const auto& forces = record.contact.tool_forces;
    const auto& moves = record.contact.tool_displacements;
    previous_tool_force.resize(forces.size(), {{0.0, 0.0, 0.0}});
    previous_tool_displacement.resize(forces.size(), {{0.0, 0.0, 0.0}});
    for (std::size_t k = 0; k < forces.size(); ++k) {
      for (unsigned c = 0; c < 3; ++c)
        tool_work -= 0.5 * (forces[k][c] + previous_tool_force[k][c]) * (moves[k][c] - previous_tool_displacement[k][c]);
      previous_tool_force[k] = forces[k];
      previous_tool_displacement[k] = moves[k];
    }
  }
  record.end_rotation = path_rotation(prm.load, record.time);
  record.external_work = end_work + tool_work;
}

double WireSolver::Impl::reaction() const {
  if (bonded_grip) {  // the pull of the top grips through the bond
    Tensor<1, 3> force, moment;
    bonded_grip->top_resultants(Point<3>(), force, moment);
    return Utilities::MPI::sum(force * load_direction, comm) * force_multiplier();
  }
  double local = 0.0;
  for (const auto& d : top_end_dofs) local += internal_force[d.index] * load_direction[d.component];
  return Utilities::MPI::sum(local, comm) * force_multiplier();
}

WireSolver::Impl::LargestPoint WireSolver::Impl::largest_point(
    const std::function<bool(const Triangulation<3>::active_cell_iterator&)>& select,
    const std::function<double(const PlasticState&)>& key) const {
  const unsigned n_q = quadrature.size();
  struct {
    double value;
    int rank;
  } local{-1.0, static_cast<int>(Utilities::MPI::this_mpi_process(comm))}, global{};
  double where[5] = {0, 0, 0, 0, 0};  // triaxiality, Lode, z, r, failure indicator
  for (const auto& cell : triangulation.active_cell_iterators()) {
    if (!cell->is_locally_owned() || !select(cell)) continue;
    for (unsigned q = 0; q < n_q; ++q) {
      const auto& p = points[cell->active_cell_index() * n_q + q];
      const double value = key(p.committed);
      if (value <= local.value) continue;
      local.value = value;
      const StressInvariants inv = stress_invariants(p.cauchy);
      const Point<3> x = cell->center();
      where[0] = inv.triaxiality;
      where[1] = inv.lode_parameter;
      where[2] = x[2];
      where[3] = std::hypot(x[0], x[1]);
      where[4] = prm.material.failure.initiation_indicator(p.committed);
    }
  }
  MPI_Allreduce(&local, &global, 1, MPI_DOUBLE_INT, MPI_MAXLOC, comm);
  MPI_Bcast(where, 5, MPI_DOUBLE, global.rank, comm);
  return {global.value, where[0], where[1], where[2], where[3], where[4]};
}

void WireSolver::Impl::record_damage(StepRecord& record) const {
  const LargestPoint largest = largest_point([](const auto&) { return true; },
                                             [this](const PlasticState& state) { return prm.material.failure.initiation_indicator(state); });
  record.damage = std::max(largest.value, 0.0);
  record.damage_triaxiality = largest.triaxiality;
  record.damage_lode = largest.lode_parameter;
  record.damage_z = largest.z;
  record.damage_r = largest.r;
}

double WireSolver::Impl::neck_radius() const {
  // The surface vertex layer nearest the imperfection centre (mid-length without imperfection);
  // every rank holds all coarse cells, so the layer is the same everywhere.
  const auto& g = prm.geometry;
  if (g.double_twist || !g.straight_axis) return 0.0;  // no single neck section
  const double z_ref = g.imperfection > 0.0 ? g.imperfection_centre : 0.5 * g.length;
  double z_layer = 0.0;
  for (const auto& cell : triangulation.active_cell_iterators())  // all coarse cells, any owner
    for (const auto f : cell->face_indices())
      if (cell->face(f)->at_boundary() && cell->face(f)->boundary_id() == kHull)
        for (const auto v : cell->face(f)->vertex_indices())
          if (std::abs(cell->face(f)->vertex(v)[2] - z_ref) < std::abs(z_layer - z_ref))
            z_layer = cell->face(f)->vertex(v)[2];
  const double h = 1e-6 * g.length;
  double smallest = std::numeric_limits<double>::max();
  for (const auto& cell : dof_handler.active_cell_iterators()) {
    if (!cell->is_locally_owned()) continue;
    for (const auto f : cell->face_indices()) {
      if (!cell->face(f)->at_boundary() || cell->face(f)->boundary_id() != kHull) continue;
      for (const auto v : cell->face(f)->vertex_indices()) {
        const Point<3> x = cell->face(f)->vertex(v);
        if (std::abs(x[2] - z_layer) > h) continue;
        const double X = x[0] + ghosted[cell->face(f)->vertex_dof_index(v, 0)];
        const double Y = x[1] + ghosted[cell->face(f)->vertex_dof_index(v, 1)];
        smallest = std::min(smallest, std::hypot(X, Y));
      }
    }
  }
  return Utilities::MPI::min(smallest, comm);
}

void WireSolver::Impl::write_fields(unsigned step, double time) {
  if (field_directory.empty()) return;
  ghosted = solution;
  DataOut<3> out;
  out.attach_dof_handler(dof_handler);
  const std::vector<std::string> names(3, "displacement_m");
  const std::vector<DataComponentInterpretation::DataComponentInterpretation> kinds(
      3, DataComponentInterpretation::component_is_part_of_vector);
  out.add_data_vector(ghosted, names, DataOut<3>::type_dof_data, kinds);
  const std::size_t n_cells = triangulation.n_active_cells();
  Vector<float> von_mises(n_cells), plastic_strain(n_cells), triaxiality(n_cells), lode(n_cells), rank(n_cells),
      damage(n_cells);
  const unsigned n_q = quadrature.size();
  for (const auto& cell : triangulation.active_cell_iterators()) {
    if (!cell->is_locally_owned()) continue;
    const std::size_t c = cell->active_cell_index();
    SymTensor2 mean_stress;
    double alpha = 0.0;
    for (unsigned q = 0; q < n_q; ++q) {
      mean_stress += points[c * n_q + q].cauchy / n_q;
      alpha += points[c * n_q + q].committed.equivalent_plastic_strain / n_q;
      damage[c] = std::max(damage[c], static_cast<float>(points[c * n_q + q].committed.damage));
    }
    const StressInvariants inv = stress_invariants(mean_stress);
    von_mises[c] = inv.von_mises;
    plastic_strain[c] = alpha;
    triaxiality[c] = inv.triaxiality;
    lode[c] = inv.lode_parameter;
    rank[c] = triangulation.locally_owned_subdomain();
  }
  out.add_data_vector(von_mises, "von_mises_Pa");
  out.add_data_vector(plastic_strain, "equivalent_plastic_strain");
  out.add_data_vector(triaxiality, "triaxiality");
  out.add_data_vector(lode, "lode_parameter");
  if (prm.material.failure.enabled()) out.add_data_vector(damage, "failure_indicator");
  out.add_data_vector(rank, "mpi_rank");
  std::vector<std::pair<std::string, Vector<float>>> contact_fields;  // kept alive until the patches are built
  for (const auto& part : contact_parts)
    for (auto& field : part->cell_fields(static_cast<unsigned>(n_cells))) contact_fields.push_back(std::move(field));
  for (const auto& [name, values] : contact_fields) out.add_data_vector(values, name);
  out.build_patches();
  std::filesystem::create_directories(field_directory);
  const std::string pvtu = out.write_vtu_with_pvtu_record(field_directory.string() + "/", "fields", step, comm, 5);
  pvd_records.emplace_back(time, pvtu);
  written_fields.push_back(pvtu);
  if (Utilities::MPI::this_mpi_process(comm) == 0) {
    std::ofstream pvd(field_directory / "fields.pvd");
    DataOutBase::write_pvd_record(pvd, pvd_records);
  }
}

// Each contact part's columns of the step record (whole specimen), with its log line for a
// converged step.
void WireSolver::Impl::record_contact_parts(StepRecord& record, bool log_step) {
  const contact::RecordScales scales{internal_force, force_multiplier(), force_multiplier() * length_multiplier()};
  for (const auto& part : contact_parts) part->record(scales, record, log_step && log.is_active() ? &log.get_stream() : nullptr);
}

}  // namespace dtwire::fem
