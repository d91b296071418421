#include "campaign_report.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <fstream>
#include <iomanip>
#include <map>
#include <sstream>

#include "../cli.hpp"
#include "campaign_graph.hpp"
#include "critical_path.hpp"
#include "report_html.hpp"
#include "report_summary.hpp"
#include "dtwire/core/atomic_file.hpp"
#include "dtwire/core/provenance.hpp"

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

// Each step's time in this run, in the campaign's order (a skipped step counts with its recorded
// time; a step not run, 0).
std::vector<double> step_seconds(const Campaign& campaign, const std::vector<StepOutcome>& outcomes) {
  std::vector<double> seconds(campaign.steps.size(), 0.0);
  for (std::size_t i = 0; i < campaign.steps.size(); ++i) {
    const auto outcome = std::find_if(outcomes.begin(), outcomes.end(),
                                      [&](const StepOutcome& o) { return o.name == campaign.steps[i].name; });
    if (outcome != outcomes.end()) seconds[i] = outcome->seconds;
  }
  return seconds;
}

// The chain of steps that bounds the wall time on any number of cores.
std::string critical_path_markdown(const Campaign& campaign, const std::vector<double>& seconds,
                                   const CriticalPath& path) {
  double summed = 0.0;
  for (const double s : seconds) summed += s;
  if (path.steps.empty() || !(path.seconds > 0.0)) return "";
  std::ostringstream md;
  md << std::fixed << std::setprecision(1) << "**Critical path**: " << path.seconds << " s of the " << summed
     << " s the steps took together: the longest chain of steps that wait for each other, so no number of "
        "cores runs this campaign in less (at most "
     << summed / path.seconds << " x faster than one step at a time). ";
  for (std::size_t k = 0; k < path.steps.size(); ++k)
    md << (k ? " -> " : "") << "`" << campaign.steps[path.steps[k]].name << "` " << seconds[path.steps[k]] << " s";
  md << ".\n\n";
  return md.str();
}

}  // namespace

std::filesystem::path write_campaign_report(const Campaign& campaign,
                                            const std::vector<StepOutcome>& outcomes,
                                            const std::filesystem::path& out) {
  const auto campaign_dir = std::filesystem::absolute(campaign.file).parent_path();
  const std::string now = utc_now_iso8601();
  std::map<StepStatus, int> counts;
  for (const StepOutcome& o : outcomes) ++counts[o.status];
  std::ostringstream md;
  md << "# " << campaign.title << "\n\n"
     << "Campaign `" << campaign.name << "` (" << campaign.file.string() << "), run with "
     << version_string() << " on " << now << ": " << outcomes.size() << " steps";
  for (const auto& [status, count] : counts) md << ", " << count << " " << status_name(status);
  if (!campaign.variables.empty()) {
    md << "; variables";
    for (const auto& [name, value] : campaign.variables) {
      const bool set = std::find(campaign.overridden.begin(), campaign.overridden.end(), name) != campaign.overridden.end();
      md << " `" << name << " = " << value << "`" << (set ? " (--var)" : " (default)");
    }
  }
  md << ". The summary comes first; every step's details, files and console log follow "
        "([steps](#steps)).\n\n";
  md << summary_markdown(campaign, outcomes, out);
  md << "## Steps\n\n| step | status | wall time (s) | note |\n|---|---|---|---|\n";
  for (const StepOutcome& o : outcomes)
    md << "| [" << o.name << "](#" << heading_anchor(o.name) << ") | " << status_name(o.status) << " | "
       << std::fixed << std::setprecision(2) << o.seconds << std::defaultfloat << " | " << o.message << " |\n";
  const std::vector<double> seconds = step_seconds(campaign, outcomes);
  const CriticalPath critical = critical_path(step_dependencies(campaign), seconds);
  md << "\n" << critical_path_markdown(campaign, seconds, critical);
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
    const auto log = step_folder(out, step.name) / "output.log";
    if (std::filesystem::exists(log)) {
      const auto relative = std::filesystem::relative(log, out).string();
      md << "Console log: [`" << relative << "`](" << relative << ").\n\n";
    }
    for (const auto& item : step.report) md << embed(expand(item, out, campaign_dir), out);
    md << "\n";
  }
  const auto report = out / "report.md";
  write_file_atomically(report, [&](std::ostream& stream) { stream << md.str(); });
  write_file_atomically(out / "report.html",
                        [&](std::ostream& stream) { stream << markdown_to_html(md.str(), campaign.title, out); });

  nlohmann::json provenance = {{"tool_version", tool_version()},
                               {"git_hash", git_hash()},
                               {"created_utc", now},
                               {"campaign_file", campaign.file.string()},
                               {"campaign_sha256", sha256_file(campaign.file)}};
  for (const StepOutcome& o : outcomes)
    provenance["steps"][o.name] = {{"status", status_name(o.status)}, {"seconds", o.seconds}};
  provenance["critical_path"]["seconds"] = critical.seconds;
  provenance["critical_path"]["steps"] = nlohmann::json::array();
  for (const std::size_t i : critical.steps) provenance["critical_path"]["steps"].push_back(campaign.steps[i].name);
  write_file_atomically(out / "provenance.json",
                        [&](std::ostream& stream) { stream << provenance.dump(2) << "\n"; });
  return report;
}

}  // namespace dtwire::app
