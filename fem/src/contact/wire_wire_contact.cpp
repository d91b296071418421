#include "wire_wire_contact.hpp"

#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/lac/full_matrix.h>

#include <boost/geometry.hpp>
#include <boost/geometry/geometries/box.hpp>
#include <boost/geometry/geometries/point.hpp>
#include <boost/geometry/index/rtree.hpp>

#include <algorithm>
#include <ostream>
#include <cmath>
#include <iterator>
#include <limits>
#include <stdexcept>

#include <map>

#include "packed_state.hpp"

namespace dtwire::fem::contact {

using namespace dealii;

namespace {

namespace bg = boost::geometry;
namespace bgi = boost::geometry::index;
using RTreePoint = bg::model::point<double, 3, bg::cs::cartesian>;
using RTreeBox = bg::model::box<RTreePoint>;

// Master and slave normals must oppose at least this much: keeps a point from projecting onto
// the far side of the other wire.
constexpr double kFacingCosine = -0.2;  // master and slave normals must oppose at least this much

bool has_id(const std::vector<unsigned>& ids, types::boundary_id id) {
  return std::find(ids.begin(), ids.end(), static_cast<unsigned>(id)) != ids.end();
}

RTreeBox inflated_box(const BilinearFace& face, double margin) {
  RTreePoint low(std::numeric_limits<double>::max(), std::numeric_limits<double>::max(),
                 std::numeric_limits<double>::max());
  RTreePoint high(-low.get<0>(), -low.get<1>(), -low.get<2>());
  for (const auto& v : face.vertex) {
    low.set<0>(std::min(low.get<0>(), v[0] - margin));
    low.set<1>(std::min(low.get<1>(), v[1] - margin));
    low.set<2>(std::min(low.get<2>(), v[2] - margin));
    high.set<0>(std::max(high.get<0>(), v[0] + margin));
    high.set<1>(std::max(high.get<1>(), v[1] + margin));
    high.set<2>(std::max(high.get<2>(), v[2] + margin));
  }
  return RTreeBox(low, high);
}

// Vertex dofs, reference vertices and the outward sign of a Q1 boundary face.
template <typename Face>
void describe_face(const typename DoFHandler<3>::active_cell_iterator& cell, unsigned f, Face& face) {
  const auto fi = cell->face(f);
  for (unsigned v = 0; v < 4; ++v) {
    face.reference[v] = fi->vertex(v);
    for (unsigned c = 0; c < 3; ++c) face.dofs[3 * v + c] = fi->vertex_dof_index(v, c);
  }
  BilinearFace geometry;
  geometry.vertex = face.reference;
  const Vector3 n = cross_product_3d(geometry.tangent_xi(0.5), geometry.tangent_eta(0.5));
  const Vector3 out = fi->center() - cell->center();
  face.normal_sign = n * out >= 0.0 ? 1.0 : -1.0;
}

}  // namespace

WireWireContact::WireWireContact(const WireContactParameters& parameters, double young, double diameter,
                                 const DoFHandler<3>& dof_handler, MPI_Comm comm)
    : parameters_(parameters), comm_(comm) {
  if (dof_handler.get_fe().degree != 1)
    throw std::invalid_argument("wire contact needs Polynomial degree = 1 (bilinear faces)");
  const QGauss<1> gauss(parameters_.points_per_direction);
  double smallest_face = std::numeric_limits<double>::max();
  std::vector<double> packed_masters;  // 12 dofs, 12 coordinates, sign per face
  for (const auto& cell : dof_handler.active_cell_iterators()) {
    if (!cell->is_locally_owned()) continue;
    for (const auto f : cell->face_indices()) {
      if (!cell->face(f)->at_boundary()) continue;
      const auto id = cell->face(f)->boundary_id();
      if (has_id(parameters_.slave_ids, id)) {
        SlaveFace face;
        describe_face(cell, f, face);
        face.cell = cell->active_cell_index();
        face.first_point = points_.size();
        BilinearFace geometry;
        geometry.vertex = face.reference;
        for (unsigned i = 0; i < gauss.size(); ++i)
          for (unsigned j = 0; j < gauss.size(); ++j) {
            SlavePoint p;
            p.xi = gauss.point(i)[0];
            p.eta = gauss.point(j)[0];
            p.weight = gauss.weight(i) * gauss.weight(j) * geometry.area_element(p.xi, p.eta);
            p.committed_position = p.position = geometry.position(p.xi, p.eta);
            points_.push_back(p);
          }
        slaves_.push_back(face);
      } else if (has_id(parameters_.master_ids, id)) {
        MasterFace face;
        describe_face(cell, f, face);
        for (const auto d : face.dofs) packed_masters.push_back(static_cast<double>(d));
        for (const auto& v : face.reference)
          for (unsigned c = 0; c < 3; ++c) packed_masters.push_back(v[c]);
        packed_masters.push_back(face.normal_sign);
      } else {
        continue;
      }
      // h of the unrefined face (a junction-refined child doubles it back per level): refining
      // resolves the junction without stiffening the penalty of every contact point.
      smallest_face = std::min(smallest_face, cell->face(f)->minimum_vertex_distance() * std::ldexp(1.0, cell->level()));
    }
  }
  // Every rank holds the whole master surface (it is small next to the volume mesh).
  const auto gathered = Utilities::MPI::all_gather(comm_, packed_masters);
  needed_ = IndexSet(dof_handler.n_dofs());
  std::vector<types::global_dof_index> master_dofs;
  for (const auto& block : gathered)
    for (std::size_t k = 0; k + 25 <= block.size(); k += 25) {
      MasterFace face;
      for (unsigned i = 0; i < 12; ++i) {
        face.dofs[i] = static_cast<types::global_dof_index>(block[k + i]);
        master_dofs.push_back(face.dofs[i]);
      }
      for (unsigned v = 0; v < 4; ++v)
        for (unsigned c = 0; c < 3; ++c) face.reference[v][c] = block[k + 12 + 3 * v + c];
      face.normal_sign = block[k + 24];
      masters_.push_back(face);
    }
  std::sort(master_dofs.begin(), master_dofs.end());
  master_dofs.erase(std::unique(master_dofs.begin(), master_dofs.end()), master_dofs.end());
  needed_.add_indices(master_dofs.begin(), master_dofs.end());
  smallest_face = Utilities::MPI::min(smallest_face, comm_);
  if (Utilities::MPI::sum(slaves_.size(), comm_) == 0 || masters_.empty())
    throw std::invalid_argument("wire contact: no slave or no master face carries the given boundary ids");
  law_.normal_penalty = parameters_.normal_penalty_factor * young / smallest_face;
  law_.tangential_penalty = parameters_.tangential_penalty_factor * young / smallest_face;
  law_.friction = parameters_.friction;
  search_distance_ = parameters_.search_distance > 0.0 ? parameters_.search_distance : 0.25 * diameter;
  keep_margin_ = 1e-3 * smallest_face;
  committed_master_values_.assign(12 * masters_.size(), 0.0);
  master_values_ = committed_master_values_;
  if (parameters_.smoothed_normals) build_normal_patches();
}

// Vertices of the master surface (keyed by their x dof) and, per master face, the faces sharing
// one of its vertices: their vertices beyond the face's own become the point's neighbours.
void WireWireContact::build_normal_patches() {
  std::map<types::global_dof_index, unsigned> vertex_of_dof;
  std::vector<std::array<unsigned, 4>> face_vertices(masters_.size());
  std::vector<std::vector<std::pair<unsigned, unsigned>>> faces_at_vertex;  // (face, corner)
  for (unsigned m = 0; m < masters_.size(); ++m)
    for (unsigned v = 0; v < 4; ++v) {
      const auto [it, added] = vertex_of_dof.emplace(masters_[m].dofs[3 * v], vertices_.size());
      if (added) {
        MasterVertex vertex;
        for (unsigned c = 0; c < 3; ++c) vertex.dofs[c] = masters_[m].dofs[3 * v + c];
        vertex.reference = masters_[m].reference[v];
        vertices_.push_back(vertex);
        faces_at_vertex.emplace_back();
      }
      face_vertices[m][v] = it->second;
      faces_at_vertex[it->second].emplace_back(m, v);
    }
  for (unsigned m = 0; m < masters_.size(); ++m) {
    MasterFace& face = masters_[m];
    std::vector<unsigned> patch(face_vertices[m].begin(), face_vertices[m].end());
    const auto local = [&](unsigned vertex) {
      const auto found = std::find(patch.begin(), patch.end(), vertex);
      if (found != patch.end()) return static_cast<unsigned>(found - patch.begin());
      patch.push_back(vertex);
      return static_cast<unsigned>(patch.size() - 1);
    };
    for (unsigned v = 0; v < 4; ++v)
      for (const auto& [other, corner] : faces_at_vertex[face_vertices[m][v]]) {
        NormalCorner c;
        for (unsigned k = 0; k < 4; ++k) c.face[k] = local(face_vertices[other][k]);
        c.corner = corner;
        c.sign = masters_[other].normal_sign;
        face.corners[v].push_back(c);
      }
    if (patch.size() - 4 > kMaxNeighbourVertices)
      throw std::invalid_argument("wire contact: a master face has " + std::to_string(patch.size() - 4) +
                                  " neighbour vertices, more than the smoothed normal supports (" +
                                  std::to_string(kMaxNeighbourVertices) + "); set 'Smoothed normals = false'");
    face.neighbours.assign(patch.begin() + 4, patch.end());
  }
}

std::vector<types::global_dof_index> WireWireContact::point_dofs(const SlaveFace& slave, const MasterFace& master) const {
  std::vector<types::global_dof_index> dofs(slave.dofs.begin(), slave.dofs.end());
  dofs.insert(dofs.end(), master.dofs.begin(), master.dofs.end());
  for (const unsigned k : master.neighbours)
    dofs.insert(dofs.end(), vertices_[k].dofs.begin(), vertices_[k].dofs.end());
  return dofs;
}

void WireWireContact::initialise(const IndexSet& relevant, const AffineConstraints<double>& constraints,
                                 const IndexSet& owned) {
  for (auto& face : masters_)
    for (unsigned i = 0; i < 12; ++i) face.value_index[i] = relevant.index_within_set(face.dofs[i]);
  for (auto& vertex : vertices_)
    for (unsigned c = 0; c < 3; ++c) vertex.value_index[c] = relevant.index_within_set(vertex.dofs[c]);
  std::vector<types::global_dof_index> constrained;
  for (auto& face : slaves_)
    for (unsigned i = 0; i < 12; ++i) {
      face.value_index[i] = relevant.index_within_set(face.dofs[i]);
      if (owned.is_element(face.dofs[i]) && constraints.is_constrained(face.dofs[i])) constrained.push_back(face.dofs[i]);
    }
  for (const auto i : needed_)
    if (owned.is_element(i) && constraints.is_constrained(i)) constrained.push_back(i);
  constrained_ = IndexSet(needed_.size());
  for (const auto& block : Utilities::MPI::all_gather(comm_, constrained))
    for (const auto i : block) constrained_.add_index(i);
  constrained_.compress();
}

BilinearFace WireWireContact::current_face(const std::array<Vector3, 4>& reference,
                                           const std::array<unsigned, 12>& index, double sign,
                                           const std::vector<double>& values) const {
  BilinearFace face;
  face.normal_sign = sign;
  for (unsigned v = 0; v < 4; ++v)
    for (unsigned c = 0; c < 3; ++c) face.vertex[v][c] = reference[v][c] + values[index[3 * v + c]];
  return face;
}

bool WireWireContact::begin_step(const StepStart& step) {
  const std::vector<double>& relevant_values = *step.relevant_values;
  std::vector<std::pair<RTreeBox, unsigned>> boxes;
  boxes.reserve(masters_.size());
  for (unsigned m = 0; m < masters_.size(); ++m) {
    const auto& face = masters_[m];
    boxes.emplace_back(inflated_box(current_face(face.reference, face.value_index, face.normal_sign, relevant_values),
                                    search_distance_),
                       m);
  }
  const bgi::rtree<std::pair<RTreeBox, unsigned>, bgi::quadratic<16>> tree(boxes.begin(), boxes.end());
  bool grown = false;
  std::vector<std::pair<RTreeBox, unsigned>> hits;
  for (auto& face : slaves_) {
    hits.clear();
    const BilinearFace geometry = current_face(face.reference, face.value_index, face.normal_sign, relevant_values);
    tree.query(bgi::intersects(inflated_box(geometry, 0.0)), std::back_inserter(hits));
    face.candidates.clear();
    for (const auto& hit : hits) face.candidates.push_back(hit.second);
    std::sort(face.candidates.begin(), face.candidates.end());
    std::vector<unsigned> merged;
    std::set_union(face.pattern.begin(), face.pattern.end(), face.candidates.begin(), face.candidates.end(),
                   std::back_inserter(merged));
    if (merged.size() != face.pattern.size()) {
      grown = true;
      face.pattern = std::move(merged);
    }
  }
  for (auto& p : points_) {
    p.multiplier = p.committed.multiplier;
    p.master = p.committed_master;
    p.flips = 0;
    p.frozen = FrictionStatus::free;
    p.master_frozen = false;
    p.status = -1;  // not yet assembled in this step
  }
  augmentations_ = 0;
  return Utilities::MPI::max(grown ? 1 : 0, comm_) == 1;
}

void WireWireContact::add_sparsity(DynamicSparsityPattern& pattern, const AffineConstraints<double>& constraints) const {
  for (const auto& face : slaves_)
    for (const unsigned m : face.pattern)
      constraints.add_entries_local_to_global(point_dofs(face, masters_[m]), pattern, false);
}

bool WireWireContact::assemble(const AssemblyTarget& target) {
  std::vector<BilinearFace> master_geometry(masters_.size());
  for (unsigned m = 0; m < masters_.size(); ++m) {
    const auto& face = masters_[m];
    master_geometry[m] = current_face(face.reference, face.value_index, face.normal_sign, target.relevant_values);
    for (unsigned i = 0; i < 12; ++i) master_values_[12 * m + i] = target.relevant_values[face.value_index[i]];
  }
  FullMatrix<double> K;
  Vector<double> local_rhs;
  for (const auto& face : slaves_) {
    const BilinearFace slave = current_face(face.reference, face.value_index, face.normal_sign, target.relevant_values);
    const unsigned n_points = parameters_.points_per_direction * parameters_.points_per_direction;
    for (unsigned q = face.first_point; q < face.first_point + n_points; ++q) {
      SlavePoint& p = points_[q];
      p.position = slave.position(p.xi, p.eta);
      const Vector3 slave_normal = slave.outward_normal(p.xi, p.eta);
      // Closest facing master face among the candidates (or the frozen one). The current face is
      // considered first and another must be nearer by a margin to replace it: over an edge two
      // faces give the same clamped distance, and a tie broken by round-off would flip the normal
      // by the facet angle from one iteration to the next.
      int best = -1;
      FaceProjection best_projection;
      bool best_inside = false;
      const auto consider = [&](unsigned m) {
        const FaceProjection proj = project_onto_face(master_geometry[m], p.position);
        if (proj.distance > search_distance_) return;
        if (master_geometry[m].outward_normal(proj.xi, proj.eta) * slave_normal > kFacingCosine) return;
        const double margin = best == p.master ? keep_margin_ : 0.0;
        const bool better = best < 0 || (proj.inside && !best_inside) ||
                            (proj.inside == best_inside && proj.distance < best_projection.distance - margin);
        if (!better) return;
        best = static_cast<int>(m);
        best_projection = proj;
        best_inside = proj.inside;
      };
      const bool current_is_candidate =
          p.master >= 0 && std::binary_search(face.candidates.begin(), face.candidates.end(), unsigned(p.master));
      if (p.master >= 0 && (p.master_frozen || current_is_candidate)) consider(static_cast<unsigned>(p.master));
      if (!p.master_frozen)
        for (const unsigned m : face.candidates)
          if (static_cast<int>(m) != p.master) consider(m);
      if (target.with_matrix && p.status >= 0 && best != p.master && best >= 0 && p.master >= 0) ++p.flips;
      p.master = best;
      if (best < 0) {
        p.last = ContactResponse{};
        if (target.with_matrix) p.status = 0;
        continue;
      }
      p.master_xi = best_projection.xi;
      p.master_eta = best_projection.eta;
      const MasterFace& master = masters_[static_cast<unsigned>(best)];
      WireContactPointInput in;
      in.slave_reference = face.reference;
      in.master_reference = master.reference;
      for (unsigned i = 0; i < 12; ++i) {
        in.slave_displacement[i] = target.relevant_values[face.value_index[i]];
        in.master_displacement[i] = master_values_[12 * best + i];
        in.master_committed_displacement[i] = committed_master_values_[12 * best + i];
      }
      in.master_sign = master.normal_sign;
      in.slave_xi = p.xi;
      in.slave_eta = p.eta;
      in.weight = p.weight;
      in.master_xi = p.master_xi;
      in.master_eta = p.master_eta;
      in.committed_slave_position = p.committed_position;
      in.gap_offset = parameters_.gap_offset;
      in.history = p.committed;
      in.history.multiplier = p.multiplier;
      in.forced = p.frozen;
      in.vertex_corners = master.corners;
      for (const unsigned k : master.neighbours) {
        in.neighbour_reference.push_back(vertices_[k].reference);
        for (unsigned c = 0; c < 3; ++c)
          in.neighbour_displacement.push_back(target.relevant_values[vertices_[k].value_index[c]]);
      }
      const WireContactPointOutput point = evaluate_wire_contact_point(in, law_, target.with_matrix);
      p.last = point.response;
      const int status = !p.last.active ? 0 : p.last.slipping ? 2 : 1;
      if (target.with_matrix) {
        if (p.status >= 0 && status != p.status && status != 0 && p.status != 0) ++p.flips;
        p.status = status;
        if (p.flips >= parameters_.flip_limit && !p.master_frozen && status != 0) {
          p.master_frozen = true;
          p.frozen = status == 2 ? FrictionStatus::slip : FrictionStatus::stick;
        }
      }
      if (!p.last.active) continue;

      const std::vector<types::global_dof_index> dofs = point_dofs(face, master);
      const unsigned n = dofs.size();
      local_rhs.reinit(n);
      if (target.with_matrix) K.reinit(n, n);
      for (unsigned i = 0; i < n; ++i) {
        local_rhs[i] = -point.force[i];
        if (!target.with_matrix) continue;
        for (unsigned j = 0; j < n; ++j) K(i, j) = point.tangent(i, j);
      }
      // Constrained dofs whose constraint this rank does not hold: drop their rows and columns
      // (the owner replaces the row by the constraint; the reaction keeps the force).
      for (unsigned i = 0; i < n; ++i)
        if (constrained_.is_element(dofs[i]) && !target.constraints.is_constrained(dofs[i])) {
          local_rhs[i] = 0.0;
          if (!target.with_matrix) continue;
          for (unsigned j = 0; j < n; ++j) K(i, j) = K(j, i) = 0.0;
        }
      if (target.with_matrix) target.constraints.distribute_local_to_global(K, local_rhs, dofs, target.matrix, target.rhs);
      else target.constraints.distribute_local_to_global(local_rhs, dofs, target.rhs);
      target.internal_force.add(dofs, point.force);
    }
  }
  return true;
}

// Uzawa update as for the rigid tools (Simo & Laursen 1992).
bool WireWireContact::augment() {
  if (augmentations_ >= parameters_.maximum_augmentations) return false;
  double penetration = 0.0;
  for (const auto& p : points_)
    if (p.last.active) penetration = std::max(penetration, -p.last.gap);
  penetration = Utilities::MPI::max(penetration, comm_);
  if (penetration <= parameters_.gap_tolerance) return false;
  for (auto& p : points_) p.multiplier = p.last.active ? p.last.pressure : 0.0;
  ++augmentations_;
  return true;
}

void WireWireContact::commit() {
  const bool augmented = parameters_.maximum_augmentations > 0;
  for (auto& p : points_) {
    p.committed_position = p.position;
    p.committed.tangential_traction = p.last.tangential_traction;
    p.committed.multiplier = augmented && p.last.active ? p.last.pressure : 0.0;
    p.committed.slip += p.last.slip_increment;
    p.committed_master = p.master;
    // mu p Delta gamma with p averaged over the step (trapezoidal rule, second order like the
    // external work; the kernel's end-of-step value overestimates it while the load grows).
    const double mean_pressure = 0.5 * (p.committed_pressure + p.last.pressure);
    dissipation_ += law_.friction * mean_pressure * p.last.slip_increment * p.weight;
    p.committed_pressure = p.last.active ? p.last.pressure : 0.0;
  }
  committed_master_values_ = master_values_;
}

std::vector<double> WireWireContact::saved_state() const {
  StateWriter out;
  for (const auto& p : points_) {
    out.put(p.committed.tangential_traction);
    out.put(p.committed.multiplier);
    out.put(p.committed.slip);
    out.put(p.committed_pressure);
    out.put(p.committed_position);
    out.put(p.committed_master);
  }
  for (const auto& face : slaves_) {
    out.put(face.pattern.size());
    for (const unsigned m : face.pattern) out.put(m);
  }
  for (const double v : committed_master_values_) out.put(v);
  out.put(dissipation_);
  return out.take();
}

void WireWireContact::restore_state(const std::vector<double>& values) {
  StateReader in(values, "wire contact");
  for (auto& p : points_) {
    p.committed.tangential_traction = in.get_vector();
    p.committed.multiplier = in.get();
    p.committed.slip = in.get();
    p.committed_pressure = in.get();
    p.committed_position = p.position = in.get_vector();
    p.committed_master = p.master = static_cast<int>(in.get_whole(-1, static_cast<long>(masters_.size()) - 1));
  }
  const long masters = static_cast<long>(masters_.size());
  for (auto& face : slaves_) {
    face.pattern.resize(static_cast<std::size_t>(in.get_whole(0, masters)));
    for (auto& m : face.pattern) m = static_cast<unsigned>(in.get_whole(0, masters - 1));
  }
  for (auto& v : committed_master_values_) v = in.get();
  master_values_ = committed_master_values_;
  dissipation_ = in.get();
  in.finish();
}

bool WireWireContact::restart_here() {
  for (auto& p : points_) {
    p.committed = ContactHistory{};
    p.committed_pressure = 0.0;
    p.committed_position = p.position;
    p.committed_master = p.master;
  }
  committed_master_values_ = master_values_;
  dissipation_ = 0.0;
  return true;
}

void WireWireContact::record(const RecordScales& scales, StepRecord& record, std::ostream* log) const {
  record.wire_contact = totals(scales.energy);
  const WireContactRecord& r = record.wire_contact;
  if (log)
    *log << "  wire contact: " << r.active_points << " active points (" << r.slipping_points << " slipping, "
         << r.frozen_points << " frozen) of " << r.candidate_pairs << " candidate face pairs, normal force "
         << r.normal_force << " N\n";
}

WireContactRecord WireWireContact::totals(double contact_scale) const {
  WireContactRecord r;
  r.enabled = true;
  r.augmentations = augmentations_;
  double area = 0.0, normal = 0.0, friction = 0.0, energy = 0.0;
  unsigned active = 0, slipping = 0, frozen = 0, pairs = 0;
  for (const auto& face : slaves_) pairs += face.candidates.size();
  for (const auto& p : points_) {
    if (p.master_frozen) ++frozen;
    if (!p.last.active) continue;
    ++active;
    if (p.last.slipping) ++slipping;
    area += p.weight;
    normal += p.last.pressure * p.weight;
    friction += p.last.tangential_traction.norm() * p.weight;
    energy += (-p.last.gap * 0.5 * (p.last.pressure + p.multiplier) +
               p.last.tangential_traction.norm_square() / (2.0 * law_.tangential_penalty)) *
              p.weight;
    r.max_pressure = std::max(r.max_pressure, p.last.pressure);
    r.max_penetration = std::max(r.max_penetration, -p.last.gap);
    if (parameters_.keep_samples)
      r.samples.push_back(ContactSample{0, p.committed_position, p.position, p.weight, p.last.pressure, p.last.gap,
                                        p.committed.slip, p.last.slipping});
  }
  for (const auto& p : points_) r.max_slip = std::max(r.max_slip, p.committed.slip);
  const auto sum = [&](double x) { return Utilities::MPI::sum(x, comm_) * contact_scale; };
  r.normal_force = sum(normal);
  r.friction_force = sum(friction);
  r.contact_energy = sum(energy);
  r.active_area = sum(area);
  r.friction_dissipation = sum(dissipation_);
  r.active_points = Utilities::MPI::sum(active, comm_);
  r.slipping_points = Utilities::MPI::sum(slipping, comm_);
  r.frozen_points = Utilities::MPI::sum(frozen, comm_);
  r.candidate_pairs = Utilities::MPI::sum(pairs, comm_);
  r.max_pressure = Utilities::MPI::max(r.max_pressure, comm_);
  r.max_penetration = Utilities::MPI::max(r.max_penetration, comm_);
  r.max_slip = Utilities::MPI::max(r.max_slip, comm_);
  return r;
}

std::vector<std::pair<std::string, Vector<float>>> WireWireContact::cell_fields(unsigned n_cells) const {
  Vector<float> pressure(n_cells), slip(n_cells);
  const unsigned n = parameters_.points_per_direction * parameters_.points_per_direction;
  for (const auto& face : slaves_)
    for (unsigned q = face.first_point; q < face.first_point + n; ++q) {
      pressure[face.cell] = std::max(pressure[face.cell], static_cast<float>(points_[q].last.pressure));
      slip[face.cell] = std::max(slip[face.cell], static_cast<float>(points_[q].committed.slip));
    }
  return {{"wire_contact_pressure_Pa", pressure}, {"wire_contact_slip_m", slip}};
}

WireWireContact::Clearance WireWireContact::clearance() const {
  double count = 0.0, touching = 0.0, sum = 0.0, largest = 0.0;
  for (const auto& p : points_) {
    if (p.master < 0) continue;
    count += 1.0;
    if (p.last.active) touching += 1.0;
    sum += std::max(p.last.gap, 0.0);
    largest = std::max(largest, p.last.gap);
  }
  Clearance c;
  c.points = static_cast<unsigned>(dealii::Utilities::MPI::sum(count, comm_));
  c.in_contact = static_cast<unsigned>(dealii::Utilities::MPI::sum(touching, comm_));
  c.mean = c.points > 0 ? dealii::Utilities::MPI::sum(sum, comm_) / c.points : 0.0;
  c.largest = dealii::Utilities::MPI::max(largest, comm_);
  return c;
}

}  // namespace dtwire::fem::contact
