#pragma once
// The FE runner of `dtwire gap --model M.prm`: re-runs the experiment through `dtwire run` as a
// subprocess (calibrate's CommandSimulator) on a copy of the .prm with the model-only effects
// switched on through its parameters (one effect per file in app/gap_model/). gap does not depend
// on fem; this lives in app/.
#include <filesystem>
#include <functional>
#include <map>
#include <string>

#include "dtwire/core/curve.hpp"
#include "dtwire/core/prm_document.hpp"
#include "dtwire/gap/effects.hpp"
#include "gap_model/model_effect.hpp"

namespace dtwire::app {

struct SimulationModel {
  gap::ModelRunner run;  // cached by the edited .prm text; each new run prints one line
  // The same runs as the whole curve (every channel and the metadata, e.g. the failure).
  std::function<Curve(const std::vector<gap::AppliedEffect>&)> run_curve;
  std::map<std::string, std::string> unsupported;  // model-only effect -> reason
  int* runs = nullptr;                              // FE runs done so far
  std::filesystem::path work;                       // run directories (removed after success)
};

// Reads the .prm as a typed document and checks its names against the solver's declarations
// (InputError naming file:line for an unknown entry or a value that is not a number). Runs go to `work` (a fresh temp
// directory when empty); each run's directory is removed after success. `settings` ("Section/Entry=value",
// `--model-set`) change the model itself before any effect: the base every run starts from. With a
// `cache_directory` every finished run's curve is kept there under a key of the edited .prm, the
// mesh file and the solver's version, and taken from there by a later command (an interrupted
// diagnosis resumes; another one asking for the same run does not run it again).
SimulationModel make_fe_model(const std::filesystem::path& prm, std::filesystem::path work = {},
                              const std::vector<std::string>& settings = {},
                              const std::filesystem::path& cache_directory = {});

// The .prm with the effects switched on (exposed for tests): `Fields` off, a relative mesh file
// made absolute, then each effect's edits (app/gap_model/). `declared` holds the solver's
// defaults. Throws ComputationError for an effect the .prm cannot express.
PrmDocument edit_prm(const PrmDocument& model, const PrmDocument& declared,
                     const std::vector<gap::AppliedEffect>& effects, const std::filesystem::path& prm_directory,
                     const GripBond& grip = {});

// The entries `dtwire run` reads with their defaults: from `$DTWIRE_FE_EXECUTABLE parameters`
// when set, else from the FE solver linked into this executable (InputError naming what is
// missing when neither).
PrmDocument solver_declarations();

}  // namespace dtwire::app
