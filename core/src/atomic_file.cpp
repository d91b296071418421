#include "dtwire/core/atomic_file.hpp"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstring>
#include <mutex>
#include <set>
#include <streambuf>
#include <vector>
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

// Each folder is swept once per process, before the first temporary is made in it.
void sweep_once(const std::filesystem::path& folder) {
  static std::mutex mutex;
  static std::set<std::filesystem::path> swept;
  const auto key = std::filesystem::absolute(folder.empty() ? "." : folder).lexically_normal();
  {
    const std::lock_guard<std::mutex> lock(mutex);
    if (!swept.insert(key).second) return;
  }
  remove_stale_temporaries(key);
}

std::string system_reason(int error) {
  return std::string(std::strerror(error)) + " (errno " + std::to_string(error) + ")";
}
}  // namespace

long temporary_writer(const std::string& name) {
  // NAME.tmp.PID.N: the last two dot-separated fields are digits, ".tmp" before them.
  const auto last_dot = name.rfind('.');
  if (last_dot == std::string::npos || last_dot == 0) return 0;
  const auto pid_dot = name.rfind('.', last_dot - 1);
  if (pid_dot == std::string::npos || pid_dot < 4 || name.compare(pid_dot - 4, 4, ".tmp") != 0) return 0;
  const std::string counter = name.substr(last_dot + 1), pid = name.substr(pid_dot + 1, last_dot - pid_dot - 1);
  const auto digits = [](const std::string& text) {
    return !text.empty() && text.size() < 11 && std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; });
  };
  if (!digits(counter) || !digits(pid) || pid_dot == 4) return 0;  // ".tmp.1.2" has no NAME
  return std::stol(pid);
}

std::size_t remove_stale_temporaries(const std::filesystem::path& folder) {
  std::size_t removed = 0;
  std::error_code error;
  std::filesystem::directory_iterator entries(folder.empty() ? "." : folder, error);
  if (error) return 0;
  for (const auto& entry : entries) {
    const long writer = temporary_writer(entry.path().filename().string());
    if (writer <= 0 || writer == ::getpid()) continue;
    if (::kill(static_cast<pid_t>(writer), 0) == 0 || errno != ESRCH) continue;  // its writer still runs
    std::error_code ignored;
    if (std::filesystem::remove_all(entry.path(), ignored) > 0) ++removed;
  }
  return removed;
}

PendingFile::PendingFile(std::filesystem::path target)
    : target_(std::move(target)), temporary_(temporary_name(target_)) {
  const auto parent = target_.parent_path();
  if (!parent.empty() && !std::filesystem::is_directory(parent))
    throw std::runtime_error(target_.string() + ": output directory '" + parent.string() +
                             "' does not exist");
  if (std::filesystem::is_directory(target_))
    throw std::runtime_error(target_.string() + ": is a directory, expected a file name");
  sweep_once(parent);
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
  sweep_once(parent);
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

namespace {

// Writes all of `size` bytes; 0 or the errno of the failure.
int write_all(int fd, const char* data, std::size_t size) {
  for (std::size_t written = 0; written < size;) {
    const ssize_t n = ::write(fd, data + written, size - written);
    if (n > 0)
      written += static_cast<std::size_t>(n);
    else if (n == 0)
      return EIO;
    else if (errno != EINTR)
      return errno;
  }
  return 0;
}

// A stream buffer onto a file descriptor that keeps the errno of the first failed write (an
// ofstream only says that something failed).
class FileDescriptorBuffer : public std::streambuf {
 public:
  explicit FileDescriptorBuffer(int fd) : fd_(fd), buffer_(1 << 16) { setp(buffer_.data(), buffer_.data() + buffer_.size()); }
  int error() const { return error_; }

 protected:
  int_type overflow(int_type c) override {
    if (sync() != 0) return traits_type::eof();
    if (!traits_type::eq_int_type(c, traits_type::eof())) sputc(traits_type::to_char_type(c));
    return traits_type::not_eof(c);
  }
  int sync() override {
    if (error_ == 0) error_ = write_all(fd_, pbase(), static_cast<std::size_t>(pptr() - pbase()));
    setp(buffer_.data(), buffer_.data() + buffer_.size());
    return error_ == 0 ? 0 : -1;
  }

 private:
  int fd_;
  int error_ = 0;
  std::vector<char> buffer_;
};

// Opens a temporary beside `target`, runs `fill(fd)` (0 or an errno), closes and renames it.
void write_through_temporary(const std::filesystem::path& target, const std::function<int(int)>& fill) {
  PendingFile pending(target);
  const int fd = ::open(pending.temporary().c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (fd < 0)
    throw std::runtime_error(target.string() + ": cannot create " + pending.temporary().filename().string() +
                             ": " + system_reason(errno));
  int error = 0;
  try {
    error = fill(fd);
  } catch (...) {
    ::close(fd);
    throw;
  }
  // close() reports what a network file system could only learn at the end (quota, no space).
  if (::close(fd) != 0 && error == 0 && errno != EINTR) error = errno;
  if (error != 0) throw std::runtime_error(target.string() + ": cannot write: " + system_reason(error));
  pending.commit();
}

}  // namespace

void write_file_atomically(const std::filesystem::path& target,
                           const std::function<void(std::ostream&)>& write) {
  write_through_temporary(target, [&](int fd) {
    FileDescriptorBuffer buffer(fd);
    std::ostream out(&buffer);
    write(out);
    out.flush();
    if (buffer.error() == 0 && !out) throw std::runtime_error(target.string() + ": cannot format the contents");
    return buffer.error();
  });
}

void write_bytes_atomically(const std::filesystem::path& target, std::string_view bytes) {
  write_through_temporary(target, [&](int fd) { return write_all(fd, bytes.data(), bytes.size()); });
}

void check_output_folder(const std::filesystem::path& folder, const std::string& option) {
  std::error_code error;
  const std::filesystem::path target = std::filesystem::absolute(folder, error).lexically_normal();
  for (std::filesystem::path p = target; !p.empty(); p = p.parent_path()) {
    if (std::filesystem::exists(p, error) && !std::filesystem::is_directory(p, error))
      throw InputError(option, "'" + p.string() + "' is a file, not a folder: expected " +
                                   (p == target ? std::string("a folder to write into")
                                                : "a path whose parents are folders (" + folder.string() + ")"));
    if (p == p.parent_path()) break;  // the root
  }
}

void check_output_file(const std::filesystem::path& file, const std::string& option) {
  std::error_code error;
  if (std::filesystem::is_directory(file, error))
    throw InputError(option, "'" + file.string() + "' is a folder: expected a file name to write");
  const std::filesystem::path folder = std::filesystem::absolute(file, error).parent_path();
  check_output_folder(folder, option);
}

}  // namespace dtwire
