#pragma once
// The quasi-static total-Lagrangian wire solver (deal.II, MPI): mesh, F-bar elements, Newton with
// line search, adaptive load stepping, reactions from the residual, field output. pimpl so
// that callers do not compile deal.II's heavy headers.
#include <filesystem>
#include <array>
#include <functional>
#include <iosfwd>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "parameters.hpp"
#include "step_record.hpp"

namespace dtwire::fem {

// The as-made start (As made/Forming history): the springback of the formed wires and what it
// leaves, per wire and axis station (profile).
struct FormingProfileRow {
  unsigned wire = 0;
  double arc_length = 0.0, z = 0.0;  // m
  double von_mises_mean = 0.0, von_mises_max = 0.0;  // Pa, over the section's quadrature points
  double plastic_strain_mean = 0.0, plastic_strain_max = 0.0;
  double damage_max = 0.0;
};
struct FormingSummary {
  bool done = false;
  unsigned steps = 0, newton_iterations = 0, cutbacks = 0;
  double seconds = 0.0;
  // Energies (J): the forming stress's elastic energy held in the mesh, and after the release;
  // the plastic and friction work of the release; the work of the holding forces as they fall.
  double initial_elastic_energy = 0.0, elastic_energy = 0.0, plastic_work = 0.0, friction_work = 0.0,
         holding_work = 0.0;
  double energy_balance = 0.0;  // |initial + holding - elastic - plastic - friction| / initial
  double largest_displacement = 0.0;  // m, of the springback
  double top_rotation = 0.0;  // rad, of the top end about the Rotation axis while it was let go
  unsigned clearance_points = 0, points_in_contact = 0;
  double clearance_mean = 0.0, clearance_largest = 0.0;  // m, after the springback
  std::vector<FormingProfileRow> profile;
  std::filesystem::path state_file;  // read from this file (As made/State file); empty: computed here
  bool after_path = false;           // the release of a twisting run (As made/Release after path)
  // Twisted pair state: the steel points that took the pair's state (the rest formed by bending)
  // and the largest distance to the pair point they took it from (m, after the offset mapping).
  std::size_t mapped_points = 0, steel_points = 0;
  double largest_mapping_distance = 0.0;
};

struct SolverStatistics {
  std::size_t dofs = 0, cells = 0;
  unsigned ranks = 1;
  std::size_t steps = 0, newton_iterations = 0, cutbacks = 0, assemblies = 0;
  std::size_t factorisations = 0;  // direct and lagged-lu solvers (this run, not counting a restart's past)
  double assembly_seconds = 0.0, solve_seconds = 0.0;
  // With softening: the run ended because no static state followed the crack (see WireSolver::run).
  bool ended_in_snap_back = false;
  FormingSummary forming;
};

class WireSolver {
 public:
  // `log` receives every stepping decision (only rank 0 writes). Fields go to field_directory
  // (empty: none).
  WireSolver(const Parameters& parameters, std::ostream& log, std::filesystem::path field_directory);
  ~WireSolver();
  WireSolver(const WireSolver&) = delete;
  WireSolver& operator=(const WireSolver&) = delete;

  // Follows the load path; on_step after every converged step (and for the initial state).
  // Throws ComputationError when a step would fall below the minimum step.
  void run(const std::function<void(const StepRecord&)>& on_step);

  // Checkpoints every `interval` converged steps (0: none) into directory/step_NNNNN/rank_R.bin;
  // restart_step >= 0 resumes from that checkpoint (same .prm, same number of ranks): the curve
  // rows up to it are replayed through on_step. Every part with state of its own (contact tools,
  // wire contact, bonded grips) is saved and restored with it.
  void set_checkpoints(const std::filesystem::path& directory, unsigned interval, int restart_step);
  // As made: where to write the state the springback leaves (empty: nowhere), for later runs'
  // As made/State file. Not written when the state was itself read from a file.
  void set_as_made_output(const std::filesystem::path& file);
  // Release after path: where to write the twisted pair state the release leaves (empty: nowhere).
  void set_twisted_pair_output(const std::filesystem::path& file);

  const SolverStatistics& statistics() const;
  const GeometryParameters& geometry() const;  // after reading the mesh
  bool is_root() const;
  std::vector<std::string> field_files() const;  // the .pvd record and .pvtu files written
  // Junction refinement (junction_refinement.hpp): the hanging-node constraints made afresh from
  // the mesh (not the solver's own), checked against the reference vertices and the solution:
  // the hanging nodes' count (all ranks) and how far a hanging node lies from the point of the
  // coarse edge or face it hangs on (m; largest over its components), before and after loading.
  struct HangingNodeCheck {
    std::size_t nodes = 0;
    double reference_gap = 0.0, displaced_gap = 0.0;
  };
  HangingNodeCheck hanging_node_check();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace dtwire::fem
