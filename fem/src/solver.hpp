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

#include "contact/contact_record.hpp"  // contact (issue 5)
#include "parameters.hpp"

namespace dtwire::fem {

// One converged load step, in SI units and for the whole wire (symmetry multipliers applied).
struct StepRecord {
  unsigned step = 0;
  double time = 0.0;
  double displacement = 0.0;  // m, elongation of the whole specimen
  double force = 0.0;         // N, axial reaction
  double plastic_dissipation = 0.0;  // J
  double elastic_energy = 0.0;       // J
  double neck_radius = 0.0;          // m, smallest deformed radius in the imperfection plane
  unsigned iterations = 0;
  // Ductile failure indicator: its largest value and, at that point, triaxiality, Lode
  // parameter, height z and distance from the axis (reference configuration, m).
  double damage = 0.0, damage_triaxiality = 0.0, damage_lode = 0.0, damage_z = 0.0, damage_r = 0.0;
  contact::ContactRecord contact;  // contact (issue 5): enabled only with tools in the .prm
  contact::WireContactRecord wire_contact;  // enabled with `subsection Wire contact`
  contact::GripRecord grip;                 // enabled with Grip interface = bonded
  // Generalised results at the top end (whole model): force and moment of the specimen on the
  // top end's constraint, the moment about the end centre; translation of that centre and the
  // prescribed rotation (rad); external work of the end and the tools (J, trapezoidal rule).
  std::array<double, 3> end_force{}, end_moment{}, end_translation{};
  std::vector<std::array<double, 3>> probe_displacements;  // m, one per Output/Probe points entry
  double end_rotation = 0.0, external_work = 0.0;

  // Every field, so that a checkpoint cannot drop one (boost::serialization).
  template <class Archive>
  void serialize(Archive& ar, const unsigned /*version*/) {
    ar& step & time & displacement & force & plastic_dissipation & elastic_energy & neck_radius & iterations;
    ar& damage & damage_triaxiality & damage_lode & damage_z & damage_r;
    ar& contact & wire_contact & grip;
    ar& end_force & end_moment & end_translation & probe_displacements & end_rotation & external_work;
  }
};

struct SolverStatistics {
  std::size_t dofs = 0, cells = 0;
  unsigned ranks = 1;
  std::size_t steps = 0, newton_iterations = 0, cutbacks = 0, assemblies = 0;
  double assembly_seconds = 0.0, solve_seconds = 0.0;
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

  const SolverStatistics& statistics() const;
  const GeometryParameters& geometry() const;  // after reading the mesh
  bool is_root() const;
  std::vector<std::string> field_files() const;  // the .pvd record and .pvtu files written

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace dtwire::fem
