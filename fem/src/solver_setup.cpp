#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q1.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/sparsity_tools.h>

#include <map>

#include "dtwire/core/error.hpp"
#include "junction_refinement.hpp"
#include "solver_impl.hpp"
#include "wire_mesh.hpp"

namespace dtwire::fem {

using namespace dealii;

void WireSolver::Impl::setup() {
  make_wire_mesh(prm.geometry, triangulation);
  refine_junctions(prm.geometry, triangulation);
  dof_handler.distribute_dofs(fe);
  owned = dof_handler.locally_owned_dofs();
  DoFTools::extract_locally_relevant_dofs(dof_handler, relevant);
  stats.dofs = dof_handler.n_dofs();
  stats.cells = triangulation.n_global_active_cells();
  stats.ranks = Utilities::MPI::n_mpi_processes(comm);

  for (const auto id : prm.load.bottom_ids) bottom_ids.insert(static_cast<types::boundary_id>(id));
  for (const auto id : prm.load.top_ids) top_ids.insert(static_cast<types::boundary_id>(id));
  load_direction[loaded_component().component] = 1.0;
  if (!prm.load.pull_direction.empty())
    for (unsigned c = 0; c < 3; ++c) load_direction[c] = prm.load.pull_direction[c];
  top_loaded_dofs = DoFTools::extract_boundary_dofs(dof_handler, fe.component_mask(loaded_component()), top_ids);
  {  // the top end's owned dofs (all support points of its faces) with their reference positions
    std::map<types::global_dof_index, Point<3>> support;
    DoFTools::map_dofs_to_support_points(MappingQ1<3>(), dof_handler, support);
    std::map<std::array<double, 3>, std::array<types::global_dof_index, 3>> point_dofs;  // same support point
    std::map<types::global_dof_index, EndDof> found;
    std::set<types::global_dof_index> counted_vertices;
    Tensor<1, 3> sum;
    double vertices = 0.0;
    std::vector<types::global_dof_index> face_dofs(fe.n_dofs_per_face());
    for (const auto& cell : dof_handler.active_cell_iterators()) {
      if (!cell->is_locally_owned()) continue;
      for (const auto f : cell->face_indices()) {
        if (!cell->face(f)->at_boundary() || top_ids.count(cell->face(f)->boundary_id()) == 0) continue;
        cell->face(f)->get_dof_indices(face_dofs);
        for (unsigned k = 0; k < face_dofs.size(); ++k) {
          const auto i = face_dofs[k];
          const Point<3>& X = support.at(i);
          point_dofs[{{X[0], X[1], X[2]}}][fe.face_system_to_component_index(k).first] = i;
          if (!owned.is_element(i) || found.count(i)) continue;
          found[i] = EndDof{i, fe.face_system_to_component_index(k).first, X, {}};
        }
        for (const auto v : cell->face(f)->vertex_indices()) {  // each owned vertex once
          const auto i = cell->face(f)->vertex_dof_index(v, 0);
          if (!owned.is_element(i) || !counted_vertices.insert(i).second) continue;
          sum += cell->face(f)->vertex(v);
          vertices += 1.0;
        }
      }
    }
    for (auto& entry : found) {
      const Point<3>& X = entry.second.reference;
      entry.second.vertex_dofs = point_dofs.at({{X[0], X[1], X[2]}});
    }
    for (const auto& entry : found) top_end_dofs.push_back(entry.second);
    for (unsigned c = 0; c < 3; ++c) rotation_centre[c] = Utilities::MPI::sum(sum[c], comm);
    vertices = Utilities::MPI::sum(vertices, comm);
    if (!(vertices > 0.0)) throw InputError("Boundary conditions", "no boundary face carries the 'Top boundary ids'");
    rotation_centre /= vertices;
    if (prm.load.rotation_centre_given)
      rotation_centre = Point<3>(prm.load.rotation_centre[0], prm.load.rotation_centre[1], prm.load.rotation_centre[2]);
    previous_end_force.assign(top_end_dofs.size(), 0.0);
    previous_end_displacement.assign(top_end_dofs.size(), 0.0);
  }
  if (prm.load.force_control) {
    force_dof = Utilities::MPI::min(top_loaded_dofs.n_elements() > 0 ? *top_loaded_dofs.begin()
                                                                      : numbers::invalid_dof_index,
                                    comm);
    relevant.add_index(force_dof);  // every rank reads its displacement and constrains to it
  }
  if (!prm.output.link_sections.empty() && !prm.geometry.double_twist)
    throw InputError("Output", "'Link sections (mm)' needs a double-twist mesh file (`dtwire mesh dt`)");
  if (prm.wire_contact.enabled) {
    if (!prm.geometry.double_twist)
      throw InputError("Wire contact", "Enabled = true needs a double-twist mesh file (`dtwire mesh dt`)");
    auto wires = std::make_unique<contact::WireWireContact>(prm.wire_contact, prm.material.young,
                                                            prm.geometry.diameter, dof_handler, comm);
    wire_contact = wires.get();
    contact_parts.push_back(std::move(wires));
    relevant.add_indices(wire_contact->needed_dofs());
  }
  if (prm.geometry.junction_cycles > 0) {
    if (prm.wire_contact.enabled && prm.wire_contact.smoothed_normals)
      throw InputError("Wire contact", "'Smoothed normals = true' needs a conforming mesh: set 'Junction refinement "
                                       "cycles = 0' (averaged normals at hanging nodes are not implemented)");
    const IndexSet shared = wire_contact ? wire_contact->needed_dofs() : IndexSet(dof_handler.n_dofs());
    make_shared_hanging_node_constraints(dof_handler, relevant, shared, comm, hanging);
    for (const auto& line : hanging.get_lines())
      for (const auto& entry : line.entries)
        if (!relevant.is_element(entry.first))
          throw std::logic_error("junction refinement: a hanging node's master dof is not locally relevant");
    log << "junction refinement: " << prm.geometry.junction_cycles << " cycle(s) within "
        << prm.geometry.junction_half_width * 1e3 << " mm of the junction planes, "
        << Utilities::MPI::sum(hanging.n_constraints(), comm) << " hanging-node constraint lines (summed over ranks)\n";
  }
  make_constraints(homogeneous, 0.0, 0.0);
  make_constraints(predictor, 0.0, 1.0);  // same sparsity; values reset per step
  solution.reinit(owned, comm);
  rhs.reinit(owned, comm);
  internal_force.reinit(owned, comm);
  increment.reinit(owned, comm);
  ghosted.reinit(owned, relevant, comm);
  if (wire_contact) {
    wire_contact->initialise(relevant, homogeneous, owned);
    refresh_relevant_values();
    contact::StepStart start;
    start.relevant_values = &relevant_values;
    wire_contact->begin_step(start);
  }
  make_matrix();

  points.assign(triangulation.n_active_cells() * quadrature.size(), QuadraturePointRecord{});
  locate_probes();
  if (prm.newton.krylov) make_rigid_body_modes();
  if (prm.contact.enabled()) {  // contact (issue 5); first in assembly order
    auto tools = std::make_unique<contact::RigidToolContact>(prm.contact, prm.material.young, dof_handler, bottom_ids,
                                                             top_ids, comm);
    rigid_contact = tools.get();
    contact_parts.insert(contact_parts.begin(), std::move(tools));
  }
  if (prm.load.grip.bonded) {  // grip interface: the bond holds the grip surfaces
    auto grips = std::make_unique<contact::BondedGrip>(prm.load.grip, prm.material.young, dof_handler, bottom_ids,
                                                       top_ids, comm);
    bonded_grip = grips.get();
    contact_parts.push_back(std::move(grips));
    log << "bonded grips: top " << bonded_grip->top_area() * 1e6 << " mm^2 (strength " << prm.load.grip.strength * 1e-6
        << " MPa, capacity " << prm.load.grip.strength * bonded_grip->top_area() * force_multiplier()
        << " N for the whole specimen), bottom " << bonded_grip->bottom_area() * 1e6 << " mm^2 (elastic), penalty "
        << bonded_grip->stiffness() * 1e-9 << " N/mm^3\n";
  }
  log << "mesh: " << stats.cells << " cells, " << stats.dofs << " dofs, " << stats.ranks << " MPI rank(s), "
      << MultithreadInfo::n_threads() << " thread(s) per rank, element "
      << (prm.formulation.fbar ? "F-bar" : "plain displacement") << " Q" << prm.formulation.degree << "\n";
}

void WireSolver::Impl::locate_probes() {
  const MappingQ1<3> mapping;
  const auto& points = prm.output.probe_points;
  for (unsigned k = 0; k < points.size(); ++k) {
    const Point<3> x(points[k][0], points[k][1], points[k][2]);
    bool found = false;
    try {
      // On a distributed mesh the search may return an invalid iterator (the point lies in
      // another rank's part) instead of throwing.
      const auto hit = GridTools::find_active_cell_around_point(mapping, dof_handler, x);
      if (hit.first.state() == IteratorState::valid && hit.first->is_locally_owned() &&
          GeometryInfo<3>::distance_to_unit_cell(hit.second) < 1e-9) {
        probes.push_back(Probe{k, hit.first, GeometryInfo<3>::project_to_unit_cell(hit.second)});
        found = true;
      }
    } catch (const std::exception&) {  // not in this rank's part of the mesh
    }
    // A point on a cell boundary may be found by two ranks: the lowest rank keeps it.
    const unsigned rank = Utilities::MPI::this_mpi_process(comm);
    const unsigned owner = Utilities::MPI::min(found ? rank : numbers::invalid_unsigned_int, comm);
    if (owner == numbers::invalid_unsigned_int)
      throw InputError("Output/Probe points (mm)", "probe point " + std::to_string(k + 1) + " (" +
                                                      std::to_string(x[0] * 1e3) + " " + std::to_string(x[1] * 1e3) +
                                                      " " + std::to_string(x[2] * 1e3) + " mm) is not inside the mesh");
    if (found && owner != rank) probes.pop_back();
  }
}

// The matrix pattern: the cells' couplings plus, with wire contact, its candidate pairs (rebuilt
// when sliding brings new master faces near a slave face).
void WireSolver::Impl::make_matrix() {
  DynamicSparsityPattern dsp(relevant);
  DoFTools::make_sparsity_pattern(dof_handler, dsp, predictor, false);
  for (const auto& part : contact_parts) part->add_sparsity(dsp, predictor);
  SparsityTools::distribute_sparsity_pattern(dsp, owned, comm, relevant);
  direct_solver.pattern_changed();
  matrix.reinit(owned, owned, dsp, comm);
}

void WireSolver::Impl::refresh_relevant_values() {
  ghosted = solution;
  relevant_values.resize(relevant.n_elements());
  std::size_t k = 0;
  for (const auto i : relevant) relevant_values[k++] = ghosted[i];
}

}  // namespace dtwire::fem
