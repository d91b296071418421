#pragma once
// Scratch files of the FE tests that run the dtwire executable: one folder per process (ctest
// runs each test in its own process, side by side) and whole-file reads of what a run wrote.
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <unistd.h>

namespace dtwire::fem::testing {

// `<tmp>/<prefix><pid>`, one per process: the first call names it and empties it.
inline const std::filesystem::path& process_scratch_dir(const std::string& prefix) {
  static const std::filesystem::path dir = [&] {
    const auto d = std::filesystem::temp_directory_path() / (prefix + std::to_string(getpid()));
    std::filesystem::remove_all(d);
    std::filesystem::create_directories(d);
    return d;
  }();
  return dir;
}

inline std::string read_text(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace dtwire::fem::testing
