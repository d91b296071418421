// `dtwire mesh` end to end: files, --check figures, and exit code 2 naming the bad option.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "../app/run_dtwire.hpp"

namespace {

using Result = dtwire::test::CommandResult;
using dtwire::test::run;

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

class MeshCommand : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() / ("dtwire_mesh_cmd_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  std::filesystem::path dir_;
};

}  // namespace

TEST_F(MeshCommand, DoubleTwistFromPrmWritesMshVtuAndReport) {
  std::ofstream(path("dt.prm")) << "set twist-length = 35\nset level = 0\n";
  const Result r = run("mesh dt --prm " + path("dt.prm") + " -o " + path("dt.msh") + " --vtu " + path("dt.vtu") +
                       " --check --report " + path("dt.md"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(std::filesystem::file_size(path("dt.msh")) > 0);
  EXPECT_TRUE(std::filesystem::file_size(path("dt.vtu")) > 0);
  for (const char* figure : {"cells (hexahedra)", "minimum scaled Jacobian", "maximum aspect ratio",
                             "minimum distance between the wire surfaces", "helix lay angle", "steel volume",
                             "| twist-length | 35 mm |"})
    EXPECT_TRUE(contains(r.output, figure)) << figure << "\n" << r.output;
  std::ifstream report(path("dt.md"));
  const std::string text((std::istreambuf_iterator<char>(report)), std::istreambuf_iterator<char>());
  EXPECT_TRUE(contains(text, "minimum scaled Jacobian"));
}

TEST_F(MeshCommand, OptionsOverrideThePrmFile) {
  std::ofstream(path("sw.prm")) << "set length = 50\n";
  const Result r = run("mesh sw --prm " + path("sw.prm") + " --length 40 --level 0 --check");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(contains(r.output, "| length | 40 mm |")) << r.output;
}

TEST_F(MeshCommand, BadValuesExitTwoNamingTheOptionOrFileLine) {
  Result r = run("mesh sw --d 0 --check");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(contains(r.output, "--d: expected a diameter > 0")) << r.output;
  r = run("mesh dt --half-turns -1 --check");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(contains(r.output, "--half-turns")) << r.output;
  std::ofstream(path("bad.prm")) << "set gap = 1\n";
  r = run("mesh dt --prm " + path("bad.prm") + " -o " + path("bad.msh"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(contains(r.output, "bad.prm:1:11: gap:")) << r.output;
  EXPECT_FALSE(std::filesystem::exists(path("bad.msh")));
}
