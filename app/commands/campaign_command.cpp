#include <CLI/CLI.hpp>

#include <algorithm>
#include <iostream>

#include "../campaign/campaign_file.hpp"
#include "../campaign/campaign_lock.hpp"
#include "../campaign/interruption.hpp"
#include "../campaign/campaign_report.hpp"
#include "../campaign/campaign_runner.hpp"
#include "../campaign/recorded_outcomes.hpp"
#include "../campaign/snakefile.hpp"
#include "../cli.hpp"
#include "../commands.hpp"
#include "../data_path.hpp"
#include "dtwire/core/atomic_file.hpp"
#include "dtwire/core/error.hpp"

namespace dtwire::app {
namespace {

// --snakefile: the workflow instead of a run. Refuses a path that exists and is not a file; makes
// the file's folder if it does not exist yet (as -o makes the output folder).
int write_snakefile(const Campaign& campaign, const std::filesystem::path& out, const std::string& file,
                    const std::vector<std::string>& variables) {
  if (std::filesystem::exists(file) && !std::filesystem::is_regular_file(file))
    throw InputError("--snakefile", "'" + file + "' exists and is not a file");
  check_external_inputs(campaign, out);
  const auto folder = std::filesystem::absolute(file).parent_path();
  std::error_code made;
  std::filesystem::create_directories(folder, made);
  if (made || !std::filesystem::is_directory(folder))
    throw InputError("--snakefile", "cannot make the folder '" + folder.string() + "' for '" + file + "'" +
                                        (made ? ": " + made.message() : ": a file of that name is in the way"));
  SnakefileOptions options{std::filesystem::absolute(out).lexically_normal(), executable_path(), variables};
  for (const CampaignStep& step : campaign.steps)
    if (!command_available(step.command.front()))
      std::cerr << "campaign: step '" << step.name << "': 'dtwire " << step.command.front()
                << "' is compiled out of this build; the workflow runs it with " << options.executable.string()
                << " all the same\n";
  write_file_atomically(file, [&](std::ostream& stream) { stream << snakefile_text(campaign, options); });
  std::cout << "campaign " << campaign.name << ": " << campaign.steps.size() << " step(s) written as "
            << file << "; run it with: snakemake -s " << file << " --cores N\n";
  return 0;
}

}  // namespace

void add_campaign_command(CLI::App& root, CommandSet& commands) {
  struct Options {
    std::string file;
    std::string out;
    bool force = false;
    std::vector<std::string> only;
    std::vector<std::string> variables;
    int jobs = 1;
    std::string snakefile;
    bool report_only = false;
    bool study = false;
  };
  auto options = std::make_shared<Options>();
  options->file = data_path("experiments/default/campaign.toml").string();
  CLI::App* command = root.add_subcommand(
      "campaign", "Run a whole study (mesh, FE, fits, export, gap) and write a report");
  CLI::Option* file = command->add_option("file", options->file, "Campaign file (.toml)")->capture_default_str();
  command->add_flag("--study", options->study,
                    "Run the full study (experiments/study/campaign.toml: the default campaign and every other "
                    "parameter set, the DT link fits, WirePM, the self-checks) instead of the default campaign")
      ->excludes(file);
  command->add_option("-o,--out", options->out,
                      "Output directory (default: campaign-out/<campaign name>)");
  command->add_flag("--force", options->force, "Re-run every step, even up-to-date ones");
  command->add_option("--only", options->only, "Run only these steps (names)");
  command->add_option("--var", options->variables,
                      "NAME=VALUE: a variable of the campaign file's [variables] (the default campaign: "
                      "as_made=true starts every DT FE step from the as-made state)");
  CLI::Option* jobs = command->add_option("-j,--jobs", options->jobs,
                      "Cores for steps side by side: a step starts when the steps it reads from are "
                      "done and its `threads` fit (default 1: one step at a time, in order)")
      ->check(CLI::Range(1, 4096));
  CLI::Option* snakefile = command->add_option(
      "--snakefile", options->snakefile,
      "Instead of running: write the campaign as a Snakemake workflow to this file (run it with "
      "`snakemake -s FILE --cores N` or a cluster profile)");
  CLI::Option* report_only = command->add_flag(
      "--report-only", options->report_only,
      "Run nothing: write the report from the outputs in the output directory (the last rule of "
      "the --snakefile workflow)");
  snakefile->excludes(report_only)->excludes(jobs);
  report_only->excludes(jobs);
  for (const char* run_only : {"--force", "--only"}) {
    command->get_option(run_only)->excludes(snakefile);
    command->get_option(run_only)->excludes(report_only);
  }
  commands.add(command, [options] {
    if (options->study) options->file = data_path("experiments/study/campaign.toml").string();
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
    if (!options->snakefile.empty())
      return write_snakefile(campaign, run_options.out, options->snakefile, options->variables);
    if (options->report_only && !std::filesystem::is_directory(run_options.out))
      throw InputError("--report-only", "no output directory " + run_options.out.string() + " to report on");
    if (options->report_only) {
      const auto recorded = recorded_outcomes(campaign, run_options.out);
      if (std::all_of(recorded.begin(), recorded.end(), [](const StepOutcome& o) {
            return o.status == StepStatus::Blocked || o.status == StepStatus::Unavailable;
          }))
        throw InputError("--report-only", "no step of campaign '" + campaign.name + "' has its outputs in " +
                                              run_options.out.string() +
                                              ": nothing to report (run the campaign into it first)");
    }
    CampaignLock lock(run_options.out);
    run_options.lock = &lock;
    if (!lock.stale_note().empty())
      std::cerr << "campaign: a stale lock in " << run_options.out.string() << " (" << lock.stale_note()
                << ") shows an earlier campaign that did not finish; taking over\n";
    const InterruptionGuard interruption;
    const auto outcomes = options->report_only ? recorded_outcomes(campaign, run_options.out)
                                               : run_campaign(campaign, run_options);
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
    if (const int signal = interruption_signal(); signal != 0) {
      std::cerr << "campaign interrupted (signal " << signal << "): the running steps were stopped and nothing new "
                << "started; the same command resumes, skipping the finished steps\n";
      return 128 + signal;
    }
    return failed || blocked ? kExitFailure : 0;
  });
}

}  // namespace dtwire::app
