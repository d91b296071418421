#pragma once
// Result files are written to a temporary name beside the target and renamed into place, so a
// crash or an error never leaves a half-written result behind.
#include <filesystem>
#include <functional>
#include <iosfwd>

namespace dtwire {

class PendingFile {
 public:
  explicit PendingFile(std::filesystem::path target);
  ~PendingFile();  // removes the temporary file unless commit() succeeded
  PendingFile(const PendingFile&) = delete;
  PendingFile& operator=(const PendingFile&) = delete;

  const std::filesystem::path& temporary() const { return temporary_; }
  const std::filesystem::path& target() const { return target_; }
  void commit();  // rename temporary -> target; throws std::runtime_error on failure

 private:
  std::filesystem::path target_;
  std::filesystem::path temporary_;
  bool committed_ = false;
};

// A result folder written under a temporary name beside the target and moved into place by
// commit(), so that one run's files never sit beside an earlier run's. An existing target is
// replaced only if it is empty or every entry in it is one `is_own_output` recognises (a file
// or folder name this command writes); otherwise the constructor throws InputError naming the
// folder and the foreign entry, before any work is done.
class PendingFolder {
 public:
  PendingFolder(std::filesystem::path target, std::function<bool(const std::string& name)> is_own_output);
  ~PendingFolder();  // removes the temporary folder unless commit() succeeded
  PendingFolder(const PendingFolder&) = delete;
  PendingFolder& operator=(const PendingFolder&) = delete;

  const std::filesystem::path& temporary() const { return temporary_; }
  const std::filesystem::path& target() const { return target_; }
  // Removes the earlier target, then renames temporary -> target; throws std::runtime_error.
  void commit();

 private:
  std::filesystem::path target_;
  std::filesystem::path temporary_;
  bool committed_ = false;
};

// Runs `write` on a stream to a temporary file, checks the stream, then renames.
void write_file_atomically(const std::filesystem::path& target,
                           const std::function<void(std::ostream&)>& write);

}  // namespace dtwire
