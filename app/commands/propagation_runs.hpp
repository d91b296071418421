#pragma once
// The DEM runs of `dtwire dem propagate`: one `dtwire dem run` subprocess per parameter set,
// each with the sets written as calibrate-format parameter files (the fit's own file with the
// drawn values in place), kept in a cache folder under a key made of dtwire's version, the run
// file's text, the `--set` entries and the parameter files' text: a second propagation (more
// samples, a resumed one, the linearised pass of the same fit) reuses every run it has.
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "dtwire/core/curve.hpp"

namespace dtwire::app {

// The headline figures of one tool, read from summary.json.
struct HeadlineFigure {
  std::string key;    // summary.json key
  std::string label;  // for tables
  std::string unit;   // as printed
  double factor = 1;  // summary value x factor = the figure in `unit`
  std::string column;  // CSV column name, with the unit
};
std::vector<HeadlineFigure> headline_figures(const std::string& tool);

// The curve whose band is drawn: x and y quantities of curve.csv.
struct CurveAxes {
  std::string x, y;
};
CurveAxes band_curve_axes(const std::string& tool);

struct RunOutcome {
  bool ok = false;        // finished without a failed check
  std::string status;     // "ok" or the run's failed check
  std::vector<double> figures;  // headline_figures order; NaN where undefined
  Curve curve;
  std::filesystem::path folder;
  bool cached = false;
};

class PropagationRunner {
 public:
  // `base_arguments`: `dem run FILE --set ...` (without --set-params, -o); `identity`: text
  // naming what else makes a run (version, run file text, entries).
  PropagationRunner(std::filesystem::path cache, std::vector<std::string> base_arguments, std::string identity,
                    std::vector<HeadlineFigure> figures);

  // Runs (or takes from the cache) one set: tag -> parameter file text. Thread-safe.
  RunOutcome run(const std::map<std::string, std::string>& parameter_files, const std::string& label);

  // Runs every set on `jobs` threads, in order of the result.
  std::vector<RunOutcome> run_all(const std::vector<std::map<std::string, std::string>>& sets,
                                  const std::vector<std::string>& labels, unsigned jobs);

  // The run folder's name for a set: SHA-256 of the identity, the arguments and the files.
  std::string key(const std::map<std::string, std::string>& parameter_files) const;

  int runs_done() const { return runs_done_; }
  int cache_hits() const { return cache_hits_; }

 private:
  std::filesystem::path cache_;
  std::vector<std::string> base_arguments_;
  std::string identity_;
  std::vector<HeadlineFigure> figures_;
  std::mutex mutex_;
  int runs_done_ = 0, cache_hits_ = 0;
};

}  // namespace dtwire::app
