#include "bonded_grip.hpp"

#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
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

RigidMotion identity_motion() {
  RigidMotion m;
  for (unsigned i = 0; i < 3; ++i) m.rotation[i][i] = 1.0;
  return m;
}

RigidMotion top_end_motion(const LoadParameters& load, const Vector3& direction, const Vector3& centre, double t) {
  RigidMotion m = identity_motion();
  m.centre = centre;
  m.translation = path_displacement(load, t) * direction;
  const double angle = path_rotation(load, t);
  if (angle != 0.0) {  // Rodrigues: R = cos I + sin [k]x + (1 - cos) k k
    Vector3 k;
    for (unsigned c = 0; c < 3; ++c) k[c] = load.rotation_axis[c];
    Matrix3 cross;
    cross[0][1] = -k[2], cross[0][2] = k[1], cross[1][0] = k[2], cross[1][2] = -k[0], cross[2][0] = -k[1],
    cross[2][1] = k[0];
    m.rotation = std::cos(angle) * m.rotation + std::sin(angle) * cross + (1.0 - std::cos(angle)) * outer_product(k, k);
  }
  return m;
}

BondedGrip::BondedGrip(const GripParameters& parameters, double young, const DoFHandler<3>& dof_handler,
                       const std::set<types::boundary_id>& bottom_ids, const std::set<types::boundary_id>& top_ids,
                       MPI_Comm comm)
    : comm_(comm), top_(identity_motion()) {
  const auto& fe = dof_handler.get_fe();
  const unsigned n_dofs = fe.n_dofs_per_cell();
  component_.resize(n_dofs);
  for (unsigned i = 0; i < n_dofs; ++i) component_[i] = fe.system_to_component_index(i).first;

  const QGauss<2> face_quadrature(fe.degree + 1);  // as the cells
  FEFaceValues<3> values(fe, face_quadrature,
                         update_values | update_quadrature_points | update_normal_vectors | update_JxW_values);
  double smallest_face = std::numeric_limits<double>::max();
  for (const auto& cell : dof_handler.active_cell_iterators()) {
    if (!cell->is_locally_owned()) continue;
    for (const auto f : cell->face_indices()) {
      if (!cell->face(f)->at_boundary()) continue;
      const auto id = cell->face(f)->boundary_id();
      const bool top = top_ids.count(id) > 0;
      if (!top && bottom_ids.count(id) == 0) continue;
      values.reinit(cell, f);
      Face face;
      face.dofs.resize(n_dofs);
      cell->get_dof_indices(face.dofs);
      face.first_point = points_.size();
      face.n_points = face_quadrature.size();
      for (unsigned q = 0; q < face_quadrature.size(); ++q) {
        Point p;
        p.reference = p.position = p.anchor = p.committed_anchor = values.quadrature_point(q);
        p.normal = values.normal_vector(q);
        p.weight = values.JxW(q);
        p.top = top;
        p.shape.resize(n_dofs);
        for (unsigned i = 0; i < n_dofs; ++i) p.shape[i] = values.shape_value(i, q);
        (top ? top_area_ : bottom_area_) += p.weight;
        points_.push_back(p);
      }
      faces_.push_back(std::move(face));
      // h of the unrefined face (a junction-refined child doubles it back per level): refining
      // resolves the junction without stiffening the penalty of every contact point.
      smallest_face = std::min(smallest_face, cell->face(f)->minimum_vertex_distance() * std::ldexp(1.0, cell->level()));
    }
  }
  smallest_face = Utilities::MPI::min(smallest_face, comm_);
  top_area_ = Utilities::MPI::sum(top_area_, comm_);
  bottom_area_ = Utilities::MPI::sum(bottom_area_, comm_);
  if (!(top_area_ > 0.0) || !(bottom_area_ > 0.0))
    throw std::invalid_argument("bonded grips: no boundary face carries the Bottom or the Top boundary ids");
  law_.stiffness = parameters.stiffness_factor * young / smallest_face;
  law_.strength = parameters.strength;
  law_.slides = false;
  top_law_ = law_;
  top_law_.slides = true;
}

bool BondedGrip::begin_step(const StepStart& step) {
  top_ = step.top_motion;
  predictor_ = !step.extrapolated;
  return false;
}

bool BondedGrip::assemble(const AssemblyTarget& target) {
  const unsigned n_dofs = component_.size();
  const RigidMotion fixed = identity_motion();
  std::vector<double> u(n_dofs);
  FullMatrix<double> K(n_dofs, n_dofs);
  Vector<double> local_rhs(n_dofs);
  for (const auto& face : faces_) {
    for (unsigned i = 0; i < n_dofs; ++i) u[i] = target.relevant_values[target.relevant.index_within_set(face.dofs[i])];
    local_rhs = 0.0;
    if (target.with_matrix) K = 0.0;
    for (unsigned q = face.first_point; q < face.first_point + face.n_points; ++q) {
      Point& p = points_[q];
      const RigidMotion& grip = p.top ? top_ : fixed;
      Vector3 displacement;
      for (unsigned i = 0; i < n_dofs; ++i) displacement[component_[i]] += p.shape[i] * u[i];
      const Vector3 anchor_displacement = grip.displacement(p.reference);
      p.position = p.reference + displacement;
      p.anchor = p.reference + anchor_displacement;
      // In the grip's frame (its surface keeps the reference normal): g = R^T (x - anchor), from
      // the displacements (the positions would lose the gap's digits to round-off: the penalty
      // force of eps |X| is far above the Newton tolerance for stiff bonds).
      const Matrix3 Rt = transpose(grip.rotation);
      p.last = evaluate_bond(p.top && !predictor_ ? top_law_ : law_, p.committed, p.normal,
                             Rt * (displacement - anchor_displacement));
      p.traction = grip.rotation * p.last.traction;
      const Matrix3 stiffness = grip.rotation * p.last.stiffness * Rt;  // d t / d x
      // The traction loads the wire: residual -int N_a t dA, tangent -int N_a N_b dt/dx dA.
      for (unsigned i = 0; i < n_dofs; ++i) {
        if (p.shape[i] == 0.0) continue;
        local_rhs[i] += p.shape[i] * p.traction[component_[i]] * p.weight;
        if (!target.with_matrix) continue;
        for (unsigned j = 0; j < n_dofs; ++j)
          if (p.shape[j] != 0.0) K(i, j) -= p.shape[i] * p.shape[j] * stiffness[component_[i]][component_[j]] * p.weight;
      }
    }
    if (target.with_matrix) target.constraints.distribute_local_to_global(K, local_rhs, face.dofs, target.matrix, target.rhs);
    else target.constraints.distribute_local_to_global(local_rhs, face.dofs, target.rhs);
  }
  if (target.with_matrix) predictor_ = false;
  return true;
}

std::vector<double> BondedGrip::saved_state() const {
  StateWriter out;
  for (const auto& p : points_) {
    out.put(p.committed.slip_vector);
    out.put(p.committed.slip);
    out.put(p.committed_traction);
    out.put(p.committed_anchor);
  }
  out.put(work_);
  out.put(dissipation_);
  return out.take();
}

void BondedGrip::restore_state(const std::vector<double>& values) {
  StateReader in(values, "bonded grip");
  for (auto& p : points_) {
    p.committed.slip_vector = in.get_vector();
    p.committed.slip = in.get();
    p.committed_traction = p.traction = in.get_vector();
    p.committed_anchor = p.anchor = in.get_vector();
  }
  work_ = in.get();
  dissipation_ = in.get();
  in.finish();
}

void BondedGrip::commit() {
  for (auto& p : points_) {
    if (p.top) work_ += 0.5 * p.weight * (p.committed_traction + p.traction) * (p.anchor - p.committed_anchor);
    dissipation_ += p.last.dissipation * p.weight;
    p.committed = p.last.history;
    p.committed_traction = p.traction;
    p.committed_anchor = p.anchor;
  }
}

void BondedGrip::top_resultants(const Vector3& centre, Vector3& force, Vector3& moment) const {
  for (const auto& p : points_) {
    if (!p.top) continue;
    force += p.traction * p.weight;
    moment += cross_product_3d(p.position - centre, p.traction * p.weight);
  }
}

void BondedGrip::record(const RecordScales& scales, StepRecord& record, std::ostream* log) const {
  record.grip = totals(scales.force, scales.energy);
  if (log)
    *log << "  bonded grips: " << record.grip.slipping_fraction * 100 << " % of the top grips' area slipping, "
         << "largest slip " << record.grip.max_slip * 1e3 << " mm\n";
}

GripRecord BondedGrip::totals(double area_scale, double energy_scale) const {
  GripRecord r;
  r.enabled = true;
  double slipping = 0.0;
  for (const auto& p : points_) {
    r.bond_energy += p.last.energy * p.weight;
    if (!p.top) continue;
    r.max_slip = std::max(r.max_slip, p.committed.slip);
    if (p.last.slipping) slipping += p.weight;
  }
  r.bond_energy = Utilities::MPI::sum(r.bond_energy, comm_) * energy_scale;
  r.slip_dissipation = Utilities::MPI::sum(dissipation_, comm_) * energy_scale;
  r.max_slip = Utilities::MPI::max(r.max_slip, comm_);
  r.slipping_fraction = Utilities::MPI::sum(slipping, comm_) / top_area_;
  r.top_area = top_area_ * area_scale;
  return r;
}

}  // namespace dtwire::fem::contact
