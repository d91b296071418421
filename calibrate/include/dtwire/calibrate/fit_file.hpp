#pragma once
// Fit definition files (TOML; format in docs/calibrate.md): the simulator (law and load paths,
// or the analytic Voce bar), target curves (CSV), fitted parameters with bounds and initial
// values, weights, loss, multi-start. Errors name file:line:column and the field.
#include <filesystem>
#include <string>
#include <vector>

#include "dtwire/calibrate/column_map.hpp"
#include "dtwire/calibrate/evaluation.hpp"
#include "dtwire/calibrate/fitter.hpp"
#include "dtwire/dem/contact_law.hpp"

namespace dtwire::calibrate {

struct FitDefinition {
  std::filesystem::path file;
  std::string title;
  std::string simulator;  // "law_replay", "command" or "voce_bar"
  std::string law;        // law_replay: contact law name; written to parameters.json
  std::string wire_type;  // written to parameters.json ("single_wire", "double_twist", ...)
  dem::ParameterMap fixed;  // law parameters that are not fitted
  std::vector<ParameterDefinition> parameters;
  std::vector<Experiment> experiments;
  std::vector<std::filesystem::path> experiment_targets;  // target CSV per experiment
  // Per experiment: where `dtwire fit --synthesize DIR` writes its target, relative to DIR
  // (the path after {targets}/, else the file name), and how its columns are mapped.
  std::vector<std::filesystem::path> experiment_target_names;
  std::vector<std::vector<ColumnMapping>> experiment_columns;
  EvaluationOptions evaluation;
  bool disk_cache = false;  // keep simulated curves as files (worth it for FE runs)
  FitOptions fit;                                  // checkpoint/progress set by the caller
  std::vector<std::filesystem::path> inputs;       // every file read (for provenance)
};

struct FitReadOptions {
  // false: the target CSVs are not read (for generating synthetic targets); experiments then
  // have empty target curves.
  bool read_targets = true;
  // Replaces the placeholder {targets} at the start of `target` paths (e.g. the folder where a
  // campaign wrote its FE curves); empty: not given.
  std::filesystem::path targets_directory;
  // Non-empty: only these experiments are read (their targets too); the others are skipped, so
  // a fit of part of a file (`fit --experiments`) does not need the rest's target files. A name
  // the file does not have is an InputError listing the file's experiments.
  std::vector<std::string> only_experiments;
};

// Throws InputError (file:line:column, field, what was expected) for any bad entry and for
// unreadable target files.
FitDefinition read_fit_file(const std::filesystem::path& file, const FitReadOptions& options = {});

}  // namespace dtwire::calibrate
