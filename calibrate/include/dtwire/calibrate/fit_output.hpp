#pragma once
// Writes a finished fit: <out>/parameters.json (read by `dtwire export`), <out>/parameters.h5
// (results store: parameters with unit and sigma, target and fitted curves, provenance),
// <out>/curves/<experiment>_{target,fitted}.csv and <out>/fit_report.md. Formats:
// docs/calibrate.md. Every file is written atomically; no NaN is written. parameters.json comes
// last; if a write fails (no space, file-size limit, I/O error) the files this call wrote are
// removed again and the error is rethrown, so the folder never shows a partial fit as finished
// (its checkpoint stays: `dtwire fit --resume` writes them once the cause is gone).
#include <filesystem>

#include "dtwire/calibrate/fit_file.hpp"
#include "dtwire/calibrate/fitter.hpp"
#include "dtwire/core/provenance.hpp"

namespace dtwire::calibrate {

void write_fit_outputs(const FitDefinition& definition, const FitResult& result,
                       const Provenance& provenance, const std::filesystem::path& out);

}  // namespace dtwire::calibrate
