#include "rigid_tool_contact.hpp"

#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "packed_state.hpp"

namespace dtwire::fem::contact {

using namespace dealii;

namespace {

Vector3 to_vector(const std::array<double, 3>& a) {
  Vector3 v;
  for (unsigned k = 0; k < 3; ++k) v[k] = a[k];
  return v;
}

}  // namespace

RigidToolContact::RigidToolContact(const ContactParameters& parameters, double young,
                                   const DoFHandler<3>& dof_handler, const std::set<types::boundary_id>& bottom_ids,
                                   const std::set<types::boundary_id>& top_ids, MPI_Comm comm)
    : parameters_(parameters), comm_(comm) {
  const auto& fe = dof_handler.get_fe();
  const unsigned n_dofs = fe.n_dofs_per_cell();
  component_.resize(n_dofs);
  for (unsigned i = 0; i < n_dofs; ++i) component_[i] = fe.system_to_component_index(i).first;

  // Face quadrature of the same order as the cells (Gauss, degree + 1 points per direction).
  const QGauss<2> face_quadrature(fe.degree + 1);
  FEFaceValues<3> values(fe, face_quadrature, update_values | update_quadrature_points | update_JxW_values);
  double smallest_face = std::numeric_limits<double>::max();
  for (const auto& cell : dof_handler.active_cell_iterators()) {
    if (!cell->is_locally_owned()) continue;
    for (const auto f : cell->face_indices()) {
      if (!cell->face(f)->at_boundary() ||
          std::find(parameters_.boundary_ids.begin(), parameters_.boundary_ids.end(), cell->face(f)->boundary_id()) ==
              parameters_.boundary_ids.end())
        continue;
      values.reinit(cell, f);
      Face face;
      face.dofs.resize(n_dofs);
      cell->get_dof_indices(face.dofs);
      face.first_point = points_.size();
      face.cell = cell->active_cell_index();
      face.n_points = face_quadrature.size();
      for (unsigned q = 0; q < face_quadrature.size(); ++q) {
        Point p;
        p.reference = values.quadrature_point(q);
        p.committed_position = p.position = p.reference;
        p.weight = values.JxW(q);
        p.shape.resize(n_dofs);
        for (unsigned i = 0; i < n_dofs; ++i) p.shape[i] = values.shape_value(i, q);
        points_.push_back(p);
      }
      faces_.push_back(std::move(face));
      // h of the unrefined face (a junction-refined child doubles it back per level): refining
      // resolves the junction without stiffening the penalty of every contact point.
      smallest_face = std::min(smallest_face, cell->face(f)->minimum_vertex_distance() * std::ldexp(1.0, cell->level()));
    }
  }
  smallest_face = Utilities::MPI::min(smallest_face, comm_);
  if (!(smallest_face < std::numeric_limits<double>::max()))
    throw std::invalid_argument("contact: no face of the wire carries the contact boundary id(s)");
  law_.normal_penalty = parameters_.normal_penalty_factor * young / smallest_face;
  law_.tangential_penalty = parameters_.tangential_penalty_factor * young / smallest_face;
  law_.friction = parameters_.friction;
  pairs_.assign(points_.size() * parameters_.tools.size(), PairState{});

  for (unsigned c = 0; c < 3; ++c) {
    ComponentMask mask(3, false);
    mask.set(c, true);
    bottom_dofs_[c] = DoFTools::extract_boundary_dofs(dof_handler, mask, bottom_ids);
    top_dofs_[c] = DoFTools::extract_boundary_dofs(dof_handler, mask, top_ids);
  }
  begin_step(StepStart{});
}

bool RigidToolContact::begin_step(const StepStart& step) {
  const double t_old = step.t_old, t_new = step.t_new;
  time_ = t_new;
  tools_.clear();
  tool_increment_.clear();
  for (const auto& t : parameters_.tools) {
    ToolGeometry g;
    g.shape = t.shape;
    g.point = to_vector(t.point) + to_vector(tool_displacement(t, t_new));
    g.direction = to_vector(t.direction);
    g.radius = t.radius;
    g.groove_axis = to_vector(t.groove_axis);
    tools_.push_back(g);
    tool_increment_.push_back(to_vector(tool_displacement(t, t_new)) - to_vector(tool_displacement(t, t_old)));
  }
  for (auto& pair : pairs_) pair.multiplier = pair.committed.multiplier;
  augmentations_ = 0;
  return false;
}

bool RigidToolContact::assemble(const AssemblyTarget& target) {
  const unsigned n_dofs = component_.size();
  const unsigned n_tools = tools_.size();
  std::vector<double> u(n_dofs), force(n_dofs);
  FullMatrix<double> K(n_dofs, n_dofs);
  Vector<double> local_rhs(n_dofs);
  for (const auto& face : faces_) {
    for (unsigned i = 0; i < n_dofs; ++i) u[i] = target.relevant_values[target.relevant.index_within_set(face.dofs[i])];
    bool touched = false;
    std::fill(force.begin(), force.end(), 0.0);
    if (target.with_matrix) K = 0.0;
    for (unsigned q = face.first_point; q < face.first_point + face.n_points; ++q) {
      Point& p = points_[q];
      p.position = p.reference;
      for (unsigned i = 0; i < n_dofs; ++i) p.position[component_[i]] += p.shape[i] * u[i];
      for (unsigned k = 0; k < n_tools; ++k) {
        PairState& pair = pairs_[q * n_tools + k];
        ContactHistory history = pair.committed;
        history.multiplier = pair.multiplier;
        try {
          pair.last = evaluate_contact(tools_[k], law_, history, p.position, p.committed_position + tool_increment_[k]);
        } catch (const std::domain_error&) {
          return false;
        }
        pair.slip = pair.committed.slip + pair.last.slip_increment;
        if (!pair.last.active) continue;
        touched = true;
        const auto& r = pair.last;
        // Contact virtual work: -int t . delta u dA, added to the internal force.
        for (unsigned i = 0; i < n_dofs; ++i) {
          if (p.shape[i] == 0.0) continue;
          force[i] -= p.shape[i] * r.traction[component_[i]] * p.weight;
          if (!target.with_matrix) continue;
          for (unsigned j = 0; j < n_dofs; ++j)
            if (p.shape[j] != 0.0)
              K(i, j) -= p.shape[i] * p.shape[j] * r.stiffness[component_[i]][component_[j]] * p.weight;
        }
      }
    }
    if (!touched) continue;
    for (unsigned i = 0; i < n_dofs; ++i) local_rhs[i] = -force[i];
    if (target.with_matrix) target.constraints.distribute_local_to_global(K, local_rhs, face.dofs, target.matrix, target.rhs);
    else target.constraints.distribute_local_to_global(local_rhs, face.dofs, target.rhs);
    target.internal_force.add(face.dofs, force);
  }
  return true;
}

// Uzawa update (Simo & Laursen 1992; Wriggers 2006, sec. 6.3.2): lambda <- <lambda - eps g>,
// i.e. the converged penalty pressure, while the largest penetration exceeds the tolerance.
bool RigidToolContact::augment() {
  if (augmentations_ >= parameters_.maximum_augmentations) return false;
  double penetration = 0.0;
  for (const auto& pair : pairs_)
    if (pair.last.active) penetration = std::max(penetration, -pair.last.gap);
  penetration = Utilities::MPI::max(penetration, comm_);
  if (penetration <= parameters_.gap_tolerance) return false;
  for (auto& pair : pairs_) pair.multiplier = pair.last.pressure;
  ++augmentations_;
  return true;
}

void RigidToolContact::commit() {
  const unsigned n_tools = tools_.size();
  const bool augmented = parameters_.maximum_augmentations > 0;
  for (std::size_t q = 0; q < points_.size(); ++q) {
    points_[q].committed_position = points_[q].position;
    for (unsigned k = 0; k < n_tools; ++k) {
      PairState& pair = pairs_[q * n_tools + k];
      pair.committed.tangential_traction = pair.last.tangential_traction;
      pair.committed.multiplier = augmented ? pair.last.pressure : 0.0;
      pair.committed.slip = pair.slip;
      dissipation_ += pair.last.dissipation * points_[q].weight;
    }
  }
}

bool RigidToolContact::restart_here() {
  for (auto& point : points_) point.committed_position = point.position;
  for (auto& pair : pairs_) {
    pair.committed = ContactHistory{};
    pair.slip = 0.0;
  }
  dissipation_ = 0.0;
  return true;
}

std::vector<double> RigidToolContact::saved_state() const {
  StateWriter out;
  for (const auto& p : points_) out.put(p.committed_position);
  for (const auto& pair : pairs_) {
    out.put(pair.committed.tangential_traction);
    out.put(pair.committed.multiplier);
    out.put(pair.committed.slip);
  }
  out.put(dissipation_);
  return out.take();
}

void RigidToolContact::restore_state(const std::vector<double>& values) {
  StateReader in(values, "rigid tool contact");
  for (auto& p : points_) p.committed_position = p.position = in.get_vector();
  for (auto& pair : pairs_) {
    pair.committed.tangential_traction = in.get_vector();
    pair.committed.multiplier = pair.multiplier = in.get();
    pair.committed.slip = pair.slip = in.get();
  }
  dissipation_ = in.get();
  in.finish();
}

std::vector<std::pair<std::string, Vector<float>>> RigidToolContact::cell_fields(unsigned n_cells) const {
  Vector<float> pressure(n_cells), slip(n_cells);
  const unsigned n_tools = tools_.size();
  for (const auto& face : faces_)
    for (unsigned q = face.first_point; q < face.first_point + face.n_points; ++q)
      for (unsigned k = 0; k < n_tools; ++k) {
        const PairState& pair = pairs_[q * n_tools + k];
        pressure[face.cell] = std::max(pressure[face.cell], static_cast<float>(pair.last.pressure));
        slip[face.cell] = std::max(slip[face.cell], static_cast<float>(pair.committed.slip));
      }
  return {{"contact_pressure_Pa", pressure}, {"contact_slip_m", slip}};
}

void RigidToolContact::record(const RecordScales& scales, StepRecord& record, std::ostream*) const {
  record.contact = totals(scales.internal_force, scales.force, scales.energy);
}

ContactRecord RigidToolContact::totals(const PETScWrappers::MPI::Vector& internal_force, double force_scale,
                                       double contact_scale) const {
  ContactRecord r;
  r.enabled = true;
  r.augmentations = augmentations_;
  const unsigned n_tools = tools_.size();
  Vector3 tangential;
  std::vector<Vector3> on_tools(n_tools);
  for (std::size_t q = 0; q < points_.size(); ++q) {
    const Point& p = points_[q];
    bool active = false;
    for (unsigned k = 0; k < n_tools; ++k) {
      const PairState& pair = pairs_[q * n_tools + k];
      if (!pair.last.active) continue;
      active = true;
      r.normal_force += pair.last.pressure * p.weight;
      r.contact_energy += (-pair.last.gap * 0.5 * (pair.last.pressure + pair.multiplier) +
                           pair.last.tangential_traction.norm_square() / (2.0 * law_.tangential_penalty)) *
                          p.weight;
      tangential += pair.last.tangential_traction * p.weight;
      on_tools[k] -= pair.last.traction * p.weight;
      r.max_pressure = std::max(r.max_pressure, pair.last.pressure);
      r.max_slip = std::max(r.max_slip, pair.committed.slip);
      r.max_penetration = std::max(r.max_penetration, -pair.last.gap);
      if (parameters_.keep_samples)
        r.samples.push_back(ContactSample{k, p.reference, p.position, p.weight, pair.last.pressure, pair.last.gap,
                                          pair.committed.slip, pair.last.slipping});
    }
    if (active) r.active_area += p.weight;
  }
  std::array<double, 3> bottom{}, top{};
  const IndexSet owned = internal_force.locally_owned_elements();
  for (unsigned c = 0; c < 3; ++c) {
    for (const auto i : bottom_dofs_[c])
      if (owned.is_element(i)) bottom[c] += internal_force[i];
    for (const auto i : top_dofs_[c])
      if (owned.is_element(i)) top[c] += internal_force[i];
  }
  const auto sum = [&](double x) { return Utilities::MPI::sum(x, comm_); };
  r.normal_force = sum(r.normal_force) * contact_scale;
  Vector3 t_sum;
  r.tool_forces.assign(n_tools, {});
  for (const auto& tool : parameters_.tools) r.tool_displacements.push_back(tool_displacement(tool, time_));
  for (unsigned c = 0; c < 3; ++c) {
    t_sum[c] = sum(tangential[c]);
    for (unsigned k = 0; k < n_tools; ++k) r.tool_forces[k][c] = sum(on_tools[k][c]) * contact_scale;
    r.bottom_reaction[c] = sum(bottom[c]) * force_scale;
    r.top_reaction[c] = sum(top[c]) * force_scale;
  }
  r.friction_force = t_sum.norm() * contact_scale;
  r.friction_dissipation = sum(dissipation_) * contact_scale;
  r.contact_energy = sum(r.contact_energy) * contact_scale;
  r.active_area = sum(r.active_area) * contact_scale;
  r.max_pressure = Utilities::MPI::max(r.max_pressure, comm_);
  r.max_slip = Utilities::MPI::max(r.max_slip, comm_);
  r.max_penetration = Utilities::MPI::max(r.max_penetration, comm_);
  return r;
}

}  // namespace dtwire::fem::contact
