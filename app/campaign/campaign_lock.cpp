#include "campaign_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "dtwire/core/error.hpp"
#include "dtwire/core/provenance.hpp"

namespace dtwire::app {
namespace {

std::string read_all(int fd) {
  std::string text;
  char buffer[256];
  ::lseek(fd, 0, SEEK_SET);
  for (ssize_t n; (n = ::read(fd, buffer, sizeof buffer)) > 0;) text.append(buffer, static_cast<std::size_t>(n));
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
  return text;
}

}  // namespace

CampaignLock::CampaignLock(const std::filesystem::path& out) {
  std::filesystem::create_directories(out);
  const auto path = out / "campaign.lock";
  fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0) throw InputError(path.string(), std::string("cannot open the campaign lock: ") + std::strerror(errno));
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    const std::string holder = read_all(fd_);
    ::close(fd_);
    fd_ = -1;
    throw InputError(path.string(), "another campaign is writing into " + out.string() + " (" +
                                        (holder.empty() ? std::string("holder unknown") : holder) +
                                        "); wait for it to finish or choose another --out");
  }
  stale_note_ = read_all(fd_);
  const std::string mine = "pid " + std::to_string(::getpid()) + ", started " + utc_now_iso8601() + "\n";
  if (::ftruncate(fd_, 0) != 0 || ::pwrite(fd_, mine.data(), mine.size(), 0) != static_cast<ssize_t>(mine.size()))
    throw InputError(path.string(), std::string("cannot write the campaign lock: ") + std::strerror(errno));
}

CampaignLock::~CampaignLock() {
  if (fd_ < 0) return;
  // Emptied, not removed: removing would let a waiting opener lock a file nobody else sees.
  if (::ftruncate(fd_, 0) != 0) { /* the next campaign reports it as stale; nothing else to do */ }
  ::close(fd_);
}

}  // namespace dtwire::app
