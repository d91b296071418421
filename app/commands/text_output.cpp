#include "text_output.hpp"

#include <filesystem>
#include <ostream>

#include "dtwire/core/atomic_file.hpp"

namespace dtwire::app {

void write_text(const std::string& path, const std::string& text) {
  if (path.empty()) return;
  const std::filesystem::path target(path);
  if (target.has_parent_path()) std::filesystem::create_directories(target.parent_path());
  write_file_atomically(target, [&](std::ostream& out) { out << text; });
}

}  // namespace dtwire::app
