#include "dtwire/core/atomic_file.hpp"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <fstream>
#include <stdexcept>
#include <system_error>

#include "dtwire/core/error.hpp"

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

PendingFolder::PendingFolder(std::filesystem::path target, std::function<bool(const std::string&)> is_own_output)
    : target_(std::move(target)) {
  target_ = target_.lexically_normal();  // "out/" -> "out/": the trailing separator goes below
  if (target_.filename().empty()) target_ = target_.parent_path();
  // The folder is replaced as a whole: not the working directory or one that holds it (the
  // caller's shell would be left in a removed folder).
  const auto cwd = std::filesystem::current_path();
  const auto resolved = std::filesystem::weakly_canonical(std::filesystem::absolute(target_));
  const auto mismatch = std::mismatch(resolved.begin(), resolved.end(), cwd.begin(), cwd.end());
  if (mismatch.first == resolved.end())
    throw InputError(target_.string(), "is the working directory or holds it; the results replace the whole "
                                       "folder: give a folder below it (e.g. --out export)");
  if (std::filesystem::exists(target_)) {
    if (!std::filesystem::is_directory(target_))
      throw InputError(target_.string(), "exists and is not a folder; expected an output folder");
    for (const auto& entry : std::filesystem::directory_iterator(target_))
      if (!is_own_output(entry.path().filename().string()))
        throw InputError(target_.string(), "holds '" + entry.path().filename().string() +
                                               "', which this command does not write; choose a new or empty "
                                               "folder (results are never mixed with other files)");
  }
  const auto parent = target_.parent_path();
  if (!parent.empty()) std::filesystem::create_directories(parent);
  temporary_ = temporary_name(target_);
  std::filesystem::create_directory(temporary_);
}

PendingFolder::~PendingFolder() {
  if (!committed_) {
    std::error_code ignored;
    std::filesystem::remove_all(temporary_, ignored);
  }
}

void PendingFolder::commit() {
  std::error_code error;
  std::filesystem::remove_all(target_, error);
  if (!error) std::filesystem::rename(temporary_, target_, error);
  if (error)
    throw std::runtime_error(target_.string() + ": cannot move the results into place: " + error.message());
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
