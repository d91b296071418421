#pragma once
// What `dtwire dem propagate` found, and the files it writes from it (formats in
// docs/reference.md, "dem propagate outputs"): summary.json, samples.csv, convergence.csv,
// sensitivity.csv, band_curve.csv, band.png and report.md.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "dtwire/calibrate/band_statistics.hpp"
#include "dtwire/calibrate/emulator.hpp"
#include "dtwire/core/curve.hpp"
#include "propagation_runs.hpp"

namespace dtwire::app {

struct PropagatedParameter {
  std::string name;  // tag-qualified ("sw.N0_N", "dt.EA_N")
  std::string unit;
  std::string fit_file;
  double value = 0.0, lower = 0.0, upper = 0.0;
  bool identified = false;
  bool normal = false;       // sampled from the covariance (else uniform over [lower, upper])
  bool logarithmic = false;  // the coordinate is ln(value)
  double coordinate_sd = 0.0;
};

struct LinearisedFigure {
  std::vector<double> gradient;      // d figure / d coordinate; NaN where no step was admissible
  std::vector<double> step;          // the coordinate step used (signed)
  std::vector<double> share;         // g_i^2 C_ii / var (diagonal share)
  double sd = 0.0;
};

// One figure's band from the Gaussian-process emulator trained on the runs so far
// (propagation_emulator.hpp).
struct EmulatedFigure {
  std::size_t training = 0;  // runs it was trained on
  calibrate::EmulatedBand band;
  bool logarithmic = false;  // trained on ln f (every run's figure > 0); Q^2 and noise sd of ln f
  double q_squared = 0.0, share_within_two_sd = 0.0, noise_sd = 0.0;
  std::vector<double> length_scales;  // per parameter, in its sampled spread
};

struct ConvergenceRow {
  std::size_t count = 0;
  std::vector<calibrate::BandStatistics> figures;
  std::vector<std::optional<EmulatedFigure>> emulated;  // per figure; empty without --emulator
};

struct PropagationResult {
  std::filesystem::path run_file;
  std::string tool, label, mode;
  std::uint64_t seed = 1;
  double tolerance = 0.1;
  std::size_t requested = 0;  // 0: auto
  std::size_t max_samples = 0;
  std::vector<HeadlineFigure> figures;
  std::vector<PropagatedParameter> parameters;
  std::vector<std::vector<double>> coordinate_covariance;  // of all parameters, block-diagonal per fit
  std::vector<double> base_figures;  // at the fitted values
  Curve base_curve;
  std::vector<std::vector<double>> sample_values;  // per drawn set: own values
  std::vector<std::vector<double>> sample_figures;  // per drawn set (NaN where undefined)
  std::vector<std::string> sample_status;           // "ok" or the failed check
  std::vector<Curve> sample_curves;                 // successful sets only
  std::vector<ConvergenceRow> convergence;
  std::vector<calibrate::BandStatistics> band;  // at the last row
  std::vector<bool> converged;
  std::optional<std::vector<LinearisedFigure>> linearised;
  // --emulator: the emulated band after the last batch, whether it converged (its ends moved by
  // at most tolerance x its width over each of the last two batches), and the emulated sets.
  bool emulator = false;
  std::size_t emulated_sets = 0, emulator_minimum_training = 0;
  std::vector<std::optional<EmulatedFigure>> emulated;
  std::vector<bool> emulator_converged;
  std::size_t accepted = 0, refused = 0;
  int runs_done = 0, cache_hits = 0;
  double wall_seconds = 0.0;
  std::vector<std::string> notes;
};

// The values of figure f over the successful sets (finite ones).
std::vector<double> figure_values(const PropagationResult& r, std::size_t f);

void write_propagation_outputs(const PropagationResult& r, const std::filesystem::path& out, bool plot);

}  // namespace dtwire::app
