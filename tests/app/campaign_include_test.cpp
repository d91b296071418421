// Issue 52: a campaign that includes another (the study includes the default campaign), and the
// split itself: the default campaign is the recommended chain, the study holds it unchanged.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>

#include "campaign/campaign_file.hpp"
#include "campaign/report_mesh_scale.hpp"
#include "cli.hpp"
#include "dtwire/core/error.hpp"

namespace dtwire::app {
namespace {

std::filesystem::path write(const std::filesystem::path& file, const std::string& text) {
  std::filesystem::create_directories(file.parent_path());
  std::ofstream(file) << text;
  return file;
}

// One folder per test: ctest runs this file's tests as parallel processes, and each clears its own.
std::filesystem::path test_root() {
  return std::filesystem::temp_directory_path() /
         (std::string("dtwire_campaign_include_") + ::testing::UnitTest::GetInstance()->current_test_info()->name());
}

const std::string kBase =
    "name = \"base\"\n[variables]\nflag = \"off\"\n"
    "[[step]]\nname = \"make\"\ncommand = [\"mesh\", \"sw\", \"--prm\", \"{campaign}/a.prm\", \"--x\", \"{flag}\", \"-o\", \"{out}/a.msh\"]\n"
    "inputs = [\"{campaign}/a.prm\"]\noutputs = [\"{out}/a.msh\"]\n";

TEST(CampaignInclude, IncludedStepsComeFirstWithTheirOwnFolderAndVariables) {
  const auto root = test_root();
  std::filesystem::remove_all(root);
  write(root / "base/campaign.toml", kBase);
  const auto study = write(root / "study/campaign.toml",
                           "name = \"study\"\ninclude = [\"../base/campaign.toml\"]\n"
                           "[[step]]\nname = \"use\"\ncommand = [\"run\", \"{campaign}/b.prm\", \"--flag\", \"{flag}\"]\n"
                           "inputs = [\"{out}/a.msh\"]\n");
  Campaign c = read_campaign(study);
  ASSERT_EQ(c.steps.size(), 2u);
  EXPECT_EQ(c.steps[0].name, "make");
  const std::string base_folder = (root / "base").lexically_normal().string();
  EXPECT_EQ(c.steps[0].command[3], base_folder + "/a.prm") << "{campaign} of an included step is its own file's folder";
  EXPECT_EQ(c.steps[0].inputs[0], base_folder + "/a.prm");
  EXPECT_EQ(c.steps[1].command[1], "{campaign}/b.prm") << "the including file's own steps keep {campaign}";
  EXPECT_EQ(c.variables.at("flag"), "off");
  apply_variables(c, {"flag=on"});
  EXPECT_EQ(c.steps[0].command[5], "on");
  EXPECT_EQ(c.steps[1].command[3], "on");
  std::filesystem::remove_all(root);
}

TEST(CampaignInclude, DuplicateNamesCyclesAndMissingFilesAreNamedAtTheirLine) {
  const auto root = test_root();
  std::filesystem::remove_all(root);
  write(root / "base/campaign.toml", kBase);
  const auto expect_error = [](const std::filesystem::path& file, const std::string& part, int line) {
    try {
      read_campaign(file);
      ADD_FAILURE() << "accepted " << file;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
      EXPECT_EQ(e.line(), line) << e.what();
    }
  };
  expect_error(write(root / "dup.toml", "name = \"d\"\ninclude = [\"base/campaign.toml\"]\n[[step]]\nname = \"make\"\n"
                                         "command = [\"mesh\", \"sw\"]\n"),
               "duplicate step name 'make' (an included campaign has it)", 4);
  write(root / "a.toml", "name = \"a\"\ninclude = [\"b.toml\"]\n[[step]]\nname = \"x\"\ncommand = [\"mesh\"]\n");
  write(root / "b.toml", "name = \"b\"\ninclude = [\"a.toml\"]\n[[step]]\nname = \"y\"\ncommand = [\"mesh\"]\n");
  expect_error(root / "a.toml", "makes a cycle", 2);
  expect_error(write(root / "missing.toml", "name = \"m\"\ninclude = [\"nowhere.toml\"]\n[[step]]\nname = \"x\"\ncommand = [\"mesh\"]\n"),
               "no campaign file", 2);
  expect_error(write(root / "vars.toml", "name = \"v\"\ninclude = [\"base/campaign.toml\"]\n[variables]\nflag = \"on\"\n"
                                          "[[step]]\nname = \"x\"\ncommand = [\"mesh\"]\n"),
               "variable 'flag' is declared by an included campaign", 4);
  std::filesystem::remove_all(root);
}

// The shipped split: the study includes every step of the default campaign as the default runs it
// (same command, inputs, outputs and threads once {campaign} is resolved), so the steps both run
// give the same answers; the default judges the recommended set beside the thesis's published sets.
TEST(CampaignSplit, TheStudyRunsEveryDefaultStepAsTheDefaultDoes) {
  const auto experiments = std::filesystem::absolute(std::filesystem::path(DTWIRE_SOURCE_DIR) / "experiments").lexically_normal();
  const Campaign main = read_campaign(experiments / "default/campaign.toml");
  const Campaign study = read_campaign(experiments / "study/campaign.toml");
  const auto folder = (experiments / "default").string();
  const auto resolved = [&](std::vector<std::string> texts) {
    for (auto& text : texts) text = expand(text, "{out}", folder);
    return texts;
  };
  for (std::size_t i = 0; i < main.steps.size(); ++i) {
    const CampaignStep& a = main.steps[i];
    ASSERT_LT(i, study.steps.size());
    const CampaignStep& b = study.steps[i];
    EXPECT_EQ(a.name, b.name);
    EXPECT_EQ(resolved(a.command), b.command) << a.name;
    EXPECT_EQ(resolved(a.inputs), b.inputs) << a.name;
    EXPECT_EQ(resolved(a.outputs), b.outputs) << a.name;
    EXPECT_EQ(a.threads, b.threads) << a.name;
  }
  EXPECT_EQ(study.variables, main.variables);
  const auto labels = [](const Campaign& c) {
    std::set<std::string> found;
    for (const CampaignStep& step : c.steps)
      if (const std::string label = label_of_command(step.command); !label.empty()) found.insert(label);
    return found;
  };
  // The recommended and published sets, each also with the beam's shear spring (its strips and punches).
  EXPECT_EQ(labels(main), (std::set<std::string>{"thesis published", "section + N-M fit", "thesis published, beam shear spring",
                                                 "section + N-M fit, beam shear spring"}));
  EXPECT_EQ(labels(study), (std::set<std::string>{"thesis published", "WirePM published", "straight-wire fit", "as-made fit",
                                                  "section fit", "section + N-M fit", "thesis published, beam shear spring",
                                                  "section + N-M fit, beam shear spring"}));
  // Its one DT fit and the SW fit of the recommended set; the export of every format.
  const auto has = [&](const Campaign& c, const std::string& name) {
    return std::any_of(c.steps.begin(), c.steps.end(), [&](const CampaignStep& s) { return s.name == name; });
  };
  for (const char* step : {"segment_fit_nm", "dt_specimen_fit", "export_nm", "dem_punch_nm", "dem_strip_nm", "gap_strip",
                           "gap_sw_backbone", "gap_sw_compression", "dem_strip_nm_beam_shear_band", "dem_punch_nm_beam_shear",
                           "dem_punch_thesis_beam_shear"})
    EXPECT_TRUE(has(main, step)) << step;
  for (const char* step : {"macro_fit", "dt_link_fit", "dem_punch_wirepm", "gap_selfcheck", "dt_twisting", "gap_punch",
                           "segment_fit", "export_as_made", "dem_strip_nm_beam_shear_sampled", "dem_punch_nm_band", "sw_bending",
                           "sw_fit_pull_spin_20deg", "sw_fit_pull_spin_unspin", "dt_pair_mesh", "dem_strip_nm_band",
                           "dem_punch_nm_beam_shear_band"})
    EXPECT_FALSE(has(main, step)) << step << " belongs to the study";
  for (const char* step : {"dem_strip_nm_beam_shear_sampled", "dem_strip_nm_band", "dem_punch_nm_band", "dem_punch_nm_beam_shear_band",
                           "sw_bending", "sw_fit_pull_spin_20deg", "sw_fit_pull_spin_unspin", "dt_pair_mesh"})
    EXPECT_TRUE(has(study, step)) << step;
}

// `dtwire campaign --study` takes the study's file (written here as a workflow: nothing runs);
// with a campaign file as well it is refused before any work.
TEST(CampaignSplit, StudyOptionRunsTheStudyFile) {
  const auto root = test_root();
  std::filesystem::remove_all(root);
  const auto workflow = root / "study.smk";
  ASSERT_EQ(run_command_line({"campaign", "--study", "-o", (root / "out").string(), "--snakefile", workflow.string()}), 0);
  std::ifstream in(workflow);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("rule macro_fit"), std::string::npos) << "a study step";
  EXPECT_NE(text.find("rule dt_specimen_fit"), std::string::npos) << "an included default step";
  EXPECT_EQ(run_command_line({"campaign", std::string(DTWIRE_SOURCE_DIR) + "/experiments/default/campaign.toml", "--study",
                              "--snakefile", workflow.string()}),
            kExitBadInput);
  std::filesystem::remove_all(root);
}

}  // namespace
}  // namespace dtwire::app
