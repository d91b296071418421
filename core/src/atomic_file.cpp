#include "dtwire/core/atomic_file.hpp"

#include <unistd.h>

#include <atomic>
#include <fstream>
#include <stdexcept>
#include <system_error>

namespace dtwire {
namespace {
std::filesystem::path temporary_name(const std::filesystem::path& target) {
  static std::atomic<unsigned> counter{0};
  std::filesystem::path tmp = target;
  tmp += ".tmp." + std::to_string(::getpid()) + "." + std::to_string(counter++);
  return tmp;
}
}  // namespace

PendingFile::PendingFile(std::filesystem::path target)
    : target_(std::move(target)), temporary_(temporary_name(target_)) {
  const auto parent = target_.parent_path();
  if (!parent.empty() && !std::filesystem::is_directory(parent))
    throw std::runtime_error(target_.string() + ": output directory '" + parent.string() +
                             "' does not exist");
  if (std::filesystem::is_directory(target_))
    throw std::runtime_error(target_.string() + ": is a directory, expected a file name");
}

PendingFile::~PendingFile() {
  if (!committed_) {
    std::error_code ignored;
    std::filesystem::remove(temporary_, ignored);
  }
}

void PendingFile::commit() {
  std::error_code error;
  std::filesystem::rename(temporary_, target_, error);
  if (error)
    throw std::runtime_error(target_.string() + ": cannot move result into place: " +
                             error.message());
  committed_ = true;
}

void write_file_atomically(const std::filesystem::path& target,
                           const std::function<void(std::ostream&)>& write) {
  PendingFile pending(target);
  {
    std::ofstream out(pending.temporary(), std::ios::binary);
    if (!out) throw std::runtime_error(target.string() + ": cannot open for writing");
    write(out);
    out.flush();
    if (!out) throw std::runtime_error(target.string() + ": write failed");
  }
  pending.commit();
}

}  // namespace dtwire
