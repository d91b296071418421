#include "campaign_report.hpp"

#include <nlohmann/json.hpp>

#include <fstream>
#include <iomanip>
#include <sstream>

#include "../cli.hpp"
#include "dtwire/core/atomic_file.hpp"
#include "dtwire/core/provenance.hpp"
#include "dtwire/version.hpp"

namespace dtwire::app {
namespace {

std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// A report item: Markdown is inlined, images are shown, anything else is linked.
std::string embed(const std::filesystem::path& item, const std::filesystem::path& out) {
  const auto relative = std::filesystem::relative(item, out).string();
  if (!std::filesystem::exists(item)) return "- (missing: `" + relative + "`)\n";
  const auto ext = item.extension().string();
  if (ext == ".md") return read_text(item) + "\n";
  if (ext == ".png" || ext == ".svg") return "![" + item.stem().string() + "](" + relative + ")\n\n";
  return "- [`" + relative + "`](" + relative + ")\n";
}

}  // namespace

std::filesystem::path write_campaign_report(const Campaign& campaign,
                                            const std::vector<StepOutcome>& outcomes,
                                            const std::filesystem::path& out) {
  const auto campaign_dir = std::filesystem::absolute(campaign.file).parent_path();
  const std::string now = utc_now_iso8601();
  std::ostringstream md;
  md << "# " << campaign.title << "\n\n"
     << "Campaign `" << campaign.name << "` (" << campaign.file.string() << "), run with "
     << version_string() << " on " << now << ".\n\n"
     << "## Steps\n\n| step | status | wall time (s) | note |\n|---|---|---|---|\n";
  for (const StepOutcome& o : outcomes)
    md << "| " << o.name << " | " << status_name(o.status) << " | " << std::fixed
       << std::setprecision(2) << o.seconds << " | " << o.message << " |\n";
  md << "\n";
  for (const CampaignStep& step : campaign.steps) {
    const auto outcome = std::find_if(outcomes.begin(), outcomes.end(),
                                      [&](const StepOutcome& o) { return o.name == step.name; });
    if (outcome == outcomes.end()) continue;
    md << "## " << step.name << "\n\n";
    if (!step.description.empty()) md << step.description << "\n\n";
    if (outcome->status == StepStatus::Unavailable || outcome->status == StepStatus::Blocked) {
      md << "Not run: " << outcome->message << ".\n\n";
      continue;
    }
    for (const auto& item : step.report) md << embed(expand(item, out, campaign_dir), out);
    md << "\n";
  }
  const auto report = out / "report.md";
  write_file_atomically(report, [&](std::ostream& stream) { stream << md.str(); });

  nlohmann::json provenance = {{"tool_version", kVersion},
                               {"git_hash", kGitHash},
                               {"created_utc", now},
                               {"campaign_file", campaign.file.string()},
                               {"campaign_sha256", sha256_file(campaign.file)}};
  for (const StepOutcome& o : outcomes)
    provenance["steps"][o.name] = {{"status", status_name(o.status)}, {"seconds", o.seconds}};
  write_file_atomically(out / "provenance.json",
                        [&](std::ostream& stream) { stream << provenance.dump(2) << "\n"; });
  return report;
}

}  // namespace dtwire::app
