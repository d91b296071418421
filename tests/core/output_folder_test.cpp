// One run's results never sit beside another's (issue 20): folders written aside and moved into
// place, and a run id that marks every file of one run.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <unistd.h>

#include "dtwire/core/atomic_file.hpp"
#include "dtwire/core/error.hpp"
#include "dtwire/core/provenance.hpp"

namespace dtwire {
namespace {

namespace fs = std::filesystem;

bool is_result(const std::string& name) { return name.size() > 4 && name.substr(name.size() - 4) == ".csv"; }

void touch(const fs::path& file) { std::ofstream(file) << "x\n"; }

fs::path fresh(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

TEST(PendingFolder, ReplacesAnEarlierRunsFolderOnlyOnCommit) {
  const fs::path root = fresh("dtwire_pending_folder");
  touch(root / "out.csv");  // not a folder: the target below is root/results
  fs::create_directories(root / "results");
  touch(root / "results" / "old_set.csv");
  {
    PendingFolder folder(root / "results", is_result);
    touch(folder.temporary() / "new_set.csv");
    EXPECT_TRUE(fs::exists(root / "results" / "old_set.csv")) << "untouched until commit";
    folder.commit();
  }
  EXPECT_FALSE(fs::exists(root / "results" / "old_set.csv"));
  EXPECT_TRUE(fs::exists(root / "results" / "new_set.csv"));
  // A failure before commit leaves the earlier results and no temporary folder.
  {
    PendingFolder folder(root / "results", is_result);
    touch(folder.temporary() / "half_written.csv");
  }
  EXPECT_TRUE(fs::exists(root / "results" / "new_set.csv"));
  std::size_t entries = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(root)) ++entries;
  EXPECT_EQ(entries, 2u) << "out.csv and results only";
  fs::remove_all(root);
}

// `--out .` would replace the working directory as a whole: refused; a trailing separator
// names the folder itself.
TEST(PendingFolder, RefusesTheWorkingDirectoryAndTakesATrailingSeparator) {
  const fs::path root = fresh("dtwire_pending_dot");
  const fs::path previous = fs::current_path();
  fs::current_path(root);
  touch("old_set.csv");
  EXPECT_THROW(PendingFolder(".", is_result), InputError);
  EXPECT_THROW(PendingFolder("..", is_result), InputError);
  EXPECT_EQ(PendingFolder("sub/", is_result).target(), fs::path("sub"));
  fs::current_path(previous);
  EXPECT_TRUE(fs::exists(root / "old_set.csv"));
  fs::remove_all(root);
}

TEST(PendingFolder, RefusesAFolderHoldingOtherFilesBeforeAnyWork) {
  const fs::path root = fresh("dtwire_pending_foreign");
  touch(root / "notes.txt");
  try {
    PendingFolder folder(root, is_result);
    FAIL() << "expected InputError";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("notes.txt"), std::string::npos) << error.what();
  }
  EXPECT_TRUE(fs::exists(root / "notes.txt"));
  EXPECT_THROW(PendingFolder(root / "notes.txt", is_result), InputError) << "a file is not a folder";
  fs::remove_all(root);
}

TEST(Provenance, EachRunGetsItsOwnId) {
  std::set<std::string> ids;
  for (int i = 0; i < 100; ++i) ids.insert(make_provenance("dtwire test").run_id);
  EXPECT_EQ(ids.size(), 100u);
  EXPECT_EQ(new_run_id().size(), std::string("20261124T121500Z-").size() + std::to_string(::getpid()).size() + 9);
}

// An output path is checked before any work: a file where a folder must be is named with the
// option; a folder that does not exist yet is fine (the command makes it).
TEST(OutputPaths, AFileInTheWayIsNamedWithItsOption) {
  const auto root = std::filesystem::temp_directory_path() / ("dtwire_output_paths_" + std::to_string(::getpid()));
  std::filesystem::remove_all(root);
  std::filesystem::create_directories(root);
  std::ofstream(root / "a_file") << "x";
  EXPECT_NO_THROW(check_output_folder(root / "new" / "deeper", "-o"));
  EXPECT_NO_THROW(check_output_file(root / "new" / "x.json", "--json"));
  try {
    check_output_folder(root / "a_file" / "sub", "-o");
    ADD_FAILURE() << "a file as a parent folder was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("-o"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("a_file' is a file, not a folder"), std::string::npos) << e.what();
  }
  EXPECT_THROW(check_output_folder(root / "a_file", "--out"), InputError);
  EXPECT_THROW(check_output_file(root, "--json"), InputError);  // a folder where a file must be
  std::filesystem::remove_all(root);
}

}  // namespace
}  // namespace dtwire
