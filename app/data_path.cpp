#include "data_path.hpp"

#include <cstdlib>

#include "dtwire/core/error.hpp"

namespace dtwire::app {

std::filesystem::path executable_path() {
  std::error_code error;
  const auto self = std::filesystem::read_symlink("/proc/self/exe", error);
  if (error) throw ComputationError("cannot find the dtwire binary (/proc/self/exe): " + error.message());
  return self;
}

std::filesystem::path data_dir() {
  if (const char* chosen = std::getenv("DTWIRE_DATA_DIR"); chosen && *chosen) return chosen;
  const auto binary = executable_path();
  for (auto folder = binary.parent_path(); !folder.empty(); folder = folder.parent_path()) {
    if (std::filesystem::is_directory(folder / "share" / "dtwire")) return folder / "share" / "dtwire";
    if (folder == folder.root_path()) break;
  }
  // None: where an installed copy would have it, so the file that is missing gets named.
  return (binary.parent_path() / ".." / "share" / "dtwire").lexically_normal();
}

std::filesystem::path data_path(const std::string& relative) { return data_dir() / relative; }

}  // namespace dtwire::app
