#include "solver.hpp"

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/timer.h>
#include <deal.II/base/work_stream.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q1.h>
#include <deal.II/grid/filtered_iterator.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/petsc_solver.h>
#include <deal.II/lac/petsc_sparse_matrix.h>
#include <deal.II/lac/petsc_vector.h>
#include <deal.II/lac/sparsity_tools.h>
#include <deal.II/numerics/data_out.h>
#include <deal.II/numerics/vector_tools.h>
#include <petscksp.h>

#include <boost/archive/binary_iarchive.hpp>
#include <boost/archive/binary_oarchive.hpp>
#include <boost/serialization/array.hpp>
#include <boost/serialization/vector.hpp>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <limits>
#include <map>
#include <set>
#include <ostream>
#include <sstream>

#include "dtwire/core/error.hpp"
#include "direct_solver.hpp"
#include "contact/bonded_grip.hpp"
#include "contact/packed_state.hpp"
#include "contact/rigid_tool_contact.hpp"  // contact (issue 5)
#include "contact/wire_wire_contact.hpp"
#include "fbar_element.hpp"
#include "wire_mesh.hpp"

namespace dtwire::fem {

using namespace dealii;

namespace {

struct QuadraturePointRecord {
  PlasticState committed, trial;
  SymTensor2 cauchy;
};

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

// Prescribed motion increment of the top end between two pseudo-times: translation a(t) d plus a
// rigid rotation R(theta(t)) about the axis through the centre c (Rodrigues' formula).
class TopEndIncrement : public Function<3> {
 public:
  TopEndIncrement(const LoadParameters& load, const Tensor<1, 3>& direction, const Point<3>& centre, double t_old,
                  double t_new)
      : Function<3>(3), load_(load), direction_(direction), centre_(centre), t_old_(t_old), t_new_(t_new) {}
  void vector_value(const Point<3>& X, Vector<double>& values) const override {
    const Tensor<1, 3> u = motion(X, t_new_) - motion(X, t_old_);
    for (unsigned c = 0; c < 3; ++c) values[c] = u[c];
  }

 private:
  Tensor<1, 3> motion(const Point<3>& X, double t) const {
    Tensor<1, 3> u = path_displacement(load_, t) * direction_;
    const double angle = path_rotation(load_, t);
    if (angle != 0.0) {
      Tensor<1, 3> k;
      for (unsigned c = 0; c < 3; ++c) k[c] = load_.rotation_axis[c];
      const Tensor<1, 3> r = X - centre_;
      const Tensor<1, 3> rotated =
          r * std::cos(angle) + cross_product_3d(k, r) * std::sin(angle) + k * (k * r) * (1.0 - std::cos(angle));
      u += rotated - r;
    }
    return u;
  }
  const LoadParameters& load_;
  Tensor<1, 3> direction_;
  Point<3> centre_;
  double t_old_, t_new_;
};

struct EndDof {  // an owned dof of the top end
  types::global_dof_index index;
  unsigned component;
  Point<3> reference;
  std::array<types::global_dof_index, 3> vertex_dofs;  // all components at its support point
};

struct AssemblyOutcome {
  bool ok = true;
  double residual = 0.0;        // l2 norm of the free (unconstrained) residual
  double force_scale = 0.0;     // l2 norm of the internal force vector, reactions included
};

}  // namespace

struct WireSolver::Impl {
  Impl(const Parameters& p, std::ostream& log_stream, std::filesystem::path fields)
      : prm(p),
        comm(MPI_COMM_WORLD),
        log(log_stream, Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0),
        triangulation(comm),
        fe(FE_Q<3>(p.formulation.degree), 3),
        dof_handler(triangulation),
        quadrature(p.formulation.degree + 1),
        material(ElasticParameters{p.material.young, p.material.poisson}, IsotropicHardening(p.material.hardening),
                 p.material.failure, p.material.kinematic),
        field_directory(std::move(fields)) {}

  Parameters prm;
  MPI_Comm comm;
  ConditionalOStream log;
  parallel::distributed::Triangulation<3> triangulation;
  FESystem<3> fe;
  DoFHandler<3> dof_handler;
  QGauss<3> quadrature;
  J2LogPlasticity material;
  std::filesystem::path field_directory;

  IndexSet owned, relevant, top_loaded_dofs;
  // Force control: the top face's u_z dofs follow this one; the prescribed force (per modelled
  // part) acts on it.
  types::global_dof_index force_dof = numbers::invalid_dof_index;
  double applied_force = 0.0;
  // Krylov option: orthonormal rigid-body modes (3 translations, 3 rotations) for GAMG.
  std::vector<PETScWrappers::MPI::Vector> rigid_body_modes;
  AffineConstraints<double> homogeneous, predictor;
  PETScWrappers::MPI::SparseMatrix matrix;
  DirectSolver direct_solver{MPI_COMM_WORLD};  // keeps MUMPS's analysis while the pattern stays
  PETScWrappers::MPI::Vector solution, rhs, internal_force, increment;
  PETScWrappers::MPI::Vector ghosted;  // solution with ghost entries
  std::vector<double> relevant_values;  // plain copy of `ghosted`: PETSc element reads are not thread-safe
  std::vector<QuadraturePointRecord> points;
  double elastic_energy = 0.0, dissipation = 0.0;
  std::unique_ptr<contact::RigidToolContact> rigid_contact;  // contact (issue 5): null without tools
  std::unique_ptr<contact::WireWireContact> wire_contact;    // null unless enabled
  std::unique_ptr<contact::BondedGrip> bonded_grip;          // Grip interface = bonded; null when clamped
  std::set<types::boundary_id> bottom_ids, top_ids;
  Tensor<1, 3> load_direction;  // unit: the load path's displacement acts along it
  Point<3> rotation_centre;
  std::vector<EndDof> top_end_dofs;
  // Probe points found in this rank's cells: (probe index, cell, reference-cell coordinates).
  struct Probe {
    unsigned index;
    typename DoFHandler<3>::active_cell_iterator cell;
    Point<3> unit_point;
  };
  std::vector<Probe> probes;
  void locate_probes();
  void record_probes(StepRecord& record);
  std::vector<double> previous_end_force, previous_end_displacement;  // per top_end_dofs entry
  double end_work = 0.0, tool_work = 0.0;
  std::vector<std::array<double, 3>> previous_tool_force, previous_tool_displacement;

  SolverStatistics stats;
  std::vector<std::string> written_fields;
  std::vector<std::pair<double, std::string>> pvd_records;

  FEValuesExtractors::Scalar loaded_component() const {
    return FEValuesExtractors::Scalar(prm.load.direction == LoadDirection::lateral ? 0 : 2);
  }
  double force_multiplier() const { return prm.geometry.quarter ? 4.0 : 1.0; }
  double length_multiplier() const { return prm.load.bottom == EndCondition::symmetry ? 2.0 : 1.0; }

  void setup();
  void make_matrix();
  void refresh_relevant_values();
  void make_constraints(AffineConstraints<double>& c, double t_old, double t_new) const;
  void record_end(StepRecord& record);
  AssemblyOutcome assemble(bool with_matrix, const AffineConstraints<double>& constraints);
  void commit();
  double reaction() const;
  double neck_radius() const;
  void record_damage(StepRecord& record) const;
  bool solve_step(double t_old, double t_new, const PETScWrappers::MPI::Vector* extrapolation,
                  unsigned& iterations, std::string& reason);
  void write_fields(unsigned step, double time);

  // Checkpoint / restart (binary, one file per rank; doubles written exactly).
  std::filesystem::path checkpoint_directory;
  unsigned checkpoint_interval = 0;
  int restart_step = -1;
  std::vector<StepRecord> history;  // every record passed to on_step
  struct SteppingState {
    double t = 0.0, dt = 0.0, last_dt = 0.0, last_knot = -1.0;
    unsigned step = 0;
  };
  std::filesystem::path checkpoint_file(unsigned step) const;
  void write_checkpoint(const SteppingState& state, const PETScWrappers::MPI::Vector& last_step);
  void read_checkpoint(unsigned step, SteppingState& state, PETScWrappers::MPI::Vector& last_step);
  // The parts that keep state of their own between steps (contact tools, wire contact, bonded
  // grips, the external-work sums) write and read it themselves, one list of doubles each.
  std::vector<std::vector<double>> part_states() const;
  void restore_part_states(const std::vector<std::vector<double>>& parts, const std::string& file);
  void make_rigid_body_modes();
  unsigned solve_krylov();  // GMRES + GAMG; returns the iterations, throws on failure
  // contact (issue 5): solve_step inside the augmented-Lagrange (Uzawa) loop.
  bool solve_contact_step(double t_old, double t_new, const PETScWrappers::MPI::Vector* extrapolation,
                          const PETScWrappers::MPI::Vector& start, unsigned& iterations, std::string& reason);
};

void WireSolver::Impl::setup() {
  make_wire_mesh(prm.geometry, triangulation);
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
  if (prm.wire_contact.enabled) {
    if (!prm.geometry.double_twist)
      throw InputError("Wire contact", "Enabled = true needs a double-twist mesh file (`dtwire mesh dt`)");
    wire_contact = std::make_unique<contact::WireWireContact>(prm.wire_contact, prm.material.young,
                                                              prm.geometry.diameter, dof_handler, comm);
    relevant.add_indices(wire_contact->needed_dofs());
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
    wire_contact->begin_step(relevant_values);
  }
  make_matrix();

  points.assign(triangulation.n_active_cells() * quadrature.size(), QuadraturePointRecord{});
  locate_probes();
  if (prm.newton.krylov) make_rigid_body_modes();
  if (prm.contact.enabled())  // contact (issue 5)
    rigid_contact = std::make_unique<contact::RigidToolContact>(prm.contact, prm.material.young, dof_handler,
                                                                bottom_ids, top_ids, comm);
  if (prm.load.grip.bonded) {  // grip interface: the bond holds the grip surfaces
    bonded_grip = std::make_unique<contact::BondedGrip>(prm.load.grip, prm.material.young, dof_handler, bottom_ids,
                                                        top_ids, comm);
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

// The matrix pattern: the cells' couplings plus, with wire contact, its candidate pairs (rebuilt
// when sliding brings new master faces near a slave face).
void WireSolver::Impl::make_matrix() {
  DynamicSparsityPattern dsp(relevant);
  DoFTools::make_sparsity_pattern(dof_handler, dsp, predictor, false);
  if (wire_contact) wire_contact->add_sparsity(dsp, predictor);
  SparsityTools::distribute_sparsity_pattern(dsp, owned, comm, relevant);
  direct_solver.reset();
  matrix.reinit(owned, owned, dsp, comm);
}

void WireSolver::Impl::refresh_relevant_values() {
  ghosted = solution;
  relevant_values.resize(relevant.n_elements());
  std::size_t k = 0;
  for (const auto i : relevant) relevant_values[k++] = ghosted[i];
}

void WireSolver::Impl::make_constraints(AffineConstraints<double>& c, double t_old, double t_new) const {
  c.clear();
  c.reinit(relevant);
  const FEValuesExtractors::Scalar ux(0), uy(1), uz(2);
  const ComponentMask all(3, true), z_only = fe.component_mask(uz);
  const auto zero = Functions::ZeroFunction<3>(3);
  const TopEndIncrement top(prm.load, load_direction, rotation_centre, t_old, t_new);
  std::map<types::boundary_id, const Function<3>*> top_map, bottom_map;
  if (!prm.load.grip.bonded) {  // bonded grips are held by the bond (contact/bonded_grip.hpp) instead
    for (const auto id : top_ids) top_map[id] = &top;
    for (const auto id : bottom_ids) bottom_map[id] = &zero;
  }
  if (prm.load.force_control) {
    // The top face translates as one along z (all u_z equal to force_dof's); clamped also
    // holds u_x, u_y.
    if (prm.load.top == EndCondition::clamped) {
      std::map<types::boundary_id, const Function<3>*> fixed;
      for (const auto id : top_ids) fixed[id] = &zero;
      VectorTools::interpolate_boundary_values(dof_handler, fixed, c, ComponentMask(std::vector<bool>{true, true, false}));
    }
    for (const auto i : top_loaded_dofs)
      if (i != force_dof && relevant.is_element(i)) {
        c.add_line(i);
        c.add_entry(i, force_dof, 1.0);
      }
  } else if (prm.load.top != EndCondition::free)
    VectorTools::interpolate_boundary_values(dof_handler, top_map, c,
                                             prm.load.top == EndCondition::clamped ? all
                                                                                   : fe.component_mask(loaded_component()));
  const ComponentMask x_and_z(std::vector<bool>{true, false, true});
  VectorTools::interpolate_boundary_values(dof_handler, bottom_map, c,
                                           prm.load.bottom == EndCondition::clamped  ? all
                                           : prm.load.bottom == EndCondition::guided ? x_and_z
                                                                                     : z_only);
  if (prm.geometry.quarter) {
    VectorTools::interpolate_boundary_values(dof_handler, kSymmetryX, zero, c, fe.component_mask(ux));
    VectorTools::interpolate_boundary_values(dof_handler, kSymmetryY, zero, c, fe.component_mask(uy));
  }
  c.close();
}

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
    internal_force.add(copy.dofs, copy.internal_force);
    elastic_energy += copy.elastic_energy;
    dissipation += copy.dissipation;
  };
  using CellFilter = FilteredIterator<typename DoFHandler<3>::active_cell_iterator>;
  WorkStream::run(CellFilter(IteratorFilters::LocallyOwnedCell(), dof_handler.begin_active()),
                  CellFilter(IteratorFilters::LocallyOwnedCell(), dof_handler.end()), worker, copier,
                  ScratchData(fe, quadrature), CopyData());
  if (rigid_contact &&  // contact (issue 5): tool tractions on the contact boundary faces
      !rigid_contact->assemble(relevant, relevant_values, with_matrix, constraints, matrix, rhs, internal_force))
    failed = true;
  if (wire_contact &&
      !wire_contact->assemble(relevant_values, with_matrix, constraints, matrix, rhs, internal_force))
    failed = true;
  if (bonded_grip) bonded_grip->assemble(relevant, relevant_values, with_matrix, constraints, matrix, rhs);
  if (force_dof != numbers::invalid_dof_index && owned.is_element(force_dof)) rhs(force_dof) += applied_force;
  if (with_matrix) matrix.compress(VectorOperation::add);
  rhs.compress(VectorOperation::add);
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
  if (rigid_contact) rigid_contact->commit();  // contact (issue 5)
  if (wire_contact) wire_contact->commit();
  if (bonded_grip) bonded_grip->commit();
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

void WireSolver::Impl::record_damage(StepRecord& record) const {
  const unsigned n_q = quadrature.size();
  struct {
    double value;
    int rank;
  } local{-1.0, static_cast<int>(Utilities::MPI::this_mpi_process(comm))}, global{};
  double where[4] = {0, 0, 0, 0};  // triaxiality, Lode, z, r
  for (const auto& cell : triangulation.active_cell_iterators()) {
    if (!cell->is_locally_owned()) continue;
    for (unsigned q = 0; q < n_q; ++q) {
      const auto& p = points[cell->active_cell_index() * n_q + q];
      if (p.committed.damage <= local.value) continue;
      local.value = p.committed.damage;
      const StressInvariants inv = stress_invariants(p.cauchy);
      const Point<3> x = cell->center();
      where[0] = inv.triaxiality;
      where[1] = inv.lode_parameter;
      where[2] = x[2];
      where[3] = std::hypot(x[0], x[1]);
    }
  }
  MPI_Allreduce(&local, &global, 1, MPI_DOUBLE_INT, MPI_MAXLOC, comm);
  MPI_Bcast(where, 4, MPI_DOUBLE, global.rank, comm);
  record.damage = std::max(global.value, 0.0);
  record.damage_triaxiality = where[0];
  record.damage_lode = where[1];
  record.damage_z = where[2];
  record.damage_r = where[3];
}

double WireSolver::Impl::neck_radius() const {
  // The surface vertex layer nearest the imperfection centre (mid-length without imperfection);
  // every rank holds all coarse cells, so the layer is the same everywhere.
  const auto& g = prm.geometry;
  if (g.double_twist) return 0.0;  // no single neck section
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

// Newton-Raphson for one load step. The start is either the previous step's increment, scaled
// (`extrapolation`, within one load-path segment; boundary values set exactly), or the
// linearised predictor: iteration 0 applies the boundary increment through inhomogeneous
// constraints (as in deal.II step-44). Backtracking line search when the residual did not drop.
bool WireSolver::Impl::solve_step(double t_old, double t_new, const PETScWrappers::MPI::Vector* extrapolation,
                                  unsigned& iterations, std::string& reason) {
  applied_force = path_force(prm.load, t_new) / force_multiplier();
  make_constraints(predictor, t_old, t_new);
  const unsigned first_free = extrapolation ? 0 : 1;  // first iteration with homogeneous constraints
  if (extrapolation) {
    increment = *extrapolation;
    predictor.distribute(increment);
    solution.add(1.0, increment);
  }
  const double floor = 1e-14 * prm.material.young * prm.geometry.diameter * prm.geometry.diameter;
  PETScWrappers::MPI::Vector previous(owned, comm), previous_increment(owned, comm);
  double previous_residual = 0.0;
  std::ostringstream history;
  history << std::scientific << std::setprecision(2);
  for (unsigned it = 0; it <= prm.newton.maximum_iterations; ++it) {
    const auto& constraints = it < first_free ? predictor : homogeneous;
    AssemblyOutcome a = assemble(true, constraints);
    if (it > first_free && prm.newton.line_search && (!a.ok || a.residual > (1.0 - 1e-4) * previous_residual)) {
      double step = 1.0;
      for (unsigned ls = 0; ls < prm.newton.maximum_line_search_steps; ++ls) {
        step *= 0.5;
        solution = previous;
        solution.add(step, previous_increment);
        a = assemble(false, homogeneous);
        if (a.ok && a.residual < (1.0 - 1e-4 * step) * previous_residual) break;
      }
      history << " [line search " << step << "]";
      if (a.ok) a = assemble(true, homogeneous);
    }
    if (!a.ok) {
      reason = "inverted element or failed return mapping at iteration " + std::to_string(it);
      log << "    newton:" << history.str() << "\n";
      return false;
    }
    if (it >= first_free) {
      const double relative = a.residual / std::max(a.force_scale, floor);
      history << " " << relative;
      // Relative to the internal forces; the absolute floor (far above round-off, far below any
      // load of interest) ends steps in which no force builds up (rigid motion before contact).
      if (a.residual <= std::max(prm.newton.relative_tolerance * std::max(a.force_scale, floor), 1e-2 * floor)) {
        iterations = it;
        log << "    newton (relative residual):" << history.str() << "\n";
        return true;
      }
      if (it > first_free && a.residual > 1e6 * previous_residual) break;
    }
    Timer timer;
    try {
      if (prm.newton.krylov) {
        history << " (gmres " << solve_krylov() << ")";
      } else {
        direct_solver.solve(matrix, increment, rhs);
      }
    } catch (const std::exception& e) {
      reason = prm.newton.krylov ? std::string("Krylov solver failed: ") + e.what() : "direct solver failed";
      stats.solve_seconds += timer.wall_time();
      return false;
    }
    stats.solve_seconds += timer.wall_time();
    constraints.distribute(increment);
    previous = solution;
    previous_increment = increment;
    previous_residual = a.residual;
    solution.add(1.0, increment);
  }
  reason = "no convergence in " + std::to_string(prm.newton.maximum_iterations) + " iterations";
  log << "    newton (relative residual):" << history.str() << "\n";
  return false;
}

// Rigid-body modes of the owned dofs from their support points, orthonormalised (PETSc's
// near-null-space contract) by modified Gram-Schmidt.
void WireSolver::Impl::make_rigid_body_modes() {
  std::map<types::global_dof_index, Point<3>> points_of;
  DoFTools::map_dofs_to_support_points(MappingQ1<3>(), dof_handler, points_of);
  std::array<IndexSet, 3> component;
  for (unsigned c = 0; c < 3; ++c) {
    std::vector<bool> mask(3, false);
    mask[c] = true;
    component[c] = DoFTools::extract_dofs(dof_handler, ComponentMask(mask));
  }
  rigid_body_modes.assign(6, PETScWrappers::MPI::Vector(owned, comm));
  for (const auto i : owned) {
    const Point<3>& x = points_of.at(i);
    unsigned c = 0;
    while (!component[c].is_element(i)) ++c;
    rigid_body_modes[c](i) = 1.0;                                                  // translations
    rigid_body_modes[3](i) = c == 0 ? -x[1] : c == 1 ? x[0] : 0.0;                 // rotation about z
    rigid_body_modes[4](i) = c == 1 ? -x[2] : c == 2 ? x[1] : 0.0;                 // about x
    rigid_body_modes[5](i) = c == 2 ? -x[0] : c == 0 ? x[2] : 0.0;                 // about y
  }
  for (unsigned m = 0; m < 6; ++m) {
    rigid_body_modes[m].compress(VectorOperation::insert);
    for (unsigned k = 0; k < m; ++k) rigid_body_modes[m].add(-(rigid_body_modes[m] * rigid_body_modes[k]), rigid_body_modes[k]);
    rigid_body_modes[m] /= rigid_body_modes[m].l2_norm();
  }
}

unsigned WireSolver::Impl::solve_krylov() {
  const auto check = [](PetscErrorCode code) {
    if (code != 0) throw std::runtime_error("PETSc error " + std::to_string(code));
  };
  std::vector<Vec> modes;
  for (const auto& v : rigid_body_modes) modes.push_back(v);
  MatNullSpace near_null_space;
  check(MatNullSpaceCreate(comm, PETSC_FALSE, static_cast<PetscInt>(modes.size()), modes.data(), &near_null_space));
  check(MatSetNearNullSpace(matrix, near_null_space));
  KSP ksp;
  check(KSPCreate(comm, &ksp));
  check(KSPSetOperators(ksp, matrix, matrix));
  check(KSPSetType(ksp, KSPGMRES));
  check(KSPGMRESSetRestart(ksp, 200));
  check(KSPSetTolerances(ksp, prm.newton.linear_tolerance, 0.0, PETSC_DEFAULT,
                         static_cast<PetscInt>(prm.newton.maximum_linear_iterations)));
  PC pc;
  check(KSPGetPC(ksp, &pc));
  check(PCSetType(pc, PCGAMG));
  check(KSPSolve(ksp, rhs, increment));
  KSPConvergedReason converged;
  PetscInt iterations = 0;
  check(KSPGetConvergedReason(ksp, &converged));
  check(KSPGetIterationNumber(ksp, &iterations));
  check(KSPDestroy(&ksp));
  check(MatNullSpaceDestroy(&near_null_space));
  if (converged < 0)
    throw std::runtime_error("GMRES did not converge (reason " + std::to_string(converged) + ") in " +
                             std::to_string(iterations) + " iterations");
  return static_cast<unsigned>(iterations);
}

// ---- contact (issue 5) ----
// Augmented Lagrangian by Uzawa iterations around Newton (Simo & Laursen 1992): after each
// converged solve the multipliers take the converged pressures and the step is solved again
// from its start (the converged increment as predictor), until the largest penetration is
// below the gap tolerance or the augmentation budget is spent. Friction history stays at the
// committed state throughout.
bool WireSolver::Impl::solve_contact_step(double t_old, double t_new, const PETScWrappers::MPI::Vector* extrapolation,
                                          const PETScWrappers::MPI::Vector& start, unsigned& iterations,
                                          std::string& reason) {
  if (rigid_contact) rigid_contact->begin_step(t_old, t_new);
  if (bonded_grip)
    bonded_grip->begin_step(contact::top_end_motion(prm.load, load_direction, rotation_centre, t_new), !extrapolation);
  if (wire_contact) {
    refresh_relevant_values();  // the committed state (after a cut-back too)
    if (wire_contact->begin_step(relevant_values)) {
      log << "    wire contact: new candidate pairs, matrix pattern rebuilt\n";
      make_matrix();
    }
  }
  if (!solve_step(t_old, t_new, extrapolation, iterations, reason)) return false;
  if (!rigid_contact && !wire_contact) return true;
  PETScWrappers::MPI::Vector converged(owned, comm);
  const auto augment = [&]() {  // both contacts update their multipliers (no short-circuit)
    const bool rigid = rigid_contact && rigid_contact->augment();
    const bool wires = wire_contact && wire_contact->augment();
    return rigid || wires;
  };
  while (augment()) {
    converged = solution;
    converged -= start;
    solution = start;
    unsigned more = 0;
    log << "    augmentation " << (rigid_contact ? rigid_contact->augmentations() : wire_contact->augmentations()) << "\n";
    if (!solve_step(t_old, t_new, &converged, more, reason)) return false;
    iterations += more;
  }
  return true;
}
// ---- end contact ----

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
  Vector<float> contact_pressure(n_cells), contact_slip(n_cells);  // contact (issue 5)
  if (rigid_contact) {
    rigid_contact->cell_fields(contact_pressure, contact_slip);
    out.add_data_vector(contact_pressure, "contact_pressure_Pa");
    out.add_data_vector(contact_slip, "contact_slip_m");
  }
  Vector<float> wire_pressure(n_cells), wire_slip(n_cells);
  if (wire_contact) {
    wire_contact->cell_fields(wire_pressure, wire_slip);
    out.add_data_vector(wire_pressure, "wire_contact_pressure_Pa");
    out.add_data_vector(wire_slip, "wire_contact_slip_m");
  }
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

std::filesystem::path WireSolver::Impl::checkpoint_file(unsigned step) const {
  char name[32];
  std::snprintf(name, sizeof name, "step_%05u", step);
  return checkpoint_directory / name / ("rank_" + std::to_string(Utilities::MPI::this_mpi_process(comm)) + ".bin");
}

namespace {
constexpr char kCheckpointMagic[16] = "dtwire-ckpt-3";
}  // namespace

// Layout: magic, then one boost binary archive: the header (ranks, DoFs, cells, quadrature
// points), the stepping state, the statistics, the step records (each serialises every field),
// this rank's solution and last step values, the committed material state of its points, and
// the state of each part (part_states).
void WireSolver::Impl::write_checkpoint(const SteppingState& state, const PETScWrappers::MPI::Vector& last_step) {
  const auto file = checkpoint_file(state.step);
  std::filesystem::create_directories(file.parent_path());
  std::vector<double> header = {static_cast<double>(stats.ranks), static_cast<double>(stats.dofs),
                                static_cast<double>(triangulation.n_active_cells()), static_cast<double>(quadrature.size())};
  std::vector<double> stepping = {static_cast<double>(state.step), state.t, state.dt, state.last_dt, state.last_knot,
                                  static_cast<double>(stats.steps), static_cast<double>(stats.newton_iterations),
                                  static_cast<double>(stats.cutbacks)};
  std::vector<double> values;
  for (const auto i : owned) values.push_back(solution[i]);
  for (const auto i : owned) values.push_back(last_step[i]);
  for (const auto& p : points) {
    for (unsigned k = 0; k < 6; ++k) values.push_back(p.committed.plastic_metric_inverse.access_raw_entry(k));
    values.insert(values.end(), {p.committed.equivalent_plastic_strain, p.committed.plastic_dissipation, p.committed.damage});
    for (unsigned k = 0; k < 6; ++k) values.push_back(p.committed.backstress.access_raw_entry(k));
  }
  const auto temporary = file.string() + ".tmp";
  {
    std::ofstream out(temporary, std::ios::binary);
    out.write(kCheckpointMagic, sizeof kCheckpointMagic);
    boost::archive::binary_oarchive archive(out);
    archive << header << stepping << history << values << part_states();
    if (!out) throw ComputationError("cannot write checkpoint " + temporary);
  }
  std::filesystem::rename(temporary, file);
  log << "  checkpoint written: " << file.parent_path().string() << "\n";
}

void WireSolver::Impl::read_checkpoint(unsigned step, SteppingState& state, PETScWrappers::MPI::Vector& last_step) {
  const auto file = checkpoint_file(step);
  std::ifstream in(file, std::ios::binary);
  char magic[sizeof kCheckpointMagic] = {};
  in.read(magic, sizeof magic);
  if (!in || std::string(magic) != kCheckpointMagic)
    throw InputError(file.string(), "not a dtwire checkpoint of this version (or missing)");
  std::vector<double> header, stepping, values;
  std::vector<std::vector<double>> parts;
  try {
    boost::archive::binary_iarchive archive(in);
    archive >> header >> stepping >> history >> values >> parts;
  } catch (const std::exception& e) {
    throw InputError(file.string(), std::string("unreadable checkpoint: ") + e.what());
  }
  const std::vector<double> expected = {static_cast<double>(stats.ranks), static_cast<double>(stats.dofs),
                                        static_cast<double>(triangulation.n_active_cells()), static_cast<double>(quadrature.size())};
  if (header != expected)
    throw InputError(file.string(), "checkpoint from another mesh, element or number of MPI ranks");
  const std::size_t n_values = 2 * owned.n_elements() + 15 * points.size();
  if (stepping.size() != 8 || values.size() != n_values)
    throw InputError(file.string(), "checkpoint of another size than this run's state");
  state.step = static_cast<unsigned>(stepping[0]);
  state.t = stepping[1];
  state.dt = stepping[2];
  state.last_dt = stepping[3];
  state.last_knot = stepping[4];
  stats.steps = static_cast<std::size_t>(stepping[5]);
  stats.newton_iterations = static_cast<std::size_t>(stepping[6]);
  stats.cutbacks = static_cast<std::size_t>(stepping[7]);
  std::size_t k = 0;
  for (const auto i : owned) solution[i] = values[k++];
  for (const auto i : owned) last_step[i] = values[k++];
  solution.compress(VectorOperation::insert);
  last_step.compress(VectorOperation::insert);
  for (auto& p : points) {
    for (unsigned j = 0; j < 6; ++j) p.committed.plastic_metric_inverse.access_raw_entry(j) = values[k++];
    p.committed.equivalent_plastic_strain = values[k++];
    p.committed.plastic_dissipation = values[k++];
    p.committed.damage = values[k++];
    for (unsigned j = 0; j < 6; ++j) p.committed.backstress.access_raw_entry(j) = values[k++];
    p.trial = p.committed;
  }
  restore_part_states(parts, file.string());
}

std::vector<std::vector<double>> WireSolver::Impl::part_states() const {
  contact::StateWriter work;
  work.put(end_work);
  work.put(tool_work);
  for (std::size_t k = 0; k < top_end_dofs.size(); ++k) {
    work.put(previous_end_force[k]);
    work.put(previous_end_displacement[k]);
  }
  work.put(previous_tool_force.size());
  for (std::size_t k = 0; k < previous_tool_force.size(); ++k)
    for (unsigned c = 0; c < 3; ++c) {
      work.put(previous_tool_force[k][c]);
      work.put(previous_tool_displacement[k][c]);
    }
  return {rigid_contact ? rigid_contact->saved_state() : std::vector<double>{},
          wire_contact ? wire_contact->saved_state() : std::vector<double>{},
          bonded_grip ? bonded_grip->saved_state() : std::vector<double>{}, work.take()};
}

void WireSolver::Impl::restore_part_states(const std::vector<std::vector<double>>& parts, const std::string& file) {
  if (parts.size() != 4) throw InputError(file, "checkpoint without the state of the contact parts");
  const auto mismatch = [&](const char* part) {
    throw InputError(file, std::string("checkpoint of a run with ") + part + ", unlike this one");
  };
  try {
    if (rigid_contact) rigid_contact->restore_state(parts[0]);
    else if (!parts[0].empty()) mismatch("contact tools");
    if (wire_contact) wire_contact->restore_state(parts[1]);
    else if (!parts[1].empty()) mismatch("wire contact");
    if (bonded_grip) bonded_grip->restore_state(parts[2]);
    else if (!parts[2].empty()) mismatch("bonded grips");
    contact::StateReader work(parts[3], "external work");
    end_work = work.get();
    tool_work = work.get();
    for (std::size_t k = 0; k < top_end_dofs.size(); ++k) {
      previous_end_force[k] = work.get();
      previous_end_displacement[k] = work.get();
    }
    previous_tool_force.resize(work.get_count());
    previous_tool_displacement.resize(previous_tool_force.size());
    for (std::size_t k = 0; k < previous_tool_force.size(); ++k)
      for (unsigned c = 0; c < 3; ++c) {
        previous_tool_force[k][c] = work.get();
        previous_tool_displacement[k][c] = work.get();
      }
    work.finish();
  } catch (const std::invalid_argument& e) {
    throw InputError(file, std::string("checkpoint does not fit this run: ") + e.what());
  }
  if (wire_contact) make_matrix();  // the restored pattern holds every pair met so far
}

void WireSolver::set_checkpoints(const std::filesystem::path& directory, unsigned interval, int restart_step) {
  impl_->checkpoint_directory = directory;
  impl_->checkpoint_interval = interval;
  impl_->restart_step = restart_step;
}

WireSolver::WireSolver(const Parameters& parameters, std::ostream& log, std::filesystem::path field_directory)
    : impl_(std::make_unique<Impl>(parameters, log, std::move(field_directory))) {
  impl_->setup();
}

WireSolver::~WireSolver() = default;

const SolverStatistics& WireSolver::statistics() const { return impl_->stats; }
const GeometryParameters& WireSolver::geometry() const { return impl_->prm.geometry; }
bool WireSolver::is_root() const { return Utilities::MPI::this_mpi_process(impl_->comm) == 0; }
std::vector<std::string> WireSolver::field_files() const {
  auto files = impl_->written_fields;
  if (!files.empty()) files.insert(files.begin(), "fields.pvd");
  return files;
}

void WireSolver::run(const std::function<void(const StepRecord&)>& on_step) {
  Impl& s = *impl_;
  const auto& stepping = s.prm.stepping;
  const auto& path = s.prm.load.path;
  const double t_end = path.back().first;
  const double tiny = 1e-12 * t_end;

  const unsigned interval = s.prm.output.fields ? s.prm.output.field_interval : 0;
  double t = 0.0, dt = stepping.initial_step;
  unsigned step = 0;
  PETScWrappers::MPI::Vector saved(s.owned, s.comm), last_step(s.owned, s.comm), scaled(s.owned, s.comm);
  double last_dt = 0.0, last_knot = -1.0;
  bool retry = false;
  s.log << std::setprecision(6);
  StepRecord record;
  if (s.restart_step >= 0) {
    Impl::SteppingState state;
    s.read_checkpoint(static_cast<unsigned>(s.restart_step), state, last_step);
    t = state.t;
    dt = state.dt;
    step = state.step;
    last_dt = state.last_dt;
    last_knot = state.last_knot;
    s.assemble(false, s.homogeneous);  // stresses for output; the committed history stays as read
    for (const auto& r : s.history) on_step(r);
    record = s.history.back();
    s.log << "restarted from the checkpoint of step " << step << " at t = " << t << "\n";
  } else {
    s.assemble(false, s.homogeneous);  // initial state (stress-free), fills the field records
    s.commit();
    record.neck_radius = s.neck_radius();
    if (s.rigid_contact) record.contact = s.rigid_contact->record(s.internal_force, s.force_multiplier(),  // issue 5
                                                                  s.force_multiplier() * s.length_multiplier());
    if (s.wire_contact) record.wire_contact = s.wire_contact->record(s.force_multiplier() * s.length_multiplier());
    if (s.bonded_grip) record.grip = s.bonded_grip->record(s.force_multiplier(), s.force_multiplier() * s.length_multiplier());
    s.record_end(record);
    s.record_probes(record);
    on_step(record);
    s.history.push_back(record);
    if (interval > 0) s.write_fields(0, 0.0);
  }
  while (t < t_end - tiny) {
    double knot = t_end;
    for (const auto& p : path)
      if (p.first > t + tiny) { knot = p.first; break; }
    double dt_try = std::min(dt, knot - t);
    if (knot - (t + dt_try) < 1e-3 * dt_try) dt_try = knot - t;  // no sliver step before a knot
    saved = s.solution;
    unsigned iterations = 0;
    std::string reason;
    s.log << "step " << step + 1 << ": t = " << t << " -> " << t + dt_try << " (dt = " << dt_try
          << "), top " << (s.prm.load.force_control ? "force " : "displacement ")
          << (s.prm.load.force_control ? path_force(s.prm.load, t + dt_try) : path_displacement(s.prm.load, t + dt_try) * 1e3)
          << (s.prm.load.force_control ? " N\n" : " mm\n");
    // Extrapolate the previous increment only inside the same load-path segment, not on a retry.
    const bool extrapolate = !retry && last_dt > 0.0 && knot == last_knot;
    if (extrapolate) {
      scaled = last_step;
      scaled *= dt_try / last_dt;
    }
    if (s.solve_contact_step(t, t + dt_try, extrapolate ? &scaled : nullptr, saved, iterations, reason)) {
      s.commit();
      last_step = s.solution;
      last_step -= saved;
      last_dt = dt_try;
      last_knot = knot;
      retry = false;
      t = std::abs(t + dt_try - knot) <= tiny ? knot : t + dt_try;
      ++step;
      ++s.stats.steps;
      s.stats.newton_iterations += iterations;
      record.step = step;
      record.time = t;
      record.displacement = (s.prm.load.force_control ? s.ghosted[s.force_dof] : path_displacement(s.prm.load, t)) *
                            s.length_multiplier();
      record.force = s.reaction();
      record.plastic_dissipation = s.dissipation * s.force_multiplier() * s.length_multiplier();
      record.elastic_energy = s.elastic_energy * s.force_multiplier() * s.length_multiplier();
      record.neck_radius = s.neck_radius();
      record.iterations = iterations;
      s.record_damage(record);
      if (s.rigid_contact) record.contact = s.rigid_contact->record(s.internal_force, s.force_multiplier(),  // issue 5
                                                                    s.force_multiplier() * s.length_multiplier());
      if (s.wire_contact) {
        record.wire_contact = s.wire_contact->record(s.force_multiplier() * s.length_multiplier());
        s.log << "  wire contact: " << record.wire_contact.active_points << " active points ("
              << record.wire_contact.slipping_points << " slipping, " << record.wire_contact.frozen_points
              << " frozen) of " << record.wire_contact.candidate_pairs << " candidate face pairs, normal force "
              << record.wire_contact.normal_force << " N\n";
      }
      if (s.bonded_grip) {
        record.grip = s.bonded_grip->record(s.force_multiplier(), s.force_multiplier() * s.length_multiplier());
        s.log << "  bonded grips: " << record.grip.slipping_fraction * 100 << " % of the top grips' area slipping, "
              << "largest slip " << record.grip.max_slip * 1e3 << " mm\n";
      }
      s.record_end(record);
      s.record_probes(record);
      s.log << "  converged in " << iterations << " iteration(s): force " << record.force << " N, neck radius "
            << record.neck_radius * 1e3 << " mm\n";
      on_step(record);
      s.history.push_back(record);
      if (interval > 0 && step % interval == 0) s.write_fields(step, t);
      if (s.prm.material.failure.enabled() && record.damage >= 1.0) {
        s.log << "  ductile failure indicator reached " << record.damage << " at z = " << record.damage_z * 1e3
              << " mm, r = " << record.damage_r * 1e3 << " mm (triaxiality " << record.damage_triaxiality
              << ", Lode parameter " << record.damage_lode << ")\n";
        if (s.prm.material.stop_at_failure) {
          s.log << "  stopping at failure (Stop at failure = true)\n";
          break;
        }
      }
      if (iterations <= stepping.easy_iterations && dt < stepping.maximum_step) {
        const double grown = std::min(stepping.maximum_step, dt * stepping.growth_factor);
        s.log << "  easy step (" << iterations << " <= " << stepping.easy_iterations << " iterations): dt "
              << dt << " -> " << grown << "\n";
        dt = grown;
      }
      if (s.checkpoint_interval > 0 && step % s.checkpoint_interval == 0)
        s.write_checkpoint({t, dt, last_dt, last_knot, step}, last_step);
    } else {
      s.solution = saved;
      retry = true;
      ++s.stats.cutbacks;
      const double reduced = dt_try * stepping.cutback_factor;
      s.log << "  step failed (" << reason << "): cut back dt " << dt_try << " -> " << reduced << "\n";
      if (reduced < stepping.minimum_step) {
        s.log << "  dt below the minimum step " << stepping.minimum_step << ": giving up at t = " << t << "\n";
        throw ComputationError("load stepping failed at pseudo-time " + std::to_string(t) + " (" + reason +
                               "; step below the minimum " + std::to_string(stepping.minimum_step) + ")");
      }
      dt = reduced;
    }
  }
  if (s.prm.output.fields && (interval == 0 || step % interval != 0)) s.write_fields(step, t);
}

}  // namespace dtwire::fem
