#pragma once
// The diagnosis of curves from several loading modes (tension, compression, bending, ...): one
// diagnosis per mode, and a combined one in which each effect is fitted jointly on the curves of
// every mode it applies to (test-setup effects with one parameter set per mode, specimen
// effects with one set over all modes; loading_mode.hpp).
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "dtwire/gap/diagnosis.hpp"

namespace dtwire::gap {

struct ModeInput {
  std::string mode;   // a name of loading_mode_names()
  std::string basis;  // how the mode was found
  std::vector<ForceCurve> labs;
  ForceCurve sim;
  ModelRunner model;  // --model of this mode, or empty
  std::map<std::string, std::string> model_unsupported;
};

struct ModeDiagnosis {
  std::string mode, basis;
  Diagnosis diagnosis;
};

struct MultiModeDiagnosis {
  Diagnosis combined;  // the top level of the JSON (the same as the mode's with one mode)
  std::vector<ModeDiagnosis> modes;
};

// `options.model` and `options.model_unsupported` are ignored (each mode brings its own).
// Throws InputError for a mode given twice or without curves.
MultiModeDiagnosis diagnose_modes(const std::vector<ModeInput>& modes, const DiagnosisOptions& options);

// diagnosis_json of the combined diagnosis plus "modes": [{"mode", "basis", "curves", and the
// keys of diagnosis_json of that mode}].
nlohmann::json multimode_json(const MultiModeDiagnosis& d);
std::string multimode_markdown(const MultiModeDiagnosis& d);

// Pairs in the combined ranking are tried among this many best single effects.
inline constexpr std::size_t kCombinedPairCandidates = 4;

}  // namespace dtwire::gap
