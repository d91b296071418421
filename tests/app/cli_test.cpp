// Smoke tests of the dtwire executable: --help on every command, --version, exit codes.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>

#include "run_dtwire.hpp"

namespace {

using dtwire::test::CommandResult;
using dtwire::test::run;

std::size_t line_count(const std::string& text) {
  return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
}

TEST(Cli, TopLevelHelpListsEveryCommand) {
  const CommandResult r = run("--help");
  EXPECT_EQ(r.exit_code, 0);
  for (const char* command : {"mesh", "run", "fit", "export", "dem", "gap", "campaign"})
    EXPECT_NE(r.output.find(command), std::string::npos) << command;
}

class CommandHelp : public ::testing::TestWithParam<const char*> {};

TEST_P(CommandHelp, ExitsZeroAndNamesTheCommand) {
  const CommandResult r = run(std::string(GetParam()) + " --help");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find(GetParam()), std::string::npos) << r.output;
}

INSTANTIATE_TEST_SUITE_P(EveryCommand, CommandHelp,
                         ::testing::Values("mesh", "run", "fit", "export", "dem", "gap",
                                           "campaign"));

TEST(Cli, VersionPrintsVersionAndGitHash) {
  const CommandResult r = run("--version");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.output.find("dtwire 0."), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("(git "), std::string::npos) << r.output;
}

TEST(Cli, UnknownOptionExitsTwoWithOneLine) {
  const CommandResult r = run("--frobnicate");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(line_count(r.output), 1u) << r.output;
  EXPECT_NE(r.output.find("frobnicate"), std::string::npos) << r.output;
}

TEST(Cli, UnknownCommandExitsTwo) {
  const CommandResult r = run("frobnicate");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(line_count(r.output), 1u) << r.output;
}

TEST(Cli, MissingCommandExitsTwo) {
  const CommandResult r = run("");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(line_count(r.output), 1u) << r.output;
}

TEST(Cli, UnknownOptionOfASubcommandExitsTwo) {
  const CommandResult r = run("campaign --no-such-option");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(line_count(r.output), 1u) << r.output;
}

TEST(Cli, BadCampaignFileExitsTwoNamingTheFile) {
  const CommandResult r = run("campaign /nonexistent/campaign.toml");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("/nonexistent/campaign.toml: no such file"), std::string::npos)
      << r.output;
}

#ifdef DTWIRE_HAVE_FEM
// `run --set Section/Entry=value`: unknown entries and bad values are refused before any work,
// and a relative 'Mesh file' is read from the working directory (the refusal names that path).
TEST(Cli, RunSetRefusesUnknownEntriesAndResolvesMeshFileFromWorkingDirectory) {
  const std::string prm = std::string(DTWIRE_SOURCE_DIR) + "/experiments/default/sw_tension.prm";
  const std::string out = ::testing::TempDir() + "dtwire_cli_set";
  CommandResult r = run("run " + prm + " --set 'Geometry/Diamter (mm)=3' -o " + out + " -q");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--set: 'Geometry/Diamter (mm)=3'"), std::string::npos) << r.output;
  r = run("run " + prm + " --set 'Geometry/Length (mm)=-3' -o " + out + " -q");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("does not match"), std::string::npos) << r.output;
  r = run("run " + prm + " --set 'Geometry/Mesh file=no_such_dir/dt.msh' -o " + out + " -q");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  const std::string expected = (std::filesystem::current_path() / "no_such_dir/dt.msh").string();
  EXPECT_NE(r.output.find(expected), std::string::npos) << r.output;
}
#endif

}  // namespace
