#pragma once
// The DEM runner of `dtwire gap --model F.toml` (issue 35): the mesh-level effects of gap's
// catalogue (test "mesh") switched on in a `dtwire dem run` input (punch or strip tension)
// through `--set` entries, one small function per effect in gap_dem_model.cpp, the run done as a
// subprocess and the tool's force-displacement curve read back. A DEM punch costs minutes, so
// every run is kept in a cache folder under a key made of the input's text, its parameter
// files, the entries and dtwire's version: an interrupted diagnosis, or a selfcheck asking for
// a run it already has, picks it up instead of running it again.
#include <filesystem>
#include <string>
#include <vector>

#include "dtwire/dem/run.hpp"
#include "gap_model_runner.hpp"

namespace dtwire::app {

struct DemModelOptions {
  std::vector<std::string> set;         // `dem run --set` entries of the base model
  std::vector<std::string> set_params;  // `dem run --set-params TAG=FILE` of the base model
  std::filesystem::path cache;          // run folders; empty: a temporary folder, removed at the end
  // Threads of the base run (no effect switched on), which a diagnosis makes alone before its
  // searches; the searches' runs take one thread each (`--jobs` of them side by side). A run's
  // curve does not depend on its thread count (the engine's sums run in a fixed order), so the
  // count is not part of the cache key.
  unsigned base_threads = 1;
};

// The base model as `dem run` reads it (InputError naming file:line, the entry or the option
// for a bad input, before any run).
dem::RunInput read_dem_model(const std::filesystem::path& toml, const DemModelOptions& options);

// Why `effect` cannot be switched on in this input ("" when it can).
std::string dem_effect_unsupported(const std::string& effect, const dem::RunInput& base);

// The `--set` entries that switch `effects` on (exposed for tests). Throws ComputationError for
// an effect the input cannot express.
std::vector<std::string> dem_effect_entries(const dem::RunInput& base,
                                            const std::vector<gap::AppliedEffect>& effects);

SimulationModel make_dem_model(const std::filesystem::path& toml, const DemModelOptions& options);

}  // namespace dtwire::app
