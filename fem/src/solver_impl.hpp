#pragma once
// The wire solver's state (WireSolver::Impl), shared by the files that each own one concern:
// set-up (solver_setup.cpp), boundary conditions (solver_boundary.cpp), assembly
// (solver_assembly.cpp), Newton and the linear solvers (solver_newton.cpp), records and fields
// (solver_records.cpp), checkpoints (solver_checkpoint.cpp) and the load stepping that tells
// the data path (solver.cpp, WireSolver::run). Private to fem/: deal.II types throughout.
#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/index_set.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/petsc_sparse_matrix.h>
#include <deal.II/lac/petsc_vector.h>

#include <array>
#include <filesystem>
#include <functional>
#include <memory>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "contact/bonded_grip.hpp"
#include "contact/rigid_tool_contact.hpp"
#include "contact/wire_wire_contact.hpp"
#include "direct_solver.hpp"
#include "j2_log_plasticity.hpp"
#include "nonlocal_average.hpp"
#include "solver.hpp"

namespace dtwire::fem {

using namespace dealii;

class WireAxes;
struct AxisLocation;

// The coating's cells (region_ids.hpp: material id + 3) stay stress-free in the forming. The
// generated straight wire's cells (material id 0) are steel.
inline bool is_coating(types::material_id id) { return id > 0 && (id - 1) % 10 >= 3; }

struct QuadraturePointRecord {
  PlasticState committed, trial;
  SymTensor2 cauchy;
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
  // Hanging-node constraints of a junction-refined mesh (junction_refinement.hpp), empty on a
  // conforming mesh: the first lines of homogeneous and predictor; internal_force is condensed
  // through them, so that a hanging node carries no force of its own.
  AffineConstraints<double> hanging;
  AffineConstraints<double> homogeneous, predictor;
  PETScWrappers::MPI::SparseMatrix matrix;
  DirectSolver direct_solver{MPI_COMM_WORLD};  // keeps MUMPS's analysis while the pattern stays
  PETScWrappers::MPI::Vector solution, rhs, internal_force, increment;
  PETScWrappers::MPI::Vector ghosted;  // solution with ghost entries
  std::vector<double> relevant_values;  // plain copy of `ghosted`: PETSc element reads are not thread-safe
  std::vector<QuadraturePointRecord> points;
  double elastic_energy = 0.0, dissipation = 0.0;
  // The parts acting on the wire's surface, in assembly order: rigid tools, wire contact, bonded
  // grips (each only when the .prm has it). The typed pointers below reach into this list for
  // what only one kind has (the wire contact's dofs, the grips' and tools' end work).
  std::vector<std::unique_ptr<contact::ContactPart>> contact_parts;
  contact::RigidToolContact* rigid_contact = nullptr;  // contact (issue 5): null without tools
  contact::WireWireContact* wire_contact = nullptr;    // null unless enabled
  contact::BondedGrip* bonded_grip = nullptr;          // Grip interface = bonded; null when clamped
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
  void commit();  // the trial history becomes the committed one (and the non-local indicator follows)
  // Non-local crack initiation (solver_nonlocal.cpp): the weights, found on first use, and the
  // indices into `points` of this rank's steel points in their order.
  std::unique_ptr<NonlocalAverage> nonlocal;
  std::vector<std::size_t> nonlocal_points;
  void make_nonlocal_average();
  void update_nonlocal_indicator();
  double reaction() const;
  double neck_radius() const;
  // The quadrature point with the largest `key` over the owned steel cells `select` accepts, on
  // every rank: the value (-1 if no cell is selected anywhere), its stress state, place (cell
  // centre: z and distance from the z axis) and failure indicator.
  struct LargestPoint {
    double value = -1.0, triaxiality = 0.0, lode_parameter = 0.0, z = 0.0, r = 0.0, damage = 0.0;
  };
  LargestPoint largest_point(const std::function<bool(const Triangulation<3>::active_cell_iterator&)>& select,
                             const std::function<double(const PlasticState&)>& key) const;
  void record_damage(StepRecord& record) const;
  // The junction's state (solver_junction.cpp): largest equivalent plastic strain of the cells
  // near a junction plane, with the triaxiality and Lode parameter there; one log line.
  void log_junction_state() const;
  bool solve_step(double t_old, double t_new, const PETScWrappers::MPI::Vector* extrapolation,
                  unsigned& iterations, std::string& reason);
  void write_fields(unsigned step, double time);

  // As made (solver_forming.cpp): the forming history put into every quadrature point, then
  // released by letting the holding forces (the initial internal forces, scaled by
  // holding_factor) fall to zero with the top end free; the same release ends a twisting run.
  bool top_released = false;
  double holding_factor = 0.0;
  PETScWrappers::MPI::Vector holding_force;
  void apply_forming_history();
  void release_forming();
  void release_top_end();
  void set_top_released(bool released);
  std::vector<Point<3>> top_end_positions() const;
  void record_forming_profile();
  // A twisting run's end (solver_twisted_pair.cpp): the state of every steel point for the
  // twist of a DT mesh; and that state mapped onto this mesh's twist (the other points keep
  // what apply_forming_history gave them).
  void write_twisted_pair_state(const std::filesystem::path& file);
  void apply_twisted_pair_state(const std::filesystem::path& file);
  // The as-made state file (solver_as_made_state.cpp): written after a springback when
  // as_made_output is set, read instead of forming when As made/State file is.
  std::filesystem::path as_made_output, twisted_pair_output;
  std::vector<double> as_made_header() const;
  void write_as_made_state(const std::filesystem::path& file);
  void read_as_made_state(const std::filesystem::path& file);
  // Every owned steel quadrature point (the coating stays stress-free) with its wire and where it
  // lies relative to that wire's axis.
  void visit_steel_points(const WireAxes& axes,
                          const std::function<void(unsigned, const AxisLocation&, QuadraturePointRecord&)>& visit);

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
  // The parts that keep state of their own between steps (each contact part, then the
  // external-work sums) write and read it themselves, one list of doubles each, by name.
  std::vector<std::string> part_names() const;
  std::vector<std::vector<double>> part_states() const;
  void restore_part_states(const std::vector<std::string>& names, const std::vector<std::vector<double>>& parts,
                           const std::string& file);
  void record_contact_parts(StepRecord& record, bool log_step);
  void make_rigid_body_modes();
  unsigned solve_krylov();  // GMRES + GAMG; returns the iterations, throws on failure
  // contact (issue 5): solve_step inside the augmented-Lagrange (Uzawa) loop.
  bool solve_contact_step(double t_old, double t_new, const PETScWrappers::MPI::Vector* extrapolation,
                          const PETScWrappers::MPI::Vector& start, unsigned& iterations, std::string& reason);
};

}  // namespace dtwire::fem
