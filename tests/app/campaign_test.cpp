#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "campaign/campaign_file.hpp"
#include "campaign/campaign_report.hpp"
#include "campaign/campaign_runner.hpp"
#include "cli.hpp"
#include "dtwire/core/error.hpp"

namespace dtwire::app {
namespace {

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

TEST(Campaign, RunsStepsResumesAndReportsUnavailableOnes) {
  const auto out = std::filesystem::temp_directory_path() / "dtwire_campaign_run";
  std::filesystem::remove_all(out);
  // A step that runs a (nested) campaign producing a report, and one with an unknown command.
  const auto inner = write_temp("dtwire_inner.toml",
                                "name = \"inner\"\n[[step]]\nname = \"nothing\"\n"
                                "command = [\"no_such_command\"]\n");
  const auto outer = write_temp(
      "dtwire_outer.toml",
      "name = \"outer\"\n[[step]]\nname = \"inner_campaign\"\n"
      "command = [\"campaign\", \"" + inner.string() + "\", \"-o\", \"{out}/inner\"]\n"
      "inputs = [\"" + inner.string() + "\"]\n"
      "outputs = [\"{out}/inner/report.md\"]\nreport = [\"{out}/inner/report.md\"]\n"
      "[[step]]\nname = \"missing\"\ncommand = [\"no_such_command\"]\n");
  const Campaign campaign = read_campaign(outer);
  const auto first = run_campaign(campaign, {out, false, {}});
  ASSERT_EQ(first.size(), 2u);
  EXPECT_EQ(first[0].status, StepStatus::Done);
  EXPECT_EQ(first[1].status, StepStatus::Unavailable);
  const auto second = run_campaign(campaign, {out, false, {}});
  EXPECT_EQ(second[0].status, StepStatus::Skipped);  // resumed: same inputs, outputs present
  const auto report = write_campaign_report(campaign, second, out);
  std::ifstream in(report);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("not available yet"), std::string::npos);
  EXPECT_NE(text.find("# inner"), std::string::npos);  // the inner report is embedded
  EXPECT_TRUE(std::filesystem::exists(out / "provenance.json"));
  std::filesystem::remove_all(out);
}

}  // namespace
}  // namespace dtwire::app

namespace dtwire::app {
namespace {

TEST(Campaign, StepWhoseProducedInputIsMissingIsBlockedNotAnError) {
  const auto out = std::filesystem::temp_directory_path() / "dtwire_campaign_blocked";
  std::filesystem::remove_all(out);
  const auto file = write_temp("dtwire_blocked.toml",
                               "name = \"b\"\n[[step]]\nname = \"needs_earlier\"\n"
                               "command = [\"campaign\", \"--help\"]\n"
                               "inputs = [\"{out}/never_written.csv\"]\n");
  const auto outcomes = run_campaign(read_campaign(file), {out, false, {}});
  ASSERT_EQ(outcomes.size(), 1u);
  EXPECT_EQ(outcomes[0].status, StepStatus::Blocked);
  EXPECT_NE(outcomes[0].message.find("never_written.csv"), std::string::npos);
  std::filesystem::remove_all(out);
}

TEST(Campaign, MissingInputOutsideTheOutputFolderIsAnInputError) {
  const auto out = std::filesystem::temp_directory_path() / "dtwire_campaign_missing";
  const auto file = write_temp("dtwire_missing.toml",
                               "name = \"m\"\n[[step]]\nname = \"a\"\n"
                               "command = [\"campaign\", \"--help\"]\n"
                               "inputs = [\"{campaign}/no_such_input.prm\"]\n");
  EXPECT_THROW(run_campaign(read_campaign(file), {out, false, {}}), InputError);
  std::filesystem::remove_all(out);
}

}  // namespace
}  // namespace dtwire::app
