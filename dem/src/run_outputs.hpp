#pragma once
// What `dtwire dem run` writes (docs/dem_engine.md): curve.csv and results.h5 (history with
// provenance), link_force_histogram.csv and pulling_angle_histogram.csv (at the peak force and
// at the end), membrane_at_peak.csv (a platter's radial sections, membrane_sections.hpp), the
// per-type link records (link_records.hpp), frames/net_<k>.vtu + net.pvd.
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "dtwire/core/results_store.hpp"
#include "dtwire/dem/membrane_sections.hpp"
#include "dtwire/dem/run.hpp"
#include "link_records.hpp"

namespace dtwire::dem {

// The run's engine figures every results.h5 carries (time step, critical step, mass scale,
// damping, nodes, links), shared by the punch and the strip tension.
void add_engine_parameters(Results& results, const RunInput& input, const RunSummary& summary);

// "ok", or "failed: <the check's message>" (curve.csv and results.h5 metadata).
std::string run_status(const RunSummary& summary);
// summary.json's "status" ("ok" or "failed") and, for a failed run, "failed_check": the check,
// the key of its bound, the time and step, the value and the bound.
void add_status(nlohmann::json& headline, const RunSummary& summary);

class RunRecorder {
 public:
  RunRecorder(const RunInput& input, const HexMesh& mesh, const RunOptions& options);
  // `mean_force`: the tool's force on the net averaged over the output interval.
  void record(const Engine& engine, double time, double displacement, double velocity, const Vector3& mean_force);
  void frame(const Engine& engine, double time);
  // net.pvd listing the frames written so far (finish writes it; the strip tension calls it alone).
  void write_frame_index() const;
  // Writes every file; fills summary's curve figures.
  void finish(const Engine& engine, RunSummary& summary);

 private:
  struct Snapshot {
    std::vector<double> link_forces, pulling_angles;
    std::vector<MembraneSection> sections;  // platter runs
  };
  Snapshot snapshot(const Engine& engine) const;

  const RunInput& input_;
  const HexMesh& mesh_;
  RunOptions options_;
  std::vector<std::vector<double>> columns_;
  Snapshot at_peak_;
  double peak_force_ = -1.0, peak_instant_force_ = 0.0;
  LinkRecorder links_;
  std::vector<std::pair<double, std::string>> frames_;
  // DT pulling angle pairs: (DT link, SW link, the DT end node they share).
  struct AnglePair {
    int twist, wire, node;
  };
  std::vector<AnglePair> angle_pairs_;
  // A platter's section radii: from just outside its base to 0.1 m inside the nearest edge.
  std::vector<double> section_radii_;
};

}  // namespace dtwire::dem
