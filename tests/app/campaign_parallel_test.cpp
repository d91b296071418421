// Issue 38: the campaign's graph, steps side by side (--jobs), the Snakemake workflow and the
// report from outputs made elsewhere (--report-only).
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <optional>

#include "campaign/campaign_file.hpp"
#include "campaign/campaign_graph.hpp"
#include "campaign/campaign_runner.hpp"
#include "campaign/critical_path.hpp"
#include "campaign/recorded_outcomes.hpp"
#include "campaign/snakefile.hpp"
#include "campaign/start_order.hpp"
#include "cli.hpp"
#include "dtwire/core/error.hpp"

namespace dtwire::app {
namespace {

std::filesystem::path write_temp(const std::string& name, const std::string& text) {
  const auto path = std::filesystem::temp_directory_path() / name;
  std::ofstream(path) << text;
  return path;
}

std::string step(const std::string& name, const std::string& extra) {
  return "[[step]]\nname = \"" + name + "\"\n" + extra;
}

TEST(CampaignGraph, StepsWaitForWhatTheyReadAndForOverlappingOutputs) {
  const auto file = write_temp(
      "dtwire_graph_deps.toml",
      "name = \"g\"\n" +
          step("a", "command = [\"campaign\", \"--help\"]\noutputs = [\"{out}/a/x.csv\"]\n") +
          step("b", "command = [\"campaign\", \"--help\"]\noutputs = [\"{out}/b\"]\n") +
          step("reads_a", "command = [\"campaign\", \"--help\"]\ninputs = [\"{out}/a/x.csv\"]\n") +
          step("inside_b", "command = [\"campaign\", \"--help\"]\ninputs = [\"{out}/b/y.csv\"]\n") +
          step("writes_into_b", "command = [\"campaign\", \"--help\"]\noutputs = [\"{out}/b/z.csv\"]\n") +
          step("names_a", "command = [\"gap\", \"--sim\", \"{out}/a/x.csv#tension\"]\n") +
          step("free", "command = [\"campaign\", \"--help\"]\noutputs = [\"{out}/free.csv\"]\n"));
  const auto waits = step_dependencies(read_campaign(file));
  using V = std::vector<std::size_t>;
  EXPECT_EQ(waits[2], V{0});
  EXPECT_EQ(waits[3], V{1});
  EXPECT_EQ(waits[4], V{1});  // both write into {out}/b
  EXPECT_EQ(waits[5], V{0});  // a path its command names, undeclared
  EXPECT_EQ(waits[6], V{});
}

// The floor of the wall time on any number of cores: a diamond a -> (b | c) -> d plus a lone
// long step e. The chain through the slower branch (a, c, d: 1 + 5 + 2 = 8 s) beats the lone
// step (7 s) and the faster branch (a, b, d: 5 s).
TEST(CampaignGraph, CriticalPathIsTheLongestChainOfWaitingSteps) {
  using V = std::vector<std::size_t>;
  const std::vector<std::vector<std::size_t>> waits{{}, {0}, {0}, {1, 2}, {}};
  const CriticalPath path = critical_path(waits, {1.0, 2.0, 5.0, 2.0, 7.0});
  EXPECT_EQ(path.steps, (V{0, 2, 3}));
  EXPECT_DOUBLE_EQ(path.seconds, 8.0);
  const CriticalPath lone = critical_path(waits, {1.0, 2.0, 5.0, 2.0, 9.0});
  EXPECT_EQ(lone.steps, V{4});
  EXPECT_DOUBLE_EQ(lone.seconds, 9.0);
  EXPECT_TRUE(critical_path({}, {}).steps.empty());
  EXPECT_THROW(critical_path(waits, {1.0, 2.0}), std::invalid_argument);
  EXPECT_THROW(critical_path({{}, {1}}, {1.0, 1.0}), std::invalid_argument);  // waits for itself
  EXPECT_THROW(critical_path({{}, {}}, {1.0, -1.0}), std::invalid_argument);
}

// The start order side by side: on the diamond above, each step's level is its time plus the
// longest chain after it (a: 1 + 5 + 2); the steps are offered cores highest level first, ties
// in the file's order; unknown step times count as the mean of the known ones, or 1 s each.
TEST(CampaignSchedule, StepsLeadingTheLongestChainToTheEndStartFirst) {
  using V = std::vector<std::size_t>;
  const std::vector<std::vector<std::size_t>> waits{{}, {0}, {0}, {1, 2}, {}};
  EXPECT_EQ(levels(waits, {1.0, 2.0, 5.0, 2.0, 7.0}), (std::vector<double>{8.0, 4.0, 7.0, 2.0, 7.0}));
  EXPECT_EQ(start_order(waits, {1.0, 2.0, 5.0, 2.0, 7.0}), (V{0, 2, 4, 1, 3}));
  // A fresh folder: the chains count steps (a 3, b and c 2, d and e 1).
  EXPECT_EQ(start_order(waits, std::vector<std::optional<double>>(5)), (V{0, 1, 2, 3, 4}));
  // a and d unknown: each takes the mean of the known 2, 5 and 7 s (a 14.3, c 9.7, e 7, b 6.7, d 4.7).
  EXPECT_EQ(start_order(waits, {std::nullopt, 2.0, 5.0, std::nullopt, 7.0}), (V{0, 2, 4, 1, 3}));
  EXPECT_THROW(levels(waits, {1.0}), std::invalid_argument);
  EXPECT_THROW(levels({{}, {1}}, {1.0, 1.0}), std::invalid_argument);  // waits for itself
}

// A ready step that needs more cores than are free holds its place: a two-thread step is not
// overtaken by every one-thread step that fits beside a running one. A step offered after it
// starts only if its earlier time ends before the running steps free the waiting step's cores
// (EASY backfilling); an unknown time never overtakes.
TEST(CampaignSchedule, AStepWaitingForCoresIsNotOvertaken) {
  using V = std::vector<std::size_t>;
  const std::optional<double> unknown;
  // One core busy for an unknown time: 5 waits for both, and 1 and 2 wait behind it.
  EXPECT_EQ(steps_to_start({{5, 2, unknown}, {1, 1, 1.0}, {2, 1, unknown}}, {{1, unknown}}, 2), V{});
  EXPECT_EQ(steps_to_start({{5, 2, unknown}, {1, 1, unknown}}, {}, 2), V{5});  // nothing runs: 5 takes both
  EXPECT_EQ(steps_to_start({{1, 1, unknown}, {2, 1, unknown}, {3, 1, unknown}}, {}, 2), (V{1, 2}));
  EXPECT_EQ(steps_to_start({{1, 1, unknown}, {5, 2, unknown}, {2, 1, unknown}}, {}, 2), V{1});
  EXPECT_EQ(steps_to_start({{7, 4, unknown}}, {}, 2), V{7});  // wider than --jobs: alone
  EXPECT_EQ(steps_to_start({}, {{1, 5.0}}, 2), V{});
  // The running step ends in 100 s: a 60 s step fits in before 5 may start, a 150 s one does not.
  EXPECT_EQ(steps_to_start({{5, 2, 900.0}, {2, 1, 60.0}, {3, 1, 150.0}}, {{1, 100.0}}, 2), V{2});
  EXPECT_EQ(steps_to_start({{5, 2, 900.0}, {3, 1, 150.0}}, {{1, 100.0}}, 2), V{});
  // On 4 cores: 5 needs all four, and one of the running steps' ends is unknown: no overtaking.
  EXPECT_EQ(steps_to_start({{5, 4, 900.0}, {2, 1, 60.0}}, {{2, 100.0}, {1, unknown}}, 4), V{});
  // 5 needs three: the step ending in 100 s frees them, the unknown one is not needed.
  EXPECT_EQ(steps_to_start({{5, 3, 900.0}, {2, 1, 60.0}, {4, 1, 60.0}}, {{1, 100.0}, {1, unknown}}, 4), (V{2, 4}));
}

TEST(CampaignGraph, ThreadsFieldIsReadAndChecked) {
  const auto good = write_temp("dtwire_threads.toml",
                               "name = \"t\"\n" + step("a", "command = [\"campaign\", \"--help\"]\nthreads = 3\n") +
                                   step("b", "command = [\"campaign\", \"--help\"]\n"));
  const Campaign c = read_campaign(good);
  EXPECT_EQ(c.steps[0].threads, 3);
  EXPECT_EQ(c.steps[1].threads, 1);
  for (const char* bad : {"0", "\"4\"", "2.5"}) {
    const auto file = write_temp("dtwire_threads_bad.toml", "name = \"t\"\n" +
                                     step("a", "command = [\"campaign\", \"--help\"]\nthreads = " + std::string(bad) + "\n"));
    try {
      read_campaign(file);
      FAIL() << "accepted threads = " << bad;
    } catch (const InputError& e) {
      EXPECT_EQ(e.line(), 5) << e.what();
      EXPECT_NE(std::string(e.what()).find("'threads'"), std::string::npos) << e.what();
    }
  }
}

// expected_seconds: a step's wall time as measured, which the start order uses in a fresh folder.
TEST(CampaignGraph, ExpectedSecondsIsReadAndChecked) {
  const auto good = write_temp("dtwire_expected.toml",
                               "name = \"t\"\n" + step("a", "command = [\"campaign\", \"--help\"]\nexpected_seconds = 150\n") +
                                   step("b", "command = [\"campaign\", \"--help\"]\nexpected_seconds = 2.5\n") +
                                   step("c", "command = [\"campaign\", \"--help\"]\n"));
  const Campaign c = read_campaign(good);
  EXPECT_EQ(c.steps[0].expected_seconds, 150.0);
  EXPECT_EQ(c.steps[1].expected_seconds, 2.5);
  EXPECT_FALSE(c.steps[2].expected_seconds);
  for (const char* bad : {"0", "-3", "\"60\"", "nan", "inf"}) {
    const auto file = write_temp("dtwire_expected_bad.toml", "name = \"t\"\n" +
                                     step("a", "command = [\"campaign\", \"--help\"]\nexpected_seconds = " + std::string(bad) + "\n"));
    try {
      read_campaign(file);
      FAIL() << "accepted expected_seconds = " << bad;
    } catch (const InputError& e) {
      EXPECT_EQ(e.line(), 5) << e.what();
      EXPECT_NE(std::string(e.what()).find("'expected_seconds'"), std::string::npos) << e.what();
    }
  }
}

TEST(CampaignJobs, BadJobsAndSnakefilePathsAreRefused) {
  const auto out = std::filesystem::temp_directory_path() / "dtwire_campaign_jobs_bad";
  std::filesystem::remove_all(out);
  const auto file = write_temp("dtwire_jobs_bad.toml", "name = \"j\"\n" + step("a", "command = [\"campaign\", \"--help\"]\n"));
  EXPECT_EQ(run_command_line({"campaign", file.string(), "-o", out.string(), "--jobs", "0"}), kExitBadInput);
  EXPECT_EQ(run_command_line({"campaign", file.string(), "-o", out.string(), "--snakefile",
                              std::filesystem::temp_directory_path().string()}),
            kExitBadInput);
  EXPECT_EQ(run_command_line({"campaign", file.string(), "-o", out.string(), "--report-only", "--jobs", "2"}),
            kExitBadInput);
  EXPECT_EQ(run_command_line({"campaign", file.string(), "-o", out.string(), "--report-only"}), kExitBadInput)
      << "no output directory yet";
  // A snakefile under a folder that does not exist: the folder is made, as -o makes its own.
  const auto new_folder = out.parent_path() / "dtwire_campaign_jobs_new_folder";
  std::filesystem::remove_all(new_folder);
  EXPECT_EQ(run_command_line({"campaign", file.string(), "-o", out.string(), "--snakefile",
                              (new_folder / "deeper" / "x.smk").string()}),
            0);
  EXPECT_TRUE(std::filesystem::is_regular_file(new_folder / "deeper" / "x.smk"));
  // ... but not through a file standing where a folder must be (exit 2 before any work).
  std::ofstream(new_folder / "a_file") << "x";
  EXPECT_EQ(run_command_line({"campaign", file.string(), "-o", out.string(), "--snakefile",
                              (new_folder / "a_file" / "x.smk").string()}),
            kExitBadInput);
  std::filesystem::remove_all(new_folder);
  CampaignOptions options;
  options.out = out;
  options.executable = DTWIRE_EXECUTABLE;
  options.jobs = 0;
  EXPECT_THROW(run_campaign(read_campaign(file), options), InputError);
  EXPECT_FALSE(std::filesystem::exists(out / "campaign_state.json"));
}

// Side by side, a failed step blocks what reads from it; the independent steps still run and the
// outcomes keep the file's order.
TEST(CampaignJobs, FailureBlocksDependentsOnlyAndOrderIsKept) {
  const auto out = std::filesystem::temp_directory_path() / "dtwire_campaign_jobs_fail";
  std::filesystem::remove_all(out);
  const auto file = write_temp(
      "dtwire_jobs_fail.toml",
      "name = \"f\"\n" + step("a", "command = [\"campaign\", \"--help\"]\noutputs = [\"{out}/never_written.csv\", \"{out}/missing.csv\"]\n") +
          step("free", "command = [\"campaign\", \"--help\"]\n") +
          step("needs_a", "command = [\"campaign\", \"--help\"]\ninputs = [\"{out}/never_written.csv\"]\n") +
          step("needs_needs_a", "command = [\"campaign\", \"--help\"]\ninputs = [\"{out}/never_written.csv\"]\n"
                                "outputs = [\"{out}/after.csv\"]\n"));
  for (int jobs : {1, 2}) {
    // A stale file from an earlier run must not let `needs_a` run on what `a` did not write now.
    std::filesystem::remove_all(out);
    std::filesystem::create_directories(out);
    std::ofstream(out / "never_written.csv") << "stale\n";
    CampaignOptions options;
    options.out = out;
    options.executable = DTWIRE_EXECUTABLE;
    options.jobs = jobs;
    const auto outcomes = run_campaign(read_campaign(file), options);
    ASSERT_EQ(outcomes.size(), 4u);
    EXPECT_EQ(outcomes[0].name, "a");
    EXPECT_EQ(outcomes[0].status, StepStatus::Failed) << jobs;
    EXPECT_EQ(outcomes[1].status, StepStatus::Done) << jobs;
    EXPECT_EQ(outcomes[2].status, StepStatus::Blocked) << jobs;
    EXPECT_NE(outcomes[2].message.find("never_written.csv"), std::string::npos) << outcomes[2].message;
    EXPECT_NE(outcomes[2].message.find("step 'a' failed"), std::string::npos) << outcomes[2].message;
    EXPECT_EQ(outcomes[3].status, StepStatus::Blocked) << jobs;
  }
  std::filesystem::remove_all(out);
}

// A step wider than --jobs still runs (alone); a step's cores are counted.
TEST(CampaignJobs, WideStepRunsAloneAndNarrowOnesShare) {
  const auto out = std::filesystem::temp_directory_path() / "dtwire_campaign_jobs_wide";
  std::filesystem::remove_all(out);
  const auto file = write_temp("dtwire_jobs_wide.toml",
                               "name = \"w\"\n" + step("wide", "command = [\"campaign\", \"--help\"]\nthreads = 8\n") +
                                   step("narrow", "command = [\"campaign\", \"--help\"]\n") +
                                   step("narrow2", "command = [\"campaign\", \"--help\"]\n"));
  CampaignOptions options;
  options.out = out;
  options.executable = DTWIRE_EXECUTABLE;
  options.jobs = 2;
  const auto outcomes = run_campaign(read_campaign(file), options);
  ASSERT_EQ(outcomes.size(), 3u);
  for (const auto& o : outcomes) EXPECT_EQ(o.status, StepStatus::Done) << o.name << ": " << o.message;
  std::ifstream in(out / "campaign_state.json");
  const auto state = nlohmann::json::parse(in);
  const auto end = [&](const char* name) {
    return state[name]["started_s"].get<double>() + state[name]["seconds"].get<double>();
  };
  // `wide` holds both cores: the narrow steps start after it ends.
  EXPECT_GE(state["narrow"]["started_s"].get<double>(), end("wide"));
  EXPECT_GE(state["narrow2"]["started_s"].get<double>(), end("wide"));
  std::filesystem::remove_all(out);
}

TEST(Snakefile, RulesCarryTheGraphThreadsAndEscapedBraces) {
  const auto file = write_temp(
      "dtwire_snake.toml",
      "name = \"s\"\n" +
          step("export", "command = [\"export\", \"--out\", \"{out}/export\"]\noutputs = [\"{out}/export\"]\nthreads = 4\n") +
          step("2nd", "command = [\"gap\", \"--json\", \"{out}/g.json\", \"--columns\", \"x{1,2}\"]\n"
                      "inputs = [\"{out}/export/sw.json\", \"{campaign}/x.prm\"]\noutputs = [\"{out}/g.json\"]\n"));
  Campaign campaign = read_campaign(file);
  SnakefileOptions options{"/data/run", "/opt/dtwire/bin/dtwire", {"as_made=true"}};
  const std::string text = snakefile_text(campaign, options);
  const auto has = [&](const std::string& fragment) { return text.find(fragment) != std::string::npos; };
  EXPECT_TRUE(has("rule dtwire_all:\n    input: \"/data/run/report.md\"")) << text;
  EXPECT_TRUE(has("rule export:")) << text;
  EXPECT_TRUE(has("directory(\"/data/run/export\")")) << text;  // another step reads inside it
  EXPECT_TRUE(has("    threads: 4\n")) << text;
  EXPECT_TRUE(has("rule step_2nd:")) << text;  // a rule name must not start with a digit
  // The input inside the folder output is read through the folder, and the rule waits for the
  // producer's marker.
  EXPECT_TRUE(has("\"/data/run/export\",\n        \"" + std::filesystem::temp_directory_path().string() + "/x.prm\",\n"
                  "        \"/data/run/steps/export/command.txt\"")) << text;
  EXPECT_TRUE(has("'x{{1,2}}'")) << text;  // a literal brace, doubled for Snakemake
  EXPECT_TRUE(has("'/opt/dtwire/bin/dtwire' 'gap' '--json' '/data/run/g.json'")) << text;
  EXPECT_TRUE(has("--report-only --var 'as_made=true'")) << text;
  EXPECT_TRUE(has("log: \"/data/run/steps/2nd/output.log\"")) << text;
}

// Steps run elsewhere: --report-only reports them done and records them, so that the runner
// then skips them.
TEST(CampaignReportOnly, OutputsMadeElsewhereAreDoneAndResumed) {
  const auto out = std::filesystem::temp_directory_path() / "dtwire_campaign_report_only";
  std::filesystem::remove_all(out);
  const auto file = write_temp("dtwire_report_only.toml",
                               "name = \"r\"\n" + step("made", "command = [\"campaign\", \"--help\"]\noutputs = [\"{out}/made.csv\"]\n") +
                                   step("not_made", "command = [\"campaign\", \"--help\"]\noutputs = [\"{out}/not_made.csv\"]\n"));
  std::filesystem::create_directories(out / "steps/made");
  std::ofstream(out / "made.csv") << "x\n1\n";
  std::ofstream(out / "steps/made/benchmark.tsv") << "s\th:m:s\tmax_rss\n12.5\t0:00:12\t10\n";
  const Campaign campaign = read_campaign(file);
  const auto outcomes = recorded_outcomes(campaign, out);
  ASSERT_EQ(outcomes.size(), 2u);
  EXPECT_EQ(outcomes[0].status, StepStatus::Done);
  EXPECT_DOUBLE_EQ(outcomes[0].seconds, 12.5);
  EXPECT_EQ(outcomes[1].status, StepStatus::Blocked);
  EXPECT_NE(outcomes[1].message.find("not_made.csv"), std::string::npos) << outcomes[1].message;
  CampaignOptions options;
  options.out = out;
  options.executable = DTWIRE_EXECUTABLE;
  options.only = {"made"};
  EXPECT_EQ(run_campaign(campaign, options)[0].status, StepStatus::Skipped);
  // Its inputs changed since (here: a state from an older build) and no Snakemake timing: the
  // recorded time stays, for the report's critical path.
  std::filesystem::remove(out / "steps/made/benchmark.tsv");
  nlohmann::json state = nlohmann::json::parse(std::ifstream(out / "campaign_state.json"));
  state["made"]["fingerprint"] = "an older build's";
  std::ofstream(out / "campaign_state.json") << state.dump();
  EXPECT_DOUBLE_EQ(recorded_outcomes(campaign, out)[0].seconds, 12.5);
  std::filesystem::remove_all(out);
}

}  // namespace
}  // namespace dtwire::app
