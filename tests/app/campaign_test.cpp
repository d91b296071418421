#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <iterator>
#include <thread>

#include "campaign/campaign_file.hpp"
#include "campaign/campaign_lock.hpp"
#include "campaign/campaign_report.hpp"
#include "campaign/campaign_runner.hpp"
#include "campaign/report_summary.hpp"
#include "cli.hpp"
#include "dtwire/core/error.hpp"

namespace dtwire::app {
namespace {

pid_t ended_group() {
  const pid_t pid = ::fork();
  if (pid == 0) ::_exit(0);
  ::waitpid(pid, nullptr, 0);
  return pid;
}

std::filesystem::path write_temp(const std::string& name, const std::string& text) {
  const auto path = std::filesystem::temp_directory_path() / name;
  std::ofstream(path) << text;
  return path;
}

TEST(Campaign, DefaultCampaignParses) {
  const Campaign c =
      read_campaign(std::filesystem::path(DTWIRE_SOURCE_DIR) / "experiments/default/campaign.toml");
  EXPECT_EQ(c.name, "default");
  EXPECT_GE(c.steps.size(), 5u);
}

TEST(Campaign, MissingCommandIsNamedWithLine) {
  const auto file = write_temp("dtwire_bad_campaign.toml", "name = \"x\"\n[[step]]\nname = \"a\"\n");
  try {
    read_campaign(file);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 2) << e.what();
    EXPECT_NE(std::string(e.what()).find("'command'"), std::string::npos) << e.what();
  }
}

TEST(Campaign, TomlSyntaxErrorGivesLineAndColumn) {
  const auto file = write_temp("dtwire_syntax.toml", "name = \"x\"\nstep = [ 1, \n");
  try {
    read_campaign(file);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_GT(e.line(), 0) << e.what();
  }
}

TEST(Campaign, DuplicateStepNamesAreRejected) {
  const auto file = write_temp("dtwire_dup.toml",
                               "[[step]]\nname = \"a\"\ncommand = [\"campaign\", \"--help\"]\n"
                               "[[step]]\nname = \"a\"\ncommand = [\"campaign\", \"--help\"]\n");
  EXPECT_THROW(read_campaign(file), InputError);
}

CampaignOptions options_for(const std::filesystem::path& out) {
  CampaignOptions options;
  options.out = out;
  options.executable = DTWIRE_EXECUTABLE;
  return options;
}

std::string read_text(const std::filesystem::path& file) {
  std::ifstream in(file);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// The error's line and a fragment of its message.
void expect_refused(const std::filesystem::path& file, int line, const std::string& fragment) {
  try {
    read_campaign(file);
    FAIL() << "no error for " << file;
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), line) << e.what();
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

TEST(Campaign, RunsStepsAsChildProcessesWithLogsAndResumes) {
  const auto out = std::filesystem::temp_directory_path() / "dtwire_campaign_run";
  std::filesystem::remove_all(out);
  // A step that runs a (nested) campaign producing a report.
  const auto inner = write_temp("dtwire_inner.toml",
                                "name = \"inner\"\n[[step]]\nname = \"help\"\n"
                                "command = [\"campaign\", \"--help\"]\n");
  const auto outer = write_temp(
      "dtwire_outer.toml",
      "name = \"outer\"\n[[step]]\nname = \"inner_campaign\"\n"
      "command = [\"campaign\", \"" + inner.string() + "\", \"-o\", \"{out}/inner\"]\n"
      "inputs = [\"" + inner.string() + "\"]\n"
      "outputs = [\"{out}/inner/report.md\"]\nreport = [\"{out}/inner/report.md\"]\n");
  const Campaign campaign = read_campaign(outer);
  const auto first = run_campaign(campaign, options_for(out));
  ASSERT_EQ(first.size(), 1u);
  EXPECT_EQ(first[0].status, StepStatus::Done) << first[0].message;
  // The child's console output is in the step's log, not on the campaign's console.
  const std::string log = read_text(step_folder(out, "inner_campaign") / "output.log");
  EXPECT_NE(log.find("campaign inner: 1 step(s)"), std::string::npos) << log;
  const auto second = run_campaign(campaign, options_for(out));
  EXPECT_EQ(second[0].status, StepStatus::Skipped);  // resumed: same inputs, outputs present
  const auto report = write_campaign_report(campaign, second, out);
  const std::string text = read_text(report);
  EXPECT_LT(text.find("## Summary"), text.find("## Steps")) << "the summary comes first";
  EXPECT_NE(text.find("# inner"), std::string::npos);  // the inner report is embedded
  EXPECT_TRUE(std::filesystem::exists(out / "provenance.json"));
  EXPECT_NE(read_text(out / "report.html").find("id=\"summary\""), std::string::npos);
  std::filesystem::remove_all(out);
}

TEST(Campaign, UnknownCommandIsRefusedBeforeAnythingRuns) {
  const auto out = std::filesystem::temp_directory_path() / "dtwire_campaign_typo";
  std::filesystem::remove_all(out);
  const auto file = write_temp("dtwire_typo.toml",
                               "name = \"t\"\n[[step]]\nname = \"first\"\ncommand = [\"campaign\", \"--help\"]\n"
                               "[[step]]\nname = \"second\"\ncommand = [\"exprot\", \"--help\"]\n");
  try {
    run_campaign(read_campaign(file), options_for(out));
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 7) << e.what();
    EXPECT_NE(std::string(e.what()).find("did you mean 'export'"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(out / "campaign_state.json")) << "a step ran";
  // Through the command line: exit 2, and the file:line on stderr.
  EXPECT_EQ(run_command_line({"campaign", file.string(), "-o", out.string()}), kExitBadInput);
  std::filesystem::remove_all(out);
}

TEST(Campaign, UnknownFieldsAreRefusedWithTheClosestName) {
  expect_refused(write_temp("dtwire_field.toml", "name = \"f\"\n[[step]]\nname = \"a\"\n"
                                                 "command = [\"campaign\", \"--help\"]\ninptus = [\"x\"]\n"),
                 5, "did you mean 'inputs'");
  expect_refused(write_temp("dtwire_top.toml", "name = \"f\"\ntitel = \"x\"\n[[step]]\nname = \"a\"\n"
                                               "command = [\"campaign\", \"--help\"]\n"),
                 2, "did you mean 'title'");
}

TEST(Campaign, PlaceholderTypoIsRefusedNotMadeAFolder) {
  expect_refused(write_temp("dtwire_placeholder.toml",
                            "name = \"p\"\n[[step]]\nname = \"a\"\n"
                            "command = [\"campaign\", \"--help\"]\noutputs = [\"{ot}/x.csv\"]\n"),
                 5, "unknown placeholder '{ot}' (did you mean 'out'?)");
}

// [variables]: defaults from the file, --var overrides, placeholders checked against the names.
TEST(Campaign, VariablesExpandWithDefaultsAndOverrides) {
  const auto file = write_temp("dtwire_variables.toml",
                               "name = \"v\"\n[variables]\nas_made = \"false\"\n[[step]]\nname = \"a\"\n"
                               "command = [\"run\", \"x.prm\", \"--set\", \"As made/Forming history={as_made}\"]\n"
                               "outputs = [\"{out}/a_{as_made}\"]\n");
  Campaign defaults = read_campaign(file);
  apply_variables(defaults, {});
  EXPECT_EQ(defaults.steps[0].command[3], "As made/Forming history=false");
  EXPECT_EQ(defaults.steps[0].outputs[0], "{out}/a_false");
  Campaign set = read_campaign(file);
  apply_variables(set, {"as_made=true"});
  EXPECT_EQ(set.steps[0].command[3], "As made/Forming history=true");
  EXPECT_EQ(set.overridden, std::vector<std::string>{"as_made"});
  Campaign typo = read_campaign(file);
  try {
    apply_variables(typo, {"asmade=true"});
    FAIL() << "accepted an unknown variable";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("did you mean 'as_made'"), std::string::npos) << e.what();
  }
  EXPECT_THROW(apply_variables(typo, {"as_made"}), InputError);  // no '='
  // A step that uses an undeclared variable is refused at its line.
  expect_refused(write_temp("dtwire_undeclared.toml", "name = \"u\"\n[variables]\nas_made = \"false\"\n[[step]]\n"
                                                      "name = \"a\"\ncommand = [\"run\", \"{as_mad}\"]\n"),
                 6, "unknown placeholder '{as_mad}' (did you mean 'as_made'?)");
  expect_refused(write_temp("dtwire_not_string.toml", "name = \"u\"\n[variables]\nas_made = false\n[[step]]\n"
                                                      "name = \"a\"\ncommand = [\"run\"]\n"),
                 3, "must be a string");
}

TEST(Campaign, OutInputThatNoEarlierStepWritesIsRefused) {
  expect_refused(write_temp("dtwire_graph.toml",
                            "name = \"g\"\n[[step]]\nname = \"a\"\ncommand = [\"campaign\", \"--help\"]\n"
                            "inputs = [\"{out}/never_written.csv\"]\n"),
                 5, "written by no earlier step");
  // Written, but only by a later step: named.
  expect_refused(write_temp("dtwire_order.toml",
                            "name = \"g\"\n[[step]]\nname = \"a\"\ncommand = [\"campaign\", \"--help\"]\n"
                            "inputs = [\"{out}/later/x.csv\"]\n"
                            "[[step]]\nname = \"b\"\ncommand = [\"campaign\", \"--help\"]\n"
                            "outputs = [\"{out}/later\"]\n"),
                 5, "step 'b' writes it, after this one");
}

TEST(Campaign, DefaultCampaignGraphIsClosed) {
  // read_campaign refuses an {out} input that no earlier step writes; the commands are known.
  // The study includes the default campaign and holds the steps checked here.
  const Campaign c = read_campaign(std::filesystem::path(DTWIRE_SOURCE_DIR) / "experiments/study/campaign.toml");
  EXPECT_NO_THROW(check_commands(c, command_names()));
  EXPECT_NO_THROW(check_commands(read_campaign(std::filesystem::path(DTWIRE_SOURCE_DIR) / "experiments/default/campaign.toml"),
                                 command_names()));
  const auto inputs_of = [&](const std::string& name) {
    for (const CampaignStep& step : c.steps)
      if (step.name == name) return step.inputs;
    ADD_FAILURE() << "no step " << name;
    return std::vector<std::string>{};
  };
  const auto reads = [&](const std::string& step, const std::string& file) {
    const auto inputs = inputs_of(step);
    return std::find(inputs.begin(), inputs.end(), file) != inputs.end();
  };
  // The DT FE runs read the campaign's own mesh; the DEM driver the exported fitted set (#16).
  for (const char* run : {"dt_tension", "dt_pull_angle", "dt_bending"})
    EXPECT_TRUE(reads(run, "{out}/meshes/dt.msh")) << run;
  EXPECT_TRUE(reads("dem_driver", "{out}/export/single_wire_parameters.json"));
  EXPECT_TRUE(reads("export", "{out}/fit/parameters.json"));
  // Every set's punch on one figure (issue 36).
  for (const char* punch : {"punch_thesis", "punch_wirepm", "punch_fitted"})
    EXPECT_TRUE(reads("dem_punch_figure", std::string("{out}/dem/") + punch + "/curve.csv")) << punch;
}

// The summary's mesh-scale table from fake runs (no DEM run needed): one row per set label with
// its punch and strip figures against the thesis and published mesh figures; a set with a
// blocked step names it, an expected set with no step is 'not yet run'.
TEST(Campaign, MeshScaleTableJudgesEverySetFromItsSummaries) {
  const auto out = std::filesystem::temp_directory_path() / "dtwire_mesh_scale_table";
  std::filesystem::remove_all(out);
  auto step = [](const std::string& name, const std::string& label) {
    return "[[step]]\nname = \"" + name + "\"\ncommand = [\"dem\", \"run\", \"x.toml\", \"--label\", \"" + label +
           "\", \"-o\", \"{out}/" + name + "\"]\noutputs = [\"{out}/" + name + "/summary.json\"]\n";
  };
  const auto file = write_temp("dtwire_mesh_scale.toml", "name = \"m\"\n" + step("punch_thesis", "thesis published") +
                                                             step("strip_thesis", "thesis published") +
                                                             step("strip_wirepm", "WirePM published") +
                                                             step("punch_fit", "straight-wire fit") + step("punch_other", "my set"));
  const Campaign campaign = read_campaign(file);
  auto write_summary = [&](const std::string& name, const std::string& text) {
    std::filesystem::create_directories(out / name);
    std::ofstream(out / name / "summary.json") << text;
  };
  write_summary("punch_thesis", R"({"label": "thesis published", "tool": "platter", "onset_displacement_mm": 236.2,
                                    "peak_force_N": 57000.0, "displacement_at_peak_mm": 530.0, "sag_after_settling_mm": 97.9,
                                    "rim_tension_at_peak_kN_per_m": 34.22, "rim_largest_sector_tension_at_peak_kN_per_m": 48.49,
                                    "rim_slope_at_peak_deg": 20.76})");
  write_summary("strip_thesis", R"({"label": "thesis published", "tool": "strip_tension", "strength_per_width_kN_per_m": 58.87,
                                    "secant_EA_10_50_kN_per_m": 1165.0})");
  write_summary("strip_wirepm", R"({"label": "WirePM published", "tool": "strip_tension", "strength_per_width_kN_per_m": 13.3,
                                    "secant_EA_10_50_kN_per_m": null})");
  write_summary("punch_other", R"({"label": "my set", "tool": "platter", "onset_displacement_mm": null,
                                   "peak_force_N": 500.0, "displacement_at_peak_mm": 700.0, "sag_after_settling_mm": 10.0})");
  std::vector<StepOutcome> outcomes;
  for (const char* name : {"punch_thesis", "strip_thesis", "strip_wirepm", "punch_other"}) outcomes.push_back({name, StepStatus::Done, 0.0, 0, ""});
  outcomes.push_back({"punch_fit", StepStatus::Blocked, 0.0, 0, ""});
  const std::string md = summary_markdown(campaign, outcomes, out);
  EXPECT_NE(md.find("| *thesis DEM punch (Previtali; validated against laboratory punches)* | 0.20 | 25 | 0.53 |"), std::string::npos) << md;
  EXPECT_NE(md.find("| *published mesh, 8x10 / 2.7 mm (EN 15381 Annex D; manufacturer)* | | | | | | 50 | about 500 |"), std::string::npos) << md;
  EXPECT_NE(md.find("| thesis published | 0.236 (+18 %) | 57.0 (+128 %) | 0.530 (+0 %) | 98 | 34.2 / 48.5, 20.8 | 58.9 (+18 %) | 1165 (+133 %) | "
                    "[punch_thesis](#punch_thesis), [strip_thesis](#strip_thesis) |"),
            std::string::npos) << md;
  EXPECT_NE(md.find("| WirePM published | not run | | | | | 13.3 (-73 %) | undefined | [strip_wirepm](#strip_wirepm) |"), std::string::npos) << md;
  EXPECT_NE(md.find("| straight-wire fit | not run | | | | | not run | | [punch_fit](#punch_fit) (blocked) |"), std::string::npos) << md;
  EXPECT_NE(md.find("| as-made fit | not yet run | | | | | | | |"), std::string::npos) << md;
  EXPECT_NE(md.find("| my set | no onset | 0.5 (-98 %) | 0.700 (+32 %) | 10 | n/a |"), std::string::npos) << md;
  // Rows in the expected order, the campaign's other sets after them (in the mesh-scale table;
  // the recommendation before it lists the sets in the order of their runs).
  const std::string table = md.substr(md.find("### Mesh-scale validation"));
  EXPECT_LT(table.find("| thesis published |"), table.find("| WirePM published |"));
  EXPECT_LT(table.find("| as-made fit |"), table.find("| my set |"));
  std::filesystem::remove_all(out);
}

TEST(Campaign, SecondCampaignIntoTheSameFolderIsRefusedByTheLock) {
  const auto out = std::filesystem::temp_directory_path() / "dtwire_campaign_lock";
  std::filesystem::remove_all(out);
  const CampaignLock held(out);
  try {
    const CampaignLock second(out);
    FAIL() << "two locks";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("pid " + std::to_string(::getpid())), std::string::npos) << e.what();
  }
  const auto file = write_temp("dtwire_locked.toml", "name = \"l\"\n[[step]]\nname = \"a\"\n"
                                                     "command = [\"campaign\", \"--help\"]\n");
  EXPECT_EQ(run_command_line({"campaign", file.string(), "-o", out.string()}), kExitBadInput);
  std::filesystem::remove_all(out);
}

TEST(Campaign, StaleLockIsReportedAndTakenOver) {
  const auto out = std::filesystem::temp_directory_path() / "dtwire_campaign_stale";
  std::filesystem::remove_all(out);
  std::filesystem::create_directories(out);
  // What a killed campaign leaves: its pid and start time, and no lock held.
  std::ofstream(out / "campaign.lock") << "pid 2147483000, started 2026-01-01T00:00:00Z\n";
  {
    const CampaignLock lock(out);
    EXPECT_NE(lock.stale_note().find("pid 2147483000"), std::string::npos) << lock.stale_note();
  }
  const CampaignLock clean(out);  // released cleanly: nothing stale
  EXPECT_EQ(clean.stale_note(), "");
  std::filesystem::remove_all(out);
}

// A step process group as a killed campaign leaves it: `sleep` in its own group, reaped by a
// thread here (as init reaps an orphan), so its end is seen.
struct OrphanStep {
  pid_t group = 0;
  int status = 0;
  std::thread reaper;
  OrphanStep() {
    group = ::fork();
    if (group == 0) {
      ::setpgid(0, 0);
      ::execl("/bin/sleep", "sleep", "60", static_cast<char*>(nullptr));
      ::_exit(127);
    }
    ::setpgid(group, group);
    reaper = std::thread([this] { ::waitpid(group, &status, 0); });
  }
  ~OrphanStep() {
    ::kill(-group, SIGKILL);
    reaper.join();
  }
};

TEST(Campaign, LockListsTheRunningStepGroups) {
  const auto out = std::filesystem::temp_directory_path() / "dtwire_campaign_lock_groups";
  std::filesystem::remove_all(out);
  OrphanStep step;
  const auto text = [&] {
    std::ifstream in(out / "campaign.lock");
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  };
  {
    CampaignLock lock(out);
    lock.add_step_group(step.group);
    const auto listed = listed_step_groups(text());
    ASSERT_EQ(listed.size(), 1u) << text();
    EXPECT_EQ(listed[0].group, step.group);
    EXPECT_EQ(listed[0].start_ticks, process_start_ticks(step.group));
    EXPECT_NE(text().find("pid " + std::to_string(::getpid())), std::string::npos) << text();
    lock.remove_step_group(step.group);
    EXPECT_TRUE(listed_step_groups(text()).empty()) << text();
  }
  EXPECT_EQ(text(), "");  // released: emptied
  std::filesystem::remove_all(out);
}

TEST(Campaign, StepGroupIsTheStaleCampaignsOnlyWithItsStartTime) {
  OrphanStep step;
  const unsigned long long start = process_start_ticks(step.group);
  ASSERT_GT(start, 0u);
  EXPECT_TRUE(step_group_alive({step.group, start}));
  EXPECT_FALSE(step_group_alive({step.group, start + 1})) << "a reused group id is another program's";
  EXPECT_FALSE(step_group_alive({ended_group(), 0}));
  EXPECT_EQ(listed_step_groups("pid 1, started x\nstep group 12 started 34\nstep group x started 1\nstep group 5\n").size(), 1u);
}

TEST(Campaign, TakeoverOfAStaleLockStopsTheStepsItStillFinds) {
  const auto out = std::filesystem::temp_directory_path() / "dtwire_campaign_takeover";
  std::filesystem::remove_all(out);
  std::filesystem::create_directories(out);
  OrphanStep step;
  std::ofstream(out / "campaign.lock") << "pid 2147483000, started 2026-01-01T00:00:00Z\nstep group " << step.group
                                        << " started " << process_start_ticks(step.group) << "\n";
  const auto before = std::chrono::steady_clock::now();
  {
    const CampaignLock lock(out, std::chrono::seconds(1));  // waits 1 s, then SIGTERM
    EXPECT_FALSE(step_group_alive({step.group, 0})) << "the takeover returned while the step runs";
  }
  EXPECT_GE(std::chrono::steady_clock::now() - before, std::chrono::seconds(1));
  step.reaper.join();
  step.reaper = std::thread([] {});
  EXPECT_TRUE(WIFSIGNALED(step.status) && WTERMSIG(step.status) == SIGTERM) << step.status;
  std::filesystem::remove_all(out);
}

}  // namespace
}  // namespace dtwire::app

namespace dtwire::app {
namespace {

TEST(Campaign, StepWhoseProducedInputIsMissingIsBlockedNotAnError) {
  const auto out = std::filesystem::temp_directory_path() / "dtwire_campaign_blocked";
  std::filesystem::remove_all(out);
  // `a` promises a file it does not write (it fails), so `b` cannot run.
  const auto file = write_temp("dtwire_blocked.toml",
                               "name = \"b\"\n[[step]]\nname = \"a\"\ncommand = [\"campaign\", \"--help\"]\n"
                               "outputs = [\"{out}/never_written.csv\"]\n"
                               "[[step]]\nname = \"needs_earlier\"\n"
                               "command = [\"campaign\", \"--help\"]\n"
                               "inputs = [\"{out}/never_written.csv\"]\n");
  const auto outcomes = run_campaign(read_campaign(file), options_for(out));
  ASSERT_EQ(outcomes.size(), 2u);
  EXPECT_EQ(outcomes[0].status, StepStatus::Failed);
  EXPECT_EQ(outcomes[1].status, StepStatus::Blocked);
  EXPECT_NE(outcomes[1].message.find("never_written.csv"), std::string::npos);
  std::filesystem::remove_all(out);
}

TEST(Campaign, MissingInputOutsideTheOutputFolderIsAnInputError) {
  const auto out = std::filesystem::temp_directory_path() / "dtwire_campaign_missing";
  std::filesystem::remove_all(out);
  const auto file = write_temp("dtwire_missing.toml",
                               "name = \"m\"\n[[step]]\nname = \"first\"\ncommand = [\"campaign\", \"--help\"]\n"
                               "[[step]]\nname = \"a\"\n"
                               "command = [\"campaign\", \"--help\"]\n"
                               "inputs = [\"{campaign}/no_such_input.prm\"]\n");
  EXPECT_THROW(run_campaign(read_campaign(file), options_for(out)), InputError);
  EXPECT_FALSE(std::filesystem::exists(out / "campaign_state.json")) << "a step ran before the check";
  std::filesystem::remove_all(out);
}

}  // namespace
}  // namespace dtwire::app
