#pragma once
// `dtwire campaign --report-only`: the outcomes of steps that ran elsewhere (a Snakemake
// workflow, snakefile.hpp, or an earlier campaign), judged from what is on disk, so that the
// report can be written without running anything.
#include <filesystem>
#include <vector>

#include "campaign_file.hpp"
#include "campaign_runner.hpp"

namespace dtwire::app {

// Per step: done if all its outputs exist (its wall time from the campaign state, else from
// Snakemake's steps/<step>/benchmark.tsv, else the state's time recorded with other inputs,
// else 0), not in this build if compiled out and without outputs, else blocked naming the
// first missing output. Steps done outside the runner
// are recorded in the campaign state, so that a later `dtwire campaign` skips them.
std::vector<StepOutcome> recorded_outcomes(const Campaign& campaign, const std::filesystem::path& out);

}  // namespace dtwire::app
