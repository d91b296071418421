#include "campaign_lock.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <iterator>
#include <sstream>
#include <thread>

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

std::string first_line(const std::string& text) { return text.substr(0, text.find('\n')); }

bool any_alive(const std::vector<StepGroup>& groups) {
  for (const StepGroup& group : groups)
    if (step_group_alive(group)) return true;
  return false;
}

// Polls until none of `groups` runs or `limit` has passed; true if none runs.
bool wait_until_gone(const std::vector<StepGroup>& groups, std::chrono::seconds limit) {
  const auto deadline = std::chrono::steady_clock::now() + limit;
  while (any_alive(groups)) {
    if (std::chrono::steady_clock::now() >= deadline) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  return true;
}

}  // namespace

std::vector<StepGroup> listed_step_groups(const std::string& lock_text) {
  std::vector<StepGroup> groups;
  std::istringstream lines(lock_text);
  for (std::string line; std::getline(lines, line);) {
    std::istringstream words(line);
    std::string step, group_word, started;
    StepGroup group;
    long id = 0;
    if (words >> step >> group_word >> id >> started >> group.start_ticks && step == "step" && group_word == "group" &&
        started == "started" && id > 1) {
      group.group = static_cast<pid_t>(id);
      groups.push_back(group);
    }  // else: the holder's line, or a damaged line that names no group
  }
  return groups;
}

namespace {

// Fields 3 and on of /proc/PID/stat (field 3, the state, first); empty if the process is gone.
std::vector<std::string> stat_fields(const std::string& pid) {
  std::ifstream stat("/proc/" + pid + "/stat");
  const std::string text((std::istreambuf_iterator<char>(stat)), std::istreambuf_iterator<char>());
  const auto name_end = text.rfind(')');  // the program name in parentheses may hold spaces
  std::vector<std::string> fields;
  if (name_end == std::string::npos) return fields;
  std::istringstream words(text.substr(name_end + 1));
  for (std::string word; words >> word;) fields.push_back(word);
  return fields;
}

// Whether a process of the group runs. Not kill(-group, 0): that counts zombies, and an orphan's
// zombie waits for whoever is PID 1 to reap it (in a container, possibly never).
bool group_has_running_member(pid_t group) {
  std::error_code error;
  for (const auto& entry : std::filesystem::directory_iterator("/proc", error)) {
    const std::string pid = entry.path().filename().string();
    if (pid.empty() || pid.find_first_not_of("0123456789") != std::string::npos) continue;
    const auto fields = stat_fields(pid);  // [0] state, [2] process group
    if (fields.size() > 2 && fields[0] != "Z" && fields[0] != "X" && std::atol(fields[2].c_str()) == group) return true;
  }
  return false;
}

}  // namespace

unsigned long long process_start_ticks(pid_t pid) {
  const auto fields = stat_fields(std::to_string(pid));
  return fields.size() > 19 ? std::strtoull(fields[19].c_str(), nullptr, 10) : 0;  // field 22
}

bool step_group_alive(const StepGroup& group) {
  if (group.group <= 1 || group.group == ::getpgrp()) return false;
  if (!group_has_running_member(group.group)) return false;
  const unsigned long long leader_start = process_start_ticks(group.group);
  return leader_start == 0 || leader_start == group.start_ticks;
}

std::vector<pid_t> stop_step_groups(const std::vector<StepGroup>& groups, std::chrono::seconds grace) {
  std::vector<pid_t> signalled;
  if (wait_until_gone(groups, grace)) return signalled;
  for (const StepGroup& group : groups)
    if (step_group_alive(group) && ::kill(-group.group, SIGTERM) == 0) signalled.push_back(group.group);
  if (wait_until_gone(groups, grace)) return signalled;
  for (const StepGroup& group : groups)
    if (step_group_alive(group)) ::kill(-group.group, SIGKILL);
  wait_until_gone(groups, std::chrono::seconds(5));  // SIGKILL cannot be refused: moments
  return signalled;
}

CampaignLock::CampaignLock(const std::filesystem::path& out, std::chrono::seconds wait_for_steps) {
  std::filesystem::create_directories(out);
  path_ = (out / "campaign.lock").string();
  fd_ = ::open(path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0) throw InputError(path_, std::string("cannot open the campaign lock: ") + std::strerror(errno));
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    const std::string holder = first_line(read_all(fd_));
    ::close(fd_);
    fd_ = -1;
    throw InputError(path_, "another campaign is writing into " + out.string() + " (" +
                                (holder.empty() ? std::string("holder unknown") : holder) +
                                "); wait for it to finish or choose another --out");
  }
  const std::string stale = read_all(fd_);
  stale_note_ = first_line(stale);
  holder_ = "pid " + std::to_string(::getpid()) + ", started " + utc_now_iso8601();
  if (!write_contents()) {
    const int error = errno;
    ::close(fd_);
    fd_ = -1;
    throw InputError(path_, std::string("cannot write the campaign lock: ") + std::strerror(error));
  }
  // The stale campaign's steps may still write into the folder: none of its steps runs again
  // beside them.
  std::vector<StepGroup> running;
  for (const StepGroup& group : listed_step_groups(stale))
    if (step_group_alive(group)) running.push_back(group);
  if (running.empty()) return;
  std::string names;
  for (const StepGroup& group : running) names += (names.empty() ? "" : ", ") + std::to_string(group.group);
  std::cerr << "campaign: steps of the stale campaign still run (process group " << names << "); waiting up to "
            << wait_for_steps.count() << " s for them to stop\n";
  const auto signalled = stop_step_groups(running, wait_for_steps);
  if (!signalled.empty())
    std::cerr << "campaign: stopped " << signalled.size() << " step process group(s) of the stale campaign\n";
}

CampaignLock::~CampaignLock() {
  if (fd_ < 0) return;
  // Emptied, not removed: removing would let a waiting opener lock a file nobody else sees.
  if (::ftruncate(fd_, 0) != 0) { /* the next campaign reports it as stale; nothing else to do */ }
  ::close(fd_);
}

void CampaignLock::add_step_group(pid_t group) {
  const std::lock_guard<std::mutex> lock(mutex_);
  groups_.insert({group, process_start_ticks(group)});
  write_contents();
}

void CampaignLock::remove_step_group(pid_t group) {
  const std::lock_guard<std::mutex> lock(mutex_);
  for (auto entry = groups_.begin(); entry != groups_.end();)
    entry = entry->first == group ? groups_.erase(entry) : std::next(entry);
  write_contents();
}

bool CampaignLock::write_contents() {
  std::string text = holder_ + "\n";
  for (const auto& [group, start] : groups_)
    text += "step group " + std::to_string(group) + " started " + std::to_string(start) + "\n";
  // Written in place, then cut to its length: a reader (a refused second campaign) sees the
  // holder's line whatever the moment.
  return ::pwrite(fd_, text.data(), text.size(), 0) == static_cast<ssize_t>(text.size()) &&
         ::ftruncate(fd_, static_cast<off_t>(text.size())) == 0;
}

}  // namespace dtwire::app
