#pragma once
// `dtwire run FILE.prm`: a virtual single-wire FE experiment (finite-strain J2 plasticity,
// deal.II). This header is deal.II-free so that the command line compiles fast.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace dtwire::fem {

struct RunOptions {
  std::filesystem::path parameter_file;
  std::vector<std::string> settings;       // "Section/Entry=value" overrides of the file (--set)
  std::filesystem::path output_directory;  // curve.csv, results.h5, run.log, fields/
  std::string command_line;                // recorded in the provenance
  bool echo = true;                        // progress on stdout (rank 0)
  int restart_step = -1;                   // >= 0: resume from output_directory/checkpoints/step_N
  // The memory a run may take (bytes; none: the available memory): larger estimates are refused.
  std::optional<std::uint64_t> max_memory;
};

// Where an as-made run leaves the state its springback reached, for later runs' As made/State
// file (fem/src/solver_as_made_state.cpp).
inline constexpr const char* kAsMadeStateFile = "as_made_state.bin";
// What a twisting run's release leaves (As made/Release after path), for a DT mesh's twist.
inline constexpr const char* kTwistedPairStateFile = "twisted_pair_state.csv";

// As made (As made/Forming history = true): the springback before the load path; or the release
// after it (As made/Release after path = true).
struct SpringbackSummary {
  bool done = false;
  bool from_state_file = false;  // read from As made/State file: the figures are that run's
  double energy_balance = 0.0;  // relative: |W0 + holding work - elastic - plastic - friction| / W0
  double largest_displacement_mm = 0.0, clearance_mean_mm = 0.0, clearance_largest_mm = 0.0, seconds = 0.0;
  double top_rotation_rad = 0.0;  // of the top end about the Rotation axis while it was let go
};

struct RunSummary {
  bool root = true;  // this process is MPI rank 0 (the one that wrote the files)
  unsigned ranks = 1;
  std::size_t dofs = 0, cells = 0;
  std::size_t steps = 0, newton_iterations = 0, cutbacks = 0;
  double peak_force_N = 0.0, displacement_at_peak_mm = 0.0;  // force of largest magnitude (signed)
  double wall_seconds = 0.0, assembly_seconds = 0.0, solve_seconds = 0.0;
  std::filesystem::path curve_csv, results_h5, log;
  SpringbackSummary springback;
};

// MPI must already be initialised (tests, benchmarks). Throws InputError for a bad .prm and
// ComputationError if the load stepping falls below its minimum step (the converged part of
// the curve is then written to curve.partial.csv).
RunSummary run_experiment(const RunOptions& options);

// For the command line: initialises MPI, PETSc and threads (deal.II MPI_InitFinalize) for the
// duration of the call, then run_experiment.
RunSummary run_experiment_with_mpi(const RunOptions& options);

// Every entry `dtwire run` reads, with its default, as a .prm listing (deal.II ShortPRM); with
// `documented`, each entry's documentation and allowed values too (deal.II PRM).
std::string parameter_listing(bool documented);

}  // namespace dtwire::fem
