#pragma once
// The human-readable campaign report, Markdown (report.md) and the same as one self-contained
// page (report.html), and its provenance (JSON), written to the output directory. The report
// opens with the summary (report_summary.hpp); the per-step details follow.
#include <filesystem>
#include <vector>

#include "campaign_file.hpp"
#include "campaign_runner.hpp"

namespace dtwire::app {

// Returns the path of report.md.
std::filesystem::path write_campaign_report(const Campaign& campaign,
                                            const std::vector<StepOutcome>& outcomes,
                                            const std::filesystem::path& out);

}  // namespace dtwire::app
