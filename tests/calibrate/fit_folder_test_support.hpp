#pragma once
// A fixture for tests that read fit files: a fresh folder per test with a small stress-strain
// target.csv, and write() to put a fit.toml beside it.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace dtwire::calibrate {

class FitFolderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("dtwire_fit_folder_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->test_suite_name()) +
            "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
    std::ofstream(dir_ / "target.csv") << "strain_1,stress_MPa\n0,0\n0.001,200\n0.01,320\n0.02,350\n";
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::filesystem::path write(const std::string& text) {
    const auto path = dir_ / "fit.toml";
    std::ofstream(path) << text;
    return path;
  }
  std::filesystem::path dir_;
};

}  // namespace dtwire::calibrate
