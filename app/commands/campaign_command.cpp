#include <CLI/CLI.hpp>

#include <iostream>

#include "../campaign/campaign_file.hpp"
#include "../campaign/campaign_lock.hpp"
#include "../campaign/campaign_report.hpp"
#include "../campaign/campaign_runner.hpp"
#include "../cli.hpp"
#include "../commands.hpp"
#include "../data_path.hpp"
#include "dtwire/core/error.hpp"
#include "dtwire/version.hpp"

namespace dtwire::app {

void add_campaign_command(CLI::App& root, CommandSet& commands) {
  struct Options {
    std::string file;
    std::string out;
    bool force = false;
    std::vector<std::string> only;
    std::vector<std::string> variables;
    int jobs = 1;
  };
  auto options = std::make_shared<Options>();
  options->file = data_path("experiments/default/campaign.toml").string();
  CLI::App* command = root.add_subcommand(
      "campaign", "Run a whole study (mesh, FE, fits, export, gap) and write a report");
  command->add_option("file", options->file, "Campaign file (.toml)")->capture_default_str();
  command->add_option("-o,--out", options->out,
                      "Output directory (default: campaign-out/<campaign name>)");
  command->add_flag("--force", options->force, "Re-run every step, even up-to-date ones");
  command->add_option("--only", options->only, "Run only these steps (names)");
  command->add_option("--var", options->variables,
                      "NAME=VALUE: a variable of the campaign file's [variables] (the default campaign: "
                      "as_made=true starts every DT FE step from the as-made state)");
  command->add_option("-j,--jobs", options->jobs,
                      "Cores for steps side by side: a step starts when the steps it reads from are "
                      "done and its `threads` fit (default 1: one step at a time, in order)")
      ->check(CLI::Range(1, 4096));
  commands.add(command, [options] {
    Campaign campaign = read_campaign(options->file);
    apply_variables(campaign, options->variables);
    CampaignOptions run_options;
    run_options.out = options->out.empty() ? std::filesystem::path("campaign-out") / campaign.name
                                           : std::filesystem::path(options->out);
    run_options.force = options->force;
    run_options.only = options->only;
    for (const auto& name : options->only) {
      const bool known = std::any_of(campaign.steps.begin(), campaign.steps.end(),
                                     [&](const CampaignStep& s) { return s.name == name; });
      if (!known) throw InputError(options->file, "--only names unknown step '" + name + "'");
    }
    check_commands(campaign, command_names());
    run_options.executable = executable_path();
    run_options.jobs = options->jobs;
    const CampaignLock lock(run_options.out);
    if (!lock.stale_note().empty())
      std::cerr << "campaign: a stale lock in " << run_options.out.string() << " (" << lock.stale_note()
                << ") shows an earlier campaign that did not finish; taking over\n";
    const auto outcomes = run_campaign(campaign, run_options);
    const auto report = write_campaign_report(campaign, outcomes, run_options.out);
    std::size_t failed = 0, unavailable = 0, blocked = 0;
    for (const auto& o : outcomes) {
      failed += o.status == StepStatus::Failed;
      unavailable += o.status == StepStatus::Unavailable;
      blocked += o.status == StepStatus::Blocked;
    }
    std::cout << "campaign " << campaign.name << ": " << outcomes.size() << " step(s), " << failed
              << " failed, " << blocked << " blocked, " << unavailable
              << " not in this build; report: " << report.string() << "\n";
    return failed || blocked ? kExitFailure : 0;
  });
}

}  // namespace dtwire::app
