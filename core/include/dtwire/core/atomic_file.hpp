#pragma once
// Result files are written to a temporary name beside the target (NAME.tmp.PID.N, PID the
// writer's process id) and renamed into place, so a crash or an error never leaves a
// half-written result behind. A writer killed outright (SIGKILL, power cut of the process) leaves
// its temporary: the next writer into the same folder removes every temporary whose PID no
// longer runs on this machine before it writes its first file there (remove_stale_temporaries).
#include <filesystem>
#include <functional>
#include <iosfwd>
#include <string_view>

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

// Runs `write` on a stream to a temporary file beside `target`, then renames it into place;
// failures as write_bytes_atomically's.
void write_file_atomically(const std::filesystem::path& target,
                           const std::function<void(std::ostream&)>& write);

// Writes `bytes` to a temporary file beside `target` and renames it into place. On any failure
// (no space, file-size limit, I/O error, permission) removes the temporary and throws
// std::runtime_error "<target>: cannot write: <system's reason>"; `target` is left as it was.
void write_bytes_atomically(const std::filesystem::path& target, std::string_view bytes);

// Removes, in `folder` (not below it), every NAME.tmp.PID.N file or folder whose PID is not this
// process and names no running process. Returns how many it removed; errors are ignored (a
// temporary that cannot be removed is no result: nothing reads it).
std::size_t remove_stale_temporaries(const std::filesystem::path& folder);

// The temporary's writer, if `name` has the form NAME.tmp.PID.N (0 otherwise).
long temporary_writer(const std::string& name);

// Checks, before any work, that a command can create or write into the output `folder` given by
// `option` (e.g. "-o"): neither it nor any of its parents is an existing file. Throws InputError
// naming the option and the file in the way. A folder that does not exist yet is fine: the
// command creates it.
void check_output_folder(const std::filesystem::path& folder, const std::string& option);

// As check_output_folder for the folder of the output `file`, and `file` is not an existing folder.
void check_output_file(const std::filesystem::path& file, const std::string& option);

}  // namespace dtwire
