// Issue 53: every write failure becomes an exception naming the file and the system's reason,
// with no temporary left behind; a killed writer's temporaries go before the next write.
#include <gtest/gtest.h>

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>

#include "dtwire/core/atomic_file.hpp"
#include "dtwire/core/error.hpp"
#include "dtwire/core/results_store.hpp"

namespace dtwire {
namespace {

namespace fs = std::filesystem;

fs::path fresh(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::size_t entries(const fs::path& dir) {
  return static_cast<std::size_t>(std::distance(fs::directory_iterator(dir), fs::directory_iterator()));
}

// A pid that names no process: a child that has ended and been reaped.
pid_t ended_pid() {
  const pid_t pid = ::fork();
  if (pid == 0) ::_exit(0);
  ::waitpid(pid, nullptr, 0);
  return pid;
}

// In the child of EXPECT_EXIT, under a 4 KiB file-size limit (SIGXFSZ ignored, as the dtwire
// command does): exits 0 if `write` threw a message that names `file` and "File too large" and
// left `dir` empty.
[[noreturn]] void write_under_file_size_limit(const fs::path& dir, const fs::path& file,
                                              const std::function<void()>& write) {
  std::signal(SIGXFSZ, SIG_IGN);
  rlimit limit;
  limit.rlim_cur = limit.rlim_max = 4096;
  ::setrlimit(RLIMIT_FSIZE, &limit);
  try {
    write();
    std::cerr << "no error\n";
    std::_Exit(1);
  } catch (const std::runtime_error& e) {
    const std::string message = e.what();
    if (message.find(file.string()) == std::string::npos || message.find("File too large") == std::string::npos) {
      std::cerr << "message: " << message << "\n";
      std::_Exit(2);
    }
  }
  if (entries(dir) != 0) {
    std::cerr << "left " << entries(dir) << " file(s)\n";
    std::_Exit(3);
  }
  std::_Exit(0);
}

void expect_file_size_limit_reported(const fs::path& dir, const fs::path& file, const std::function<void()>& write) {
  EXPECT_EXIT(write_under_file_size_limit(dir, file, write), ::testing::ExitedWithCode(0), "");
}

TEST(IoFaults, FileSizeLimitIsReportedWithTheFileAndNoTemporaryStays) {
  const fs::path dir = fresh("dtwire_io_faults_text");
  const fs::path file = dir / "curve.csv";
  expect_file_size_limit_reported(dir, file, [&] {
    write_file_atomically(file, [](std::ostream& out) { out << std::string(100000, 'x'); });
  });
  fs::remove_all(dir);
}

TEST(IoFaults, Hdf5WriteUnderAFileSizeLimitIsReportedNotACrash) {
  const fs::path dir = fresh("dtwire_io_faults_h5");
  const fs::path file = dir / "results.h5";
  Results results;
  Curve curve;
  curve.add_channel("force", *find_unit("N"), std::vector<double>(20000, 1.5));
  results.curves.emplace_back("history", curve);
  results.parameters.push_back({"E", 2.1e11, "Pa", std::nullopt});
  expect_file_size_limit_reported(dir, file, [&] { write_results(results, file); });
  write_results(results, file);  // without the limit the same file is written and reads back
  EXPECT_EQ(read_results(file).parameters.at(0).value, 2.1e11);
  fs::remove_all(dir);
}

TEST(IoFaults, Hdf5ErrorStackIsTheMessage) {
  const fs::path dir = fresh("dtwire_io_faults_stack");
  const fs::path file = dir / "results.h5";
  Results results;
  results.parameters.push_back({"E", 2.1e11, "Pa", std::nullopt});
  write_results(results, file);
  fs::resize_file(file, fs::file_size(file) / 2);  // a truncated file: HDF5 itself refuses it
  try {
    read_results(file);
    FAIL() << "a truncated file was read";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(file.string()), std::string::npos) << message;
    // The stack's records (function: description), not only "open failed".
    EXPECT_NE(message.find("H5F"), std::string::npos) << message;
    EXPECT_NE(message.find("truncated"), std::string::npos) << message;
  }
  fs::remove_all(dir);
}

TEST(IoFaults, TemporaryNamesAreRecognised) {
  EXPECT_EQ(temporary_writer("results.h5.tmp.1234.0"), 1234);
  EXPECT_EQ(temporary_writer("curve.csv.tmp.77.12"), 77);
  EXPECT_EQ(temporary_writer("export.tmp.5.1"), 5);
  EXPECT_EQ(temporary_writer(".tmp.5.1"), 0);  // no NAME
  EXPECT_EQ(temporary_writer("curve.csv"), 0);
  EXPECT_EQ(temporary_writer("notes.tmp.txt"), 0);
  EXPECT_EQ(temporary_writer("a.tmp.x.1"), 0);
  EXPECT_EQ(temporary_writer("a.tmp.1."), 0);
}

TEST(IoFaults, StaleTemporariesOfEndedWritersAreRemovedOthersStay) {
  const fs::path dir = fresh("dtwire_io_faults_stale");
  const std::string dead = std::to_string(ended_pid());
  const std::string alive = std::to_string(::getppid());  // the test's parent runs
  const std::string self = std::to_string(::getpid());
  for (const std::string& name : {"curve.csv.tmp." + dead + ".0", "results.h5.tmp." + dead + ".3",
                                  "curve.csv.tmp." + alive + ".0", "curve.csv.tmp." + self + ".7",
                                  std::string("curve.csv"), std::string("notes.tmp.txt")})
    std::ofstream(dir / name) << "x\n";
  fs::create_directories(dir / ("export.tmp." + dead + ".1") / "sub");  // a PendingFolder's
  EXPECT_EQ(remove_stale_temporaries(dir), 3u);
  EXPECT_FALSE(fs::exists(dir / ("curve.csv.tmp." + dead + ".0")));
  EXPECT_FALSE(fs::exists(dir / ("export.tmp." + dead + ".1")));
  for (const std::string& name : {"curve.csv.tmp." + alive + ".0", "curve.csv.tmp." + self + ".7",
                                  std::string("curve.csv"), std::string("notes.tmp.txt")})
    EXPECT_TRUE(fs::exists(dir / name)) << name;
  fs::remove_all(dir);
}

TEST(IoFaults, TheFirstWriteIntoAFolderRemovesItsStaleTemporaries) {
  const fs::path dir = fresh("dtwire_io_faults_first_write");
  const fs::path stale = dir / ("link_type_histograms.csv.tmp." + std::to_string(ended_pid()) + ".0");
  std::ofstream(stale) << "half a row";
  write_file_atomically(dir / "summary.json", [](std::ostream& out) { out << "{}\n"; });
  EXPECT_FALSE(fs::exists(stale));
  EXPECT_EQ(entries(dir), 1u);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace dtwire
